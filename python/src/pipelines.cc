// The pipelines a command runs, with their results as Python objects: update
// (`femup run`), noise study (`femup noise`), diagnosis (`femup diagnose`: the
// cantilever's own pipeline or the ranking on any other structure), modes
// (`femup modes`) and simulated test records (`femup simulate`). Each releases
// the GIL while it computes.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/diagnose_study.h"
#include "femup/studies/modes_study.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/simulate_study.h"
#include "femup/studies/structure_diagnosis.h"
#include "femup/studies/update_study.h"

namespace femup_python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One row of an update's factor table.
struct Factor {
  std::string name, kind;
  std::vector<std::string> tags;
  double estimate = kNaN;
  double preset = kNaN;          // the study's truth, NaN when it gives none
  double error = kNaN;           // estimate - preset
  double standard_error = kNaN;  // linearised, NaN when not computed
  bool fixed = false;
};

std::vector<Factor> Factors(const femup::UpdateResult& r) {
  std::vector<Factor> out;
  const Eigen::VectorXd& x = r.solution.x;
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    Factor f;
    f.name = r.parameters[i].name;
    f.kind = femup::ToString(r.parameters[i].kind);
    f.tags = r.parameters[i].tags;
    if (k < x.size()) f.estimate = x[k];
    if (r.preset && k < r.preset->size()) {
      f.preset = (*r.preset)[k];
      f.error = f.estimate - f.preset;
    }
    if (k < r.solution.standard_error.size())
      f.standard_error = r.solution.standard_error[k];
    f.fixed = i < r.fixed.size() && r.fixed[i];
    out.push_back(std::move(f));
  }
  return out;
}

// The gap summary diagnosis.json reports per class (gap_before / gap_after):
// RMS relative frequency error and mean MAC on fitted and held-out modes.
void Accumulate(const femup::EffectFitData& data,
                const std::vector<femup::PredictedState>& pred, double* sum_sq,
                int* count, double* mac_sum, int* mac_count) {
  for (std::size_t s = 0; s < data.states.size() && s < pred.size(); ++s) {
    for (std::size_t j = 0; j < data.states[s].modes.size() && j < pred[s].modes.size();
         ++j) {
      const double e =
          pred[s].modes[j].frequency_hz / data.states[s].modes[j].frequency_hz - 1;
      *sum_sq += e * e;
      ++*count;
      if (data.states[s].modes[j].shape.size() > 0) {
        *mac_sum += pred[s].modes[j].mac;
        ++*mac_count;
      }
    }
  }
}

py::dict Gap(const femup::DiagnosisResult& r,
             const std::vector<femup::PredictedState>& fitted,
             const std::vector<femup::PredictedState>& held) {
  double ss = 0, ms = 0;
  int n = 0, mn = 0;
  Accumulate(r.fitted_data, fitted, &ss, &n, &ms, &mn);
  py::dict g;
  g["rms_frequency_error"] = n > 0 ? std::sqrt(ss / n) : kNaN;
  g["mean_mac"] = mn > 0 ? ms / mn : kNaN;
  ss = ms = 0;
  n = mn = 0;
  Accumulate(r.held_out_data, held, &ss, &n, &ms, &mn);
  g["rms_frequency_error_held_out"] = n > 0 ? std::sqrt(ss / n) : kNaN;
  g["mean_mac_held_out"] = mn > 0 ? ms / mn : kNaN;
  return g;
}

// Measured and predicted frequencies of fitted (or held-out) modes, flat.
py::dict Frequencies(const femup::EffectFitData& data,
                     const std::vector<femup::PredictedState>& pred) {
  std::vector<double> measured, predicted, mac;
  std::vector<std::string> state;
  std::vector<int> number;
  for (std::size_t s = 0; s < data.states.size() && s < pred.size(); ++s) {
    for (std::size_t j = 0; j < data.states[s].modes.size() && j < pred[s].modes.size();
         ++j) {
      state.push_back(data.states[s].state);
      number.push_back(data.states[s].modes[j].number);
      measured.push_back(data.states[s].modes[j].frequency_hz);
      predicted.push_back(pred[s].modes[j].frequency_hz);
      mac.push_back(pred[s].modes[j].mac);
    }
  }
  py::dict out;
  out["state"] = state;
  out["mode"] = number;
  out["measured_hz"] = py::array(py::cast(measured));
  out["predicted_hz"] = py::array(py::cast(predicted));
  out["mac"] = py::array(py::cast(mac));
  return out;
}

