#include "femup/solvers/sampled_evidence.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

#include "femup/core/counter_rng.h"
#include "femup/core/errors.h"

namespace femup {

Invalid SampledEvidenceOptions::Validate() const {
  if (samples < 10) return {"samples", "must be at least 10"};
  if (!(prior_share > 0 && prior_share <= 1)) return {"prior_share", "must be in (0, 1]"};
  if (!(spread > 0) || !std::isfinite(spread))
    return {"spread", "must be positive and finite"};
  if (tail_dof < 1) return {"tail_dof", "must be at least 1"};
  if (stages < 1 || stages > samples) return {"stages", "must be from 1 to samples"};
  if (!(temperature >= 1) || !std::isfinite(temperature))
    return {"temperature", "must be finite and >= 1"};
  return {};
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
  if (const Invalid bad = options.Validate())
    throw InputError("evidence_sampling", bad.ToString());
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
  // A t component with the scale matrix spread^2 * covariance; false when the
  // covariance is not positive definite.
  auto make = [&](const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance,
                  TComponent* t) {
    const Eigen::LLT<Eigen::MatrixXd> llt(covariance * (options.spread * options.spread));
    if (llt.info() != Eigen::Success) return false;
    t->mean = mean;
    t->l = llt.matrixL();
    t->log_norm = std::lgamma(0.5 * (nu + dd)) - std::lgamma(0.5 * nu) -
                  0.5 * dd * std::log(nu * pi) - t->l.diagonal().array().log().sum();
    return t->l.allFinite();
  };
  std::vector<TComponent> initial;
  for (std::size_t c = 0; c < components.size(); ++c) {
    const EvidenceComponent& e = components[c];
    const std::string where =
        "evidence_sampling.component[" + std::to_string(c + 1) + "]";
    if (e.mean.size() != d || e.covariance.rows() != d || e.covariance.cols() != d)
      throw InputError(where, "mean and covariance must match the range's size");
    if (!e.mean.allFinite() || !e.covariance.allFinite())
      throw InputError(where, "has non-finite entries");
    TComponent t;
    if (!make(e.mean, e.covariance, &t))
      throw InputError(where, "the covariance is not positive definite");
    initial.push_back(std::move(t));
  }

  // Each stage draws options.samples / stages points (the last the remainder): a
  // share from the prior, the rest spread evenly over that stage's components. The
  // weights use the mixture of all stages' proposals, each with its share of all draws
  // (the balance heuristic of multiple importance sampling: unbiased whatever the
  // adaptation did).
  struct Stage {
    int draws = 0, from_prior = 0;
    std::vector<TComponent> components;
  };
  std::vector<Stage> stages;
  const int num_stages = options.stages;
  const int total = options.samples;
  Eigen::MatrixXd theta(total, d);
  EvidenceSamples out;
  out.num_parts = num_parts;
  out.log_weight.setConstant(total, kMinusInf);
  out.chi2.setZero(total, num_parts);
  std::vector<char> evaluated(static_cast<std::size_t>(total), 0);
  const Eigen::ArrayXd range = (upper - lower).array();

  // log q(x) of the mixture of stages 0..last, each weighted by its draws / n.
  auto log_proposal = [&](const Eigen::VectorXd& x, std::size_t last, int n) {
    double log_q = kMinusInf;
    for (std::size_t s = 0; s <= last; ++s) {
      const Stage& st = stages[s];
      if (st.from_prior > 0)
        log_q = LogSumExp(log_q,
                          std::log(static_cast<double>(st.from_prior) / n) - log_volume);
      const int rest = st.draws - st.from_prior;
      if (rest == 0 || st.components.empty()) continue;
      const double share = std::log(static_cast<double>(rest) /
                                    (n * static_cast<double>(st.components.size())));
      for (const TComponent& t : st.components)
        log_q = LogSumExp(log_q, share + t.LogDensity(x, nu));
    }
    return log_q;
  };

  int next = 0;
  Eigen::VectorXd z(d), x(d), chi2(num_parts);
  std::vector<TComponent> current = initial;
  for (int s = 0; s < num_stages; ++s) {
    Stage st;
    st.draws = s + 1 == num_stages ? total - next : total / num_stages;
    st.components = current;
    st.from_prior =
        st.components.empty()
            ? st.draws
            : std::max(1, static_cast<int>(std::lround(options.prior_share * st.draws)));
    stages.push_back(st);
    const Stage& here = stages.back();
    const int rest = here.draws - here.from_prior;
    for (int k = 0; k < here.draws; ++k, ++next) {
      CounterRng rng(options.seed, options.stream, static_cast<std::uint64_t>(next));
      if (k < here.from_prior) {
        for (Eigen::Index i = 0; i < d; ++i)
          x[i] = lower[i] + 0.5 * (rng.Symmetric() + 1.0) * range[i];
      } else {
        const std::size_t c = static_cast<std::size_t>(k - here.from_prior) *
                              here.components.size() / static_cast<std::size_t>(rest);
        const TComponent& t = here.components[c];
        for (Eigen::Index i = 0; i < d; ++i) z[i] = rng.Gaussian();
        double g = 0;
        for (int j = 0; j < nu; ++j) {
          const double u = rng.Gaussian();
          g += u * u;
        }
        x = t.mean + t.l * z * std::sqrt(nu / std::max(g, 1e-300));
      }
      theta.row(next) = x.transpose();
      bool inside = true;
      for (Eigen::Index i = 0; i < d && inside; ++i)
        inside = x[i] >= lower[i] && x[i] <= upper[i];
      if (!inside) {
        ++out.outside;
        continue;
      }
      chi2.setZero(num_parts);
      if (!misfit(x, &chi2) || chi2.size() != num_parts || !chi2.allFinite()) {
        ++out.failed;
        continue;
      }
      evaluated[static_cast<std::size_t>(next)] = 1;
      out.chi2.row(next) = chi2.transpose();
    }
    if (s + 1 == num_stages) break;
    // Adapt: the initial components plus, for the first k parts (k = 1..parts),
    // a component at the posterior's weighted mean and covariance so far.
    current = initial;
    // log pi - log q of the draws so far (once; the parts only change the misfit).
    Eigen::VectorXd log_ratio = Eigen::VectorXd::Constant(next, kMinusInf);
    for (int i = 0; i < next; ++i) {
      if (!evaluated[static_cast<std::size_t>(i)]) continue;
      x = theta.row(i).transpose();
      log_ratio[i] = -log_volume - log_proposal(x, stages.size() - 1, next);
    }
    for (int parts = 1; parts <= num_parts; ++parts) {
      Eigen::VectorXd lw = Eigen::VectorXd::Constant(next, kMinusInf);
      double top = kMinusInf;
      for (int i = 0; i < next; ++i) {
        if (log_ratio[i] == kMinusInf) continue;
        lw[i] =
            log_ratio[i] - 0.5 * out.chi2.row(i).head(parts).sum() / options.temperature;
        top = std::max(top, lw[i]);
      }
      if (top == kMinusInf) continue;
      const Eigen::ArrayXd w = (lw.array() - top).exp();
      const double sum = w.sum();
      if (sum * sum / w.square().sum() < 2 * (dd + 1)) continue;  // too few to say
      const Eigen::VectorXd mean = theta.topRows(next).transpose() * w.matrix() / sum;
      const Eigen::MatrixXd centred = theta.topRows(next).rowwise() - mean.transpose();
      Eigen::MatrixXd cov = centred.transpose() * w.matrix().asDiagonal() * centred / sum;
      cov.diagonal().array() += 1e-8 * range.square();
      TComponent t;
      if (make(mean, cov, &t)) current.push_back(std::move(t));
    }
  }
  for (int i = 0; i < total; ++i) {
    if (!evaluated[static_cast<std::size_t>(i)]) continue;
    x = theta.row(i).transpose();
    out.log_weight[i] = -log_volume - log_proposal(x, stages.size() - 1, total);
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
