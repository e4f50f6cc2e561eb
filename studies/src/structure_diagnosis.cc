#include "femup/studies/structure_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/fe/form_variant.h"
#include "femup/core/fe/sensor.h"

namespace femup {
namespace {

// A mesh that moves a measured mode by more than this many frequency noise
// standard deviations is not converged for the data (DiagnosisSpec::refine_mesh).
constexpr double kMeshErrorInNoise = 3.0;

// A measured state on the refined model's DOFs: a sensor on a node at that
// node's DOF there (variant.dofs), one between nodes placed again on the finer
// mesh from where it was stated.
ModalData OnRefinedModel(const ModalData& d, const FormVariant& variant,
                         const Structure& refined, const std::string& where) {
  ModalData out = d;
  for (int& dof : out.sensor_dofs) dof = variant.dofs.at(static_cast<std::size_t>(dof));
  if (!d.HasInterpolatedSensors()) return out;
  const int n = static_cast<int>(refined.dof_labels.size());
  std::vector<Eigen::Triplet<double>> t;
  if (d.sensor_specs.size() == static_cast<std::size_t>(d.sensor_weights.rows())) {
    for (std::size_t i = 0; i < d.sensor_specs.size(); ++i) {
      SensorRow row;
      ThrowIfInvalid(LocateSensor(refined, d.sensor_specs[i], &row), where + ".sensors");
      for (const auto& [dof, w] : row.weights)
        t.emplace_back(static_cast<int>(i), dof, w);
    }
  } else {  // read through the model's own interpolation of its nodes
    for (int k = 0; k < d.sensor_weights.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(d.sensor_weights, k); it; ++it)
        t.emplace_back(static_cast<int>(it.row()),
                       variant.dofs.at(static_cast<std::size_t>(it.col())), it.value());
  }
  out.sensor_weights.resize(d.sensor_weights.rows(), n);
  out.sensor_weights.setFromTriplets(t.begin(), t.end());
  return out;
}

// The finer-mesh variant the diagnosis runs on (DiagnosisSpec::refine_mesh),
// or null; `note` says why, with how far the model's mesh moves a mode.
const FormVariant* MeshToDiagnoseOn(const Structure& model,
                                    const std::vector<ModalData>& measured,
                                    const DiagnosisSpec& spec, std::string* note) {
  if (!spec.refine_mesh) return nullptr;
  int modes = 1;
  for (const ModalData& d : measured) modes = std::max(modes, d.num_modes());
  modes = std::min(modes, static_cast<int>(model.stiffness.rows()));
  for (const FormVariant& v : model.form_variants) {
    if (!v.model) continue;
    const ModeChanges c = PairedModeChanges(model, v, modes);
    // Relative frequency change: half the relative eigenvalue change.
    const Eigen::VectorXd moved =
        0.5 * c.eigenvalue_change.cwiseQuotient(c.modes.eigenvalues).cwiseAbs();
    Eigen::Index worst = 0;
    const double most = moved.maxCoeff(&worst);
    if (most / spec.frequency_noise <= kMeshErrorInNoise) continue;
    std::ostringstream what;
    what << std::setprecision(3) << "the model's mesh is not converged for the measured "
         << "modes: " << v.name << " moves its mode " << worst + 1 << " by " << 100 * most
         << " % (" << most / spec.frequency_noise
         << " frequency noise units), so the diagnosis ran on that mesh, its nodes and "
            "candidates named as the model's (diagnosis.refine_mesh: false keeps the "
            "model's mesh)";
    *note = what.str();
    return &v;
  }
  return nullptr;
}

// The modes the verdict is checked on (DiagnosisSpec::held_out), as (state,
// mode) indexes: "auto" the highest of each state with three or more, "none"
// nothing, a list the named ones (each must be measured; InputError naming
// the study file and diagnosis.held_out otherwise).
std::vector<std::pair<int, int>> HeldOutModes(const DiagnosisSpec& spec,
                                              const std::vector<ModalData>& measured,
                                              const std::string& path) {
  std::vector<std::pair<int, int>> out;
  if (spec.held_out == "auto") {
    for (std::size_t i = 0; i < measured.size(); ++i)
      if (measured[i].num_modes() >= 3)
        out.emplace_back(static_cast<int>(i), measured[i].num_modes() - 1);
  } else if (spec.held_out == "list") {
    for (const auto& named : spec.held_out_modes) {
      // Not a structured binding: a lambda below reads the state (C++17).
      const std::string& state = named.first;
      const int mode = named.second;
      const auto it = std::find_if(measured.begin(), measured.end(),
                                   [&](const ModalData& d) { return d.state == state; });
      if (it == measured.end()) {
        throw InputError(path, "diagnosis.held_out: no measured state '" + state + "'");
      }
      if (mode < 1 || mode > it->num_modes()) {
        throw InputError(path, "diagnosis.held_out: state " + state + " has modes 1.." +
                                   std::to_string(it->num_modes()) + ", not " +
                                   std::to_string(mode));
      }
      out.emplace_back(static_cast<int>(it - measured.begin()), mode - 1);
    }
  }
  return out;
}

}  // namespace

StructureDiagnosisResult RunStructureDiagnosis(const Study& study) {
  if (study.measurements.empty())
    throw InputError(study.path, "measurements: missing (nothing to diagnose)");
  if (study.structure.stiffness.rows() == 0 && study.structure.type == "space_frame") {
    throw InputError(study.path,
                     "model: femup diagnose runs on space_frame models up to 60000 DOF "
                     "(each stiffness group's matrices are held apart); this one has " +
                         std::to_string(study.model.num_dofs()) +
                         ": fewer levels, bays or elements_per_member");
  }
  if (study.structure.stiffness.rows() == 0) {
    throw InputError(
        study.path, "model.type: femup diagnose does not run on " + study.structure.type +
                        " models yet (they are assembled without per-member matrices, "
                        "which every effect family acts on); chain, cantilever, "
                        "plane_frame and matrix_market models with element matrices "
                        "can be diagnosed");
  }
  const DiagnosisSpec spec = study.diagnosis.value_or(DiagnosisSpec());
  StructureDiagnosisResult r;
  r.study_name = study.name;
  r.description = study.description;
  r.model_type = study.structure.type;
  r.dof_labels = study.model.dof_labels();
  r.confidence = spec.confidence;
  r.gap_confidence = spec.gap_confidence;
  r.gap_explained = spec.gap_explained;
  r.map = MapGeometry(study.structure);

  EffectRankingOptions options;
  options.kinds = spec.candidates;
  options.frequency_sigma = spec.frequency_noise;
  options.shape_sigma = spec.shape_noise;
  options.use_shapes = spec.use_shapes;
  options.solver = spec.solver;
  options.priors = spec.priors;
  options.formulation_error = spec.formulation_error;
  options.form_error_on_shapes = spec.form_error_on_shapes;
  options.form_step = spec.form_step;
  options.form_fit = spec.form_fit;
  options.bagging_copies = spec.bagging_copies;
  options.max_members = spec.max_members;
  options.rotary_inertia = spec.rotary_inertia;
  options.members_fitted = spec.members_fitted;
  options.gap_confidence = spec.gap_confidence;
  options.gap_explained = spec.gap_explained;
  options.frequency_temperature = spec.frequency_temperature;
  options.max_effects =
      spec.MaxEffectsFor(/*own_pipeline=*/false, study.measurements.size());
  options.pair_places = spec.pair_places;
  options.stiffness_uncertainty = spec.stiffness_uncertainty;
  options.mass_uncertainty = spec.mass_uncertainty;
  r.priors = spec.priors;
  // A named family that does not apply is the study's error, before any fit.
  for (const std::string& kind : options.kinds) {
    const auto known = ModelEffectKinds();
    if (std::find(known.begin(), known.end(), kind) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(study.path, "diagnosis.candidates: '" + kind +
                                       "' is not a family a " + r.model_type +
                                       " model knows (" + list + ")");
    }
    for (const FamilyApplicability& a : ApplicableModelEffects(study.structure)) {
      if (a.kind == kind && !a.why_not.empty()) {
        throw InputError(study.path, "diagnosis.candidates: " + kind +
                                         " does not apply to this " + r.model_type +
                                         " model: " + a.why_not);
      }
    }
  }
  for (const PreparedState& p : PrepareMeasurements(study))
    r.measured.push_back(p.at_sensors);
  // Measured modes in ascending order, as every model lists its own: the
  // pairing in order and the mode numbers rely on it. Two modes closer than
  // the noise can make them (a symmetric structure's pair of sway modes, which
  // a test may list by shape: examples/diagnosis/jacket.yaml lists 6.738 Hz
  // before 6.723 Hz) may come in either order; a mode listed below the one
  // before it by more than 5 standard deviations of the stated frequency noise
  // is the study's error, refused before any fit.
  constexpr double kSwapSigmas = 5;
  for (std::size_t i = 0; i < r.measured.size(); ++i) {
    const Eigen::VectorXd& f = r.measured[i].frequencies_hz;
    for (Eigen::Index j = 1; j < f.size(); ++j) {
      if (f[j] >= f[j - 1] * (1 - kSwapSigmas * spec.frequency_noise)) continue;
      std::ostringstream msg;
      msg << study.measurements[i].field << " (state " << r.measured[i].state
          << "): frequencies must be listed in ascending order (mode 1 the lowest; modes "
             "within "
          << kSwapSigmas << " standard deviations of the stated frequency noise of each "
          << "other in either); mode " << j << " is " << f[j - 1] << " Hz and mode "
          << j + 1 << " is " << f[j] << " Hz";
      throw InputError(study.path, msg.str());
    }
  }
  options.held_out = HeldOutModes(spec, r.measured, study.path);
  std::string refined_note;
  const FormVariant* refined =
      MeshToDiagnoseOn(study.structure, r.measured, spec, &refined_note);
  std::vector<ModalData> data = r.measured;
  if (refined) {
    for (std::size_t i = 0; i < data.size(); ++i)
      data[i] = OnRefinedModel(data[i], *refined, *refined->model,
                               study.measurements.at(i).field);
  }
  try {
    r.ranking =
        RankModelEffects(refined ? *refined->model : study.structure, data, options);
    if (refined) r.ranking.notes.insert(r.ranking.notes.begin(), refined_note);
  } catch (const InputError& e) {
    // The study's own fields (diagnosis.priors.*, ...): name the study file.
    if (e.where().rfind("diagnosis", 0) == 0) throw InputError(study.path, e.what());
    throw;
  }
  return r;
}

}  // namespace femup
