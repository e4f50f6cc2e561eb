#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "effect_ranking_steps.h"
#include "femup/solvers/bagged_posterior.h"

namespace femup::effect_ranking_steps {

constexpr double kMaxFrequencyTemperature = 1e4;  // 100 noise units a mode
constexpr int kTemperatureGrid = 41;

MarginalTemperature MarginalFrequencyTemperature(
    const Eigen::VectorXd& residual, const Eigen::MatrixXd& jacobian,
    const std::vector<char>& is_frequency, int num_frequencies, double shape_temperature,
    const Eigen::VectorXd& theta, const ClassPriors& priors) {
  const Eigen::Index n = residual.size();
  double chi2_f = 0, chi2_s = 0;  // at the stated noise
  for (Eigen::Index r = 0; r < n; ++r)
    (is_frequency[r] ? chi2_f : chi2_s) += residual[r] * residual[r];
  const double span = std::log(kMaxFrequencyTemperature);
  const double du = span / (kTemperatureGrid - 1);
  std::vector<double> log_term(kTemperatureGrid), precision(kTemperatureGrid);
  std::vector<ModelEvidence> evidences(kTemperatureGrid);
  Eigen::VectorXd scale(n);
  for (int g = 0; g < kTemperatureGrid; ++g) {
    const double t = std::exp(g * du);
    for (Eigen::Index r = 0; r < n; ++r)
      scale[r] = 1.0 / std::sqrt(is_frequency[r] ? t : shape_temperature);
    const double chi2 = chi2_f / t + chi2_s / shape_temperature;
    const Eigen::MatrixXd jac = scale.asDiagonal() * jacobian;
    evidences[g] = LaplaceEvidence(chi2, jac, theta, priors.lower, priors.upper, 1.0,
                                   priors.mean, priors.sigma);
    // Trapezoid weights of the uniform half, plus the point mass at T = 1.
    const double w =
        0.5 * du / span * ((g == 0 || g == kTemperatureGrid - 1) ? 0.5 : 1.0) +
        (g == 0 ? 0.5 : 0.0);
    log_term[g] =
        evidences[g].log_evidence - 0.5 * num_frequencies * std::log(t) + std::log(w);
    precision[g] = 1.0 / t;
  }
  const auto most = std::max_element(log_term.begin(), log_term.end());
  double sum = 0, mean_precision = 0;
  for (int g = 0; g < kTemperatureGrid; ++g) {
    const double e = std::exp(log_term[g] - *most);
    sum += e;
    mean_precision += e * precision[g];
  }
  MarginalTemperature m;
  m.evidence = evidences[most - log_term.begin()];
  m.log_evidence = *most + std::log(sum);
  m.evidence.log_evidence = m.log_evidence;
  m.temperature = sum / mean_precision;
  return m;
}

NoiseTemperatures NoiseTemperaturesOf(const Eigen::VectorXd& best_residual,
                                      int num_params,
                                      const std::vector<char>& is_frequency,
                                      int shape_modes) {
  const auto rows = static_cast<int>(best_residual.size());
  NoiseTemperatures t;
  double chi2_f = 0, chi2_s = 0;
  for (int r = 0; r < rows; ++r) {
    const double v = best_residual[r] * best_residual[r];
    if (is_frequency[static_cast<std::size_t>(r)]) {
      chi2_f += v;
      ++t.num_frequencies;
    } else {
      chi2_s += v;
    }
  }
  const int dof_f = std::max(1, t.num_frequencies - num_params);
  const int dof_s = std::max(1, rows - t.num_frequencies - shape_modes);
  const int dof = std::max(1, rows - shape_modes - num_params);
  t.best_chi2_p_value =
      boost::math::gamma_q(0.5 * dof, 0.5 * best_residual.squaredNorm());
  const double p_f = boost::math::gamma_q(0.5 * dof_f, 0.5 * chi2_f);
  const double p_s =
      rows > t.num_frequencies ? boost::math::gamma_q(0.5 * dof_s, 0.5 * chi2_s) : 1.0;
  t.frequency = p_f < 0.01 ? std::max(1.0, chi2_f / dof_f) : 1.0;
  t.shape = p_s < 0.01 ? std::max(1.0, chi2_s / dof_s) : 1.0;
  return t;
}

std::map<std::string, double> Probabilities(const std::vector<Eigen::VectorXd>& residuals,
                                            const std::vector<Eigen::MatrixXd>& jacobians,
                                            const std::vector<ClassPriors>& priors,
                                            const std::vector<char>& is_frequency,
                                            const NoiseTemperatures& noise,
                                            const Eigen::VectorXd& row_scale,
                                            bool marginal, int bagging_copies,
                                            std::vector<RankedClass>* classes) {
  std::vector<RankedClass>& c = *classes;
  Eigen::VectorXd log_evidence(c.size()), prior(c.size());
  // Each class's rows as its evidence weighs them (the bagged posterior
  // resamples them): row_scale, or with a marginal temperature the class's
  // own mean precision on the frequencies.
  std::vector<Eigen::VectorXd> class_scale(c.size(), row_scale);
  for (std::size_t i = 0; i < c.size(); ++i) {
    prior[i] = std::exp(c[i].log_prior);
    if (marginal) {
      const MarginalTemperature m = MarginalFrequencyTemperature(
          residuals[i], jacobians[i], is_frequency, noise.num_frequencies, noise.shape,
          c[i].theta, priors[i]);
      c[i].evidence = m.evidence;
      c[i].frequency_temperature = m.temperature;
      log_evidence[i] = m.log_evidence;
      for (Eigen::Index r = 0; r < residuals[i].size(); ++r)
        if (is_frequency[r]) class_scale[i][r] = 1.0 / std::sqrt(m.temperature);
      continue;
    }
    const double chi2 = residuals[i].cwiseProduct(row_scale).squaredNorm();
    const Eigen::MatrixXd jac = row_scale.asDiagonal() * jacobians[i];
    c[i].evidence =
        LaplaceEvidence(chi2, jac, c[i].theta, priors[i].lower, priors[i].upper, 1.0,
                        priors[i].mean, priors[i].sigma);
    c[i].frequency_temperature = noise.frequency;
    log_evidence[i] = c[i].evidence.log_evidence;
  }
  const Eigen::VectorXd laplace = PosteriorProbabilities(log_evidence, prior);
  Eigen::VectorXd p = laplace;
  if (bagging_copies > 0) {
    std::vector<ClassFit> fits_for_bagging(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      ClassFit& b = fits_for_bagging[i];
      b.residual = residuals[i].cwiseProduct(class_scale[i]);
      b.log_evidence = log_evidence[static_cast<Eigen::Index>(i)];
      b.prior = prior[static_cast<Eigen::Index>(i)];
    }
    BaggingOptions bagging;
    bagging.copies = bagging_copies;
    // Frequencies are drawn among the frequencies and shape entries among
    // the shape entries: a copy has the measured design.
    std::vector<int> strata(is_frequency.begin(), is_frequency.end());
    p = BaggedPosteriorProbabilities(fits_for_bagging, bagging, strata);
  }
  std::map<std::string, double> by_kind;
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i].probability = p[i];
    c[i].laplace_probability = laplace[i];
    by_kind[c[i].kind] += p[i];
  }
  return by_kind;
}

}  // namespace femup::effect_ranking_steps