void BindUpdate(py::module_& m) {
  py::class_<Factor>(m, "Factor", "One factor of an update: name, estimate, error.")
      .def_readonly("name", &Factor::name)
      .def_readonly("kind", &Factor::kind)
      .def_readonly("tags", &Factor::tags)
      .def_readonly("estimate", &Factor::estimate)
      .def_readonly("preset", &Factor::preset, "the study's truth, NaN when none")
      .def_readonly("error", &Factor::error, "estimate - preset (NaN without a preset)")
      .def_readonly("standard_error", &Factor::standard_error,
                    "linearised standard error (NaN when not computed)")
      .def_readonly("fixed", &Factor::fixed)
      .def("__repr__", [](const Factor& f) {
        return "<femup.Factor " + f.name + " = " + std::to_string(f.estimate) + ">";
      });

  py::class_<femup::StateComparison>(m, "StateComparison")
      .def_readonly("state", &femup::StateComparison::state)
      .def_property_readonly(
          "immersion",
          [](const femup::StateComparison& s) { return femup::ToString(s.immersion); })
      .def_readonly("measured_hz", &femup::StateComparison::measured_hz)
      .def_readonly("model_hz", &femup::StateComparison::model_hz, "nominal model")
      .def_readonly("updated_hz", &femup::StateComparison::updated_hz)
      .def_readonly("model_mac", &femup::StateComparison::model_mac)
      .def_readonly("updated_mac", &femup::StateComparison::updated_mac)
      .def_readonly("measured_shapes", &femup::StateComparison::measured_shapes)
      .def_readonly("model_shapes", &femup::StateComparison::model_shapes)
      .def_readonly("updated_shapes", &femup::StateComparison::updated_shapes)
      .def_readonly("shape_dofs", &femup::StateComparison::shape_dofs);

  py::class_<femup::AddedMassSummary>(m, "AddedMassSummary")
      .def_readonly("present", &femup::AddedMassSummary::present)
      .def_readonly("sa", &femup::AddedMassSummary::sa, "Eq. 36")
      .def_readonly("wet_elements", &femup::AddedMassSummary::wet_elements)
      .def_readonly("total_kg", &femup::AddedMassSummary::total_kg)
      .def_readonly("wet_length_m", &femup::AddedMassSummary::wet_length_m)
      .def_readonly("per_length", &femup::AddedMassSummary::per_length, "kg/m")
      .def_readonly("eq2_coefficients", &femup::AddedMassSummary::eq2_coefficients);

  py::class_<femup::UpdateResult>(m, "UpdateResult", "What `femup run` computes.")
      .def_readonly("study_name", &femup::UpdateResult::study_name)
      .def_readonly("model_description", &femup::UpdateResult::model_description)
      .def_readonly("num_dofs", &femup::UpdateResult::num_dofs)
      .def_property_readonly(
          "factors", [](const femup::UpdateResult& r) { return Factors(r); },
          "per parameter: name, kind, tags, estimate, preset, error, standard error, "
          "fixed")
      .def_property_readonly(
          "parameters",
          [](py::object self) {
            return RefList(self.cast<const femup::UpdateResult&>().parameters, self);
          })
      .def_property_readonly("parameter_names",
                             [](const femup::UpdateResult& r) {
                               std::vector<std::string> names;
                               for (const auto& p : r.parameters) names.push_back(p.name);
                               return names;
                             })
      .def_readonly("preset", &femup::UpdateResult::preset)
      .def_readonly("fixed", &femup::UpdateResult::fixed)
      .def_readonly("method", &femup::UpdateResult::method)
      .def_readonly("solver_name", &femup::UpdateResult::solver_name)
      .def_readonly("problem", &femup::UpdateResult::problem, "Z d = F (LinearProblem)")
      .def_property_readonly(
          "form", [](const femup::UpdateResult& r) { return femup::ToString(r.form); })
      .def_readonly("num_fem_modes", &femup::UpdateResult::num_fem_modes)
      .def_readonly("normal_system", &femup::UpdateResult::normal_system)
      .def_readonly("identifiability_unconstrained",
                    &femup::UpdateResult::identifiability_unconstrained)
      .def_readonly("solution", &femup::UpdateResult::solution)
      .def_readonly("states", &femup::UpdateResult::states)
      .def_readonly("sources", &femup::UpdateResult::sources)
      .def_readonly("added_mass_summary", &femup::UpdateResult::added_mass_summary)
      .def_property_readonly(
          "added_mass",
          [](py::object self) {
            return CscView(self.cast<const femup::UpdateResult&>().added_mass, self);
          },
          "dMa (Eq. 32-33), scipy.sparse")
      .def_property_readonly(
          "updated_stiffness",
          [](py::object self) {
            return CscView(self.cast<const femup::UpdateResult&>().updated_stiffness,
                           self);
          })
      .def_property_readonly(
          "updated_dry_mass",
          [](py::object self) {
            return CscView(self.cast<const femup::UpdateResult&>().updated_dry_mass,
                           self);
          })
      .def_readonly("dof_labels", &femup::UpdateResult::dof_labels)
      .def("report", &femup::UpdateReport, "the terminal summary of `femup run`");

  m.def("run_update", &femup::RunUpdate, py::arg("study"),
        py::call_guard<py::gil_scoped_release>(),
        "`femup run`: identify the factors, build the updated model, compare. A failed "
        "or rank-deficient solve is in result.solution.summary.");
}

