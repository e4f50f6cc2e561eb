#include "femup/studies/study.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include "femup/builders.h"
#include "femup/errors.h"
#include "femup/matrix_market.h"
#include "femup/plane_frame.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/effects.h"
#include "femup/problems/model_effects.h"
#include "femup/space_frame.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

// The largest built-in models a study may describe. A cantilever keeps each
// element's matrices at the size of the whole model, so its memory grows with
// the square of the element count (measured: 0.45 GB at 3000 elements, 1.5 GB at
// 5000). Builds for fuzzing (scripts/fuzz.sh defines the usual macro
// FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION) accept small models only, so that
// the study fuzzer spends its time in the reader rather than in building
// legitimate large models under the sanitizers (a 1000-element cantilever takes
// 7 s there).
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr int kMaxCantileverElements = 100;
constexpr long long kFuzzingMaxSpaceFrameDofs = 600;  // otherwise Validate's 5e7
#else
constexpr int kMaxCantileverElements = 5000;
#endif
// Space frames up to this size get a Structure of per-group matrices (about
// groups x 3 n x n sparse matrices) for femup diagnose; larger ones only
// what femup run needs.
constexpr int kMaxDiagnosedSpaceFrameDofs = 60000;

// A YAML node with its field path, for messages like
// "study.yaml:12:5: model.section.E: expected a number, found 'abc'".
class Field {
 public:
  Field(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }

  std::string Where() const {
    std::ostringstream w;
    w << file_;
    if (!node_.Mark().is_null())
      w << ":" << node_.Mark().line + 1 << ":" << node_.Mark().column + 1;
    return w.str();
  }
  [[noreturn]] void Fail(const std::string& what) const {
    throw InputError(Where(), (path_.empty() ? std::string("") : path_ + ": ") + what);
  }

