// A sensor: a point on the structure and the direction it measures in. Its
// reading of a displacement field (a mode shape) is a weighted sum of the
// model's DOFs, interpolated with the shape functions of the line element the
// point lies on, so meshes need not follow the sensors (issue 26, item 3).
//
// Along a straight line element from end A to end B (length L, unit axis e,
// xi in [0, 1] the point's position), with translations u and rotation vectors
// theta at the ends:
//   u(xi) = e e' ((1 - xi) u_A + xi u_B)                     axial: linear
//         + P (N1 u_A + N3 u_B) + L (N2 theta_A + N4 theta_B) x e   bending
// P = I - e e', and N1..N4 the cubic Hermite functions (1 - 3 xi^2 + 2 xi^3,
// xi - 2 xi^2 + xi^3, 3 xi^2 - 2 xi^3, -xi^2 + xi^3): the transverse
// displacement of an Euler-Bernoulli element, exact for any end loads, and
// its slope at an end is theta x e. The reading along a unit direction d is
// d' u(xi), so the weight of theta_A is L N2 (e x d). The rotation at xi
// (for a point mass's rotary inertia) is the axis' twist interpolated
// linearly plus the bending rotation e x du/ds.
//
// DOFs the model does not have at a node are held at zero there (a rigid
// support); a direction the model has no DOFs for anywhere (z on a plane
// frame) is an error.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/core/invalid.h"

namespace femup {

// Where a sensor is, as a study states it: exactly one of a DOF label, a node
// (with a direction), a point (with a direction), or a position along a
// cantilever (the direction defaults to its transverse x).
struct SensorSpec {
  std::string dof;   // "n3:ux"; a leading '-' reverses the sensor
  std::string node;  // "n12"
  bool has_at = false;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  // m, the model's axes
  bool has_x = false;
  double x = 0;  // m from the base along a cantilever
  // A unit vector, or zero: the default where there is one (a cantilever's
  // transverse x).
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};

// A sensor placed on the model: the reading is sum_k weight_k phi[dof_k].
struct SensorRow {
  std::string name;  // "n3:ux", or "x=1.23:ux", "at(1, 2, 0):uy"
  std::vector<std::pair<int, double>> weights;  // (model DOF, weight), DOFs distinct
  // The single DOF the sensor reads with weight 1 (a sensor on a node along a
  // DOF's axis), or -1.
  int SingleDof() const;
};

// "x", "-y", "z" -> a unit vector along that axis. Invalid names what was
// expected. (A study may also give three numbers; its reader normalises them.)
Invalid ParseSensorDirection(const std::string& text, Eigen::Vector3d* direction);

// Places `spec` on `structure`. Invalid (field "dof", "node", "at", "x" or
// "direction") for a DOF label the model lacks, an unknown node, a point
// farther from every line element than 1e-3 of its length (naming the nearest
// and how far), a position along a model that is not a cantilever or beyond
// its length, no direction where one is needed, or a direction the model has
// no DOFs for.
Invalid LocateSensor(const Structure& structure, const SensorSpec& spec, SensorRow* row);

// Interpolation weights at a point xi in [0, 1] of a line element: the
// translation along `direction` (rotation = false) or the rotation about it
// (rotation = true); with `slope`, the weights' derivatives with respect to xi
// (a point mass whose position is fitted). DOFs the model lacks
// are left out (held at zero).
std::vector<std::pair<int, double>> SegmentWeights(const Structure& structure,
                                                   const LineSegment& segment, double xi,
                                                   const Eigen::Vector3d& direction,
                                                   bool rotation, bool slope = false);

// The DOF indices of a structure by label ("n3:ux" -> 7), of every node or
// only of `nodes` (names) where that is not empty: made once for SegmentWeights
// in a loop (a point mass between nodes whose position is fitted asks at every
// evaluation).
using DofLabelIndex = std::map<std::string, int>;
DofLabelIndex IndexDofLabels(const Structure& structure,
                             const std::vector<std::string>& nodes = {});
// SegmentWeights with the index made once; it must hold the segment's nodes.
std::vector<std::pair<int, double>> SegmentWeights(const Structure& structure,
                                                   const DofLabelIndex& dofs,
                                                   const LineSegment& segment, double xi,
                                                   const Eigen::Vector3d& direction,
                                                   bool rotation, bool slope = false);

// The sensors' readings of full-DOF shapes: rows = sensors, one column per
// shape column.
Eigen::MatrixXd ReadSensors(const std::vector<SensorRow>& sensors,
                            const Eigen::MatrixXd& shapes);

// The sensors as a sparse matrix, sensors x num_dofs.
SparseMatrix SensorMatrix(const std::vector<SensorRow>& sensors, int num_dofs);

}  // namespace femup
