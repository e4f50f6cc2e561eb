#include "femup/solvers/model_evidence.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>

#include "femup/core/errors.h"

namespace femup {

ModelEvidence LaplaceEvidence(double chi2, const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper, double temperature) {
  return LaplaceEvidence(chi2, jacobian, x, lower, upper, temperature, Eigen::VectorXd(),
                         Eigen::VectorXd());
}

ModelEvidence LaplaceEvidence(double chi2, const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& x, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper, double temperature,
                              const Eigen::VectorXd& normal_mean,
                              const Eigen::VectorXd& normal_sigma) {
  const Eigen::Index n = x.size();
  const bool any_normal = normal_mean.size() > 0 || normal_sigma.size() > 0;
  if (any_normal && (normal_mean.size() != n || normal_sigma.size() != n)) {
    throw InputError("evidence.normal",
                     "normal_mean and normal_sigma need one entry per parameter");
  }
  for (Eigen::Index i = 0; any_normal && i < n; ++i) {
    if (!(normal_sigma[i] >= 0) || !std::isfinite(normal_sigma[i]) ||
        !std::isfinite(normal_mean[i])) {
      throw InputError("evidence.normal[" + std::to_string(i + 1) + "]",
                       "the mean must be finite and sigma finite and >= 0");
    }
  }
  auto normal = [&](Eigen::Index i) { return any_normal && normal_sigma[i] > 0; };
  if (lower.size() != n || upper.size() != n || (n > 0 && jacobian.cols() != n)) {
    throw InputError("evidence",
                     "x, lower, upper and the Jacobian's columns differ in size");
  }
  if (!(chi2 >= 0) || !std::isfinite(chi2))
    throw InputError("evidence.chi2", "must be finite and >= 0");
  if (!(temperature >= 1) || !std::isfinite(temperature))
    throw InputError("evidence.temperature", "must be finite and >= 1");
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(upper[i] > lower[i]) || !std::isfinite(upper[i] - lower[i])) {
      throw InputError("evidence.range[" + std::to_string(i + 1) + "]",
                       "the prior range must be finite and not empty");
    }
  }
  if (n > 0 && !jacobian.allFinite())
    throw InputError("evidence.jacobian", "has non-finite entries");
  ModelEvidence e;
  e.chi2 = chi2;
  e.num_parameters = static_cast<int>(n);
  e.log_evidence = -0.5 * chi2 / temperature;
  if (n == 0) return e;
  const Eigen::ArrayXd range = (upper - lower).array();
  Eigen::MatrixXd h = jacobian.transpose() * jacobian / temperature;
  const double two_pi = 2 * std::acos(-1.0);
  // Per parameter: the prior's precision on H's diagonal and the log of its
  // density at x (uniform priors only: as vectors, the sums in the order they
  // always had).
  double log_prior_density = 0;
  if (!any_normal) {
    h.diagonal().array() += two_pi / range.square();
    log_prior_density = -range.log().sum();
  }
  for (Eigen::Index i = 0; any_normal && i < n; ++i) {
    if (normal(i)) {
      const double z = (x[i] - normal_mean[i]) / normal_sigma[i];
      h(i, i) += 1 / (normal_sigma[i] * normal_sigma[i]);
      log_prior_density -=
          0.5 * std::log(two_pi) + std::log(normal_sigma[i]) + 0.5 * z * z;
    } else {
      h(i, i) += two_pi / (range[i] * range[i]);
      log_prior_density -= std::log(range[i]);
    }
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(h);
  const Eigen::MatrixXd l = llt.matrixL();
  const double log_det_h = 2 * l.diagonal().array().log().sum();
  double log_occam = 0.5 * (n * std::log(two_pi) - log_det_h) + log_prior_density;
  const double edge = 1e-6;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (normal(i)) continue;
    if (x[i] <= lower[i] + edge * range[i] || x[i] >= upper[i] - edge * range[i])
      log_occam -= std::log(2.0);
  }
  e.log_occam = std::min(0.0, log_occam);
  e.log_evidence += e.log_occam;
  e.covariance = llt.solve(Eigen::MatrixXd::Identity(n, n));
  e.sigma = e.covariance.diagonal().cwiseSqrt();
  return e;
}

double LogPredictiveDensity(const Eigen::VectorXd& residual,
                            const Eigen::MatrixXd& jacobian,
                            const Eigen::MatrixXd& covariance, double temperature) {
  const Eigen::Index m = residual.size();
  const Eigen::Index n = covariance.rows();
  if (covariance.cols() != n || jacobian.rows() != m || (n > 0 && jacobian.cols() != n)) {
    throw InputError("predictive", "residuals, Jacobian and covariance differ in size");
  }
  if (!(temperature >= 1) || !std::isfinite(temperature))
    throw InputError("predictive.temperature", "must be finite and >= 1");
  if (!residual.allFinite() || !jacobian.allFinite() || !covariance.allFinite())
    throw InputError("predictive", "has non-finite entries");
  if (m == 0) return 0.0;
  Eigen::MatrixXd s = Eigen::MatrixXd::Identity(m, m);
  if (n > 0) s += jacobian * covariance * jacobian.transpose() / temperature;
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success)
    throw InputError("predictive.covariance", "is not positive semi-definite");
  const Eigen::MatrixXd l = llt.matrixL();
  const double log_det = 2 * l.diagonal().array().log().sum();
  return -0.5 * residual.dot(llt.solve(residual)) / temperature - 0.5 * log_det;
}

BasinMixture CombineBasins(const std::vector<double>& log_evidence,
                           const std::vector<double>& log_predictive) {
  if (log_evidence.empty() || log_evidence.size() != log_predictive.size())
    throw InputError("basins",
                     "needs one predictive density per basin and at least one basin");
  for (std::size_t k = 0; k < log_evidence.size(); ++k) {
    if (!std::isfinite(log_evidence[k]) || !std::isfinite(log_predictive[k]))
      throw InputError("basins",
                       "basin " + std::to_string(k + 1) +
                           ": log evidence and log predictive density must be finite");
  }
  // log-sum-exp, shifted by the largest term against overflow.
  auto log_sum = [](const std::vector<double>& v) {
    const double top = *std::max_element(v.begin(), v.end());
    double sum = 0;
    for (double x : v) sum += std::exp(x - top);
    return top + std::log(sum);
  };
  std::vector<double> joint(log_evidence.size());
  for (std::size_t k = 0; k < joint.size(); ++k)
    joint[k] = log_evidence[k] + log_predictive[k];
  BasinMixture m;
  m.log_evidence = log_sum(log_evidence);
  m.log_predictive = log_sum(joint) - m.log_evidence;
  return m;
}

Eigen::VectorXd PosteriorProbabilities(const Eigen::VectorXd& log_evidence,
                                       const Eigen::VectorXd& prior) {
  if (log_evidence.size() != prior.size() || log_evidence.size() == 0) {
    throw InputError("posterior", "needs one prior per class and at least one class");
  }
  if (!(prior.array() > 0).all() || !prior.allFinite())
    throw InputError("posterior.prior",
                     "prior probabilities must be positive and finite");
  if (!log_evidence.allFinite())
    throw InputError("posterior.log_evidence", "log evidences must be finite");
  Eigen::ArrayXd s = log_evidence.array() + prior.array().log();
  s -= s.maxCoeff();
  const Eigen::ArrayXd w = s.exp();
  return (w / w.sum()).matrix();
}

}  // namespace femup
