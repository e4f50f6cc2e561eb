// femup diagnose (diagnose_study.h): RunDiagnosis checks the stated priors and
// runs the steps of diagnose_study_steps.h (data, fits, evidence, localisation)
// and states the verdict; the outputs and the report are in the reporting
// layer (reporting/src/diagnose_outputs.cc).
#include "femup/studies/diagnose_study.h"

#include <algorithm>
#include <iomanip>
#include <memory>
#include <sstream>

#include "diagnose_study_steps.h"
#include "femup/core/errors.h"
#include "femup/problems/effect_priors.h"
#include "femup/solvers/nonlinear_solver.h"

namespace femup {

std::string diagnose_steps::Fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

using diagnose_steps::Fixed;

DiagnosisResult RunDiagnosis(const Study& study) {
  if (!study.cantilever) {
    throw InputError(study.path,
                     "model: diagnose needs a cantilever model (type: cantilever)");
  }
  if (study.measurements.empty())
    throw InputError(study.path, "measurements: missing (nothing to diagnose)");
  const DiagnosisSpec spec = study.diagnosis.value_or(DiagnosisSpec());
  const CantileverSpec& nominal = *study.cantilever;
  DiagnosisResult r;
  r.study_name = study.name;
  r.description = study.description;
  r.length = BeamLength(nominal);
  r.frequency_noise = spec.frequency_noise;
  r.shape_noise = spec.shape_noise;
  r.form_error_fraction = spec.form_error;
  r.confidence = spec.confidence;
  r.priors = spec.priors;

  // The stated priors (effect_priors.h), checked before any work: families the
  // diagnosis tries, quantities of theirs, no regions (the cantilever's effects
  // are placed by a fitted height), no normal prior with sampled evidence.
  const std::vector<std::string> kinds =
      spec.candidates.empty() ? DefaultEffects() : spec.candidates;
  EffectOptions effect_options;
  effect_options.rotary_inertia = spec.rotary_inertia;
  {
    auto fail = [&](const std::string& field, const std::string& what) {
      throw InputError(study.path, "diagnosis." + field + ": " + what);
    };
    if (const Invalid bad = spec.priors.Validate())
      throw InputError(study.path, bad.Under("diagnosis").ToString());
    auto tried = [&](const std::string& kind) {
      return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
    };
    for (const auto& [kind, w] : spec.priors.weights)
      if (kind != "none" && !tried(kind))
        fail("weights." + kind, "is not among the families tried");
    for (const FamilyPrior& f : spec.priors.families) {
      const std::string field = "priors." + f.kind;
      if (!tried(f.kind)) fail(field, "is not among the families tried");
      if (!f.regions.empty())
        fail(field + ".regions",
             "the cantilever's effects are placed by a fitted height, not by region: "
             "state x_m: [from, to] instead");
      for (const QuantityPrior& q : f.quantities)
        if (q.normal && spec.evidence == "sampled")
          fail(field + "." + q.quantity,
               "a normal prior needs evidence: laplace (the sampled evidence draws from "
               "uniform priors)");
      try {
        WithFamilyPrior(CreateEffect(f.kind, effect_options), f, nominal);
      } catch (const InputError& e) {
        fail(field + "." + e.where(), std::string(e.what()).substr(e.where().size() + 2));
      }
    }
  }
  // A family's effect with its stated priors.
  auto make_effect = [&](const std::string& kind) {
    std::unique_ptr<Effect> e = CreateEffect(kind, effect_options);
    if (const FamilyPrior* f = spec.priors.Find(kind))
      e = WithFamilyPrior(std::move(e), *f, nominal);
    return e;
  };

  diagnose_steps::PrepareData(study, spec, nominal, &r);

  NonlinearSolverOptions options;
  // chi2 to 1e-6 relative is far finer than any evidence difference that matters.
  options.max_iterations = 60;
  options.function_tolerance = 1e-7;
  options.gradient_tolerance = 1e-8;
  options.parameter_tolerance = 1e-6;
  options.initial_trust_region = 1e4;
  options.kkt_tolerance = 1e-3;
  options.max_restarts = 0;
  const std::unique_ptr<NonlinearSolver> solver =
      CreateNonlinearSolver(spec.solver, options);

  // Candidate classes.
  std::vector<std::vector<std::string>> classes{{}};
  for (const auto& k : kinds) classes.push_back({k});
  const std::size_t num_singles = kinds.size();
  if (spec.MaxEffectsFor(/*own_pipeline=*/true, /*measured_states=*/1) >= 2) {
    for (std::size_t a = 0; a < kinds.size(); ++a)
      for (std::size_t b = a + 1; b < kinds.size(); ++b)
        classes.push_back({kinds[a], kinds[b]});
  }
  const std::size_t num_pairs = classes.size() - 1 - num_singles;

  diagnose_steps::FitClasses(classes, nominal, make_effect, *solver, &r);

  diagnose_steps::ScoreClasses(spec, kinds, num_singles, num_pairs, make_effect, &r);

  // Verdict.
  const DiagnosisCandidate& top = r.candidates.front();
  r.verdict_probability = top.probability;
  r.separated = top.probability >= spec.confidence;
  double cumulative = 0;
  for (const auto& c : r.candidates) {
    r.indistinguishable.push_back(c.label);
    cumulative += c.probability;
    if (cumulative >= spec.confidence) break;
  }
  if (r.separated) r.indistinguishable.clear();
  std::ostringstream v;
  if (top.kinds.empty()) {
    v << "no significant gap: the residual is within what the stated noise explains";
  } else {
    v << top.label;
  }
  v << " (P = " << Fixed(top.probability, 3) << ")";
  if (!r.separated) {
    v << "; the data cannot separate ";
    for (std::size_t i = 0; i < r.indistinguishable.size(); ++i) {
      const auto& c = *std::find_if(
          r.candidates.begin(), r.candidates.end(),
          [&](const DiagnosisCandidate& x) { return x.label == r.indistinguishable[i]; });
      v << (i == 0                                ? ""
            : i + 1 == r.indistinguishable.size() ? " and "
                                                  : ", ")
        << c.label << " (" << Fixed(c.probability, 2) << ")";
    }
  }
  r.verdict = v.str();

  // Where: one element at a time.
  diagnose_steps::LocaliseByElement(spec, nominal, *solver, &r);
  return r;
}

}  // namespace femup
