// Evidence for a model class by importance sampling: the integral of the
// likelihood over a uniform prior on a box, estimated from draws of a defensive
// mixture (Hesterberg 1995): a share of the draws from the prior box itself and
// the rest from heavy-tailed (Student t) components centred on the local optima
// a fit found, each with the Laplace covariance (model_evidence.h) widened.
// Where the posterior is a ridge or has several modes (a location along the
// structure that few modes cannot pin down, data that fit exactly along a
// curve), Laplace's approximation at one optimum is far off; this estimate is
// unbiased for any proposal that covers the posterior, and says how well it did
// (effective sample size, standard error).
//
// Likelihood with whitened residuals: exp(-chi2(theta) / (2 T)), T >= 1 a noise
// temperature, the constant -n/2 log(2 pi T) left out, as in LaplaceEvidence:
//   log Z(T) = log integral exp(-chi2(theta) / 2T) pi(theta) d theta,
// pi = 1 / volume on [lower, upper]. The misfit may have several parts (fitted
// and held-out data, say); the draws are kept, so the evidence of any subset of
// parts at any temperature comes from the same draws (LogEvidenceFromSamples),
// and log Z(fitted + held-out) - log Z(fitted) is the exact posterior predictive
// density of the held-out part.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "femup/core/invalid.h"

namespace femup {

struct SampledEvidenceOptions {
  int samples = 2000;        // draws in all, >= 10
  double prior_share = 0.2;  // of the draws from the prior box, in (0, 1]
  double spread = 1.5;       // multiplies the components' standard deviations, > 0
  int tail_dof = 5;          // Student t degrees of freedom of the components, >= 1
  // Adaptive stages (>= 1): after each stage but the last, the next one's
  // components are the given ones plus, for the first k parts of the misfit
  // (k = 1..parts), one at the weighted mean and covariance of the draws so far
  // (the posterior of those parts at `temperature`).
  int stages = 3;
  double temperature = 1.0;  // of the posterior the stages adapt to, >= 1
  std::uint64_t seed = 20261124;
  std::uint64_t stream = 0;  // e.g. a class's index: independent draws per class
  // Ok when valid, else the field and what is wrong.
  Invalid Validate() const;
};

// A proposal component: a local optimum and a covariance (positive definite).
struct EvidenceComponent {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;
};

// chi2 of each part of the data at theta into *chi2 (resized by the callee or
// already of size num_parts); false where the model cannot be evaluated there
// (the draw then counts with likelihood 0).
using MisfitFunction =
    std::function<bool(const Eigen::VectorXd& theta, Eigen::VectorXd* chi2)>;

struct EvidenceSamples {
  int num_parts = 0;
  // Per draw: log pi(theta) - log q(theta) (-inf outside the box or where the
  // misfit failed) and the chi2 of each part.
  Eigen::VectorXd log_weight;
  Eigen::MatrixXd chi2;  // draws x parts
  int outside = 0;       // draws outside the prior box (not evaluated)
  int failed = 0;        // draws where the misfit returned false
};

// Draws options.samples points in options.stages stages and evaluates the
// misfit at those inside the box. With no components the first stage draws from
// the prior only.
// Throws InputError for invalid options, an empty or non-finite box, or a
// component of the wrong size or with a covariance that is not positive
// definite.
EvidenceSamples SampleEvidence(const MisfitFunction& misfit, int num_parts,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                               const std::vector<EvidenceComponent>& components,
                               const SampledEvidenceOptions& options);

struct SampledLogEvidence {
  double log_evidence = 0;
  // Kish's effective number of draws, (sum w)^2 / sum w^2.
  double effective_samples = 0;
  // Standard error of log Z (delta method: the relative standard error of the
  // mean weight); +inf when no draw has a positive weight.
  double log_standard_error = 0;
};

// log Z(T) of the parts marked true in `parts` (size num_parts), from the draws.
// log_evidence is -inf when no draw has a positive weight. Throws InputError
// for a wrong mask size or T < 1.
SampledLogEvidence LogEvidenceFromSamples(const EvidenceSamples& samples,
                                          const std::vector<bool>& parts,
                                          double temperature = 1.0);

}  // namespace femup
