#include "femup/solvers/sampled_evidence.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "femup/counter_rng.h"
#include "femup/errors.h"

namespace femup {

std::string SampledEvidenceOptions::Validate() const {
  if (samples < 10) return "samples: must be at least 10";
  if (!(prior_share > 0 && prior_share <= 1)) return "prior_share: must be in (0, 1]";
  if (!(spread > 0) || !std::isfinite(spread))
    return "spread: must be positive and finite";
  if (tail_dof < 1) return "tail_dof: must be at least 1";
  return "";
}

namespace {

constexpr double kMinusInf = -std::numeric_limits<double>::infinity();

// Log density of a multivariate Student t (location mu, scale matrix with
// Cholesky factor l, nu degrees of freedom) at x.
struct TComponent {
  Eigen::VectorXd mean;
  Eigen::MatrixXd l;  // lower Cholesky factor of the scale matrix
  double log_norm = 0;
  double LogDensity(const Eigen::VectorXd& x, int nu) const {
    const Eigen::VectorXd y =
        l.triangularView<Eigen::Lower>().solve(x - mean);  // L^-1 (x - mu)
    const double d = static_cast<double>(mean.size());
    return log_norm - 0.5 * (nu + d) * std::log1p(y.squaredNorm() / nu);
  }
};

double LogSumExp(double a, double b) {
  if (a == kMinusInf) return b;
  if (b == kMinusInf) return a;
  const double m = std::max(a, b);
  return m + std::log(std::exp(a - m) + std::exp(b - m));
}

}  // namespace

EvidenceSamples SampleEvidence(const MisfitFunction& misfit, int num_parts,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                               const std::vector<EvidenceComponent>& components,
                               const SampledEvidenceOptions& options) {
  const std::string invalid = options.Validate();
  if (!invalid.empty()) throw InputError("evidence_sampling", invalid);
  const Eigen::Index d = lower.size();
  if (upper.size() != d || d == 0)
    throw InputError("evidence_sampling.range",
                     "lower and upper must have the same, non-zero size");
  if (num_parts < 1) throw InputError("evidence_sampling.parts", "must be at least 1");
  double log_volume = 0;
  for (Eigen::Index i = 0; i < d; ++i) {
    if (!(upper[i] > lower[i]) || !std::isfinite(upper[i] - lower[i]))
      throw InputError("evidence_sampling.range[" + std::to_string(i + 1) + "]",
                       "the prior range must be finite and not empty");
    log_volume += std::log(upper[i] - lower[i]);
  }
  const int nu = options.tail_dof;
  const double dd = static_cast<double>(d);
  const double pi = std::acos(-1.0);
  std::vector<TComponent> comps;
  for (std::size_t c = 0; c < components.size(); ++c) {
    const EvidenceComponent& e = components[c];
    const std::string where =
        "evidence_sampling.component[" + std::to_string(c + 1) + "]";
    if (e.mean.size() != d || e.covariance.rows() != d || e.covariance.cols() != d)
      throw InputError(where, "mean and covariance must match the range's size");
    if (!e.mean.allFinite() || !e.covariance.allFinite())
      throw InputError(where, "has non-finite entries");
    const Eigen::LLT<Eigen::MatrixXd> llt(e.covariance *
                                          (options.spread * options.spread));
    if (llt.info() != Eigen::Success)
      throw InputError(where, "the covariance is not positive definite");
    TComponent t;
    t.mean = e.mean;
    t.l = llt.matrixL();
    t.log_norm = std::lgamma(0.5 * (nu + dd)) - std::lgamma(0.5 * nu) -
                 0.5 * dd * std::log(nu * pi) - t.l.diagonal().array().log().sum();
    comps.push_back(std::move(t));
  }

  const int n = options.samples;
  const int num_prior =
      comps.empty() ? n
                    : std::max(1, static_cast<int>(std::lround(options.prior_share * n)));
  const int per_component =
      comps.empty() ? 0 : (n - num_prior) / static_cast<int>(comps.size());
  const int used = num_prior + per_component * static_cast<int>(comps.size());
  // Deterministic mixture: the shares are the numbers of draws of each kind.
  const double log_prior_share = std::log(static_cast<double>(num_prior) / used);
  const double log_component_share =
      per_component > 0 ? std::log(static_cast<double>(per_component) / used) : kMinusInf;

  EvidenceSamples out;
  out.num_parts = num_parts;
  out.log_weight.setConstant(used, kMinusInf);
  out.chi2.setZero(used, num_parts);
  Eigen::VectorXd theta(d), z(d), chi2(num_parts);
  for (int s = 0; s < used; ++s) {
    CounterRng rng(options.seed, options.stream, static_cast<std::uint64_t>(s));
    if (s < num_prior) {
      for (Eigen::Index i = 0; i < d; ++i)
        theta[i] = lower[i] + 0.5 * (rng.Symmetric() + 1.0) * (upper[i] - lower[i]);
    } else {
      const TComponent& t =
          comps[static_cast<std::size_t>((s - num_prior) / per_component)];
      for (Eigen::Index i = 0; i < d; ++i) z[i] = rng.Gaussian();
      double g = 0;
      for (int k = 0; k < nu; ++k) {
        const double u = rng.Gaussian();
        g += u * u;
      }
      theta = t.mean + t.l * z * std::sqrt(nu / std::max(g, 1e-300));
    }
    bool inside = true;
    for (Eigen::Index i = 0; i < d && inside; ++i)
      inside = theta[i] >= lower[i] && theta[i] <= upper[i];
    if (!inside) {
      ++out.outside;
      continue;
    }
    chi2.setZero(num_parts);
    if (!misfit(theta, &chi2) || chi2.size() != num_parts || !chi2.allFinite()) {
      ++out.failed;
      continue;
    }
    double log_q = log_prior_share - log_volume;
    for (const TComponent& t : comps)
      log_q = LogSumExp(log_q, log_component_share + t.LogDensity(theta, nu));
    out.log_weight[s] = -log_volume - log_q;
    out.chi2.row(s) = chi2.transpose();
  }
  return out;
}

SampledLogEvidence LogEvidenceFromSamples(const EvidenceSamples& samples,
                                          const std::vector<bool>& parts,
                                          double temperature) {
  if (static_cast<int>(parts.size()) != samples.num_parts)
    throw InputError(
        "evidence_sampling.parts",
        "the mask needs one entry per part (" + std::to_string(samples.num_parts) + ")");
  if (!(temperature >= 1) || !std::isfinite(temperature))
    throw InputError("evidence_sampling.temperature", "must be finite and >= 1");
  const Eigen::Index n = samples.log_weight.size();
  Eigen::VectorXd lw(n);
  double top = kMinusInf;
  for (Eigen::Index s = 0; s < n; ++s) {
    double misfit = 0;
    for (int p = 0; p < samples.num_parts; ++p)
      if (parts[static_cast<std::size_t>(p)]) misfit += samples.chi2(s, p);
    lw[s] = samples.log_weight[s] == kMinusInf
                ? kMinusInf
                : samples.log_weight[s] - 0.5 * misfit / temperature;
    top = std::max(top, lw[s]);
  }
  SampledLogEvidence r;
  if (n == 0 || top == kMinusInf) {
    r.log_evidence = kMinusInf;
    r.log_standard_error = std::numeric_limits<double>::infinity();
    return r;
  }
  double sum = 0, sum2 = 0;
  for (Eigen::Index s = 0; s < n; ++s) {
    const double w = lw[s] == kMinusInf ? 0.0 : std::exp(lw[s] - top);
    sum += w;
    sum2 += w * w;
  }
  const double count = static_cast<double>(n);
  r.log_evidence = top + std::log(sum / count);
  r.effective_samples = sum * sum / sum2;
  const double mean = sum / count;
  const double variance = std::max(0.0, sum2 / count - mean * mean);
  r.log_standard_error = std::sqrt(variance / count) / mean;
  return r;
}

}  // namespace femup
