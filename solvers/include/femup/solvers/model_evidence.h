// Evidence for a model class from a least-squares fit (Laplace's approximation):
// how probable the data are under the class, averaged over its prior, so that
// classes with different numbers of parameters can be compared (MacKay 1992;
// Beck and Yuen 2004 for structural model classes).
//
// With whitened residuals r(x) (unit variance under the stated noise), chi2 =
// ||r(x*)||^2 at the best fit x*, and a uniform prior on the box [lower, upper]:
//   log Z = -chi2 / (2 T) + log Occam,
//   log Occam = 1/2 log det(2 pi H^-1) - sum_i log(upper_i - lower_i)
//               - (log 2 for each parameter at a bound),
//   H = J'J / T + diag(2 pi / (upper_i - lower_i)^2),
// the small diagonal term being the Gaussian whose peak density equals the
// uniform prior's (variance range^2 / 2 pi), so that a direction the data do
// not see costs nothing (Occam factor exactly 1 there); log Occam
// is capped at 0. T >= 1 is a noise temperature: the stated variances times T
// (T = 1: the noise as stated). The constant -n/2 log(2 pi T) common to all
// classes fitted to the same data is left out.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace femup {

struct ModelEvidence {
  double log_evidence = 0;
  double chi2 = 0;       // at the best fit (not divided by T)
  double log_occam = 0;  // <= 0
  int num_parameters = 0;
  Eigen::VectorXd sigma;       // posterior standard deviations (Laplace), per parameter
  Eigen::MatrixXd covariance;  // posterior covariance H^-1 (Laplace)
};

// x, lower, upper: the parameters at the best fit and the prior box (empty for
// a class without parameters); jacobian: whitened, residuals x parameters.
// Throws InputError for size mismatches, an empty or non-finite box, T < 1 or a
// negative or non-finite chi2.
ModelEvidence LaplaceEvidence(double chi2, const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper, double temperature = 1.0);

// The same where some parameters have a Gaussian prior N(normal_mean_i,
// normal_sigma_i^2) in their own coordinate (normal_sigma_i > 0; 0 = the
// uniform prior on [lower_i, upper_i]), which for them replaces the uniform
// one: the box only bounds the fit (no range term, no bound penalty). x is the
// posterior's mode (the fit included the residuals (x_i - mean_i) / sigma_i)
// and chi2 the data's part of its misfit alone; then
//   log Occam = 1/2 log det(2 pi H^-1) - sum_uniform log(upper_i - lower_i)
//               - sum_gaussian [log(sqrt(2 pi) sigma_i)
//                               + 1/2 ((x_i - mean_i) / sigma_i)^2],
// H's diagonal term being 1 / sigma_i^2 for a Gaussian parameter (the prior
// density at the mode times the posterior's volume; exact for a linear model
// with Gaussian priors only, the prior's misfit not divided by T).
// normal_mean and normal_sigma: one entry per parameter each, or both empty
// (every prior uniform: the function above). Throws InputError as above and
// for their sizes, a negative or non-finite sigma or a non-finite mean.
ModelEvidence LaplaceEvidence(double chi2, const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper, double temperature,
                              const Eigen::VectorXd& normal_mean,
                              const Eigen::VectorXd& normal_sigma);

// Log density of data left out of a fit, predicted from it (the Laplace
// posterior predictive, linearised): with the held-out whitened residuals r at
// the best fit, their Jacobian J and the fit's posterior covariance C,
//   r ~ N(0, S),  S = T I + J C J',
//   log p = -1/2 r' S^-1 r - 1/2 log det(S / T)
// (the constant -m/2 log(2 pi T) common to all classes is left out, as in
// LaplaceEvidence). A class whose parameters the fitted data leave loose
// predicts with a wide S and gains less from a lucky held-out match: the
// complexity penalty that a plug-in likelihood -1/2 r'r / T lacks.
// Throws InputError for size mismatches, non-finite input or T < 1.
double LogPredictiveDensity(const Eigen::VectorXd& residual,
                            const Eigen::MatrixXd& jacobian,
                            const Eigen::MatrixXd& covariance, double temperature = 1.0);

// A posterior with several separated modes (the basins of a multi-start fit:
// a location few data cannot pin down), each approximated by Laplace at its
// own optimum: the class's evidence is their sum, Z = sum_k Z_k, and held-out
// data are predicted by the mixture, p = sum_k Z_k p_k / Z. Takes log Z_k and
// log p_k (the same size, at least one; finite) and returns log Z and log p.
// Throws InputError otherwise.
struct BasinMixture {
  double log_evidence = 0;
  double log_predictive = 0;
};
BasinMixture CombineBasins(const std::vector<double>& log_evidence,
                           const std::vector<double>& log_predictive);

// Posterior probabilities from log evidences and prior probabilities (same
// size; priors > 0, not necessarily normalised): softmax of log Z + log prior.
Eigen::VectorXd PosteriorProbabilities(const Eigen::VectorXd& log_evidence,
                                       const Eigen::VectorXd& prior);

}  // namespace femup
