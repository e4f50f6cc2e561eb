#include "femup/studies/simulate_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/fe/dof_labels.h"
#include "femup/core/fe/strip_theory.h"
#include "femup/core/io/csv_series.h"
#include "femup/core/io/uff.h"
#include "femup/core/linalg/modal.h"

namespace femup {
namespace {

// Structural mass per length of the top element, whose nodes are both free
// (for reporting the added mass as a ratio).
double TopElementMassPerLength(const Structure& s) {
  const Eigen::VectorXd r = internal::TransverseUnitTranslation(s.dof_labels);
  for (auto it = s.elements.rbegin(); it != s.elements.rend(); ++it) {
    if (it->x1 > it->x0) return r.dot(it->mass * r) / (it->x1 - it->x0);
  }
  return 0;
}

}  // namespace

SimulateResult RunSimulate(const Study& study) {
  if (!study.records) {
    throw InputError(study.path,
                     "records: the study has no records section "
                     "(sample_rate_hz, duration_s, sensors, impulse, states)");
  }
  const RecordsSpec& rs = *study.records;
  const ParametrisedModel& model = study.model;
  SimulateResult r;
  r.study_name = study.name;
  r.description = study.structure.description;
  r.sample_rate_hz = rs.sample_rate_hz;
  r.impulse_dof = rs.impulse_dof;
  r.impulse_label = model.dof_labels()[rs.impulse_dof];
  const Eigen::VectorXd d =
      study.truth ? *study.truth : Eigen::VectorXd::Zero(model.num_parameters());
  const SparseMatrix stiffness = model.UpdatedStiffness(d);
  const double structural_mass_per_length = TopElementMassPerLength(study.structure);
  for (std::size_t k = 0; k < rs.states.size(); ++k) {
    const RecordStateSpec& spec = rs.states[k];
    SimulatedState st;
    st.spec = spec;
    SparseMatrix mass = spec.immersion == Immersion::kWet ? model.UpdatedWetMass(d)
                                                          : model.UpdatedDryMass(d);
    if (spec.water) {
      const StripTheoryWater& w = *spec.water;
      const std::string where = "records.states[" + std::to_string(k + 1) + "].water";
      try {
        st.added_mass_coefficient =
            w.coefficient > 0 ? w.coefficient
                              : RectangleAddedMassCoefficient(w.width, w.thickness);
        st.added_mass_per_length =
            StripAddedMassPerLength(w.fluid_density, w.width, st.added_mass_coefficient);
        mass += WetTransverseAddedMass(study.structure, st.added_mass_per_length, w.depth,
                                       w.fade);
      } catch (const InputError& e) {
        throw InputError(study.path, where + ": " + e.what());
      }
    }
    st.structural_mass_per_length = structural_mass_per_length;
    const Modes all = SolveModes(stiffness, mass);
    // An ideal anti-aliasing filter: modes above the cut-off are left out.
    const double cutoff = rs.cutoff_hz > 0 ? rs.cutoff_hz : 0.4 * rs.sample_rate_hz;
    const Eigen::VectorXd all_hz = all.FrequenciesHz();
    int kept = 0;
    while (kept < all.size() && all_hz[kept] <= cutoff) ++kept;
    if (kept == 0) {
      throw InputError(study.path, "records: no mode lies below the cut-off of " +
                                       std::to_string(cutoff) + " Hz");
    }
    Modes modes;
    modes.eigenvalues = all.eigenvalues.head(kept);
    modes.shapes = all.shapes.leftCols(kept);
    st.cutoff_hz = cutoff;
    TimeResponseOptions o;
    o.sample_rate_hz = rs.sample_rate_hz;
    o.duration_s = rs.duration_s;
    o.sensor_dofs = rs.sensor_dofs;
    o.quantity = ResponseQuantity::kAcceleration;
    o.damping = DampingModel::kModal;
    for (int j = 0; j < modes.size(); ++j) {
      o.damping_ratios.push_back(
          spec.damping_ratios[std::min<std::size_t>(j, spec.damping_ratios.size() - 1)]);
    }
    o.noise_level = rs.noise;
    o.noise_seed = rs.seed + 1000003ULL * k;  // a different stream per state
    Eigen::VectorXd impulse = Eigen::VectorXd::Zero(model.num_dofs());
    impulse[rs.impulse_dof] = rs.impulse;
    st.response = SimulateImpulseResponse(modes, impulse, o);
    for (int dof : rs.sensor_dofs) st.sensors.push_back(model.dof_labels()[dof]);
    // The modes recorded, with their shapes at the sensors.
    const Eigen::VectorXd hz = modes.FrequenciesHz();
    std::vector<int> keep;
    for (int j = 0; j < modes.size(); ++j) {
      if (hz[j] > 0) keep.push_back(j);
    }
    st.frequencies_hz.resize(static_cast<Eigen::Index>(keep.size()));
    st.damping_ratios.resize(static_cast<Eigen::Index>(keep.size()));
    st.shapes.resize(static_cast<Eigen::Index>(rs.sensor_dofs.size()),
                     static_cast<Eigen::Index>(keep.size()));
    for (std::size_t j = 0; j < keep.size(); ++j) {
      const auto c = static_cast<Eigen::Index>(j);
      st.frequencies_hz[c] = hz[keep[j]];
      st.damping_ratios[c] = o.damping_ratios[keep[j]];
      for (std::size_t i = 0; i < rs.sensor_dofs.size(); ++i)
        st.shapes(static_cast<Eigen::Index>(i), c) =
            modes.shapes(rs.sensor_dofs[i], keep[j]);
      Eigen::Index imax = 0;
      const double peak = st.shapes.col(c).cwiseAbs().maxCoeff(&imax);
      if (peak > 0) st.shapes.col(c) /= st.shapes(imax, c);
    }
    r.states.push_back(std::move(st));
  }
  return r;
}

}  // namespace femup