  // Keys must be among `allowed`.
  void ExpectKeys(std::initializer_list<const char*> allowed) const {
    if (!node_.IsMap()) Fail("expected a mapping of keys to values");
    for (const auto& kv : node_) {
      const std::string key = Key(kv.first);
      bool ok = false;
      for (const char* a : allowed) ok = ok || key == a;
      if (!ok) {
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        Field(kv.first, file_, Join(key))
            .Fail("unknown key (expected one of: " + list + ")");
      }
    }
  }
  // The text of `key`, a key of this mapping. A key that is not a plain value
  // (YAML allows null, a list or a mapping as a key: "? [a, b]: 1", "[a]: 1")
  // fails with this field's path.
  std::string Key(const YAML::Node& key) const {
    if (key.IsScalar()) return key.Scalar();
    const char* found = key.IsNull()       ? "an empty (null) key"
                        : key.IsSequence() ? "a list"
                        : key.IsMap()      ? "a mapping"
                                           : "an undefined key";
    Field(key, file_, path_)
        .Fail(std::string("expected each key to be a name, found ") + found +
              (key.IsNull() ? " (quote it, \"null\", to mean the word)" : ""));
  }
  bool Has(const std::string& key) const { return node_.IsMap() && node_[key]; }
  Field operator[](const std::string& key) const {
    if (!Has(key)) Fail("missing required key '" + key + "'");
    return Field(node_[key], file_, Join(key));
  }
  std::vector<Field> Items() const {
    if (!node_.IsSequence()) Fail("expected a list");
    std::vector<Field> out;
    for (std::size_t i = 0; i < node_.size(); ++i) {
      out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i + 1) + "]");
    }
    return out;
  }

  std::string Str() const {
    if (!node_.IsScalar()) Fail("expected a text value");
    return node_.Scalar();
  }
  double Num() const {
    if (!node_.IsScalar()) Fail("expected a number");
    const std::string s = node_.Scalar();
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(s, &used);
    } catch (...) {
      used = 0;
    }
    if (used == 0 || used != s.size()) Fail("expected a number, found '" + s + "'");
    if (!std::isfinite(v)) Fail("expected a finite number, found '" + s + "'");
    return v;
  }
  double Positive() const {
    const double v = Num();
    if (!(v > 0)) Fail("expected a positive number, found " + node_.Scalar());
    return v;
  }
  double NonNegative() const {
    const double v = Num();
    if (!(v >= 0)) Fail("expected a number >= 0, found " + node_.Scalar());
    return v;
  }
  int Int() const {
    const double v = Num();
    if (v != std::floor(v) || std::abs(v) > 1e9) Fail("expected a whole number");
    return static_cast<int>(v);
  }
  // A random seed: a whole number from 0 to 2^53 (the integers a double holds
  // exactly), so that a seed is read as written and never converted out of
  // range (found by fuzzing: 2.2e29 overflowed unsigned long long).
  unsigned long long Seed() const {
    const double v = Num();
    if (!(v >= 0 && v <= 9007199254740992.0) || v != std::floor(v))
      Fail("expected a whole number from 0 to 2^53 = 9007199254740992, found " +
           node_.Scalar());
    return static_cast<unsigned long long>(v);
  }
  bool Bool() const {
    const std::string s = Str();
    if (s == "true" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "no" || s == "off") return false;
    Fail("expected true or false, found '" + s + "'");
  }
  std::vector<double> Numbers() const {
    std::vector<double> out;
    for (const Field& f : Items()) out.push_back(f.Num());
    return out;
  }
  const std::string& file() const { return file_; }

 private:
  std::string Join(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

std::vector<int> ElementIds(const Field& f) {
  std::vector<int> ids;
  for (const Field& item : f.Items()) {
    const int id = item.Int();
    if (id < 1) item.Fail("element ids start at 1");
    ids.push_back(id);
  }
  return ids;
}

Structure ReadChain(const Field& m) {
  m.ExpectKeys({"type", "masses", "springs", "wet"});
  ChainSpec spec;
  spec.masses = m["masses"].Numbers();
  spec.springs = m["springs"].Numbers();
  if (spec.springs.size() != spec.masses.size()) {
    m["springs"].Fail("has " + std::to_string(spec.springs.size()) +
                      " values; expected " + std::to_string(spec.masses.size()) +
                      " (one spring below each mass)");
  }
  for (std::size_t i = 0; i < spec.masses.size(); ++i) {
    if (!(spec.masses[i] > 0))
      m["masses"].Items()[i].Fail("expected a positive mass (kg)");
    if (!(spec.springs[i] > 0))
      m["springs"].Items()[i].Fail("expected a positive stiffness (N/m)");
  }
  spec.wet.assign(spec.masses.size(), false);
  if (m.Has("wet")) {
    for (const Field& item : m["wet"].Items()) {
      const int id = item.Int();
      if (id < 1 || id > static_cast<int>(spec.masses.size())) {
        item.Fail("mass " + std::to_string(id) + " does not exist (masses are 1.." +
                  std::to_string(spec.masses.size()) + ")");
      }
      spec.wet[id - 1] = true;
    }
  }
  return BuildSpringMassChain(spec);
}

Structure ReadCantilever(const Field& m, CantileverSpec* out) {
  m.ExpectKeys({"type", "length", "elements", "node_heights", "section", "water_depth",
                "added_mass_basis", "support", "lumped_masses", "distributed_masses",
                "stiffness_changes", "point_masses", "axial_force"});
  CantileverSpec spec;
  if (m.Has("node_heights")) {
    if (m.Has("length") || m.Has("elements")) {
      m.Fail("give either node_heights or length and elements, not both");
    }
    spec.node_heights = m["node_heights"].Numbers();
    if (spec.node_heights.size() > kMaxCantileverElements + 1u) {
      m["node_heights"].Fail("has " + std::to_string(spec.node_heights.size()) +
                             " nodes; expected at most " +
                             std::to_string(kMaxCantileverElements + 1) + " (" +
                             std::to_string(kMaxCantileverElements) + " elements)");
    }
  } else {
    const int elements = m["elements"].Int();
    if (elements < 1) m["elements"].Fail("expected at least one element");
    if (elements > kMaxCantileverElements) {
      m["elements"].Fail("expected at most " + std::to_string(kMaxCantileverElements) +
                         " elements, found " + std::to_string(elements) +
                         " (the memory of a cantilever grows with the square of its "
                         "element count)");
    }
    spec.node_heights = UniformHeights(m["length"].Positive(), elements);
  }
  const Field s = m["section"];
  s.ExpectKeys({"E", "A", "I", "rho"});
  spec.section = {s["E"].Positive(), s["A"].Positive(), s["I"].Positive(),
                  s["rho"].Positive()};
  if (m.Has("water_depth")) spec.water_depth = m["water_depth"].NonNegative();
  // N, tension positive (a riser's tension), compression negative (a pile's load).
  if (m.Has("axial_force")) spec.axial_force = m["axial_force"].Num();
  if (m.Has("added_mass_basis")) {
    const Field f = m["added_mass_basis"];
    if (!AddedMassBasisFromString(f.Str(), &spec.added_mass_basis)) {
      f.Fail("unknown basis '" + f.Str() + "' (expected element_mass or transverse)");
    }
  }
  if (m.Has("support")) {
    const Field f = m["support"];
    f.ExpectKeys({"transverse", "axial", "rotation"});
    if (f.Has("transverse")) spec.support_transverse = f["transverse"].NonNegative();
    if (f.Has("axial")) spec.support_axial = f["axial"].NonNegative();
    if (f.Has("rotation")) spec.support_rotation = f["rotation"].NonNegative();
  }
  if (m.Has("lumped_masses")) {
    for (const Field& f : m["lumped_masses"].Items()) {
      f.ExpectKeys({"node", "mass", "rotary_inertia"});
      LumpedMass lm;
      lm.node = f["node"].Int();
      if (lm.node < 0 || lm.node >= static_cast<int>(spec.node_heights.size())) {
        f["node"].Fail("node " + std::to_string(lm.node) + " is not in 0.." +
                       std::to_string(spec.node_heights.size() - 1) + " (0 is the base)");
      }
      lm.mass = f["mass"].NonNegative();
      if (f.Has("rotary_inertia")) lm.rotary_inertia = f["rotary_inertia"].NonNegative();
      spec.lumped_masses.push_back(lm);
    }
  }
  if (m.Has("distributed_masses")) {
    for (const Field& f : m["distributed_masses"].Items()) {
      f.ExpectKeys({"from", "to", "mass_per_length", "fade"});
      CantileverSpec::DistributedMass d;
      d.z0 = f["from"].NonNegative();
      d.z1 = f["to"].NonNegative();
      if (!(d.z1 > d.z0)) f["to"].Fail("expected a height above from (m)");
      d.mass_per_length = f["mass_per_length"].NonNegative();
      if (f.Has("fade")) d.fade = f["fade"].NonNegative();
      spec.distributed_masses.push_back(d);
    }
  }
  if (m.Has("stiffness_changes")) {
    for (const Field& f : m["stiffness_changes"].Items()) {
      f.ExpectKeys({"from", "to", "factor"});
      CantileverSpec::StiffnessChange c;
      c.z0 = f["from"].NonNegative();
      c.z1 = f["to"].NonNegative();
      if (!(c.z1 > c.z0)) f["to"].Fail("expected a height above from (m)");
      c.factor = f["factor"].Num();
      if (!(c.factor > -1)) {
        f["factor"].Fail("expected a number > -1 (E I becomes E I (1 + factor)), found " +
                         f["factor"].Str());
      }
      spec.stiffness_changes.push_back(c);
    }
  }
  if (m.Has("point_masses")) {
    for (const Field& f : m["point_masses"].Items()) {
      f.ExpectKeys({"height", "mass", "rotary_inertia"});
      CantileverSpec::PointMass p;
      p.height = f["height"].NonNegative();
      p.mass = f["mass"].NonNegative();
      if (f.Has("rotary_inertia")) p.rotary_inertia = f["rotary_inertia"].NonNegative();
      spec.point_masses.push_back(p);
    }
  }
  *out = spec;
  try {
    return BuildCantilever(spec);
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
}

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
  const std::string invalid = d->priors.Validate();
  if (!invalid.empty()) f.Fail(invalid);
}

DiagnosisSpec ReadDiagnosis(const Field& f, const Study& study) {
  f.ExpectKeys({"noise", "candidates", "max_effects", "held_out", "use_shapes",
                "mesh_error", "form_error", "localise", "solver", "confidence",
                "evidence", "evidence_samples", "priors", "weights"});
  DiagnosisSpec d;
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

Structure ReadMatrixMarketModel(const Field& m) {
  m.ExpectKeys({"type", "stiffness", "mass", "dof_labels", "elements"});
  MatrixMarketModelSpec spec;
  if (m.Has("stiffness")) spec.stiffness_file = m["stiffness"].Str();
  if (m.Has("mass")) spec.mass_file = m["mass"].Str();
  if (m.Has("dof_labels")) {
    for (const Field& f : m["dof_labels"].Items()) spec.dof_labels.push_back(f.Str());
  }
  for (const Field& f : m["elements"].Items()) {
    f.ExpectKeys({"id", "label", "stiffness", "mass", "added_mass", "dofs", "wet"});
    MatrixMarketElement e;
    e.id = f["id"].Int();
    if (f.Has("label")) e.label = f["label"].Str();
    if (f.Has("stiffness")) e.stiffness_file = f["stiffness"].Str();
    if (f.Has("mass")) e.mass_file = f["mass"].Str();
    if (f.Has("added_mass")) e.added_mass_file = f["added_mass"].Str();
    if (f.Has("dofs")) {
      for (const Field& d : f["dofs"].Items()) {
        const int dof = d.Int();
        if (dof < 1) d.Fail("DOF numbers start at 1");
        e.dofs.push_back(dof - 1);
      }
    }
    if (f.Has("wet")) e.wet = f["wet"].Bool();
    spec.elements.push_back(e);
  }
  const std::string base = fs::path(m.file()).parent_path().string();
  try {
    return ImportMatrixMarketStructure(spec, base.empty() ? "." : base);
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
}

FrameSection3d ReadTube(const Field& f, const FrameSection3d& defaults) {
  f.ExpectKeys({"diameter", "wall", "E", "nu", "rho"});
  const double diameter = f["diameter"].Positive();
  const double wall = f["wall"].Positive();
  if (wall > diameter / 2) f["wall"].Fail("must not exceed half the diameter");
  const double E = f.Has("E") ? f["E"].Positive() : defaults.E;
  const double nu = f.Has("nu")      ? f["nu"].NonNegative()
                    : defaults.G > 0 ? defaults.E / (2 * defaults.G) - 1
                                     : 0.3;
  const double rho = f.Has("rho") ? f["rho"].Positive() : defaults.rho;
  if (!(nu < 0.5)) f["nu"].Fail("Poisson's ratio must be below 0.5");
  return CircularTube(diameter, wall, E, nu, rho);
}

// A jacket-like space frame (space_frame.h): the model and its factors come
// from the generator; `structure` gets the description, labels and, for
// plots, each DOF's height.
// A 2D plane frame (portal, multi-bay, multi-storey) as a Structure of members.
Structure ReadPlaneFrame(const Field& m) {
  m.ExpectKeys({"type", "storeys", "bays", "storey_height", "bay_width",
                "elements_per_member", "wet_storeys", "column", "beam", "base"});
  PlaneFrameSpec spec;
  spec.storeys = m["storeys"].Int();
  spec.bays = m["bays"].Int();
  spec.storey_height = m["storey_height"].Positive();
  spec.bay_width = m["bay_width"].Positive();
  if (m.Has("elements_per_member"))
    spec.elements_per_member = m["elements_per_member"].Int();
  if (m.Has("wet_storeys")) spec.wet_storeys = m["wet_storeys"].Int();
  for (const char* which : {"column", "beam"}) {
    const Field s = m[which];
    s.ExpectKeys({"E", "A", "I", "rho"});
    const BeamSection section{s["E"].Positive(), s["A"].Positive(), s["I"].Positive(),
                              s["rho"].Positive()};
    (std::string(which) == "column" ? spec.column : spec.beam) = section;
  }
  if (m.Has("base")) {
    // Springs at every column base; a direction not given stays rigid.
    const Field b = m["base"];
    b.ExpectKeys({"horizontal", "vertical", "rotation"});
    if (b.Has("horizontal")) spec.base.horizontal = b["horizontal"].Positive();
    if (b.Has("vertical")) spec.base.vertical = b["vertical"].Positive();
    if (b.Has("rotation")) spec.base.rotation = b["rotation"].Positive();
    if (spec.base.rigid()) b.Fail("give at least one of horizontal, vertical, rotation");
  }
  spec.blocks_per_storey = 1;
  const std::string invalid = spec.Validate();
  if (!invalid.empty()) {
    const auto colon = invalid.find(':');
    m[invalid.substr(0, colon)].Fail(invalid.substr(colon + 2));
  }
  return BuildPlaneFrameStructure(spec);
}

ParametrisedModel ReadSpaceFrame(const Field& m, Structure* structure) {
  m.ExpectKeys({"type", "levels", "bays_x", "bays_y", "level_height", "bay_width_x",
                "bay_width_y", "elements_per_member", "blocks_per_level", "bracing",
                "water_depth", "theory", "legs", "braces", "horizontals"});
  SpaceFrameSpec spec;
  if (m.Has("levels")) spec.levels = m["levels"].Int();
  if (m.Has("bays_x")) spec.bays_x = m["bays_x"].Int();
  if (m.Has("bays_y")) spec.bays_y = m["bays_y"].Int();
  if (m.Has("level_height")) spec.level_height = m["level_height"].Positive();
  if (m.Has("bay_width_x")) spec.bay_width_x = m["bay_width_x"].Positive();
  if (m.Has("bay_width_y")) spec.bay_width_y = m["bay_width_y"].Positive();
  if (m.Has("elements_per_member"))
    spec.elements_per_member = m["elements_per_member"].Int();
  if (m.Has("blocks_per_level")) spec.blocks_per_level = m["blocks_per_level"].Int();
  if (m.Has("bracing") && !FaceBracingFromString(m["bracing"].Str(), &spec.bracing))
    m["bracing"].Fail("expected none, diagonal or x");
  if (m.Has("water_depth")) spec.water_depth = m["water_depth"].NonNegative();
  if (m.Has("theory") && !BeamTheoryFromString(m["theory"].Str(), &spec.theory))
    m["theory"].Fail("expected euler_bernoulli or timoshenko");
  if (m.Has("legs")) spec.legs = ReadTube(m["legs"], spec.legs);
  if (m.Has("braces")) spec.braces = ReadTube(m["braces"], spec.braces);
  if (m.Has("horizontals"))
    spec.horizontals = ReadTube(m["horizontals"], spec.horizontals);
  const std::string invalid = spec.Validate();
  if (!invalid.empty()) {
    // "bays_x: must be >= 1" -> model.bays_x: must be >= 1;
    // "legs.Iy: ..." -> model.legs: Iy: ...
    const std::string field = invalid.substr(0, invalid.find(':'));
    const std::string key = field.substr(0, field.find('.'));
    if (!m.Has(key)) m.Fail(invalid);
    std::string rest = invalid.substr(key.size());
    while (!rest.empty() && (rest[0] == ':' || rest[0] == '.' || rest[0] == ' '))
      rest.erase(0, 1);
    m[key].Fail(rest);
  }
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  {
    // SpaceFrameSpec::Validate's estimate of the DOFs, at once (the exact count,
    // SpaceFrameModelSize, takes seconds for a large frame under the sanitizers).
    const double nx = spec.bays_x + 1.0, ny = spec.bays_y + 1.0;
    const double faces = 2.0 * (spec.bays_x + spec.bays_y);
    const double members = nx * ny + (nx - 1) * ny + nx * (ny - 1) + 4 * faces;
    const double dofs =
        6.0 * spec.levels * (nx * ny + faces + (spec.elements_per_member - 1) * members);
    if (dofs > kFuzzingMaxSpaceFrameDofs) {
      m.Fail("has about " + std::to_string(static_cast<long long>(dofs)) +
             " DOFs; a build for fuzzing takes at most " +
             std::to_string(kFuzzingMaxSpaceFrameDofs));
    }
  }
#endif
  ParametrisedModel model;
  try {
    model = BuildSpaceFrame(spec);
    if (model.num_dofs() <= kMaxDiagnosedSpaceFrameDofs) {
      // Every group's matrices, the nodes and heights: femup diagnose acts on them.
      *structure = BuildSpaceFrameStructure(spec);
      return model;
    }
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
  // Too large to hold each group's matrices (femup diagnose refuses it):
  // description, labels and heights for femup run.
  std::ostringstream d;
  d << "space frame, " << spec.bays_x << " x " << spec.bays_y << " bays, " << spec.levels
    << " levels of " << spec.level_height << " m, " << ToString(spec.bracing)
    << " bracing, water " << spec.water_depth << " m";
  structure->type = "space_frame";
  structure->description = d.str();
  structure->dof_labels = model.dof_labels();
  const SpaceFrameGeometryData geometry = SpaceFrameGeometry(spec);
  structure->dof_positions.reserve(model.num_dofs());
  for (const Eigen::Vector3d& node : geometry.nodes) {
    for (int k = 0; k < 6; ++k) structure->dof_positions.push_back(node.z());
  }
  for (std::size_t k = 0; k < geometry.nodes.size(); ++k)
    structure->nodes.push_back({"n" + std::to_string(k + 1), geometry.nodes[k]});
  structure->length = spec.levels * spec.level_height;
  // Shape plots: the sway (ux) of the corner leg at X = Y = 0, bottom to top.
  std::vector<std::pair<double, int>> leg;
  for (std::size_t k = 0; k < geometry.nodes.size(); ++k) {
    const Eigen::Vector3d& node = geometry.nodes[k];
    if (std::abs(node.x()) < 1e-9 && std::abs(node.y()) < 1e-9)
      leg.emplace_back(node.z(), static_cast<int>(6 * k));
  }
  std::sort(leg.begin(), leg.end());
  for (const auto& [z, dof] : leg) structure->plot_dofs.push_back(dof);
  return model;
}

ParameterFamily ReadFamily(const Field& f) {
  ParameterFamily family;
  using Scope = ParameterFamily::Scope;
  using Selection = ParameterFamily::Selection;
  auto scope_of = [&](const Field& s) {
    const std::string v = s.Str();
    if (v == "none") return Scope::kNone;
    if (v == "per_element") return Scope::kPerElement;
    if (v == "single") return Scope::kSingle;
    if (v == "groups") return Scope::kGroups;
    s.Fail("unknown layout '" + v + "' (expected none, per_element, single or groups)");
  };
  if (f.IsScalar()) {
    family.scope = scope_of(f);
    if (family.scope == Scope::kGroups)
      f.Fail("groups need a list: {groups: [[1, 2], [3]]}");
    return family;
  }
  f.ExpectKeys({"layout", "select", "groups"});
  family.scope = f.Has("layout")
                     ? scope_of(f["layout"])
                     : (f.Has("groups") ? Scope::kGroups : Scope::kPerElement);
  if (f.Has("select")) {
    const std::string v = f["select"].Str();
    if (v == "all") {
      family.selection = Selection::kAll;
    } else if (v == "wet") {
      family.selection = Selection::kWet;
    } else if (v == "dry") {
      family.selection = Selection::kDry;
    } else {
      f["select"].Fail("unknown selection '" + v + "' (expected all, wet or dry)");
    }
  }
  if (family.scope == Scope::kGroups) {
    for (const Field& g : f["groups"].Items()) family.groups.push_back(ElementIds(g));
  } else if (f.Has("groups")) {
    f["groups"].Fail("groups are only used with layout: groups");
  }
  return family;
}

std::vector<int> ReadSensors(const Field& f, const ParametrisedModel& model) {
  std::vector<int> dofs;
  for (const Field& item : f.Items()) {
    const std::string label = item.Str();
    const int dof = model.FindDof(label);
    if (dof < 0) {
      std::string some;
      for (int i = 0; i < std::min(model.num_dofs(), 6); ++i) {
        some += (i ? ", " : "") + model.dof_labels()[i];
      }
      item.Fail("no model DOF is labelled '" + label + "' (labels look like: " + some +
                (model.num_dofs() > 6 ? ", ..." : "") + ")");
    }
    dofs.push_back(dof);
  }
  return dofs;
}

// A path in the study file, taken relative to the study file's folder.
std::string RelativeToStudy(const Field& f) {
  const fs::path p(f.Str());
  if (p.is_absolute()) return p.string();
  const fs::path base = fs::path(f.file()).parent_path();
  return (base / p).lexically_normal().string();
}

ExpansionOptions ReadExpansion(const Field& f) {
  ExpansionOptions o;
  if (f.IsScalar()) {
    o.method = f.Str();
  } else {
    f.ExpectKeys({"method", "modes"});
    if (f.Has("method")) o.method = f["method"].Str();
    if (f.Has("modes")) o.num_modes = f["modes"].Int();
  }
  const std::string invalid = o.Validate();
  if (!invalid.empty()) {
    const auto colon = invalid.find(':');
    const std::string key = invalid.substr(0, colon) == "num_modes" ? "modes" : "method";
    (f.IsMap() && f.Has(key) ? f[key] : f).Fail(invalid.substr(colon + 2));
  }
  return o;
}

IdentifyOptions ReadIdentify(const Field& f) {
  f.ExpectKeys({"file", "format", "max_frequency_hz", "stable_orders", "orders",
                "first_sample", "min_emac", "max_damping_ratio", "tolerances"});
  IdentifyOptions o;
  o.file = RelativeToStudy(f["file"]);
  if (f.Has("format")) o.format = f["format"].Str();
  if (f.Has("max_frequency_hz")) o.max_frequency_hz = f["max_frequency_hz"].NonNegative();
  if (f.Has("stable_orders")) o.min_consecutive = f["stable_orders"].Int();
  if (f.Has("orders")) {
    const Field of = f["orders"];
    of.ExpectKeys({"min", "max", "step"});
    if (of.Has("min")) o.stabilisation.min_order = of["min"].Int();
    if (of.Has("max")) o.stabilisation.max_order = of["max"].Int();
    if (of.Has("step")) o.stabilisation.order_step = of["step"].Int();
  }
  if (f.Has("first_sample")) o.stabilisation.era.first_sample = f["first_sample"].Int();
  if (f.Has("tolerances")) {
    const Field tf = f["tolerances"];
    tf.ExpectKeys({"frequency", "damping", "mac"});
    if (tf.Has("frequency"))
      o.stabilisation.frequency_tolerance = tf["frequency"].Positive();
    if (tf.Has("damping")) o.stabilisation.damping_tolerance = tf["damping"].Positive();
    if (tf.Has("mac")) o.stabilisation.mac_tolerance = tf["mac"].Positive();
  }
  if (f.Has("min_emac")) o.stabilisation.era.min_emac = f["min_emac"].NonNegative();
  if (f.Has("max_damping_ratio"))
    o.stabilisation.era.max_damping_ratio = f["max_damping_ratio"].Positive();
  const std::string invalid = o.Validate();
  if (!invalid.empty()) f.Fail(invalid);
  return o;
}

// Sensors of record channels: a DOF label per channel, "-label" for a sensor
// pointing against the DOF, "skip" for a channel not used.
void ReadChannelSensors(const Field& f, const ParametrisedModel& model,
                        MeasurementSpec* m) {
  std::set<int> seen;
  for (const Field& item : f.Items()) {
    std::string label = item.Str();
    if (label == "skip") {
      m->channel_dofs.push_back(-1);
      m->channel_signs.push_back(0.0);
      continue;
    }
    double sign = 1.0;
    if (!label.empty() && (label[0] == '-' || label[0] == '+')) {
      sign = label[0] == '-' ? -1.0 : 1.0;
      label = label.substr(1);
    }
    const int dof = model.FindDof(label);
    if (dof < 0) {
      item.Fail("no model DOF is labelled '" + label +
                "' (give a DOF label per channel, '-label' for a reversed sensor, "
                "or skip)");
    }
    if (!seen.insert(dof).second) item.Fail("DOF '" + label + "' is listed twice");
    m->channel_dofs.push_back(dof);
    m->channel_signs.push_back(sign);
  }
  if (seen.empty()) f.Fail("no channel is mapped to a model DOF");
}

RecordsSpec ReadRecords(const Field& f, const ParametrisedModel& model) {
  f.ExpectKeys({"sample_rate_hz", "duration_s", "sensors", "impulse", "noise", "seed",
                "states", "cutoff_hz"});
  RecordsSpec r;
  r.sample_rate_hz = f["sample_rate_hz"].Positive();
  r.duration_s = f["duration_s"].Positive();
  if (r.sample_rate_hz * r.duration_s < 16)
    f["duration_s"].Fail("gives fewer than 16 samples at this sample rate");
  if (r.sample_rate_hz * r.duration_s > 1e7)
    f["duration_s"].Fail("gives more than 10^7 samples per channel");
  r.sensor_dofs = ReadSensors(f["sensors"], model);
  {
    const Field i = f["impulse"];
    i.ExpectKeys({"dof", "amplitude"});
    const int dof = model.FindDof(i["dof"].Str());
    if (dof < 0) i["dof"].Fail("no model DOF is labelled '" + i["dof"].Str() + "'");
    r.impulse_dof = dof;
    if (i.Has("amplitude")) {
      r.impulse = i["amplitude"].Num();
      if (r.impulse == 0) i["amplitude"].Fail("expected a non-zero impulse (N s)");
    }
  }
  if (f.Has("noise")) r.noise = f["noise"].NonNegative();
  if (f.Has("cutoff_hz")) {
    r.cutoff_hz = f["cutoff_hz"].Positive();
    if (r.cutoff_hz > r.sample_rate_hz / 2)
      f["cutoff_hz"].Fail("is above the Nyquist frequency (half the sample rate)");
  }
  if (f.Has("seed")) r.seed = f["seed"].Seed();
  std::set<std::string> names, files;
  for (const Field& sf : f["states"].Items()) {
    sf.ExpectKeys({"state", "immersion", "damping", "water", "file"});
    RecordStateSpec st;
    st.state = sf["state"].Str();
    if (!names.insert(st.state).second)
      sf["state"].Fail("state '" + st.state + "' is listed twice");
    st.immersion = st.state == "water" ? Immersion::kWet : Immersion::kDry;
    if (sf.Has("immersion")) {
      const std::string v = sf["immersion"].Str();
      if (v != "wet" && v != "dry")
        sf["immersion"].Fail("expected wet or dry, found '" + v + "'");
      st.immersion = v == "wet" ? Immersion::kWet : Immersion::kDry;
    }
    if (sf.Has("damping")) {
      const Field d = sf["damping"];
      st.damping_ratios = d.IsScalar() ? std::vector<double>{d.Num()} : d.Numbers();
      if (st.damping_ratios.empty()) d.Fail("expected at least one damping ratio");
      for (double z : st.damping_ratios) {
        if (!(z >= 0 && z < 1)) d.Fail("damping ratios must be in [0, 1)");
      }
    }
    if (sf.Has("water")) {
      const Field w = sf["water"];
      w.ExpectKeys(
          {"depth", "fluid_density", "width", "thickness", "coefficient", "fade"});
      StripTheoryWater water;
      water.depth = w["depth"].Positive();
      if (w.Has("fluid_density")) water.fluid_density = w["fluid_density"].Positive();
      water.width = w["width"].Positive();
      if (w.Has("thickness")) water.thickness = w["thickness"].Positive();
      if (w.Has("coefficient")) water.coefficient = w["coefficient"].Positive();
      if (water.coefficient == 0 && water.thickness == 0)
        w.Fail("give the section's thickness (along the motion) or the coefficient C_A");
      if (w.Has("fade")) water.fade = w["fade"].NonNegative();
      if (st.immersion != Immersion::kWet) w.Fail("water needs immersion: wet");
      st.water = water;
    }
    st.file = sf["file"].Str();
    const std::string ext = fs::path(st.file).extension().string();
    if (ext != ".uff" && ext != ".unv" && ext != ".csv")
      sf["file"].Fail("expected a .uff, .unv or .csv file name, got '" + st.file + "'");
    if (fs::path(st.file).has_parent_path() || st.file.empty())
      sf["file"].Fail("expected a plain file name (it is written in the output folder)");
    if (!files.insert(st.file).second)
      sf["file"].Fail("file '" + st.file + "' is listed twice");
    r.states.push_back(st);
  }
  if (r.states.empty()) f["states"].Fail("expected at least one state");
  return r;
}

// A UFF modes_file (.uff, .unv): which model DOF each node component is.
//   uff_dofs: {"101:+Y": n3:ux, "102:-Y": n5:ux, "7": skip, "*": skip}
//     "<node>:<direction>" (X, Y, Z, RX, RY, RZ with an optional sign, or the
//     UFF codes 1..6) to a DOF label ("-label": the DOF points against the
//     direction), "<node>": skip for a node not used, "*": skip to leave out
//     every node nothing else maps (otherwise such a node is an error);
//   geometry_file: the nodes named by neither are matched to model nodes by
//     their coordinates (datasets 15 / 2411 of this file), within
//     geometry_tolerance (m; default 1 % of the model's largest extent), along
//     uff_directions (default: every direction of the data the model node has).
bool IsUffFile(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".uff" || ext == ".unv";
}

const char* const kUffKeys[] = {"uff_dofs", "geometry_file", "geometry_tolerance",
                                "uff_directions"};

UffDofMap ReadUffMap(const Field& f, const ParametrisedModel& model,
                     const std::vector<ModelNode>& nodes) {
  if (f.Has("sensors")) {
    f["sensors"].Fail(
        "a UFF modes_file names its nodes: map them with uff_dofs ({\"101:+Y\": "
        "n3:ux}) or place them by their coordinates with geometry_file, not with "
        "sensors");
  }
  if (!f.Has("uff_dofs") && !f.Has("geometry_file")) {
    f["modes_file"].Fail(
        "a UFF modes_file needs uff_dofs ({\"101:+Y\": n3:ux, \"7\": skip}) or "
        "geometry_file (nodes matched to the model's by coordinates) to say which "
        "model DOF each node component is");
  }
  UffDofMap map;
  if (f.Has("uff_dofs")) {
    const Field uf = f["uff_dofs"];
    if (!uf.IsMap() || uf.node().size() == 0) {
      uf.Fail(
          "expected a mapping of \"node:direction\" to model DOF labels, e.g. "
          "{\"101:+Y\": n3:ux, \"102:-Y\": n5:ux, \"7\": skip}");
    }
    std::set<std::pair<int, int>> components;
    std::set<int> dofs;
    for (const auto& kv : uf.node()) {
      const std::string key = uf.Key(kv.first);
      const Field value(kv.second, uf.file(), uf.path() + "." + key);
      const Field key_field(kv.first, uf.file(), uf.path() + "." + key);
      if (key == "*") {
        if (value.Str() != "skip")
          value.Fail(
              "\"*\" takes skip: the nodes no other entry (or geometry_file) "
              "maps are left out");
        map.skip_unmapped = true;
        continue;
      }
      const std::size_t colon = key.find(':');
      const std::string node_text = key.substr(0, colon);
      int node = 0;
      std::size_t used = 0;
      try {
        node = std::stoi(node_text, &used);
      } catch (...) {
        used = 0;
      }
      int direction = 0;
      if (used == 0 || used != node_text.size() ||
          (colon != std::string::npos &&
           !ParseUffDirection(key.substr(colon + 1), &direction))) {
        key_field.Fail(
            "expected \"<node>:<direction>\" (a UFF node number; X, Y, Z, RX, RY or RZ "
            "with an optional sign, or 1..6) or \"<node>\" with skip, found '" +
            key + "'");
      }
      const std::string source = value.Where() + ": " + value.path();
      const std::string label = value.Str();
      if (label == "skip") {
        if (colon != std::string::npos) {
          value.Fail("skip leaves out a whole node: write \"" + node_text +
                     "\": skip (components of a mapped node that are not listed are "
                     "not used anyway)");
        }
        map.skipped.push_back({node, source});
        continue;
      }
      if (colon == std::string::npos) {
        key_field.Fail("a node without a direction takes skip; map a component as \"" +
                       node_text + ":+X\": <DOF label>");
      }
      if (!components.insert({node, std::abs(direction)}).second) {
        key_field.Fail("node " + node_text + " direction " +
                       UffDirectionName(std::abs(direction)) + " is listed twice");
      }
      std::string dof_label = label;
      if (!dof_label.empty() && (dof_label[0] == '-' || dof_label[0] == '+')) {
        if (dof_label[0] == '-') direction = -direction;
        dof_label.erase(0, 1);
      }
      const int dof = model.FindDof(dof_label);
      if (dof < 0) {
        std::string some;
        for (int i = 0; i < std::min(model.num_dofs(), 6); ++i)
          some += (i ? ", " : "") + model.dof_labels()[i];
        value.Fail("no model DOF is labelled '" + dof_label + "' (labels look like: " +
                   some + (model.num_dofs() > 6 ? ", ..." : "") +
                   "; '-label' for a DOF pointing against the direction, or skip)");
      }
      if (!dofs.insert(dof).second) value.Fail("DOF '" + dof_label + "' is listed twice");
      UffSensor sensor;
      sensor.node = node;
      sensor.direction = direction;
      sensor.dof = dof;
      sensor.source = source;
      map.sensors.push_back(sensor);
    }
    std::set<int> mapped;
    for (const UffSensor& s : map.sensors) mapped.insert(s.node);
    for (const UffSkippedNode& k : map.skipped) {
      if (mapped.count(k.node)) {
        throw InputError(k.source, "node " + std::to_string(k.node) +
                                       " is skipped and also mapped; expected one or the "
                                       "other");
      }
    }
  }
  if (f.Has("geometry_file")) {
    if (nodes.empty()) {
      f["geometry_file"].Fail(
          "this model has no node coordinates (a chain or a Matrix Market model); map "
          "the UFF nodes with uff_dofs");
    }
    map.by_geometry = true;
    map.geometry_file = RelativeToStudy(f["geometry_file"]);
    map.model_nodes = nodes;
    if (f.Has("geometry_tolerance")) {
      map.tolerance = f["geometry_tolerance"].Positive();
    } else {
      Eigen::Vector3d lo = nodes[0].xyz, hi = nodes[0].xyz;
      for (const ModelNode& n : nodes) {
        lo = lo.cwiseMin(n.xyz);
        hi = hi.cwiseMax(n.xyz);
      }
      map.tolerance = 0.01 * (hi - lo).maxCoeff();
      if (!(map.tolerance > 0)) map.tolerance = 1e-3;
    }
    if (f.Has("uff_directions")) {
      std::set<int> seen;
      for (const Field& item : f["uff_directions"].Items()) {
        int d = 0;
        if (!ParseUffDirection(item.Str(), &d))
          item.Fail(
              "expected a direction: X, Y, Z, RX, RY or RZ (optionally signed) or "
              "1..6, found '" +
              item.Str() + "'");
        if (!seen.insert(std::abs(d)).second) item.Fail("direction is listed twice");
        map.directions.push_back(d);
      }
      if (map.directions.empty()) f["uff_directions"].Fail("expected at least one");
    }
  } else {
    for (const char* key : {"geometry_tolerance", "uff_directions"}) {
      if (f.Has(key))
        f[key].Fail(
            "applies to nodes placed by their coordinates: it needs geometry_file");
    }
  }
  return map;
}

MeasurementSpec ReadMeasurement(const Field& f, const ParametrisedModel& model,
                                bool have_truth, const std::vector<ModelNode>& nodes) {
  f.ExpectKeys({"state", "immersion", "simulate_modes", "frequencies_hz", "shapes",
                "sensors", "identify", "modes_file", "modes", "expansion", "uff_dofs",
                "geometry_file", "geometry_tolerance", "uff_directions"});
  MeasurementSpec m;
  m.field = f.path();
  m.state = f["state"].Str();
  m.immersion = m.state == "water" ? Immersion::kWet : Immersion::kDry;
  if (f.Has("immersion")) {
    const std::string v = f["immersion"].Str();
    if (v == "wet") {
      m.immersion = Immersion::kWet;
    } else if (v == "dry") {
      m.immersion = Immersion::kDry;
    } else {
      f["immersion"].Fail("expected wet or dry, found '" + v + "'");
    }
  }
  if (f.Has("expansion")) m.expansion = ReadExpansion(f["expansion"]);
  if (f.Has("identify") || f.Has("modes_file")) {
    for (const char* other : {"simulate_modes", "frequencies_hz", "shapes"}) {
      if (f.Has(other)) {
        f[other].Fail(std::string("give modes either from a file (identify / modes_file) "
                                  "or as ") +
                      other + ", not both");
      }
    }
    if (f.Has("identify") && f.Has("modes_file"))
      f.Fail("give either identify (a record file) or modes_file, not both");
    if (f.Has("identify")) {
      m.identify = ReadIdentify(f["identify"]);
    } else {
      m.modes_file = RelativeToStudy(f["modes_file"]);
    }
    if (!m.modes_file.empty() && IsUffFile(m.modes_file)) {
      m.uff_map = ReadUffMap(f, model, nodes);
    } else {
      for (const char* key : kUffKeys) {
        if (f.Has(key))
          f[key].Fail(
              "maps the nodes of a UFF modes_file (.uff, .unv); this "
              "measurement has none");
      }
      ReadChannelSensors(f["sensors"], model, &m);
    }
    if (f.Has("modes")) {
      const Field mf = f["modes"];
      if (mf.IsScalar()) {
        const int n = mf.Int();
        if (n < 1) mf.Fail("expected the number of lowest modes to use (>= 1)");
        if (n > model.num_dofs()) {
          mf.Fail("expected at most " + std::to_string(model.num_dofs()) +
                  " modes (the model has " + std::to_string(model.num_dofs()) +
                  " DOFs), found " + std::to_string(n));
        }
        for (int i = 1; i <= n; ++i) m.use_modes.push_back(i);
      } else {
        std::set<int> seen;
        for (const Field& item : mf.Items()) {
          const int k = item.Int();
          if (k < 1) item.Fail("identified modes are numbered from 1 (lowest frequency)");
          if (!seen.insert(k).second)
            item.Fail("mode " + std::to_string(k) + " is listed twice");
          m.use_modes.push_back(k);
        }
      }
    }
    m.data.state = m.state;
    m.data.immersion = m.immersion;
    return m;
  }
  if (f.Has("modes")) {
    f["modes"].Fail("modes selects identified modes; it needs identify or modes_file");
  }
  for (const char* key : kUffKeys) {
    if (f.Has(key))
      f[key].Fail(
          "maps the nodes of a UFF modes_file (.uff, .unv); this measurement "
          "has none");
  }
  if (m.expansion && f.Has("simulate_modes")) {
    f["expansion"].Fail("simulated modes are known at every DOF; nothing to expand");
  }
  if (f.Has("simulate_modes")) {
    if (f.Has("frequencies_hz") || f.Has("shapes")) {
      f.Fail("give either simulate_modes or measured frequencies_hz/shapes, not both");
    }
    if (!have_truth) {
      f["simulate_modes"].Fail(
          "simulated measurements need a 'truth' section with the "
          "factors of the real structure");
    }
    m.simulate_modes = f["simulate_modes"].Int();
    if (m.simulate_modes < 1 || m.simulate_modes > model.num_dofs()) {
      f["simulate_modes"].Fail("expected 1.." + std::to_string(model.num_dofs()) +
                               " modes");
    }
    return m;
  }
  m.data.state = m.state;
  m.data.immersion = m.immersion;
  const std::vector<double> freq = f["frequencies_hz"].Numbers();
  m.data.frequencies_hz = Eigen::Map<const Eigen::VectorXd>(freq.data(), freq.size());
  if (f.Has("sensors")) m.data.sensor_dofs = ReadSensors(f["sensors"], model);
  if (f.Has("shapes")) {
    const auto modes = f["shapes"].Items();
    const int rows = m.data.sensor_dofs.empty()
                         ? model.num_dofs()
                         : static_cast<int>(m.data.sensor_dofs.size());
    if (modes.size() != freq.size()) {
      f["shapes"].Fail("has " + std::to_string(modes.size()) + " shapes for " +
                       std::to_string(freq.size()) + " frequencies (one shape per mode)");
    }
    m.data.shapes.resize(rows, static_cast<Eigen::Index>(modes.size()));
    for (std::size_t j = 0; j < modes.size(); ++j) {
      const std::vector<double> v = modes[j].Numbers();
      if (static_cast<int>(v.size()) != rows) {
        modes[j].Fail("has " + std::to_string(v.size()) + " entries; expected " +
                      std::to_string(rows) +
                      (m.data.sensor_dofs.empty()
                           ? " (one per model DOF, or list the sensors)"
                           : " (one per sensor)"));
      }
      for (int i = 0; i < rows; ++i) m.data.shapes(i, j) = v[i];
    }
  } else if (f.Has("sensors")) {
    f["sensors"].Fail("sensors are listed but no shapes are given");
  }
  try {
    m.data.Validate(model.num_dofs(), f.path());
  } catch (const InputError& e) {
    f.Fail(e.what());
  }
  if (m.expansion && (!m.data.HasShapes() || m.data.sensor_dofs.empty())) {
    f["expansion"].Fail(
        "expansion needs shapes measured at listed sensors (these shapes are " +
        std::string(m.data.HasShapes() ? "complete already)" : "missing)"));
  }
  return m;
}

// A value per parameter from a mapping whose keys are parameter kinds ("mass",
// "stiffness", "added_mass": every parameter of that kind) or parameter names
// (which override their kind). `read` turns one value field into a number pair.
template <typename Read>
void ForEachParameterKey(const Field& f, const ParametrisedModel& model, Read read) {
  if (!f.IsMap()) f.Fail("expected a mapping of parameter names or kinds to values");
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& kv : f.node()) {
      const std::string key = f.Key(kv.first);
      const Field value(kv.second, f.file(), f.path() + "." + key);
      ParameterKind kind;
      const bool is_kind = ParameterKindFromString(key, &kind);
      if (pass == 0 && is_kind) {
        for (int i : model.ParametersOfKind(kind)) read(value, i);
      } else if (pass == 1 && !is_kind) {
        const int i = model.FindParameter(key);
        if (i < 0) {
          std::string names;
          for (const auto& n : model.ParameterNames())
            names += (names.empty() ? "" : ", ") + n;
          value.Fail("no parameter or kind is called '" + key +
                     "' (kinds: mass, stiffness, added_mass; parameters: " + names + ")");
        }
        read(value, i);
      }
    }
  }
}

double BoundValue(const Field& f) {
  if (f.IsScalar()) {
    const std::string s = f.node().Scalar();
    if (s == "-inf" || s == "-.inf") return -std::numeric_limits<double>::infinity();
    if (s == "inf" || s == ".inf" || s == "+inf")
      return std::numeric_limits<double>::infinity();
    if (s == "null" || s == "~" || s.empty()) return std::nan("");
  }
  return f.Num();
}

RegularisationOptions ReadRegularisation(const Field& f) {
  f.ExpectKeys({"parameter_choice", "lambda", "noise_norm", "discrepancy_factor",
                "operator", "grid_points", "lambda_min", "lambda_max"});
  RegularisationOptions o;
  if (f.Has("parameter_choice")) o.parameter_choice = f["parameter_choice"].Str();
  if (f.Has("lambda")) o.lambda = f["lambda"].NonNegative();
  if (f.Has("noise_norm")) o.noise_norm = f["noise_norm"].Positive();
  if (f.Has("discrepancy_factor"))
    o.discrepancy_factor = f["discrepancy_factor"].Positive();
  if (f.Has("operator")) o.op = f["operator"].Str();
  if (f.Has("grid_points")) o.grid_points = f["grid_points"].Int();
  if (f.Has("lambda_min")) o.lambda_min = f["lambda_min"].NonNegative();
  if (f.Has("lambda_max")) o.lambda_max = f["lambda_max"].NonNegative();
  const std::string invalid = o.Validate();
  if (!invalid.empty()) {
    const std::string key = invalid.substr(0, invalid.find(':'));
    (f.Has(key) ? f[key] : f).Fail(invalid.substr(invalid.find(':') + 2));
  }
  return o;
}

SolverSpec ReadSolver(const Field& sf, const ParametrisedModel& model) {
  sf.ExpectKeys({"label", "method", "name", "rank_tolerance", "scale_columns",
                 "truncation", "regularisation", "prior_mean", "max_iterations",
                 "kkt_tolerance", "confidence_level", "trust_region", "hessian",
                 "sensitivity"});
  SolverSpec spec;
  if (sf.Has("method")) spec.method = sf["method"].Str();
  if (spec.method != "linear" && spec.method != "sensitivity")
    sf["method"].Fail(
        "unknown method '" + spec.method +
        "' (expected linear: the paper's Z d = F, or sensitivity: iterative "
        "eigen-sensitivity updating)");
  spec.name =
      sf.Has("name") ? sf["name"].Str() : (spec.method == "linear" ? "lstsq" : "ceres");
  spec.label = sf.Has("label") ? sf["label"].Str() : spec.method + " (" + spec.name + ")";
  LinearSolverOptions& lo = spec.linear;
  NonlinearSolverOptions& no = spec.nonlinear;
  if (sf.Has("rank_tolerance"))
    lo.relative_rank_tolerance = sf["rank_tolerance"].Positive();
  if (sf.Has("scale_columns")) lo.scale_columns = sf["scale_columns"].Bool();
  if (sf.Has("truncation")) lo.truncation = sf["truncation"].Int();
  if (sf.Has("regularisation"))
    lo.regularisation = ReadRegularisation(sf["regularisation"]);
  if (sf.Has("max_iterations"))
    lo.max_iterations = no.max_iterations = sf["max_iterations"].Int();
  if (sf.Has("kkt_tolerance"))
    lo.kkt_tolerance = no.kkt_tolerance = sf["kkt_tolerance"].Positive();
  if (sf.Has("confidence_level")) lo.confidence_level = sf["confidence_level"].Positive();
  if (sf.Has("trust_region")) no.trust_region = sf["trust_region"].Str();
  if (sf.Has("hessian")) no.hessian = sf["hessian"].Str();
  if (sf.Has("prior_mean")) {
    spec.prior_mean = Eigen::VectorXd::Zero(model.num_parameters());
    ForEachParameterKey(sf["prior_mean"], model,
                        [&](const Field& v, int i) { spec.prior_mean[i] = v.Num(); });
  }
  if (sf.Has("sensitivity")) {
    const Field tf = sf["sensitivity"];
    tf.ExpectKeys({"frequency_sigma", "shape_sigma", "shape_noise", "shape_scaling",
                   "use_shapes", "extra_modes", "min_mac", "prior_sigma", "threads"});
    EigenSensitivityOptions& so = spec.sensitivity;
    if (tf.Has("frequency_sigma")) so.frequency_sigma = tf["frequency_sigma"].Positive();
    if (tf.Has("shape_sigma")) so.shape_sigma = tf["shape_sigma"].Positive();
    if (tf.Has("shape_noise")) so.shape_noise = tf["shape_noise"].Str();
    if (tf.Has("shape_scaling")) so.shape_scaling = tf["shape_scaling"].Str();
    if (tf.Has("use_shapes")) so.use_shapes = tf["use_shapes"].Bool();
    if (tf.Has("extra_modes")) so.extra_modes = tf["extra_modes"].Int();
    if (tf.Has("min_mac")) so.min_mac = tf["min_mac"].NonNegative();
    if (tf.Has("threads")) so.threads = tf["threads"].Int();
    if (tf.Has("prior_sigma")) {
      so.prior_sigma = Eigen::VectorXd::Zero(model.num_parameters());
      ForEachParameterKey(tf["prior_sigma"], model, [&](const Field& v, int i) {
        so.prior_sigma[i] = v.NonNegative();
      });
      if (spec.prior_mean.size() > 0) so.prior_mean = spec.prior_mean;
    }
    const std::string invalid = so.Validate();
    if (!invalid.empty()) tf.Fail(invalid);
  }
  try {
    if (spec.method == "linear") {
      CreateLinearSolver(spec.name, lo);
    } else {
      CreateNonlinearSolver(spec.name, no);
    }
  } catch (const InputError& e) {
    sf.Fail(e.what());
  }
  return spec;
}

void CheckMassPositiveDefinite(const Field& model_field, const ParametrisedModel& model) {
  Eigen::SimplicialLLT<SparseMatrix> llt(model.mass());
  if (llt.info() != Eigen::Success) {
    model_field.Fail(
        "the mass matrix is not positive definite (every DOF needs mass or "
        "rotary inertia, and no mass may be negative)");
  }
}

}  // namespace

namespace {

// "study.yaml:3:7" for a yaml-cpp error (the file alone without a position).
std::string WhereIn(const std::string& path, const YAML::Exception& e) {
  std::ostringstream w;
  w << path;
  if (!e.mark.is_null()) w << ":" << e.mark.line + 1 << ":" << e.mark.column + 1;
  return w.str();
}

// The study whose parsed YAML is `root`; with `model_only`, its model and
// factors alone (ParseStudyModel).
Study ReadStudy(const YAML::Node& root, const std::string& path, bool model_only) {
  const Field top(root, path, "");
  if (model_only) {
    top.ExpectKeys({"name", "description", "model", "parameters", "truth"});
  } else {
    top.ExpectKeys({"name", "description", "model", "parameters", "truth", "measurements",
                    "system", "solver", "noise_study", "output", "records", "diagnosis"});
  }
  Study study;
  study.path = path;
  study.name = top.Has("name") ? top["name"].Str() : fs::path(path).stem().string();
  if (top.Has("description")) study.description = top["description"].Str();

  const Field mf = top["model"];
  const std::string type = mf["type"].Str();
  if (type == "chain") {
    study.structure = ReadChain(mf);
  } else if (type == "cantilever") {
    CantileverSpec spec;
    study.structure = ReadCantilever(mf, &spec);
    study.cantilever = spec;
  } else if (type == "matrix_market") {
    study.structure = ReadMatrixMarketModel(mf);
  } else if (type == "space_frame") {
    study.model = ReadSpaceFrame(mf, &study.structure);
  } else if (type == "plane_frame") {
    study.structure = ReadPlaneFrame(mf);
  } else {
    mf["type"].Fail("unknown model type '" + type +
                    "' (expected chain, cantilever, plane_frame, matrix_market or "
                    "space_frame)");
  }
  const bool generated = type == "space_frame";  // the generator sets the factors

  ParameterPlan plan = PaperParameterPlan();
  if (generated && top.Has("parameters")) {
    for (const char* family : {"mass", "stiffness", "added_mass"}) {
      if (top["parameters"].Has(family)) {
        top["parameters"][family].Fail(
            "a space_frame model has its factors by level and block (see "
            "blocks_per_level); parameters may fix, bound or relate them only");
      }
    }
  }
  if (!(top.Has("parameters") && top["parameters"].Has("added_mass")) &&
      std::none_of(study.structure.elements.begin(), study.structure.elements.end(),
                   [](const ElementMatrices& e) { return e.wet; })) {
    // Nothing is wet and the study asks for no added mass: the default is none
    // (asked for explicitly, it is still an error below).
    plan.added_mass.scope = ParameterFamily::Scope::kNone;
  }
  if (top.Has("parameters")) {
    const Field pf = top["parameters"];
    pf.ExpectKeys({"mass", "stiffness", "added_mass", "fix", "bounds", "equalities"});
    if (pf.Has("mass")) plan.mass = ReadFamily(pf["mass"]);
    if (pf.Has("stiffness")) plan.stiffness = ReadFamily(pf["stiffness"]);
    if (pf.Has("added_mass")) plan.added_mass = ReadFamily(pf["added_mass"]);
  }
  if (!generated) {
    try {
      study.model = BuildModel(study.structure, plan);
    } catch (const InputError& e) {
      (top.Has("parameters") ? top["parameters"] : mf).Fail(e.what());
    }
  }
  CheckMassPositiveDefinite(mf, study.model);

  auto parameter_index = [&](const Field& key_field, const std::string& name) {
    const int i = study.model.FindParameter(name);
    if (i < 0) {
      std::string names;
      for (const auto& n : study.model.ParameterNames())
        names += (names.empty() ? "" : ", ") + n;
      key_field.Fail("no parameter is called '" + name + "' (parameters: " + names + ")");
    }
    return i;
  };
  if (top.Has("parameters") && top["parameters"].Has("fix")) {
    const Field ff = top["parameters"]["fix"];
    if (!ff.IsMap()) ff.Fail("expected a mapping of parameter names to known values");
    for (const auto& kv : ff.node()) {
      const std::string name = ff.Key(kv.first);
      const Field value(kv.second, ff.file(), ff.path() + "." + name);
      parameter_index(value, name);
      study.fixed[name] = value.Num();
    }
  }
  if (top.Has("parameters") && top["parameters"].Has("bounds")) {
    const int n = study.model.num_parameters();
    study.lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
    study.upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    ForEachParameterKey(top["parameters"]["bounds"], study.model,
                        [&](const Field& v, int i) {
                          const std::vector<Field> pair = v.Items();
                          if (pair.size() != 2)
                            v.Fail("expected [lower, upper] (use -inf / inf for none)");
                          const double lo = BoundValue(pair[0]), hi = BoundValue(pair[1]);
                          if (std::isnan(lo) || std::isnan(hi))
                            v.Fail("a bound is empty; use -inf / inf for none");
                          if (lo > hi) v.Fail("lower bound exceeds upper bound");
                          study.lower[i] = lo;
                          study.upper[i] = hi;
                        });
    for (const auto& [name, value] : study.fixed) {
      const int i = study.model.FindParameter(name);
      if (value < study.lower[i] || value > study.upper[i])
        top["parameters"]["fix"][name].Fail(
            "the fixed value is outside the parameter's bounds");
    }
  }
  if (top.Has("parameters") && top["parameters"].Has("equalities")) {
    const std::vector<Field> rows = top["parameters"]["equalities"].Items();
    const int n = study.model.num_parameters();
    study.equality_matrix = Eigen::MatrixXd::Zero(rows.size(), n);
    study.equality_rhs = Eigen::VectorXd::Zero(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      rows[r].ExpectKeys({"coefficients", "value"});
      const Field cf = rows[r]["coefficients"];
      if (!cf.IsMap()) cf.Fail("expected a mapping of parameter names to coefficients");
      for (const auto& kv : cf.node()) {
        const std::string name = cf.Key(kv.first);
        const Field value(kv.second, cf.file(), cf.path() + "." + name);
        study.equality_matrix(r, parameter_index(value, name)) = value.Num();
      }
      study.equality_rhs[r] = rows[r].Has("value") ? rows[r]["value"].Num() : 0.0;
    }
  }
  if (top.Has("truth")) {
    const Field tf = top["truth"];
    if (!tf.IsMap()) tf.Fail("expected a mapping of parameter names to factor values");
    Eigen::VectorXd truth = Eigen::VectorXd::Zero(study.model.num_parameters());
    ForEachParameterKey(tf, study.model,
                        [&](const Field& value, int i) { truth[i] = value.Num(); });
    study.truth = truth;
  }
  if (model_only) return study;
  if (top.Has("records")) study.records = ReadRecords(top["records"], study.model);
  if (study.records && !top.Has("measurements")) return study;

  for (const Field& f : top["measurements"].Items()) {
    study.measurements.push_back(
        ReadMeasurement(f, study.model, study.truth.has_value(), study.structure.nodes));
  }
  if (study.measurements.empty()) top["measurements"].Fail("expected at least one state");
  {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < study.measurements.size(); ++i) {
      if (!seen.insert(study.measurements[i].state).second) {
        top["measurements"].Items()[i]["state"].Fail(
            "state '" + study.measurements[i].state + "' is listed twice");
      }
    }
  }

  if (top.Has("system")) {
    const Field sf = top["system"];
    sf.ExpectKeys({"form", "fem_modes"});
    if (sf.Has("form") && !SystemFormFromString(sf["form"].Str(), &study.system.form)) {
      sf["form"].Fail("unknown form '" + sf["form"].Str() +
                      "' (expected stacked or summed)");
    }
    if (sf.Has("fem_modes")) {
      const Field f = sf["fem_modes"];
      if (f.IsScalar() && f.node().Scalar() == "all") {
        study.system.num_fem_modes = -1;
      } else {
        study.system.num_fem_modes = f.Int();
        if (study.system.num_fem_modes < 1 ||
            study.system.num_fem_modes > study.model.num_dofs()) {
          f.Fail("expected 'all' or 1.." + std::to_string(study.model.num_dofs()));
        }
      }
    }
  }
  if (top.Has("solver")) study.solver = ReadSolver(top["solver"], study.model);
  if (top.Has("diagnosis")) study.diagnosis = ReadDiagnosis(top["diagnosis"], study);
  if (top.Has("noise_study")) {
    const Field nf = top["noise_study"];
    nf.ExpectKeys({"levels", "draws", "seed", "distribution", "figure_level",
                   "shape_level_ratio", "shape_noise", "compare"});
    NoiseStudySpec spec;
    spec.levels = nf["levels"].Numbers();
    for (std::size_t i = 0; i < spec.levels.size(); ++i) {
      if (!(spec.levels[i] >= 0 && spec.levels[i] < 1)) {
        nf["levels"].Items()[i].Fail(
            "a corruption level is relative: expected 0 <= level < 1");
      }
    }
    if (spec.levels.empty()) nf["levels"].Fail("expected at least one level");
    if (nf.Has("draws")) {
      spec.draws = nf["draws"].Int();
      if (spec.draws < 1) nf["draws"].Fail("expected at least one draw");
    }
    if (nf.Has("seed")) spec.seed = nf["seed"].Seed();
    if (nf.Has("distribution") &&
        !NoiseDistributionFromString(nf["distribution"].Str(), &spec.distribution)) {
      nf["distribution"].Fail("expected gaussian or uniform");
    }
    if (nf.Has("figure_level")) spec.figure_level = nf["figure_level"].NonNegative();
    if (nf.Has("shape_level_ratio"))
      spec.shape_level_ratio = nf["shape_level_ratio"].NonNegative();
    if (nf.Has("shape_noise")) {
      spec.shape_noise = nf["shape_noise"].Str();
      if (spec.shape_noise != "entry" && spec.shape_noise != "peak") {
        nf["shape_noise"].Fail("expected entry or peak, got '" + spec.shape_noise + "'");
      }
    }
    if (nf.Has("compare")) {
      for (const Field& item : nf["compare"].Items())
        spec.compare.push_back(ReadSolver(item, study.model));
    }
    if (!study.truth)
      nf.Fail("a noise study needs a 'truth' section (the preset factors)");
    study.noise_study = spec;
  }
  if (top.Has("output")) {
    const Field of = top["output"];
    of.ExpectKeys({"plots"});
    if (of.Has("plots")) study.plots = of["plots"].Bool();
  }
  return study;
}

}  // namespace

namespace {

Study ParseStudyText(std::string_view text, const std::string& path, bool model_only) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw InputError(WhereIn(path, e), "not valid YAML/JSON: " + e.msg);
  }
  try {
    return ReadStudy(root, path, model_only);
  } catch (const YAML::Exception& e) {
    // Every read goes through Field, which checks a node's type first; should
    // yaml-cpp still object, it is the file's content, never an internal error.
    throw InputError(WhereIn(path, e), "unexpected YAML content: " + e.msg);
  }
}

}  // namespace

Study ParseStudy(std::string_view text, const std::string& path) {
  return ParseStudyText(text, path, false);
}

Study ParseStudyModel(std::string_view text, const std::string& path) {
  return ParseStudyText(text, path, true);
}

Study LoadStudy(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, "study file not found");
  if (!fs::is_regular_file(path)) throw InputError(path, "is not a file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) throw InputError(path, "cannot read the study file");
  return ParseStudy(text.str(), path);
}

}  // namespace femup