void BindNoise(py::module_& m) {
  py::class_<femup::RmStatistics>(m, "RmStatistics")
      .def_readonly("mean", &femup::RmStatistics::mean)
      .def_readonly("std_dev", &femup::RmStatistics::std_dev)
      .def_readonly("median", &femup::RmStatistics::median)
      .def_readonly("p90", &femup::RmStatistics::p90);
  py::class_<femup::SolverScores>(m, "SolverScores")
      .def_readonly("label", &femup::SolverScores::label)
      .def_readonly("rm_average", &femup::SolverScores::rm_average)
      .def_readonly("rm_median", &femup::SolverScores::rm_median)
      .def_readonly("usable_draws", &femup::SolverScores::usable_draws)
      .def_readonly("seconds", &femup::SolverScores::seconds);
  py::class_<femup::NoiseStudyResult>(m, "NoiseStudyResult",
                                      "What `femup noise` computes.")
      .def_readonly("study_name", &femup::NoiseStudyResult::study_name)
      .def_readonly("spec", &femup::NoiseStudyResult::spec)
      .def_property_readonly(
          "levels", [](const femup::NoiseStudyResult& r) { return r.spec.levels; })
      .def_readonly("parameter_names", &femup::NoiseStudyResult::parameter_names)
      .def_readonly("preset", &femup::NoiseStudyResult::preset)
      .def_readonly("added_mass_indices", &femup::NoiseStudyResult::added_mass_indices)
      .def_readonly("rm", &femup::NoiseStudyResult::rm,
                    "rm[level][k]: statistics of added-mass factor k")
      .def_property_readonly(
          "rm_mean",
          [](const femup::NoiseStudyResult& r) {
            Eigen::MatrixXd out(r.rm.size(), r.added_mass_indices.size());
            for (std::size_t l = 0; l < r.rm.size(); ++l) {
              for (std::size_t k = 0; k < r.rm[l].size(); ++k) {
                out(static_cast<Eigen::Index>(l), static_cast<Eigen::Index>(k)) =
                    r.rm[l][k].mean;
              }
            }
            return out;
          },
          "levels x added-mass factors: mean Rm (%)")
      .def_readonly("rm_average", &femup::NoiseStudyResult::rm_average)
      .def_readonly("usable_draws", &femup::NoiseStudyResult::usable_draws)
      .def_readonly("figure_level", &femup::NoiseStudyResult::figure_level)
      .def_readonly("figure_mean", &femup::NoiseStudyResult::figure_mean)
      .def_readonly("figure_std", &femup::NoiseStudyResult::figure_std)
      .def_readonly("figure_first_draw", &femup::NoiseStudyResult::figure_first_draw)
      .def_readonly("comparison", &femup::NoiseStudyResult::comparison)
      .def("report", &femup::NoiseReport);
  m.def(
      "run_noise_study",
      [](const femup::Study& study, int threads) {
        femup::NoiseRunOptions options;
        options.threads = threads;
        return femup::RunNoiseStudy(study, options);
      },
      py::arg("study"), py::arg("threads") = 1, py::call_guard<py::gil_scoped_release>(),
      "`femup noise`: Rm of the added-mass factors per corruption level; the same "
      "numbers for any number of threads.");
}

