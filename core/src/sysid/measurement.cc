#include "femup/core/sysid/measurement.h"

#include <cmath>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/linalg/node_ordering.h"

namespace femup {

const char* ToString(Immersion immersion) {
  return immersion == Immersion::kWet ? "wet" : "dry";
}

Eigen::VectorXd ModalData::Eigenvalues() const {
  return (2 * M_PI * frequencies_hz.array()).square().matrix();
}

Eigen::MatrixXd ModalData::AtSensors(const Eigen::MatrixXd& full) const {
  if (HasInterpolatedSensors()) return sensor_weights * full;
  if (sensor_dofs.empty()) return full;
  return full(sensor_dofs, Eigen::all);
}

bool ModalData::IsComplete(int num_dofs) const {
  if (!HasShapes() || HasInterpolatedSensors()) return false;
  if (sensor_dofs.empty()) return shapes.rows() == num_dofs;
  std::vector<bool> seen(num_dofs, false);
  for (int d : sensor_dofs) {
    if (d >= 0 && d < num_dofs) seen[d] = true;
  }
  for (bool s : seen) {
    if (!s) return false;
  }
  return true;
}

void ModalData::Validate(int num_dofs, const std::string& where) const {
  if (num_modes() == 0) throw InputError(where + ".frequencies", "no mode is given");
  for (int j = 0; j < num_modes(); ++j) {
    if (!(frequencies_hz[j] > 0) || !std::isfinite(frequencies_hz[j])) {
      std::ostringstream msg;
      msg << "mode " << j + 1 << " has frequency " << frequencies_hz[j]
          << "; expected a positive finite value in Hz";
      throw InputError(where + ".frequencies", msg.str());
    }
  }
  if (!HasShapes()) return;
  if (shapes.cols() != num_modes()) {
    std::ostringstream msg;
    msg << shapes.cols() << " mode shapes for " << num_modes()
        << " frequencies; expected one shape per frequency";
    throw InputError(where + ".shapes", msg.str());
  }
  if (HasInterpolatedSensors()) {
    if (!sensor_dofs.empty()) {
      throw InputError(where + ".sensors",
                       "sensors are given both as DOFs and as interpolation weights");
    }
    if (sensor_weights.cols() != num_dofs || sensor_weights.rows() != shapes.rows()) {
      std::ostringstream msg;
      msg << "each shape has " << shapes.rows() << " entries for "
          << sensor_weights.rows() << " sensors on " << sensor_weights.cols()
          << " DOFs; expected one entry per sensor on the model's " << num_dofs
          << " DOFs";
      throw InputError(where + ".shapes", msg.str());
    }
    for (int k = 0; k < sensor_weights.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(sensor_weights, k); it; ++it) {
        if (!std::isfinite(it.value()))
          throw InputError(where + ".sensors", "has a NaN or infinite weight");
      }
    }
  }
  const int expected_rows = HasInterpolatedSensors() ? static_cast<int>(shapes.rows())
                            : sensor_dofs.empty()    ? num_dofs
                                                  : static_cast<int>(sensor_dofs.size());
  if (shapes.rows() != expected_rows) {
    std::ostringstream msg;
    msg << "each shape has " << shapes.rows() << " entries; expected " << expected_rows
        << (sensor_dofs.empty() ? " (one per model DOF; or list the sensors)"
                                : " (one per sensor)");
    throw InputError(where + ".shapes", msg.str());
  }
  if (!shapes.allFinite()) {
    throw InputError(where + ".shapes", "has a NaN or infinite entry");
  }
  for (std::size_t i = 0; i < sensor_dofs.size(); ++i) {
    if (sensor_dofs[i] < 0 || sensor_dofs[i] >= num_dofs) {
      std::ostringstream msg;
      msg << "sensor " << i + 1 << " is on DOF index " << sensor_dofs[i]
          << ", outside the model's " << num_dofs << " DOFs";
      throw InputError(where + ".sensors", msg.str());
    }
    for (std::size_t k = 0; k < i; ++k) {
      if (sensor_dofs[k] == sensor_dofs[i]) {
        throw InputError(where + ".sensors", "sensors " + std::to_string(k + 1) +
                                                 " and " + std::to_string(i + 1) +
                                                 " are on the same DOF");
      }
    }
  }
  for (int j = 0; j < num_modes(); ++j) {
    if (shapes.col(j).norm() == 0) {
      throw InputError(where + ".shapes",
                       "mode " + std::to_string(j + 1) + " is all zero");
    }
  }
}

Eigen::MatrixXd ModalData::FullShapes(int num_dofs, const std::string& where) const {
  if (!HasShapes()) {
    throw InputError(where + ".shapes",
                     "the linear correction-factor method needs mode shapes; none given");
  }
  if (HasInterpolatedSensors()) {
    std::ostringstream msg;
    msg << "shapes are read by " << shapes.rows()
        << " sensors between nodes; the linear method needs every DOF: expand them "
           "(expansion: {method: serep | lsq} on the measurement) or use method: "
           "sensitivity";
    throw InputError(where + ".shapes", msg.str());
  }
  if (!IsComplete(num_dofs)) {
    std::ostringstream msg;
    msg << "shapes are given at " << shapes.rows() << " of the model's " << num_dofs
        << " DOFs; the linear method needs every DOF: expand them (expansion: {method: "
           "serep | lsq | dynamic} on the measurement) or use method: sensitivity";
    throw InputError(where + ".shapes", msg.str());
  }
  if (sensor_dofs.empty()) return shapes;
  Eigen::MatrixXd full(num_dofs, shapes.cols());
  for (std::size_t i = 0; i < sensor_dofs.size(); ++i)
    full.row(sensor_dofs[i]) = shapes.row(i);
  return full;
}

ModalData PredictModes(const ParametrisedModel& model, const Eigen::VectorXd& d,
                       Immersion immersion, int num_modes, const std::string& state) {
  const SparseMatrix k = model.UpdatedStiffness(d);
  const SparseMatrix m =
      immersion == Immersion::kWet ? model.UpdatedWetMass(d) : model.UpdatedDryMass(d);
  EigenOptions options;
  options.num_modes = num_modes;
  const Modes modes = SolveModes(k, m, WithNodeOrdering(options, model.dof_labels()));
  ModalData out;
  out.state = state;
  out.immersion = immersion;
  out.frequencies_hz = modes.FrequenciesHz();
  out.shapes = modes.shapes;
  return out;
}

}  // namespace femup
