// Study files: loaded from a path or parsed from text (femup/__init__.py turns
// a Python dict into that text), with the C++ reader's checks and messages;
// the study's parts, its measured states and one identification of its
// factors (SolveFactors, any method and solver).
#include <optional>
#include <string>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/studies/factor_solve.h"
#include "femup/studies/study.h"

namespace femup_python {

namespace {

void BindSpecs(py::module_& m) {
  py::class_<femup::SolverSpec>(m, "SolverSpec", "How the factors are found (`solver:`).")
      .def(py::init<>())
      .def_readwrite("label", &femup::SolverSpec::label)
      .def_readwrite("method", &femup::SolverSpec::method, "linear or sensitivity")
      .def_readwrite("name", &femup::SolverSpec::name,
                     "linear: lstsq, tsvd, tikhonov, bvls, ceres, ipopt; sensitivity: "
                     "ceres, ipopt")
      .def_readwrite("linear", &femup::SolverSpec::linear)
      .def_readwrite("nonlinear", &femup::SolverSpec::nonlinear)
      .def_readwrite("sensitivity", &femup::SolverSpec::sensitivity)
      .def_readwrite("prior_mean", &femup::SolverSpec::prior_mean);

  py::class_<femup::NoiseStudySpec>(m, "NoiseStudySpec", "The study's `noise_study:`.")
      .def(py::init<>())
      .def_readwrite("levels", &femup::NoiseStudySpec::levels)
      .def_readwrite("shape_level_ratio", &femup::NoiseStudySpec::shape_level_ratio)
      .def_readwrite("shape_noise", &femup::NoiseStudySpec::shape_noise)
      .def_readwrite("compare", &femup::NoiseStudySpec::compare)
      .def_readwrite("draws", &femup::NoiseStudySpec::draws)
      .def_readwrite("seed", &femup::NoiseStudySpec::seed)
      .def_readwrite("figure_level", &femup::NoiseStudySpec::figure_level);

  py::class_<femup::DiagnosisSpec>(m, "DiagnosisSpec", "The study's `diagnosis:`.")
      .def(py::init<>())
      .def_readwrite("frequency_noise", &femup::DiagnosisSpec::frequency_noise)
      .def_readwrite("shape_noise", &femup::DiagnosisSpec::shape_noise)
      .def_readwrite("candidates", &femup::DiagnosisSpec::candidates)
      .def_readwrite("max_effects", &femup::DiagnosisSpec::max_effects)
      .def_readwrite("pair_places", &femup::DiagnosisSpec::pair_places)
      .def_readwrite("held_out", &femup::DiagnosisSpec::held_out)
      .def_readwrite("use_shapes", &femup::DiagnosisSpec::use_shapes)
      .def_readwrite("mesh_error", &femup::DiagnosisSpec::mesh_error)
      .def_readwrite("formulation_error", &femup::DiagnosisSpec::formulation_error)
      .def_readwrite("form_error_on_shapes", &femup::DiagnosisSpec::form_error_on_shapes)
      .def_readwrite("form_step", &femup::DiagnosisSpec::form_step)
      .def_readwrite("form_fit", &femup::DiagnosisSpec::form_fit)
      .def_readwrite("stiffness_uncertainty",
                     &femup::DiagnosisSpec::stiffness_uncertainty)
      .def_readwrite("mass_uncertainty", &femup::DiagnosisSpec::mass_uncertainty)
      .def_readwrite("gap_confidence", &femup::DiagnosisSpec::gap_confidence)
      .def_readwrite("gap_explained", &femup::DiagnosisSpec::gap_explained)
      .def_property(
          "frequency_temperature",
          [](const femup::DiagnosisSpec& d) {
            return femup::ToString(d.frequency_temperature);
          },
          [](femup::DiagnosisSpec& d, const std::string& name) {
            const auto t = femup::FrequencyTemperatureNamed(name);
            if (!t) {
              throw femup::InputError(
                  "DiagnosisSpec.frequency_temperature",
                  "expected auto, threshold or marginal, found '" + name + "'");
            }
            d.frequency_temperature = *t;
          },
          "\"auto\" (marginal unless the model's own form variants are allowed for), "
          "\"threshold\" (the best fit's temperature where it fails) or \"marginal\" "
          "(each class's evidence integrated over it)")
      .def_readwrite("rotary_inertia", &femup::DiagnosisSpec::rotary_inertia)
      .def_readwrite("refine_mesh", &femup::DiagnosisSpec::refine_mesh)
      .def_readwrite("engine", &femup::DiagnosisSpec::engine)
      .def_readwrite("bagging_copies", &femup::DiagnosisSpec::bagging_copies)
      .def_readwrite("form_error", &femup::DiagnosisSpec::form_error)
      .def_readwrite("localise", &femup::DiagnosisSpec::localise)
      .def_readwrite("solver", &femup::DiagnosisSpec::solver)
      .def_readwrite("confidence", &femup::DiagnosisSpec::confidence)
      .def_readwrite("evidence", &femup::DiagnosisSpec::evidence)
      .def_readwrite("evidence_samples", &femup::DiagnosisSpec::evidence_samples);

  py::class_<femup::MeasurementSpec>(m, "MeasurementSpec",
                                     "One entry of `measurements:`.")
      .def_readonly("state", &femup::MeasurementSpec::state)
      .def_property_readonly(
          "immersion",
          [](const femup::MeasurementSpec& s) { return femup::ToString(s.immersion); })
      .def_readonly("simulate_modes", &femup::MeasurementSpec::simulate_modes)
      .def_readonly("data", &femup::MeasurementSpec::data, "the modes given in the study")
      .def_readonly("modes_file", &femup::MeasurementSpec::modes_file)
      .def_property_readonly("identify_file",
                             [](const femup::MeasurementSpec& s) {
                               return s.identify ? s.identify->file : std::string();
                             })
      .def_readonly("use_modes", &femup::MeasurementSpec::use_modes)
      .def_readonly("field", &femup::MeasurementSpec::field);

  py::class_<femup::PreparedState>(m, "PreparedState",
                                   "A measured state ready for the solvers.")
      .def_readonly("data", &femup::PreparedState::data, "what the factors are fitted to")
      .def_readonly("at_sensors", &femup::PreparedState::at_sensors,
                    "as measured, before expansion")
      .def_readonly("identified", &femup::PreparedState::identified,
                    "IdentifyResult when identified from a record file, else None")
      .def_readonly("identified_modes", &femup::PreparedState::identified_modes)
      .def_readonly("source", &femup::PreparedState::source)
      .def_readonly("expansion_method", &femup::PreparedState::expansion_method)
      .def_readonly("expansion_modes", &femup::PreparedState::expansion_modes)
      .def_readonly("expansion_sensor_mac", &femup::PreparedState::expansion_sensor_mac)
      .def_readonly("expansion_condition", &femup::PreparedState::expansion_condition);
}

void BindStudy(py::module_& m) {
  py::class_<femup::Study>(
      m, "Study",
      "A study file read and checked (femup.load_study, femup.study_from_dict). The "
      "solver, noise_study and diagnosis settings may be changed before a run, like "
      "the command line's --solver and --method.")
      .def_readonly("path", &femup::Study::path)
      .def_readwrite("name", &femup::Study::name)
      .def_readonly("description", &femup::Study::description)
      .def_readonly("structure", &femup::Study::structure)
      .def_readonly("model", &femup::Study::model)
      .def_property_readonly(
          "is_cantilever", [](const femup::Study& s) { return s.cantilever.has_value(); })
      .def_readonly("cantilever", &femup::Study::cantilever,
                    "the CantileverSpec when the model is a cantilever, else None")
      .def_readonly("truth", &femup::Study::truth, "preset factors (model order) or None")
      .def_readonly("fixed", &femup::Study::fixed)
      .def_readonly("lower", &femup::Study::lower)
      .def_readonly("upper", &femup::Study::upper)
      .def_readonly("equality_matrix", &femup::Study::equality_matrix)
      .def_readonly("equality_rhs", &femup::Study::equality_rhs)
      .def_readonly("measurements", &femup::Study::measurements)
      .def_property_readonly(
          "system_form",
          [](const femup::Study& s) { return femup::ToString(s.system.form); })
      .def_property_readonly("num_fem_modes",
                             [](const femup::Study& s) { return s.system.num_fem_modes; })
      .def_readwrite("solver", &femup::Study::solver)
      .def_property(
          "noise_study",
          [](femup::Study& s) { return s.noise_study ? &*s.noise_study : nullptr; },
          [](femup::Study& s, std::optional<femup::NoiseStudySpec> spec) {
            s.noise_study = std::move(spec);
          },
          py::return_value_policy::reference_internal,
          "NoiseStudySpec (changes apply to the study) or None")
      .def_property(
          "diagnosis",
          [](femup::Study& s) { return s.diagnosis ? &*s.diagnosis : nullptr; },
          [](femup::Study& s, std::optional<femup::DiagnosisSpec> spec) {
            s.diagnosis = std::move(spec);
          },
          py::return_value_policy::reference_internal,
          "DiagnosisSpec (changes apply to the study) or None")
      .def_readwrite("plots", &femup::Study::plots)
      .def("__repr__", [](const femup::Study& s) {
        return "<femup.Study " + s.name + ": " + s.structure.description + ", " +
               std::to_string(s.model.num_dofs()) + " DOFs, " +
               std::to_string(s.model.num_parameters()) + " factors, " +
               std::to_string(s.measurements.size()) + " measured state(s)>";
      });

  m.def("load_study", &femup::LoadStudy, py::arg("path"),
        "Reads and checks a study file (YAML or JSON); InputError names file, line, "
        "field.");
  m.def("parse_study", &femup::ParseStudy, py::arg("text"), py::arg("path"),
        "A study from its text; `path` stands for the file in messages, and file names "
        "in the study are relative to its folder.");
  m.def("parse_study_model", &femup::ParseStudyModel, py::arg("text"), py::arg("path"),
        "A study's model and factors alone (model, parameters, truth, name, "
        "description), checked as a study file is; no measurements needed.");
  m.def("prepare_measurements", &femup::PrepareMeasurements, py::arg("study"),
        py::call_guard<py::gil_scoped_release>(),
        "The measured states: given, simulated from the truth, identified from records, "
        "read from UFF modes; expanded where the study asks.");
  m.def("measured_states", &femup::MeasuredStates, py::arg("study"),
        py::call_guard<py::gil_scoped_release>());

  py::class_<femup::FactorSolve>(m, "FactorSolve")
      .def_readonly("problem", &femup::FactorSolve::problem,
                    "Z d = F with the constraints")
      .def_readonly("solution", &femup::FactorSolve::solution)
      .def_readonly("nonlinear_residuals", &femup::FactorSolve::nonlinear_residuals);
  m.def("fem_modes_for", &femup::FemModesFor, py::arg("study"),
        py::call_guard<py::gil_scoped_release>(),
        "The FEM modes of the nominal model that solve_factors needs.");
  m.def(
      "solve_factors",
      [](const femup::Study& study, const femup::SolverSpec& spec,
         const femup::Modes& fem_modes, const std::vector<femup::ModalData>& measured) {
        py::gil_scoped_release release;
        return femup::SolveFactors(study, spec, fem_modes, measured);
      },
      py::arg("study"), py::arg("spec"), py::arg("fem_modes"), py::arg("measured"),
      "One identification of the study's factors from `measured` (any method and "
      "solver), with its fixed values, bounds and equalities.");
}

}  // namespace

void InitStudies(py::module_& m) {
  BindSpecs(m);
  BindStudy(m);
}

}  // namespace femup_python
