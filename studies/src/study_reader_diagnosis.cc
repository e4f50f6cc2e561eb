// The diagnosis section of a study file (femup diagnose): noise, candidate
// effects, held-out modes, the solver and evidence; and the stated priors and
// weights, checked against the families, quantities and regions of the study's
// model (docs/diagnosis.md).
#include <algorithm>
#include <memory>
#include <set>

#include "femup/core/errors.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/effects.h"
#include "femup/problems/model_effects.h"
#include "study_reader.h"

namespace femup::study_reader {
namespace {

std::string Listed(const std::vector<std::string>& items) {
  std::string list;
  for (const auto& x : items) list += (list.empty() ? "" : ", ") + x;
  return list;
}

// A family named under diagnosis.priors or diagnosis.weights (at `at`) must be
// one the diagnosis of this model tries.
void CheckStatedFamily(const Field& at, const std::string& kind, const Study& study,
                       const DiagnosisSpec& d) {
  const bool cantilever = study.cantilever.has_value();
  const std::vector<std::string> known =
      cantilever ? AvailableEffects() : ModelEffectKinds();
  if (std::find(known.begin(), known.end(), kind) == known.end()) {
    at.Fail("unknown family '" + kind + "' (the " + study.structure.type +
            " model's families: " + Listed(known) + ")");
  }
  if (!d.candidates.empty() &&
      std::find(d.candidates.begin(), d.candidates.end(), kind) == d.candidates.end()) {
    at.Fail(kind + " is not among diagnosis.candidates (" + Listed(d.candidates) +
            "): state priors for the families the diagnosis tries");
  }
  if (cantilever && d.candidates.empty()) {
    const std::vector<std::string> tried = DefaultEffects();
    if (std::find(tried.begin(), tried.end(), kind) == tried.end()) {
      at.Fail(kind + " is not among the default candidates (" + Listed(tried) +
              "); list it in diagnosis.candidates");
    }
  }
  if (!cantilever) {
    for (const FamilyApplicability& a : ApplicableModelEffects(study.structure)) {
      if (a.kind == kind && !a.why_not.empty()) {
        at.Fail(kind + " does not apply to this " + study.structure.type +
                " model: " + a.why_not);
      }
    }
  }
}

// diagnosis.priors and diagnosis.weights, checked against the study's model:
// the family's quantities on this model, their ranges, the regions it can act
// at (docs/diagnosis.md, "Stated priors").
void ReadStatedPriors(const Field& f, const Study& study, DiagnosisSpec* d) {
  const bool cantilever = study.cantilever.has_value();
  if (f.Has("priors")) {
    const Field pf = f["priors"];
    if (!pf.IsMap()) pf.Fail("expected a mapping of families to what is known of them");
    for (const auto& kv : pf.node()) {
      const std::string kind = pf.Key(kv.first);
      const Field ff = pf[kind];
      CheckStatedFamily(ff, kind, study, *d);
      if (!ff.IsMap() || ff.node().size() == 0) {
        ff.Fail(
            "expected a mapping of the family's quantities (and regions) to what is "
            "known of them");
      }
      // The family's parameters on this model, and (any structure but the
      // cantilever) its instances, for the regions.
      std::vector<EffectParameter> params;
      std::vector<std::unique_ptr<ModelEffect>> instances;
      try {
        if (cantilever) {
          params = CreateEffect(kind)->Parameters(*study.cantilever);
        } else {
          instances = CreateModelEffects(kind, study.structure);
          if (!instances.empty()) params = instances.front()->Parameters();
        }
      } catch (const InputError& e) {
        ff.Fail(e.what());
      }
      std::vector<std::string> keys;
      for (const EffectParameter& p : params)
        if (!p.quantity.empty()) keys.push_back(p.quantity);
      if (!cantilever) keys.push_back("regions");
      FamilyPrior prior;
      prior.kind = kind;
      for (const auto& q : ff.node()) {
        const std::string key = ff.Key(q.first);
        const Field v = ff[key];
        if (key == "regions" && cantilever) {
          v.Fail(
              "the cantilever's effects are placed by a fitted height, not by region: "
              "state x_m: [from, to] (m above the support) for attached_mass or "
              "stiffness_loss");
        }
        if (key == "regions") {
          for (const Field& item : v.Items()) prior.regions.push_back(item.Str());
          if (prior.regions.empty()) v.Fail("expected at least one element or node");
          try {
            KeepStatedRegions(CreateModelEffects(kind, study.structure), study.structure,
                              prior);
          } catch (const InputError& e) {
            const std::string what = std::string(e.what()).substr(e.where().size() + 2);
            const std::size_t open = e.where().find('[');
            if (open == std::string::npos) v.Fail(what);
            v.Items()[std::stoul(e.where().substr(open + 1)) - 1].Fail(what);
          }
          continue;
        }
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
          v.Fail("unknown key for " + kind + " on this " + study.structure.type +
                 " model (expected one of: " + Listed(keys) + ")");
        }
        QuantityPrior qp;
        qp.quantity = key;
        if (v.IsSequence()) {
          const std::vector<Field> ends = v.Items();
          if (ends.size() != 2)
            v.Fail("expected [lower, upper] or {normal: [mean, std]}");
          qp.lower = ends[0].Num();
          qp.upper = ends[1].Num();
          if (qp.lower > qp.upper)
            v.Fail("lower " + ends[0].Str() + " > upper " + ends[1].Str());
          if (qp.lower == qp.upper) {
            v.Fail("lower = upper = " + ends[0].Str() +
                   " leaves nothing to fit (state a range, or {normal: [mean, std]})");
          }
        } else if (v.IsMap()) {
          v.ExpectKeys({"normal"});
          const std::vector<Field> ms = v["normal"].Items();
          if (ms.size() != 2) v["normal"].Fail("expected [mean, std]");
          qp.normal = true;
          qp.mean = ms[0].Num();
          qp.sigma = ms[1].Num();
          if (!(qp.sigma > 0))
            ms[1].Fail("expected a positive standard deviation, found " + ms[1].Str());
          if (cantilever && d->evidence == "sampled") {
            v.Fail(
                "a normal prior needs diagnosis.evidence: laplace (the sampled evidence "
                "draws from uniform priors); state a range [lower, upper] instead");
          }
        } else {
          v.Fail("expected [lower, upper] or {normal: [mean, std]}");
        }
        FamilyPrior one;
        one.kind = kind;
        one.quantities = {qp};
        try {
          ApplyFamilyPrior(params, one);
        } catch (const InputError& e) {
          v.Fail(std::string(e.what()).substr(e.where().size() + 2));
        }
        prior.quantities.push_back(qp);
      }
      d->priors.families.push_back(std::move(prior));
    }
  }
  if (f.Has("weights")) {
    const Field wf = f["weights"];
    if (!wf.IsMap()) wf.Fail("expected a mapping of families (and none) to weights");
    for (const auto& kv : wf.node()) {
      const std::string kind = wf.Key(kv.first);
      const Field w = wf[kind];
      if (kind != "none") CheckStatedFamily(w, kind, study, *d);
      d->priors.weights[kind] = w.Positive();
    }
  }
  if (const Invalid bad = d->priors.Validate()) f.Fail(bad.ToString());
}

}  // namespace

