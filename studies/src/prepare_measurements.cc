// The measured states of a study, made ready for the solvers: simulated from
// the truth, given, identified from a record file by ERA, read from the
// modes.json of `femup identify` or from the modes of a UFF file (dataset 55);
// then expanded from the sensors to every DOF where the study asks.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/io/uff.h"
#include "femup/core/io/uff_modes.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/linalg/node_ordering.h"
#include "femup/core/sysid/expansion.h"
#include "femup/studies/study.h"
#include "modes_json.h"

namespace femup {
namespace {

using internal::FileModes;
using internal::ReadModesJson;

FileModes ModesOfIdentify(const IdentifyResult& r) {
  FileModes out;
  out.channels = r.channels;
  for (const StableMode& m : r.modes) {
    out.frequencies_hz.push_back(m.mode.frequency_hz);
    out.shapes.push_back(m.mode.shape);
  }
  return out;
}

std::string ListHz(const std::vector<double>& hz) {
  std::ostringstream s;
  s.precision(5);
  for (std::size_t i = 0; i < hz.size(); ++i) s << (i ? ", " : "") << hz[i];
  return hz.empty() ? "none" : s.str() + " Hz";
}

// Picks the used modes and maps the channels to model DOFs.
void FromFileModes(const MeasurementSpec& m, const FileModes& fm,
                   const std::string& source, int num_dofs, PreparedState* out) {
  const std::string where = m.field + (m.identify ? ".identify" : ".modes_file");
  std::vector<int> use = m.use_modes;
  if (use.empty()) {
    for (std::size_t k = 0; k < fm.frequencies_hz.size(); ++k)
      use.push_back(static_cast<int>(k) + 1);
  }
  if (use.empty()) {
    throw InputError(source, where +
                                 ": no mode was identified (see the stabilisation "
                                 "diagram; widen the orders or lower stable_orders)");
  }
  for (int k : use) {
    if (k > static_cast<int>(fm.frequencies_hz.size())) {
      throw InputError(m.field + ".modes",
                       "mode " + std::to_string(k) + " is asked for, but " + source +
                           " gives " + std::to_string(fm.frequencies_hz.size()) +
                           " stable mode(s): " + ListHz(fm.frequencies_hz));
    }
  }
  const std::size_t channels = m.channel_dofs.size();
  for (int k : use) {
    if (static_cast<std::size_t>(fm.shapes[k - 1].size()) != channels) {
      std::string names;
      for (std::size_t i = 0; i < fm.channels.size(); ++i)
        names += (i ? ", " : "") + fm.channels[i];
      throw InputError(m.field + ".sensors",
                       "lists " + std::to_string(channels) + " sensors, but " + source +
                           " has " + std::to_string(fm.shapes[k - 1].size()) +
                           " channels" + (names.empty() ? "" : " (" + names + ")") +
                           "; give one DOF label (or skip) per channel, in order");
    }
  }
  ModalData& d = out->data;
  d.state = m.state;
  d.immersion = m.immersion;
  for (std::size_t i = 0; i < channels; ++i) {
    if (m.channel_dofs[i] >= 0) d.sensor_dofs.push_back(m.channel_dofs[i]);
  }
  d.frequencies_hz.resize(static_cast<Eigen::Index>(use.size()));
  d.shapes.resize(static_cast<Eigen::Index>(d.sensor_dofs.size()),
                  static_cast<Eigen::Index>(use.size()));
  for (std::size_t j = 0; j < use.size(); ++j) {
    d.frequencies_hz[static_cast<Eigen::Index>(j)] = fm.frequencies_hz[use[j] - 1];
    const Eigen::VectorXd& v = fm.shapes[use[j] - 1];
    Eigen::Index row = 0;
    for (std::size_t i = 0; i < channels; ++i) {
      if (m.channel_dofs[i] < 0) continue;
      d.shapes(row++, static_cast<Eigen::Index>(j)) =
          m.channel_signs[i] * v[static_cast<Eigen::Index>(i)];
    }
  }
  out->identified_modes = use;
  out->source = source;
  d.Validate(num_dofs, source + " (" + m.field + ")");
}

// Modes of UFF dataset 55 at the DOFs the measurement's map gives (the
// geometry read here, from the modes file itself or another UFF file).
void FromUffModes(const Study& study, const MeasurementSpec& m, PreparedState* out) {
  const UffFile file = ReadUff(m.modes_file);
  UffDofMap map = *m.uff_map;
  if (map.by_geometry) {
    if (map.geometry_file == m.modes_file) {
      map.geometry = UffNodeCoordinates(file, map.geometry_file);
    } else {
      map.geometry = UffNodeCoordinates(ReadUff(map.geometry_file), map.geometry_file);
    }
  }
  UffModes u =
      ExtractUffModes(file, m.modes_file, map, study.model.dof_labels(), m.use_modes);
  ModalData& d = out->data;
  d.state = m.state;
  d.immersion = m.immersion;
  for (const UffSensor& s : u.sensors) d.sensor_dofs.push_back(s.dof);
  d.frequencies_hz.resize(static_cast<Eigen::Index>(u.modes.size()));
  for (std::size_t j = 0; j < u.modes.size(); ++j)
    d.frequencies_hz[static_cast<Eigen::Index>(j)] = u.modes[j].frequency_hz;
  d.shapes = u.shapes;
  out->identified_modes = u.used;
  out->source = m.modes_file;
  d.Validate(study.model.num_dofs(), m.modes_file + " (" + m.field + ")");
  out->uff = std::move(u);
}

void Expand(const Study& study, const MeasurementSpec& m, PreparedState* out) {
  const ExpansionOptions& o = *m.expansion;
  const ParametrisedModel& model = study.model;
  // The nominal model with the known (fixed) factors.
  Eigen::VectorXd d0 = Eigen::VectorXd::Zero(model.num_parameters());
  for (const auto& [name, value] : study.fixed) d0[model.FindParameter(name)] = value;
  const SparseMatrix k = model.UpdatedStiffness(d0);
  const SparseMatrix mass = m.immersion == Immersion::kWet ? model.UpdatedWetMass(d0)
                                                           : model.UpdatedDryMass(d0);
  const ModalData& s = out->at_sensors;
  const int sensors = s.HasInterpolatedSensors() ? static_cast<int>(s.shapes.rows())
                                                 : static_cast<int>(s.sensor_dofs.size());
  const int wanted = o.num_modes > 0 ? o.num_modes : sensors;
  EigenOptions eo;
  if (model.num_dofs() > eo.dense_limit)
    eo.num_modes = std::min(wanted, model.num_dofs() - 1);
  Modes modes;
  try {
    modes = SolveModes(k, mass, WithNodeOrdering(eo, model.dof_labels()));
  } catch (const InputError& e) {
    throw InputError(m.field + ".expansion", std::string("model modes: ") + e.what());
  }
  ModalData& d = out->data;
  d.sensor_dofs.clear();
  d.sensor_weights = SparseMatrix();
  d.sensor_names.clear();
  d.sensor_specs.clear();
  d.shapes.resize(model.num_dofs(), s.num_modes());
  out->expansion_method = o.method;
  out->expansion_modes = o.method == "dynamic" ? 0 : wanted;
  out->expansion_sensor_mac.resize(s.num_modes());
  out->expansion_condition.resize(s.num_modes());
  const Eigen::VectorXd lambda = s.Eigenvalues();
  for (int j = 0; j < s.num_modes(); ++j) {
    ExpandedShape e;
    try {
      e = s.HasInterpolatedSensors()
              ? ExpandShape(k, mass, modes, s.sensor_weights, s.shapes.col(j), lambda[j],
                            o)
              : ExpandShape(k, mass, modes, s.sensor_dofs, s.shapes.col(j), lambda[j], o);
    } catch (const InputError& err) {
      throw InputError(m.field + ".expansion",
                       "mode " + std::to_string(j + 1) + ": " + err.what());
    }
    d.shapes.col(j) = e.shape;
    out->expansion_sensor_mac[j] = e.sensor_mac;
    out->expansion_condition[j] = e.condition_number;
  }
}

}  // namespace

std::vector<PreparedState> PrepareMeasurements(const Study& study) {
  std::vector<PreparedState> out;
  for (const MeasurementSpec& m : study.measurements) {
    PreparedState p;
    if (m.simulate_modes > 0) {
      p.data =
          PredictModes(study.model, *study.truth, m.immersion, m.simulate_modes, m.state);
    } else if (m.identify) {
      p.identified = RunIdentify(*m.identify);
      FromFileModes(m, ModesOfIdentify(*p.identified), m.identify->file,
                    study.model.num_dofs(), &p);
    } else if (m.uff_map) {
      FromUffModes(study, m, &p);
    } else if (!m.modes_file.empty()) {
      FromFileModes(m, ReadModesJson(m.modes_file), m.modes_file, study.model.num_dofs(),
                    &p);
    } else {
      p.data = m.data;
    }
    p.at_sensors = p.data;
    if (m.expansion) Expand(study, m, &p);
    out.push_back(std::move(p));
  }
  return out;
}

std::vector<ModalData> MeasuredStates(const Study& study) {
  std::vector<ModalData> out;
  for (PreparedState& p : PrepareMeasurements(study)) out.push_back(std::move(p.data));
  return out;
}

}  // namespace femup
