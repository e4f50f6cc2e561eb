// Measured modal data for one state of the structure (in air, in water, ...).
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/fe/sensor.h"

namespace femup {

enum class Immersion { kDry, kWet };        // which mass the state sees: M~dry or M~wet
const char* ToString(Immersion immersion);  // "dry", "wet"

struct ModalData {
  std::string state;  // a name: "air", "water", "water_1.2m"
  Immersion immersion = Immersion::kDry;
  Eigen::VectorXd frequencies_hz;  // one per measured mode, > 0
  // Mode shapes, one column per mode, one row per sensor DOF. Any scaling.
  Eigen::MatrixXd shapes;
  // Model DOF (0-based) of each row of `shapes`; empty means every model DOF in
  // order (rows == num_dofs).
  std::vector<int> sensor_dofs;
  // Sensors between nodes (sensor.h): row i of `shapes` is the reading
  // sensor_weights.row(i) * phi of a model shape phi. When given (rows: one per
  // shape row; columns: the model's DOFs), sensor_dofs is empty.
  SparseMatrix sensor_weights;
  std::vector<std::string> sensor_names;  // one per sensor row where given
  // Where the sensors were stated (one per row, with sensor_weights), so that
  // another mesh of the structure can place them again.
  std::vector<SensorSpec> sensor_specs;

  bool HasInterpolatedSensors() const { return sensor_weights.size() > 0; }
  // The rows of full-DOF shapes (one column each) that the sensors read.
  Eigen::MatrixXd AtSensors(const Eigen::MatrixXd& full) const;

  int num_modes() const { return static_cast<int>(frequencies_hz.size()); }
  Eigen::VectorXd Eigenvalues() const;  // (2 pi f)^2, rad^2/s^2
  bool HasShapes() const { return shapes.cols() > 0; }
  bool IsComplete(int num_dofs) const;  // shapes given at every model DOF
  // Throws InputError (naming `where`) on non-positive or non-finite
  // frequencies, NaN shapes, shape count/size mismatches, bad sensor DOFs.
  void Validate(int num_dofs, const std::string& where) const;
  // Shapes on all model DOFs (rows in model order). Throws InputError when the
  // shapes are incomplete.
  Eigen::MatrixXd FullShapes(int num_dofs, const std::string& where) const;
};

// The modes the model predicts for factors d in the given immersion: the lowest
// `num_modes` eigenpairs of (K~, M~dry) or (K~, M~wet), shapes at all DOFs.
ModalData PredictModes(const ParametrisedModel& model, const Eigen::VectorXd& d,
                       Immersion immersion, int num_modes, const std::string& state);

}  // namespace femup