void BindDiagnosis(py::module_& m) {
  py::class_<femup::ModelEvidence>(m, "ModelEvidence")
      .def_readonly("log_evidence", &femup::ModelEvidence::log_evidence)
      .def_readonly("chi2", &femup::ModelEvidence::chi2)
      .def_readonly("log_occam", &femup::ModelEvidence::log_occam)
      .def_readonly("num_parameters", &femup::ModelEvidence::num_parameters)
      .def_readonly("sigma", &femup::ModelEvidence::sigma);
  py::class_<femup::EffectLocation>(m, "EffectLocation", "NaN where it does not apply.")
      .def_readonly("depth", &femup::EffectLocation::depth)
      .def_readonly("x", &femup::EffectLocation::x)
      .def_readonly("x0", &femup::EffectLocation::x0)
      .def_readonly("x1", &femup::EffectLocation::x1);
  py::class_<femup::EffectMagnitude>(m, "EffectMagnitude")
      .def_readonly("name", &femup::EffectMagnitude::name)
      .def_readonly("unit", &femup::EffectMagnitude::unit)
      .def_readonly("value", &femup::EffectMagnitude::value)
      .def("__repr__", [](const femup::EffectMagnitude& e) {
        return "<femup.EffectMagnitude " + e.name + " = " + std::to_string(e.value) +
               " " + e.unit + ">";
      });
  py::class_<femup::PredictedMode>(m, "PredictedMode")
      .def_readonly("model_mode", &femup::PredictedMode::model_mode)
      .def_readonly("frequency_hz", &femup::PredictedMode::frequency_hz)
      .def_readonly("mac", &femup::PredictedMode::mac)
      .def_readonly("shape", &femup::PredictedMode::shape);
  py::class_<femup::PredictedState>(m, "PredictedState")
      .def_readonly("modes", &femup::PredictedState::modes);

  py::class_<femup::DiagnosisCandidate>(m, "DiagnosisCandidate",
                                        "One model class of the cantilever diagnosis.")
      .def_readonly("label", &femup::DiagnosisCandidate::label)
      .def_readonly("kinds", &femup::DiagnosisCandidate::kinds)
      .def_readonly("probability", &femup::DiagnosisCandidate::probability)
      .def_readonly("converged", &femup::DiagnosisCandidate::converged)
      .def_readonly("message", &femup::DiagnosisCandidate::message)
      .def_readonly("theta", &femup::DiagnosisCandidate::theta)
      .def_readonly("names", &femup::DiagnosisCandidate::names)
      .def_readonly("evidence", &femup::DiagnosisCandidate::evidence)
      .def_readonly("chi2", &femup::DiagnosisCandidate::chi2)
      .def_readonly("held_out_chi2", &femup::DiagnosisCandidate::held_out_chi2)
      .def_readonly("held_out_log_predictive",
                    &femup::DiagnosisCandidate::held_out_log_predictive)
      .def_readonly("score", &femup::DiagnosisCandidate::score)
      .def_readonly("evidence_method", &femup::DiagnosisCandidate::evidence_method)
      .def_readonly("starts", &femup::DiagnosisCandidate::starts)
      .def_readonly("locations", &femup::DiagnosisCandidate::locations)
      .def_readonly("magnitudes", &femup::DiagnosisCandidate::magnitudes)
      .def_readonly("fitted", &femup::DiagnosisCandidate::fitted)
      .def_readonly("held_out", &femup::DiagnosisCandidate::held_out);
  py::class_<femup::ElementIndicator>(m, "ElementIndicator")
      .def_readonly("element", &femup::ElementIndicator::element)
      .def_readonly("x0", &femup::ElementIndicator::x0)
      .def_readonly("x1", &femup::ElementIndicator::x1)
      .def_readonly("stiffness_factor", &femup::ElementIndicator::stiffness_factor)
      .def_readonly("stiffness_chi2_drop", &femup::ElementIndicator::stiffness_chi2_drop)
      .def_readonly("mass_factor", &femup::ElementIndicator::mass_factor)
      .def_readonly("mass_chi2_drop", &femup::ElementIndicator::mass_chi2_drop);

  py::class_<femup::DiagnosisResult>(m, "DiagnosisResult",
                                     "What `femup diagnose` computes for a cantilever.")
      .def_readonly("study_name", &femup::DiagnosisResult::study_name)
      .def_readonly("verdict", &femup::DiagnosisResult::verdict)
      .def_readonly("verdict_probability", &femup::DiagnosisResult::verdict_probability)
      .def_readonly("separated", &femup::DiagnosisResult::separated)
      .def_readonly("indistinguishable", &femup::DiagnosisResult::indistinguishable)
      .def_readonly("confidence", &femup::DiagnosisResult::confidence)
      .def_property_readonly(
          "candidates",
          [](py::object self) {
            return RefList(self.cast<const femup::DiagnosisResult&>().candidates, self);
          },
          "the classes, most probable first")
      .def_readonly("kind_probabilities", &femup::DiagnosisResult::kind_probabilities)
      .def_readonly("localisation", &femup::DiagnosisResult::localisation)
      .def_readonly("temperature", &femup::DiagnosisResult::temperature)
      .def_readonly("best_chi2_p_value", &femup::DiagnosisResult::best_chi2_p_value)
      .def_readonly("degrees_of_freedom", &femup::DiagnosisResult::degrees_of_freedom)
      .def_readonly("frequency_noise", &femup::DiagnosisResult::frequency_noise)
      .def_readonly("shape_noise", &femup::DiagnosisResult::shape_noise)
      .def_readonly("mesh_error", &femup::DiagnosisResult::mesh_error)
      .def_readonly("form_error", &femup::DiagnosisResult::form_error)
      .def_readonly("warnings", &femup::DiagnosisResult::warnings)
      .def(
          "gap",
          [](const femup::DiagnosisResult& r, int index) {
            if (index < -1 || index >= static_cast<int>(r.candidates.size())) {
              throw femup::InputError("index", "no class " + std::to_string(index));
            }
            if (index < 0) return Gap(r, r.nominal_fitted, r.nominal_held_out);
            const auto& c = r.candidates[static_cast<std::size_t>(index)];
            return Gap(r, c.fitted, c.held_out);
          },
          py::arg("index") = -1,
          "The gap summary of diagnosis.json (gap_before for index -1, the nominal "
          "model; "
          "gap_after of the class at `index`): rms_frequency_error, mean_mac and their "
          "held-out counterparts.")
      .def(
          "frequencies",
          [](const femup::DiagnosisResult& r, int index, bool held_out) {
            if (index < -1 || index >= static_cast<int>(r.candidates.size())) {
              throw femup::InputError("index", "no class " + std::to_string(index));
            }
            const auto& data = held_out ? r.held_out_data : r.fitted_data;
            if (index < 0)
              return Frequencies(data, held_out ? r.nominal_held_out : r.nominal_fitted);
            const auto& c = r.candidates[static_cast<std::size_t>(index)];
            return Frequencies(data, held_out ? c.held_out : c.fitted);
          },
          py::arg("index") = -1, py::arg("held_out") = false,
          "Measured and predicted frequencies and MACs (arrays) of the nominal model "
          "(index -1) or a class, on fitted or held-out modes.")
      .def("report", &femup::DiagnosisReport);
  m.def("run_diagnosis", &femup::RunDiagnosis, py::arg("study"),
        py::call_guard<py::gil_scoped_release>(),
        "The cantilever's diagnosis (InputError for other models: use "
        "run_structure_diagnosis, or diagnose for either).");

  py::class_<femup::PairedModeMisfit>(
      m, "PairedModeMisfit",
      "What a fit predicts for one measured mode: the paired model frequency and "
      "the MAC at the sensors (NaN where shapes were not compared).")
      .def_readonly("state", &femup::PairedModeMisfit::state)
      .def_readonly("mode", &femup::PairedModeMisfit::mode)
      .def_readonly("measured_hz", &femup::PairedModeMisfit::measured_hz)
      .def_readonly("model_hz", &femup::PairedModeMisfit::model_hz)
      .def_readonly("mac", &femup::PairedModeMisfit::mac);

  py::class_<femup::HeldOutCheck>(
      m, "HeldOutCheck",
      "The verdict fitted again without the held-out modes, and its and the nominal "
      "model's predictions of them.")
      .def_readonly("kind", &femup::HeldOutCheck::kind)
      .def_readonly("region", &femup::HeldOutCheck::region)
      .def_readonly("theta", &femup::HeldOutCheck::theta)
      .def_readonly("nominal", &femup::HeldOutCheck::nominal)
      .def_readonly("refit", &femup::HeldOutCheck::refit)
      .def_readonly("ok", &femup::HeldOutCheck::ok)
      .def_readonly("why", &femup::HeldOutCheck::why);

  py::class_<femup::RankedClass>(m, "RankedClass",
                                 "One class of the ranking on any structure.")
      .def_readonly("kind", &femup::RankedClass::kind)
      .def_readonly("region", &femup::RankedClass::region)
      .def_readonly("probability", &femup::RankedClass::probability)
      .def_readonly("laplace_probability", &femup::RankedClass::laplace_probability)
      .def_readonly("group_probability", &femup::RankedClass::group_probability)
      .def_readonly("equivalent", &femup::RankedClass::equivalent)
      .def_readonly("names", &femup::RankedClass::names)
      .def_readonly("theta", &femup::RankedClass::theta)
      .def_readonly("chi2", &femup::RankedClass::chi2)
      .def_readonly("explained", &femup::RankedClass::explained,
                    "the share of the nominal misfit beyond the noise the class removes")
      .def_readonly("frequency_temperature", &femup::RankedClass::frequency_temperature)
      .def_readonly("evidence", &femup::RankedClass::evidence)
      .def_readonly("log_prior", &femup::RankedClass::log_prior)
      .def_readonly("converged", &femup::RankedClass::converged)
      .def_readonly("fitted", &femup::RankedClass::fitted)
      .def_readonly("location", &femup::RankedClass::location)
      .def_readonly("magnitudes", &femup::RankedClass::magnitudes)
      .def_readonly("modes", &femup::RankedClass::modes,
                    "Each measured mode at the class's fit (for none: the nominal "
                    "model's), state by state.")
      .def("__repr__", [](const femup::RankedClass& c) {
        return "<femup.RankedClass " + c.kind +
               (c.region.empty() ? "" : " at " + c.region) + ": " +
               std::to_string(c.probability) + ">";
      });
  py::class_<femup::FormErrorAllowance>(m, "FormErrorAllowance")
      .def_readonly("name", &femup::FormErrorAllowance::name)
      .def_readonly("max_frequency_change",
                    &femup::FormErrorAllowance::max_frequency_change)
      .def_readonly("noise_units", &femup::FormErrorAllowance::noise_units);
  py::class_<femup::EffectRanking>(m, "EffectRanking")
      .def_readonly("classes", &femup::EffectRanking::classes)
      .def_readonly("kind_probabilities", &femup::EffectRanking::kind_probabilities)
      .def_property_readonly(
          "family_presence",
          [](const femup::EffectRanking& r) { return femup::FamilyPresence(r); },
          "Each family's probability alone or in a pair (femup::FamilyPresence).")
      .def_readonly("held_out", &femup::EffectRanking::held_out,
                    "The held-out check (diagnosis.held_out), or None.")
      .def_readonly("gap_probability", &femup::EffectRanking::gap_probability)
      .def_readonly("gap_below_confidence", &femup::EffectRanking::gap_below_confidence)
      .def_readonly("gap_unexplained", &femup::EffectRanking::gap_unexplained)
      .def_readonly("gap_within_noise", &femup::EffectRanking::gap_within_noise)
      .def_readonly("nominal_misfit", &femup::EffectRanking::nominal_misfit)
      .def_readonly("noise_misfit", &femup::EffectRanking::noise_misfit)
      .def_readonly("temperature", &femup::EffectRanking::temperature)
      .def_readonly("shape_temperature", &femup::EffectRanking::shape_temperature)
      .def_property_readonly("frequency_temperature",
                             [](const femup::EffectRanking& r) {
                               return femup::ToString(r.frequency_temperature);
                             })
      .def_readonly("best_chi2_p_value", &femup::EffectRanking::best_chi2_p_value)
      .def_readonly("num_residuals", &femup::EffectRanking::num_residuals)
      .def_readonly("bagging_copies", &femup::EffectRanking::bagging_copies)
      .def_readonly("skipped", &femup::EffectRanking::skipped)
      .def_readonly("form_errors", &femup::EffectRanking::form_errors);
  py::class_<femup::StructureDiagnosisResult>(
      m, "StructureDiagnosisResult", "What `femup diagnose` computes for other models.")
      .def_readonly("study_name", &femup::StructureDiagnosisResult::study_name)
      .def_readonly("model_type", &femup::StructureDiagnosisResult::model_type)
      .def_readonly("measured", &femup::StructureDiagnosisResult::measured)
      .def_readonly("dof_labels", &femup::StructureDiagnosisResult::dof_labels)
      .def_readonly("ranking", &femup::StructureDiagnosisResult::ranking)
      .def_property_readonly(
          "classes",
          [](const femup::StructureDiagnosisResult& r) { return r.ranking.classes; })
      .def_readonly("confidence", &femup::StructureDiagnosisResult::confidence)
      .def("report", &femup::StructureDiagnosisReport);
  m.def("run_structure_diagnosis", &femup::RunStructureDiagnosis, py::arg("study"),
        py::call_guard<py::gil_scoped_release>(),
        "The diagnosis on any model (effects as changes of the model), femup "
        "diagnose's default engine.");
  m.def(
      "diagnose",
      [](const femup::Study& study) -> py::object {
        if (study.measurements.empty()) {
          throw femup::InputError(study.path, "measurements: missing");
        }
        const femup::DiagnosisSpec spec =
            study.diagnosis.value_or(femup::DiagnosisSpec());
        if (spec.Engine() == "model_effects") {
          femup::StructureDiagnosisResult r;
          {
            py::gil_scoped_release release;
            r = femup::RunStructureDiagnosis(study);
          }
          return py::cast(std::move(r));
        }
        femup::DiagnosisResult r;
        {
          py::gil_scoped_release release;
          r = femup::RunDiagnosis(study);
        }
        return py::cast(std::move(r));
      },
      py::arg("study"),
      "`femup diagnose`: run_structure_diagnosis, or run_diagnosis for a cantilever "
      "whose diagnosis.engine is cantilever, as the command line dispatches.");
}

