// The evidence of a diagnosis's classes (diagnose_study_steps.h): Laplace's at
// every separated basin, the noise temperature when even the best class fails,
// importance sampling when the study asks for it, and the posterior
// probabilities of the classes and of each kind.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "diagnose_study_steps.h"
#include "femup/problems/effect_priors.h"
#include "femup/solvers/sampled_evidence.h"

namespace femup::diagnose_steps {
namespace {

// Upper tail of chi2 with nu degrees of freedom (Wilson-Hilferty).
double Chi2UpperTail(double chi2, int nu) {
  if (nu <= 0) return chi2 > 0 ? 0.0 : 1.0;
  const double v = nu;
  const double z = (std::cbrt(chi2 / v) - (1 - 2 / (9 * v))) / std::sqrt(2 / (9 * v));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

}  // namespace

void ScoreClasses(const DiagnosisSpec& spec, const std::vector<std::string>& kinds,
                  std::size_t num_singles, std::size_t num_pairs,
                  const EffectFactory& make_effect, DiagnosisResult* result) {
  DiagnosisResult& r = *result;
  // Evidence, at the stated noise, then tempered if even the best class fails.
  auto prior_box = [&](const std::vector<const Effect*>& effects, Eigen::VectorXd* lo,
                       Eigen::VectorXd* hi) {
    const auto params = EffectSetParameters(r.fitted_data, effects);
    lo->resize(static_cast<Eigen::Index>(params.size()));
    hi->resize(lo->size());
    for (std::size_t i = 0; i < params.size(); ++i) {
      (*lo)[static_cast<Eigen::Index>(i)] = params[i].lower;
      (*hi)[static_cast<Eigen::Index>(i)] = params[i].upper;
    }
  };
  auto score_all = [&](double temperature) {
    for (DiagnosisCandidate& c : r.candidates) {
      std::vector<std::unique_ptr<Effect>> effects;
      for (const auto& k : c.kinds) effects.push_back(make_effect(k));
      Eigen::VectorXd lo, hi;
      prior_box(Pointers(effects), &lo, &hi);
      const std::vector<EffectParameter> params =
          EffectSetParameters(r.fitted_data, Pointers(effects));
      Eigen::VectorXd normal_mean, normal_sigma;
      LocalNormalPriors(params, c.theta, &normal_mean, &normal_sigma);
      c.evidence = LaplaceEvidence(c.chi2, c.jacobian, c.theta, lo, hi, temperature,
                                   normal_mean, normal_sigma);
      c.held_out_log_predictive = LogPredictiveDensity(
          c.held_out_residual, c.held_out_jacobian, c.evidence.covariance, temperature);
      // Laplace's approximation at every separated basin the multi-start fit
      // found, summed (a posterior with several modes: a location that few
      // modes cannot pin down), and the held-out modes' density as the mixture
      // of each basin's prediction, weighted by its evidence. One basin: the
      // best fit's Laplace evidence and prediction as they are.
      std::vector<double> log_z{c.evidence.log_evidence};
      std::vector<double> log_p{c.held_out_log_predictive};
      std::vector<const LocalOptimum*> order;
      for (const LocalOptimum& o : c.optima) order.push_back(&o);
      std::sort(
          order.begin(), order.end(),
          [](const LocalOptimum* a, const LocalOptimum* b) { return a->chi2 < b->chi2; });
      // The kept basins: where, their chi2, and their Laplace covariance.
      std::vector<Eigen::VectorXd> kept_theta{c.theta};
      std::vector<double> kept_chi2{c.chi2};
      std::vector<Eigen::LDLT<Eigen::MatrixXd>> kept_covariance;
      if (c.theta.size() > 0) kept_covariance.emplace_back(c.evidence.covariance);
      const std::vector<const Effect*> ptrs = Pointers(effects);
      for (const LocalOptimum* o : order) {
        // Optima whose likelihood is below e^-15 of the best's add nothing.
        if (!o->predicts || o->chi2 > c.chi2 + 30 * temperature || c.theta.size() == 0 ||
            !o->jacobian.allFinite())
          continue;
        LocalNormalPriors(params, o->theta, &normal_mean, &normal_sigma);
        const ModelEvidence e = LaplaceEvidence(o->chi2, o->jacobian, o->theta, lo, hi,
                                                temperature, normal_mean, normal_sigma);
        const Eigen::LDLT<Eigen::MatrixXd> covariance(e.covariance);
        // The same basin as a kept one: within 3 of its posterior standard
        // deviations, measured by either basin's covariance, or no barrier
        // between the two (chi2 halfway no more than 2 T above the higher of
        // the two).
        bool separate = true;
        for (std::size_t k = 0; k < kept_theta.size() && separate; ++k) {
          const Eigen::VectorXd d = o->theta - kept_theta[k];
          std::vector<PredictedState> halfway;
          std::string unused;
          separate =
              d.dot(kept_covariance[k].solve(d)) > 9 && d.dot(covariance.solve(d)) > 9 &&
              PredictEffectModes(r.fitted_data, ptrs, 0.5 * (o->theta + kept_theta[k]),
                                 &halfway, &unused) &&
              EffectResiduals(r.fitted_data, halfway).squaredNorm() >
                  std::max(o->chi2, kept_chi2[k]) + 2 * temperature;
        }
        if (!separate) continue;
        log_z.push_back(e.log_evidence);
        log_p.push_back(LogPredictiveDensity(o->held_out_residual, o->held_out_jacobian,
                                             e.covariance, temperature));
        kept_theta.push_back(o->theta);
        kept_chi2.push_back(o->chi2);
        kept_covariance.push_back(covariance);
      }
      c.basins = static_cast<int>(log_z.size());
      if (log_z.size() > 1) {
        const BasinMixture mix = CombineBasins(log_z, log_p);
        c.evidence.log_occam += mix.log_evidence - c.evidence.log_evidence;
        c.evidence.log_evidence = mix.log_evidence;
        c.held_out_log_predictive = mix.log_predictive;
      }
      c.score = c.evidence.log_evidence + c.held_out_log_predictive;
      c.laplace_score = c.score;
    }
  };
  // The same by importance sampling over each class's prior (sampled_evidence.h),
  // the proposal's components at the distinct optima of its multi-start fit: the
  // evidence of the fitted modes, and of fitted and held-out modes together, from
  // the same draws (their difference is the held-out modes' predictive density).
  // Classes whose Laplace score is more than kSampledBelow under the best keep
  // it: their probability is below e^-kSampledBelow either way.
  constexpr double kSampledBelow = 25;
  // The largest standard error of a sampled log evidence that replaces Laplace's.
  constexpr double kSampledStandardError = 0.2;
  auto sample_all = [&](double temperature) {
    double best_laplace = -std::numeric_limits<double>::infinity();
    for (const DiagnosisCandidate& c : r.candidates)
      best_laplace = std::max(best_laplace, c.laplace_score);
    for (std::size_t i = 0; i < r.candidates.size(); ++i) {
      DiagnosisCandidate& c = r.candidates[i];
      if (c.theta.size() == 0) continue;  // no parameters: Laplace is exact
      if (c.laplace_score < best_laplace - kSampledBelow) continue;
      std::vector<std::unique_ptr<Effect>> effects;
      for (const auto& k : c.kinds) effects.push_back(make_effect(k));
      const std::vector<const Effect*> ptrs = Pointers(effects);
      Eigen::VectorXd lo, hi;
      prior_box(ptrs, &lo, &hi);
      std::vector<EvidenceComponent> components;
      for (const LocalOptimum& o : c.optima) {
        // Optima whose likelihood is below e^-15 of the best's add nothing.
        if (o.chi2 > c.chi2 + 30 * temperature) continue;
        components.push_back(
            {o.theta, LaplaceEvidence(o.chi2, o.jacobian, o.theta, lo, hi, temperature)
                          .covariance});
      }
      const bool has_held_out = !r.held_out_data.states.empty();
      std::vector<PredictedState> predicted;
      std::string unused;
      const MisfitFunction misfit = [&](const Eigen::VectorXd& t, Eigen::VectorXd* chi2) {
        chi2->setZero(2);
        if (!PredictEffectModes(r.fitted_data, ptrs, t, &predicted, &unused))
          return false;
        (*chi2)[0] = EffectResiduals(r.fitted_data, predicted).squaredNorm();
        if (!has_held_out) return true;
        if (!PredictEffectModes(r.held_out_data, ptrs, t, &predicted, &unused))
          return false;
        (*chi2)[1] = EffectResiduals(r.held_out_data, predicted).squaredNorm();
        return true;
      };
      SampledEvidenceOptions sampling;
      sampling.samples = spec.evidence_samples;
      sampling.stream = i;  // classes in a fixed order: the same draws on every run
      sampling.temperature = temperature;
      const EvidenceSamples draws =
          SampleEvidence(misfit, 2, lo, hi, components, sampling);
      const SampledLogEvidence fitted =
          LogEvidenceFromSamples(draws, {true, false}, temperature);
      const SampledLogEvidence all =
          LogEvidenceFromSamples(draws, {true, true}, temperature);
      c.evidence_draws = static_cast<int>(draws.log_weight.size());
      c.evidence_effective_draws = all.effective_samples;
      c.evidence_standard_error = all.log_standard_error;
      // A poor proposal (a thin curved ridge in several dimensions) shows as few
      // effective draws and a large error, and its estimate is biased low: keep
      // Laplace's then.
      if (!std::isfinite(fitted.log_evidence) || !std::isfinite(all.log_evidence) ||
          std::max(fitted.log_standard_error, all.log_standard_error) >
              kSampledStandardError)
        continue;
      c.evidence_method = "sampled";
      c.evidence.log_evidence = fitted.log_evidence;
      c.evidence.log_occam = fitted.log_evidence + 0.5 * c.chi2 / temperature;
      c.held_out_log_predictive = all.log_evidence - fitted.log_evidence;
      c.score = all.log_evidence;
    }
  };
  score_all(1.0);
  const auto best =
      std::max_element(r.candidates.begin(), r.candidates.end(),
                       [](const DiagnosisCandidate& a, const DiagnosisCandidate& b) {
                         return a.score < b.score;
                       });
  const int nu = std::max(1, r.degrees_of_freedom - best->evidence.num_parameters);
  r.best_chi2_p_value = Chi2UpperTail(best->chi2, nu);
  if (r.best_chi2_p_value < 0.01) {
    r.temperature = std::max(1.0, best->chi2 / nu);
    score_all(r.temperature);
    std::ostringstream w;
    w << "even the best class (" << best->label
      << ") leaves chi2 = " << Fixed(best->chi2, 1) << " on " << nu
      << " degrees of freedom (p = " << r.best_chi2_p_value
      << "): the stated noise is too small or no candidate is the true form; the noise "
         "is "
         "scaled by sqrt("
      << Fixed(r.temperature, 2) << ") for the probabilities";
    r.warnings.push_back(w.str());
  }
  if (spec.evidence == "sampled") sample_all(r.temperature);
  Eigen::VectorXd scores(static_cast<Eigen::Index>(r.candidates.size()));
  Eigen::VectorXd prior(scores.size());
  const std::size_t pairs =
      spec.MaxEffectsFor(/*own_pipeline=*/true, /*measured_states=*/1) >= 2 ? num_pairs
                                                                            : 0;
  for (std::size_t i = 0; i < r.candidates.size(); ++i) {
    const auto& c = r.candidates[i];
    scores[static_cast<Eigen::Index>(i)] = c.score;
    prior[static_cast<Eigen::Index>(i)] =
        LevelPrior(spec.priors, c.kinds, num_singles, pairs);
  }
  const Eigen::VectorXd post = PosteriorProbabilities(scores, prior);
  for (std::size_t i = 0; i < r.candidates.size(); ++i)
    r.candidates[i].probability = post[static_cast<Eigen::Index>(i)];
  std::stable_sort(r.candidates.begin(), r.candidates.end(),
                   [](const DiagnosisCandidate& a, const DiagnosisCandidate& b) {
                     return a.probability > b.probability;
                   });
  std::vector<std::string> all_kinds{"none"};
  all_kinds.insert(all_kinds.end(), kinds.begin(), kinds.end());
  for (const auto& k : all_kinds) {
    double p = 0;
    for (const auto& c : r.candidates) {
      if ((k == "none" && c.kinds.empty()) ||
          std::find(c.kinds.begin(), c.kinds.end(), k) != c.kinds.end())
        p += c.probability;
    }
    r.kind_probabilities.emplace_back(k, p);
  }
}

}  // namespace femup::diagnose_steps
