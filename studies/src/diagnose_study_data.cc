// The data of a diagnosis (diagnose_study_steps.h): the measured states as
// observed bending modes at their transverse sensors, the noise of each mode
// (stated, the nominal mesh's error and the form error), the fitted and
// held-out modes, and the nominal model's modes paired with them.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "diagnose_study_steps.h"
#include "femup/core/errors.h"
#include "femup/core/fe/sensor.h"

namespace femup::diagnose_steps {
namespace {

bool EndsWith(const std::string& s, const char* tail) {
  const std::string t(tail);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// Adds midpoints to every element.
CantileverSpec Refined(const CantileverSpec& spec) {
  CantileverSpec fine = spec;
  fine.node_heights.clear();
  for (std::size_t i = 0; i + 1 < spec.node_heights.size(); ++i) {
    fine.node_heights.push_back(spec.node_heights[i]);
    fine.node_heights.push_back(0.5 * (spec.node_heights[i] + spec.node_heights[i + 1]));
  }
  fine.node_heights.push_back(spec.node_heights.back());
  // Lumped masses sit on nodes: node k becomes node 2k.
  for (LumpedMass& m : fine.lumped_masses) m.node *= 2;
  return fine;
}

// Bending frequencies 1..count of a spec (no effects), for the mesh check.
Eigen::VectorXd BendingFrequencies(const CantileverSpec& spec, int count) {
  Eigen::VectorXd f;
  Eigen::MatrixXd unused;
  std::string why;
  if (!BendingModesAtSensors(spec, {}, count, &f, &unused, &why))
    throw InputError("model", "the nominal model cannot be solved: " + why);
  return f;
}

}  // namespace

void PrepareData(const Study& study, const DiagnosisSpec& spec,
                 const CantileverSpec& nominal, DiagnosisResult* result) {
  DiagnosisResult& r = *result;
  // Measured states as observed modes at their sensors.
  const std::vector<PreparedState> prepared = PrepareMeasurements(study);
  const std::vector<std::string>& labels = study.model.dof_labels();
  std::vector<ObservedState> observed;
  std::vector<std::vector<int>> sensor_rows;  // per state, the shape rows used
  bool any_wet = false;
  int highest = 1;
  for (std::size_t s = 0; s < prepared.size(); ++s) {
    const ModalData& md = prepared[s].at_sensors;
    ObservedState st;
    st.state = md.state;
    st.immersion = md.immersion;
    any_wet = any_wet || md.immersion == Immersion::kWet;
    std::vector<int> rows;  // rows of md.shapes used
    if (md.HasShapes()) {
      const int num_rows = static_cast<int>(md.shapes.rows());
      // Sensors between nodes read ux and rz of both ends of their element.
      const Eigen::SparseMatrix<double, Eigen::RowMajor> weights = md.sensor_weights;
      for (int i = 0; i < num_rows && md.HasInterpolatedSensors(); ++i) {
        std::vector<std::pair<std::string, double>> terms;
        bool axial = false;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(weights, i);
             it; ++it) {
          terms.emplace_back(labels.at(static_cast<std::size_t>(it.col())), it.value());
          axial = axial || EndsWith(terms.back().first, ":uy");
        }
        if (axial) continue;  // not a bending sensor
        rows.push_back(i);
        st.sensors.push_back(md.sensor_names.at(static_cast<std::size_t>(i)));
        st.sensor_terms.push_back(terms);
      }
      for (int i = 0; i < num_rows && !md.HasInterpolatedSensors(); ++i) {
        const int dof = md.sensor_dofs.empty() ? i : md.sensor_dofs[i];
        const std::string& label = labels.at(dof);
        if (EndsWith(label, ":uy")) continue;  // axial: not a bending sensor
        if (md.sensor_dofs.empty() && !EndsWith(label, ":ux")) continue;
        rows.push_back(i);
        st.sensors.push_back(label);
      }
      if (rows.size() < 2) {
        r.warnings.push_back(
            "state " + md.state +
            ": fewer than 2 transverse sensors; its shapes are not used");
        st.sensors.clear();
        st.sensor_terms.clear();
        rows.clear();
      }
    }
    for (int j = 1; j < md.num_modes(); ++j) {
      // A cantilever's bending modes come in one order (mode k has k - 1
      // nodes); the pairing and the mode numbers rely on it.
      if (!(md.frequencies_hz[j] > md.frequencies_hz[j - 1])) {
        std::ostringstream msg;
        msg << "state " << md.state << ": frequencies must be listed in ascending order "
            << "(bending mode 1 first); mode " << j << " is " << md.frequencies_hz[j - 1]
            << " Hz and mode " << j + 1 << " is " << md.frequencies_hz[j] << " Hz";
        throw InputError("measurements", msg.str());
      }
    }
    for (int j = 0; j < md.num_modes(); ++j) {
      ObservedMode m;
      m.number =
          prepared[s].identified_modes.empty() ? j + 1 : prepared[s].identified_modes[j];
      m.frequency_hz = md.frequencies_hz[j];
      m.frequency_sigma = spec.frequency_noise;
      if (!rows.empty()) {
        m.shape.resize(static_cast<Eigen::Index>(rows.size()));
        for (std::size_t i = 0; i < rows.size(); ++i)
          m.shape[static_cast<Eigen::Index>(i)] = md.shapes(rows[i], j);
      }
      highest = std::max(highest, m.number);
      st.modes.push_back(m);
    }
    observed.push_back(st);
    sensor_rows.push_back(rows);
  }

