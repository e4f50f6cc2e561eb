// Posterior probabilities of model classes that hold when every class is wrong
// (a bagged posterior over the residuals: the bootstrap of pointwise
// log-likelihoods of Yao, Vehtari, Simpson and Gelman's pseudo-BMA+, Bayesian
// Analysis 2018; Huggins and Miller on bagged posteriors for model selection,
// Bayesian Analysis 2023).
//
// Laplace evidences (model_evidence.h) compare classes as if one of them made
// the data up to the stated noise. When none does (the model's own form error,
// an effect no family describes exactly), a difference in chi2 that comes from
// a few residuals the best class happens to fit decides with the certainty of
// a difference spread over all of them. The bagged posterior averages the
// posterior over bootstrap copies of the residuals: each copy draws the n
// residual rows n times with replacement (multinomial weights w, within
// strata: below), every class is scored on the copy by
//   log Z_w = log Z - (sum_i w_i r_i^2 - chi2) / 2
// (its fit, Occam factor and prior held; r its whitened residuals at the fit,
// chi2 = sum_i r_i^2), and the probabilities are the mean over copies of the
// copies' posteriors. On average a copy scores every class as the data do
// (E w_i = 1); a verdict that every part of the data supports stays certain,
// one that rests on a few residuals is shared with the classes the rest of
// the data prefer. The fits are not redone on a copy: a refit would gain
// each parameter about one unit of chi2 from the copy's own noise and favour
// the classes with more parameters over "none".
//
// Copies are drawn by a counter-based generator from (seed, copy): the same
// numbers on every machine and thread.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "femup/core/invalid.h"

namespace femup {

struct BaggingOptions {
  int copies = 400;  // bootstrap copies of the residuals (>= 1)
  std::uint64_t seed = 20261127;
  // Ok when valid, else the field and what is wrong.
  Invalid Validate() const;
};

// One class as fitted to the data: its whitened residuals at the fit (n, the
// same rows for every class), log evidence and prior probability (> 0, not
// necessarily normalised).
struct ClassFit {
  Eigen::VectorXd residual;
  double log_evidence = 0;
  double prior = 1;
};

// The bagged posterior probabilities, one per class, summing to 1. strata:
// one label per residual row (empty: all rows one stratum); each copy draws as
// many rows from each stratum as it has, so that a copy keeps the experiment's
// design (as many frequencies and as many shape entries as measured) and
// varies only which of them carry the weight. Throws InputError for invalid
// options, no classes, residuals of different lengths or none, non-finite
// values, a prior <= 0 or strata of another length.
Eigen::VectorXd BaggedPosteriorProbabilities(const std::vector<ClassFit>& classes,
                                             const BaggingOptions& options,
                                             const std::vector<int>& strata = {});

}  // namespace femup