DiagnosisSpec ReadDiagnosis(const Field& f, const Study& study) {
  f.ExpectKeys({"engine",
                "noise",
                "candidates",
                "max_effects",
                "held_out",
                "use_shapes",
                "mesh_error",
                "formulation_error",
                "form_error_on_shapes",
                "refine_mesh",
                "bagging_copies",
                "max_members",
                "members_fitted",
                "form_error",
                "localise",
                "solver",
                "confidence",
                "gap_confidence",
                "gap_explained",
                "evidence",
                "evidence_samples",
                "priors",
                "weights",
                "form_step",
                "form_fit",
                "rotary_inertia",
                "pair_places",
                "model_uncertainty",
                "frequency_temperature"});
  DiagnosisSpec d;
  if (f.Has("engine")) {
    d.engine = f["engine"].Str();
    if (d.engine != "model_effects" && d.engine != "cantilever") {
      f["engine"].Fail("expected model_effects or cantilever, found '" + d.engine + "'");
    }
    if (d.engine == "cantilever" && !study.cantilever) {
      f["engine"].Fail(
          "the cantilever's own pipeline needs a cantilever model (type: cantilever); "
          "every model type runs on model_effects");
    }
  }
  if (f.Has("noise")) {
    const Field n = f["noise"];
    n.ExpectKeys({"frequency", "shape"});
    if (n.Has("frequency")) {
      d.frequency_noise = n["frequency"].Positive();
      if (d.frequency_noise >= 0.5)
        n["frequency"].Fail("a relative standard deviation: expected 0 < value < 0.5");
    }
    if (n.Has("shape")) {
      d.shape_noise = n["shape"].Positive();
      if (d.shape_noise >= 1)
        n["shape"].Fail("relative to the largest entry: expected 0 < value < 1");
    }
  }
  if (f.Has("candidates")) {
    const std::vector<std::string> known = AvailableEffects();
    std::set<std::string> seen;
    for (const Field& item : f["candidates"].Items()) {
      const std::string k = item.Str();
      if (std::find(known.begin(), known.end(), k) == known.end()) {
        std::string list;
        for (const auto& x : known) list += (list.empty() ? "" : ", ") + x;
        item.Fail("unknown effect '" + k + "' (expected " + list + ")");
      }
      if (!seen.insert(k).second) item.Fail("effect '" + k + "' is listed twice");
      d.candidates.push_back(k);
    }
    if (d.candidates.empty()) f["candidates"].Fail("expected at least one effect");
  }
  if (f.Has("max_effects")) {
    d.max_effects = f["max_effects"].Int();
    if (d.max_effects < 1 || d.max_effects > 2)
      f["max_effects"].Fail("expected 1 (single effects) or 2 (also pairs)");
  }
  if (f.Has("pair_places")) {
    d.pair_places = f["pair_places"].Int();
    if (d.pair_places < 2 && d.pair_places != -1)
      f["pair_places"].Fail("expected at least 2, or -1 (every place)");
  }
  if (f.Has("model_uncertainty")) {
    const Field u = f["model_uncertainty"];
    if (d.Engine() == "cantilever") {
      u.Fail(
          "the cantilever's own pipeline does not allow for a stated model uncertainty; "
          "engine: model_effects does");
    }
    u.ExpectKeys({"stiffness", "mass"});
    const auto read = [&](const char* key, double* out) {
      if (!u.Has(key)) return;
      *out = u[key].Num();
      if (!(*out >= 0 && *out < 0.5)) {
        u[key].Fail("a relative standard deviation of the model's overall " +
                    std::string(key) + ": expected 0 <= value < 0.5, found " +
                    u[key].Str());
      }
    };
    read("stiffness", &d.stiffness_uncertainty);
    read("mass", &d.mass_uncertainty);
  }
  if (f.Has("held_out")) {
    const Field h = f["held_out"];
    if (h.IsScalar()) {
      d.held_out = h.Str();
      if (d.held_out != "auto" && d.held_out != "none")
        h.Fail("expected auto, none or a list of {state, mode}");
    } else {
      d.held_out = "list";
      for (const Field& item : h.Items()) {
        item.ExpectKeys({"state", "mode"});
        d.held_out_modes.emplace_back(item["state"].Str(), item["mode"].Int());
      }
    }
  }
  if (f.Has("use_shapes")) d.use_shapes = f["use_shapes"].Bool();
  if (f.Has("mesh_error")) d.mesh_error = f["mesh_error"].Bool();
  if (f.Has("formulation_error")) d.formulation_error = f["formulation_error"].Bool();
  if (f.Has("form_error_on_shapes"))
    d.form_error_on_shapes = f["form_error_on_shapes"].Bool();
  if (f.Has("form_step")) d.form_step = f["form_step"].Bool();
  if (f.Has("form_fit")) d.form_fit = f["form_fit"].Bool();
  if (f.Has("rotary_inertia")) d.rotary_inertia = f["rotary_inertia"].Bool();
  if (f.Has("refine_mesh")) d.refine_mesh = f["refine_mesh"].Bool();
  if (f.Has("bagging_copies")) {
    d.bagging_copies = f["bagging_copies"].Int();
    if (d.bagging_copies < 0 || d.bagging_copies > 100000)
      f["bagging_copies"].Fail(
          "bootstrap copies of the residuals: expected 0 (Laplace probabilities alone) "
          "to 100000");
  }
  if (f.Has("max_members")) {
    d.max_members = f["max_members"].Int();
    if (d.max_members < -1)
      f["max_members"].Fail(
          "members tried one by one for stiffness loss: expected >= 0, or -1 for every "
          "member");
  }
  if (f.Has("members_fitted")) {
    d.members_fitted = f["members_fitted"].Int();
    if (d.members_fitted < -1)
      f["members_fitted"].Fail(
          "members fitted after the screen: expected >= 0, or -1 to fit every member");
  }
  if (f.Has("form_error")) {
    d.form_error = f["form_error"].Num();
    if (!(d.form_error >= 0 && d.form_error < 1))
      f["form_error"].Fail(
          "a fraction of the nominal misfit: expected 0 <= value < 1, found " +
          f["form_error"].Str());
  }
  if (f.Has("localise")) d.localise = f["localise"].Bool();
  if (f.Has("solver")) {
    d.solver = f["solver"].Str();
    if (d.solver != "ceres" && d.solver != "ipopt")
      f["solver"].Fail("expected ceres or ipopt, found '" + d.solver + "'");
  }
  if (f.Has("confidence")) {
    d.confidence = f["confidence"].Num();
    if (!(d.confidence > 0.5 && d.confidence < 1))
      f["confidence"].Fail("expected a probability between 0.5 and 1");
  }
  if (f.Has("gap_confidence")) {
    d.gap_confidence = f["gap_confidence"].Num();
    if (!(d.gap_confidence >= 0 && d.gap_confidence < 1))
      f["gap_confidence"].Fail(
          "the probability a gap must reach to be named: expected 0 (the most probable "
          "family) up to, not including, 1");
  }
  if (f.Has("gap_explained")) {
    d.gap_explained = f["gap_explained"].Num();
    if (d.Engine() == "cantilever") {
      f["gap_explained"].Fail(
          "the cantilever's own pipeline does not read it; engine: model_effects does");
    }
    if (!(d.gap_explained >= 0 && d.gap_explained < 1))
      f["gap_explained"].Fail(
          "the share of the nominal misfit beyond the noise an effect must remove to be "
          "named: expected 0 (the most probable family) up to, not including, 1");
  }
  if (f.Has("frequency_temperature")) {
    const std::string t = f["frequency_temperature"].Str();
    if (d.Engine() == "cantilever") {
      f["frequency_temperature"].Fail(
          "the cantilever's own pipeline has its own noise temperature; engine: "
          "model_effects reads this key");
    }
    const auto named = FrequencyTemperatureNamed(t);
    if (!named)
      f["frequency_temperature"].Fail("expected auto, threshold or marginal, found '" +
                                      t + "'");
    d.frequency_temperature = *named;
  }
  if (f.Has("evidence")) {
    d.evidence = f["evidence"].Str();
    if (d.evidence != "sampled" && d.evidence != "laplace")
      f["evidence"].Fail("expected sampled or laplace, found '" + d.evidence + "'");
  }
  if (f.Has("evidence_samples")) {
    d.evidence_samples = f["evidence_samples"].Int();
    if (d.evidence_samples < 100 || d.evidence_samples > 1000000)
      f["evidence_samples"].Fail("expected a number of draws from 100 to 1000000");
  }
  ReadStatedPriors(f, study, &d);
  return d;
}

}  // namespace femup::study_reader