  // Discretisation error of the nominal mesh, added to the noise.
  Eigen::VectorXd mesh_error = Eigen::VectorXd::Zero(highest);
  if (spec.mesh_error) {
    const Eigen::VectorXd coarse = BendingFrequencies(nominal, highest);
    const Eigen::VectorXd fine = BendingFrequencies(Refined(nominal), highest);
    mesh_error = (coarse.array() / fine.array() - 1).abs().matrix();
  }

  // Fitted and held-out modes.
  r.fitted_data.nominal = r.held_out_data.nominal = nominal;
  r.fitted_data.shape_sigma = r.held_out_data.shape_sigma = spec.shape_noise;
  r.fitted_data.use_shapes = r.held_out_data.use_shapes = spec.use_shapes;
  r.fitted_data.wet_only_added_mass = r.held_out_data.wet_only_added_mass = any_wet;
  std::set<std::pair<std::string, int>> held(spec.held_out_modes.begin(),
                                             spec.held_out_modes.end());
  for (const auto& h : held) {
    const auto it =
        std::find_if(observed.begin(), observed.end(),
                     [&](const ObservedState& o) { return o.state == h.first; });
    if (it == observed.end())
      throw InputError("diagnosis.held_out",
                       "no measured state is called '" + h.first + "'");
    if (h.second < 1 || h.second > static_cast<int>(it->modes.size())) {
      throw InputError("diagnosis.held_out", "state " + h.first + " has modes 1.." +
                                                 std::to_string(it->modes.size()) +
                                                 ", not " + std::to_string(h.second));
    }
  }
  // Per state, the nominal model's modes by number (frequencies, and shapes at
  // the sensors) for the families' form error: a fraction of the nominal
  // model's misfit, per frequency and per shape entry (measured, not fitted,
  // so every class is judged with the same uncertainty); and the mesh's error
  // in the shapes: each entry's change when every element is halved (node k
  // becomes node 2k).
  for (std::size_t s = 0; s < observed.size(); ++s) {
    ObservedState& st = observed[s];
    const bool shape_mesh = spec.mesh_error && !st.sensors.empty();
    Eigen::VectorXd nominal_hz;
    Eigen::MatrixXd coarse, fine;
    if (shape_mesh || spec.form_error > 0) {
      std::string why;
      if (!BendingModesAtSensors(nominal, st.sensors, highest, &nominal_hz, &coarse, &why,
                                 st.sensor_terms))
        throw InputError("model", "the nominal model cannot be solved: " + why);
    }
    if (shape_mesh) {
      std::vector<std::string> fine_sensors;
      std::vector<std::vector<std::pair<std::string, double>>> fine_terms;
      const ModalData& md = prepared[s].at_sensors;
      if (md.HasInterpolatedSensors()) {  // the same points on the halved elements
        const Structure fine_beam = BuildCantilever(Refined(nominal));
        fine_sensors = st.sensors;
        for (const int row : sensor_rows[s]) {
          SensorRow placed;
          ThrowIfInvalid(
              LocateSensor(fine_beam, md.sensor_specs.at(static_cast<std::size_t>(row)),
                           &placed),
              study.measurements[s].field + ".sensors");
          fine_terms.emplace_back();
          for (const auto& [dof, w] : placed.weights)
            fine_terms.back().emplace_back(fine_beam.dof_labels[dof], w);
        }
      }
      for (std::size_t i = 0; i < st.sensors.size() && fine_terms.empty(); ++i) {
        const std::string& label = st.sensors[i];
        const std::size_t colon = label.find(':');
        fine_sensors.push_back("n" +
                               std::to_string(2 * std::stoi(label.substr(1, colon - 1))) +
                               label.substr(colon));
      }
      Eigen::VectorXd unused;
      std::string why;
      if (!BendingModesAtSensors(Refined(nominal), fine_sensors, highest, &unused, &fine,
                                 &why, fine_terms))
        throw InputError("model", "the refined nominal model cannot be solved: " + why);
    }
    for (std::size_t j = 0; j < st.modes.size(); ++j) {
      ObservedMode& m = st.modes[j];
      const int k = m.number - 1;
      const double e = mesh_error[k];
      const double form =
          spec.form_error > 0
              ? spec.form_error * std::abs(nominal_hz[k] / m.frequency_hz - 1)
              : 0.0;
      m.frequency_sigma =
          std::sqrt(m.frequency_sigma * m.frequency_sigma + e * e + form * form);
      if (m.shape.size() > 0 && (shape_mesh || spec.form_error > 0)) {
        const Eigen::VectorXd c = coarse.col(k);
        Eigen::ArrayXd var =
            Eigen::ArrayXd::Constant(m.shape.size(), spec.shape_noise * spec.shape_noise);
        if (shape_mesh) {
          const Eigen::VectorXd f = fine.col(k);
          var += (c - f * (f.dot(c) / f.squaredNorm())).array().square();
        }
        if (spec.form_error > 0) {
          const Eigen::VectorXd t = m.shape / m.shape.cwiseAbs().maxCoeff();
          var +=
              (spec.form_error * (c * (c.dot(t) / c.squaredNorm()) - t).array()).square();
        }
        m.shape_sigma = var.sqrt().matrix();
      }
      r.mesh_error.push_back(e);
      r.form_error.push_back(form);
    }
    ObservedState fit = st, out = st;
    fit.modes.clear();
    out.modes.clear();
    const int count = static_cast<int>(st.modes.size());
    for (int j = 0; j < count; ++j) {
      bool is_held = false;
      if (spec.held_out == "auto") {
        is_held = count >= 3 && j == count - 1;
      } else if (spec.held_out == "list") {
        is_held = held.count({st.state, j + 1}) > 0;
      }
      (is_held ? out : fit).modes.push_back(st.modes[j]);
    }
    // Both sets pair against all of the state's measured shapes, so a held-out
    // mode never takes the model mode a fitted one has.
    fit.companions = out.modes;
    out.companions = fit.modes;
    if (!fit.modes.empty()) r.fitted_data.states.push_back(fit);
    if (!out.modes.empty()) r.held_out_data.states.push_back(out);
  }
  if (r.fitted_data.states.empty())
    throw InputError("diagnosis.held_out",
                     "every measured mode is held out; none left to fit");
  {
    if (const Invalid bad = r.fitted_data.Validate())
      throw InputError("measurements", bad.ToString());
  }
  r.degrees_of_freedom = EffectDegreesOfFreedom(r.fitted_data);

  std::string why;
  if (!PredictEffectModes(r.fitted_data, {}, Eigen::VectorXd(), &r.nominal_fitted, &why))
    throw InputError("model", "the nominal model cannot be paired with the data: " + why);
  if (!r.held_out_data.states.empty() &&
      !PredictEffectModes(r.held_out_data, {}, Eigen::VectorXd(), &r.nominal_held_out,
                          &why))
    throw InputError("model", "the nominal model cannot be paired with the data: " + why);
}

}  // namespace femup::diagnose_steps
