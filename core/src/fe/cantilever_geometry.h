// Private to femup_core: the geometry of a vertical cantilever made by
// BuildCantilever (nodes and DOFs recovered from the labels, shape functions
// along an element, a Gauss rule), shared by the matrices of strip theory and of
// local modifications.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "femup/core/fe/structure.h"

namespace femup::internal {

// 4-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree <= 7.
inline constexpr std::array<double, 4> kGaussX = {
    -0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480,
    0.86113631159405257522};
inline constexpr std::array<double, 4> kGaussW = {
    0.34785484513745385737, 0.65214515486254614263, 0.65214515486254614263,
    0.34785484513745385737};

using Vector6 = Eigen::Matrix<double, 6, 1>;

// A node of the cantilever: its height and its global DOFs (-1 where fixed).
struct Node {
  bool seen = false;
  double z = 0;
  std::array<int, 3> dof = {-1, -1, -1};  // ux, uy, rz
};

// Nodes of a BuildCantilever structure (node k = "n<k>", element i joins nodes i
// and i+1) from its DOF labels, DOF positions and the elements' x0/x1. A base
// node with no labels is fully fixed. Throws InputError ("structure.*", "not a
// vertical cantilever from BuildCantilever") for anything else.
std::vector<Node> CantileverNodes(const Structure& s);

// Global DOFs [ux1 uy1 rz1 ux2 uy2 rz2] of element `e` (0-based).
inline std::array<int, 6> ElementDofs(const std::vector<Node>& nodes, std::size_t e) {
  const Node& a = nodes[e];
  const Node& b = nodes[e + 1];
  return {a.dof[0], a.dof[1], a.dof[2], b.dof[0], b.dof[1], b.dof[2]};
}

// Global ux along a vertical element (nodes at heights z0 < z1, x = 0) in terms
// of its global DOFs [ux1 uy1 rz1 ux2 uy2 rz2], at xi = (z - z0) / L. The local
// transverse axis of fe.h is -x for such an element, so the rotation terms
// change sign: a positive rz (counter-clockwise) tilts the axis towards -x, and
// rz = -dux/dz.
inline Vector6 TransverseShape(double xi, double length) {
  const double xi2 = xi * xi, xi3 = xi2 * xi;
  Vector6 n;
  n << 1 - 3 * xi2 + 2 * xi3, 0, -length * (xi - 2 * xi2 + xi3), 3 * xi2 - 2 * xi3, 0,
      -length * (xi3 - xi2);
  return n;
}

// d/dz of TransverseShape (z the height, 1/m on the ux terms).
inline Vector6 TransverseSlope(double xi, double length) {
  const double xi2 = xi * xi;
  Vector6 n;
  n << (-6 * xi + 6 * xi2) / length, 0, -(1 - 4 * xi + 3 * xi2),
      (6 * xi - 6 * xi2) / length, 0, -(3 * xi2 - 2 * xi);
  return n;
}

// d2/dz2 of TransverseShape.
inline Vector6 TransverseCurvature(double xi, double length) {
  const double l2 = length * length;
  Vector6 n;
  n << (-6 + 12 * xi) / l2, 0, (4 - 6 * xi) / length, (6 - 12 * xi) / l2, 0,
      (2 - 6 * xi) / length;
  return n;
}

// Global uy along the element (linear).
inline Vector6 AxialShape(double xi) {
  Vector6 n;
  n << 0, 1 - xi, 0, 0, xi, 0;
  return n;
}

}  // namespace femup::internal
