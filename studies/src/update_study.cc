// femup run (update_study.h): RunUpdate, the nominal model's modes, the
// correction factors, the updated model and its comparison with the measured
// modes; update_study_outputs.cc writes the files, plots and the report.
#include "femup/studies/update_study.h"

#include <algorithm>
#include <limits>

#include "femup/core/errors.h"
#include "femup/core/fe/dof_labels.h"
#include "femup/core/linalg/modal.h"
#include "femup/studies/factor_solve.h"

namespace femup {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Pairs predicted modes with the measured ones (by MAC when shapes exist,
// otherwise by order) and fills frequencies, MACs and shapes at the sensors.
void Compare(const ModalData& measured, const ModalData& predicted, int num_dofs,
             Eigen::VectorXd* hz, Eigen::VectorXd* mac, Eigen::MatrixXd* shapes_out,
             std::vector<int>* dofs_out) {
  const int nm = measured.num_modes();
  hz->setConstant(nm, kNaN);
  mac->setConstant(nm, kNaN);
  // The model DOF of each sensor row (none for sensors between nodes).
  std::vector<int> dofs = measured.sensor_dofs;
  if (dofs.empty() && !measured.HasInterpolatedSensors()) {
    for (int i = 0; i < num_dofs; ++i) dofs.push_back(i);
  }
  const Eigen::MatrixXd at_sensors = measured.AtSensors(predicted.shapes);
  shapes_out->setConstant(at_sensors.rows(), nm, kNaN);
  *dofs_out = dofs;
  if (measured.HasShapes()) {
    const auto pairs = PairModesByMac(measured.shapes, at_sensors, 0.0);
    for (int j = 0; j < nm; ++j) {
      const int c = pairs[j].candidate;
      if (c < 0) continue;
      (*hz)[j] = predicted.frequencies_hz[c];
      (*mac)[j] = pairs[j].mac;
      Eigen::VectorXd s = at_sensors.col(c);
      // Scale to the measured shape for plotting (least squares).
      const double ss = s.squaredNorm();
      if (ss > 0) s *= s.dot(measured.shapes.col(j)) / ss;
      shapes_out->col(j) = s;
    }
  } else {
    for (int j = 0; j < nm && j < predicted.num_modes(); ++j) {
      (*hz)[j] = predicted.frequencies_hz[j];
    }
  }
}

AddedMassSummary SummariseAddedMass(const Study& study, const Eigen::VectorXd& d,
                                    const SparseMatrix& added_mass,
                                    const std::vector<PreparedState>& sources) {
  AddedMassSummary a;
  const ParametrisedModel& model = study.model;
  const std::vector<int> idx = model.ParametersOfKind(ParameterKind::kAddedMass);
  a.present = !idx.empty();
  double sum = 0;
  for (int i : idx) {
    for (int e : model.parameter(i).elements) {
      sum += d[i];
      ++a.wet_elements;
      // A space frame's factors list geometry elements, not the Structure's
      // groups (space_frame.h): no element length to take from it.
      const int k =
          study.structure.type == "space_frame" ? -1 : study.structure.FindElement(e);
      if (k >= 0) {
        const ElementMatrices& em = study.structure.elements[k];
        a.wet_length_m += em.x1 - em.x0;
      }
    }
  }
  if (a.wet_elements > 0) a.sa = sum / a.wet_elements;
  const Eigen::VectorXd r = internal::TransverseUnitTranslation(model.dof_labels());
  if (added_mass.rows() == r.size()) a.total_kg = r.dot(added_mass * r);
  if (a.wet_length_m > 0) a.per_length = a.total_kg / a.wet_length_m;
  const ModalData* dry = nullptr;
  const ModalData* wet = nullptr;
  for (const PreparedState& p : sources) {
    if (p.at_sensors.immersion == Immersion::kDry && !dry) dry = &p.at_sensors;
    if (p.at_sensors.immersion == Immersion::kWet && !wet) wet = &p.at_sensors;
  }
  if (dry && wet) {
    for (int k = 0; k < std::min(dry->num_modes(), wet->num_modes()); ++k) {
      const double q = dry->frequencies_hz[k] / wet->frequencies_hz[k];
      a.eq2_coefficients.push_back(q * q - 1.0);
    }
  }
  return a;
}

}  // namespace

UpdateResult RunUpdate(const Study& study) {
  UpdateResult r;
  r.study_name = study.name;
  r.model_description = study.structure.description;
  r.num_dofs = study.model.num_dofs();
  r.dof_positions = study.structure.dof_positions;
  r.plot_dofs = study.structure.plot_dofs;
  r.dof_labels = study.model.dof_labels();
  for (const Parameter& p : study.model.parameters()) {
    Parameter copy = p;
    copy.basis = BasisMatrix();
    r.parameters.push_back(copy);
  }
  r.preset = study.truth;
  r.form = study.system.form;

  // Step 1: FEM modes of the nominal model.
  const Modes fem = FemModesFor(study);
  r.normal_system = UsesNormalCorrectionSystem(study);
  r.num_fem_modes = r.normal_system                  ? study.model.num_dofs()
                    : study.system.num_fem_modes < 0 ? fem.size()
                                                     : study.system.num_fem_modes;

  // Step 2: the factors, by the linear method (Z d = F) or eigen-sensitivity.
  r.sources = PrepareMeasurements(study);
  std::vector<ModalData> measured;
  for (const PreparedState& p : r.sources) measured.push_back(p.data);
  FactorSolve fs = SolveFactors(study, study.solver, fem, measured);
  r.problem = std::move(fs.problem);
  r.solution = std::move(fs.solution);
  r.method = study.solver.method;
  r.solver_name = study.solver.name;
  if (r.problem.A.size() > 0) {
    r.identifiability_unconstrained =
        AnalyseIdentifiability(r.problem.A, r.problem.names, r.problem.groups,
                               study.solver.linear.relative_rank_tolerance);
  }
  r.fixed.assign(r.parameters.size(), false);
  for (const auto& f : r.problem.fixed) r.fixed[f.first] = true;

  // Steps 3-4: the added-mass matrix, the updated model and the comparison.
  const Eigen::VectorXd& d = r.solution.x;
  r.added_mass = study.model.AddedMass(d);
  r.updated_stiffness = study.model.UpdatedStiffness(d);
  r.updated_dry_mass = study.model.UpdatedDryMass(d);
  if (d.allFinite())
    r.added_mass_summary = SummariseAddedMass(study, d, r.added_mass, r.sources);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(study.model.num_parameters());
  for (const PreparedState& source : r.sources) {
    // Compared where it was measured (at the sensors, before any expansion).
    const ModalData& m = source.at_sensors;
    StateComparison c;
    c.state = m.state;
    c.immersion = m.immersion;
    c.measured_hz = m.frequencies_hz;
    const int count = std::min(study.model.num_dofs(), m.num_modes() + 4);
    const ModalData nominal =
        PredictModes(study.model, zero, m.immersion, count, "model");
    std::vector<int> dofs;
    Compare(m, nominal, r.num_dofs, &c.model_hz, &c.model_mac, &c.model_shapes, &dofs);
    if (r.solution.summary.usable() && d.allFinite()) {
      try {
        const ModalData updated =
            PredictModes(study.model, d, m.immersion, count, "updated");
        Compare(m, updated, r.num_dofs, &c.updated_hz, &c.updated_mac, &c.updated_shapes,
                &c.shape_dofs);
      } catch (const InputError& e) {
        // The estimated factors can make the updated mass indefinite: a result.
        r.solution.summary.message +=
            " | updated model has no valid modes: " + std::string(e.what());
        c.updated_hz.setConstant(m.num_modes(), kNaN);
        c.updated_mac.setConstant(m.num_modes(), kNaN);
      }
    }
    c.shape_dofs = dofs;
    c.measured_shapes = m.HasShapes() ? m.shapes : Eigen::MatrixXd();
    r.states.push_back(c);
  }
  return r;
}

}  // namespace femup