void BindModesAndSimulate(py::module_& m) {
  py::class_<femup::ModesResult>(m, "ModesResult", "What `femup modes` computes.")
      .def_readonly("study_name", &femup::ModesResult::study_name)
      .def_readonly("model_description", &femup::ModesResult::model_description)
      .def_readonly("nominal", &femup::ModesResult::nominal)
      .def_readonly("dof_labels", &femup::ModesResult::dof_labels)
      .def_readonly("max_residual", &femup::ModesResult::max_residual)
      .def_readonly("max_orthogonality_error",
                    &femup::ModesResult::max_orthogonality_error)
      .def("report", &femup::ModesReport);
  m.def("run_modes", &femup::RunModes, py::arg("study"), py::arg("num_modes") = 0,
        py::call_guard<py::gil_scoped_release>(),
        "Modal analysis of the study's nominal model (num_modes <= 0: all, or 10 above "
        "1500 DOFs).");

  py::class_<femup::SimulatedState>(m, "SimulatedState")
      .def_property_readonly("state",
                             [](const femup::SimulatedState& s) { return s.spec.state; })
      .def_property_readonly("immersion",
                             [](const femup::SimulatedState& s) {
                               return femup::ToString(s.spec.immersion);
                             })
      .def_property_readonly(
          "records", [](const femup::SimulatedState& s) { return s.response.data; },
          "channels x samples (accelerations, noise included)")
      .def_property_readonly(
          "sample_rate_hz",
          [](const femup::SimulatedState& s) { return s.response.sample_rate_hz; })
      .def_readonly("sensors", &femup::SimulatedState::sensors)
      .def_readonly("frequencies_hz", &femup::SimulatedState::frequencies_hz)
      .def_readonly("damping_ratios", &femup::SimulatedState::damping_ratios)
      .def_readonly("shapes", &femup::SimulatedState::shapes)
      .def_readonly("cutoff_hz", &femup::SimulatedState::cutoff_hz);
  py::class_<femup::SimulateResult>(m, "SimulateResult",
                                    "What `femup simulate` computes.")
      .def_readonly("study_name", &femup::SimulateResult::study_name)
      .def_readonly("sample_rate_hz", &femup::SimulateResult::sample_rate_hz)
      .def_readonly("impulse_label", &femup::SimulateResult::impulse_label)
      .def_readonly("states", &femup::SimulateResult::states)
      .def("report", &femup::SimulateReport);
  m.def(
      "run_simulate", &femup::RunSimulate, py::arg("study"),
      py::call_guard<py::gil_scoped_release>(),
      "Test records of the study's `records:` (its truth factors, strip-theory water).");
}

}  // namespace

void InitPipelines(py::module_& m) {
  BindUpdate(m);
  BindNoise(m);
  BindDiagnosis(m);
  BindModesAndSimulate(m);
}

}  // namespace femup_python
