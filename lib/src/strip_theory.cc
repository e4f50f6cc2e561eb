#include "femup/strip_theory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "assembly.h"
#include "femup/errors.h"
#include "femup/fe.h"

namespace femup {

using internal::FromTriplets;
using internal::Scatter;
using internal::Triplets;

namespace {

const double kPi = std::acos(-1.0);

std::string Str(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

void RequirePositiveFinite(const char* field, double v, const char* unit) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw InputError(
        field, "must be positive and finite (" + std::string(unit) + "), got " + Str(v));
  }
}

// DNV-RP-C205 (2010) Table A-1, rectangle: a/b (finite entries, increasing) and
// C_A. The entry a/b = inf, C_A = 1 is handled separately.
constexpr std::array<double, 7> kAOverB = {0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0};
constexpr std::array<double, 7> kRectangleCa = {2.23, 1.98, 1.70, 1.51, 1.36, 1.21, 1.14};

// 4-point Gauss-Legendre on [-1, 1]: exact for polynomials of degree <= 7.
constexpr std::array<double, 4> kGaussX = {
    -0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480,
    0.86113631159405257522};
constexpr std::array<double, 4> kGaussW = {0.34785484513745385737, 0.65214515486254614263,
                                           0.65214515486254614263,
                                           0.34785484513745385737};

using Vector6 = Eigen::Matrix<double, 6, 1>;

// Global ux along a vertical element (nodes at heights z0 < z1, x = 0) in terms
// of its global DOFs [ux1 uy1 rz1 ux2 uy2 rz2], at xi = (z - z0) / L. The local
// transverse axis of fe.h is -x for such an element, so the rotation terms
// change sign: a positive rz (counter-clockwise) tilts the axis towards -x.
Vector6 TransverseShape(double xi, double length) {
  const double xi2 = xi * xi, xi3 = xi2 * xi;
  Vector6 n;
  n << 1 - 3 * xi2 + 2 * xi3, 0, -length * (xi - 2 * xi2 + xi3), 3 * xi2 - 2 * xi3, 0,
      -length * (xi3 - xi2);
  return n;
}

// Adds the integral over [lo, hi] (heights) of N N' m(z) with m(z) = m_lo at lo
// varying linearly to m_hi at hi.
void AddPiece(double z0, double length, double lo, double hi, double m_lo, double m_hi,
              Matrix6* out) {
  if (!(hi > lo)) return;
  const double half = 0.5 * (hi - lo);
  for (std::size_t q = 0; q < kGaussX.size(); ++q) {
    const double t = 0.5 * (1 + kGaussX[q]);  // 0..1 along the piece
    const double z = lo + t * (hi - lo);
    const double m = m_lo + t * (m_hi - m_lo);
    const Vector6 n = TransverseShape((z - z0) / length, length);
    *out += (kGaussW[q] * half * m) * (n * n.transpose());
  }
}

struct Node {
  bool seen = false;
  double z = 0;
  std::array<int, 3> dof = {-1, -1, -1};  // ux, uy, rz
};

const char kNotCantilever[] = "not a vertical cantilever from BuildCantilever: ";

// Nodes of a BuildCantilever structure from its DOF labels and positions.
std::vector<Node> CantileverNodes(const Structure& s) {
  const std::size_t n = s.dof_labels.size();
  const std::size_t num_elements = s.elements.size();
  if (num_elements == 0) {
    throw InputError("structure.elements", std::string(kNotCantilever) + "no elements");
  }
  if (s.dof_positions.size() != n) {
    throw InputError("structure.dof_positions",
                     std::string(kNotCantilever) + "has " +
                         std::to_string(s.dof_positions.size()) + " entries for " +
                         std::to_string(n) + " DOF labels");
  }
  if (static_cast<std::size_t>(s.stiffness.rows()) != n) {
    throw InputError("structure.dof_labels",
                     std::string(kNotCantilever) + "has " + std::to_string(n) +
                         " labels for " + std::to_string(s.stiffness.rows()) + " DOFs");
  }
  static const char* kNames[3] = {"ux", "uy", "rz"};
  std::vector<Node> nodes(num_elements + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& label = s.dof_labels[i];
    const std::string where = "structure.dof_labels[" + std::to_string(i + 1) + "]";
    const std::size_t colon = label.find(':');
    int kind = -1;
    long node = -1;
    if (label.size() > 1 && label[0] == 'n' && colon != std::string::npos && colon > 1) {
      const std::string digits = label.substr(1, colon - 1);
      if (digits.find_first_not_of("0123456789") == std::string::npos &&
          digits.size() < 9) {
        node = std::stol(digits);
      }
      for (int k = 0; k < 3; ++k) {
        if (label.compare(colon + 1, std::string::npos, kNames[k]) == 0) kind = k;
      }
    }
    if (node < 0 || kind < 0) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' is not 'n<k>:ux', 'n<k>:uy' or 'n<k>:rz'");
    }
    if (static_cast<std::size_t>(node) > num_elements) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' names a node beyond the " +
                                  std::to_string(num_elements) + " elements");
    }
    Node& nd = nodes[node];
    const double z = s.dof_positions[i];
    if (nd.dof[kind] >= 0 || (nd.seen && nd.z != z)) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' repeats a DOF or disagrees on the node height");
    }
    nd.seen = true;
    nd.z = z;
    nd.dof[kind] = static_cast<int>(i);
  }
  for (std::size_t e = 0; e < num_elements; ++e) {
    const ElementMatrices& el = s.elements[e];
    const std::string where = "structure.elements[" + std::to_string(e + 1) + "]";
    const double expected_x0 = e == 0 ? 0.0 : s.elements[e - 1].x1;
    if (!(el.x1 > el.x0) || !std::isfinite(el.x1) || el.x0 != expected_x0) {
      throw InputError(where, std::string(kNotCantilever) + "x0 = " + Str(el.x0) +
                                  ", x1 = " + Str(el.x1) +
                                  "; expected increasing heights from 0, each element "
                                  "starting where the one below ends");
    }
    const Node& lower = nodes[e];
    const Node& upper = nodes[e + 1];
    if ((e > 0 && !lower.seen) || !upper.seen || (lower.seen && lower.z != el.x0) ||
        upper.z != el.x1) {
      throw InputError(where, std::string(kNotCantilever) + "nodes n" +
                                  std::to_string(e) + " and n" + std::to_string(e + 1) +
                                  " do not have DOFs at x0 = " + Str(el.x0) +
                                  " and x1 = " + Str(el.x1));
    }
  }
  return nodes;
}

}  // namespace

double RectangleAddedMassCoefficient(double width_normal, double depth_along) {
  RequirePositiveFinite("width_normal", width_normal, "m");
  if (!(depth_along >= 0) || !std::isfinite(depth_along)) {
    throw InputError("depth_along",
                     "must be finite and >= 0 (m), got " + Str(depth_along));
  }
  const double b_over_a = depth_along / width_normal;
  if (b_over_a <= 1.0 / kAOverB.back()) {
    // a/b >= 10: linear in b/a from the flat plate (b/a = 0, C_A = 1).
    const double t = b_over_a * kAOverB.back();
    return (1 - t) * 1.0 + t * kRectangleCa.back();
  }
  const double a_over_b = width_normal / depth_along;
  if (a_over_b < kAOverB.front()) {
    throw InputError("width_normal / depth_along",
                     "a/b = " + Str(a_over_b) +
                         " is outside the table of DNV-RP-C205 Table A-1, which covers "
                         "a/b in [0.1, inf)");
  }
  std::size_t k = 0;
  while (k + 2 < kAOverB.size() && a_over_b > kAOverB[k + 1]) ++k;
  const double t =
      std::log(a_over_b / kAOverB[k]) / std::log(kAOverB[k + 1] / kAOverB[k]);
  return (1 - t) * kRectangleCa[k] + t * kRectangleCa[k + 1];
}

double CircleAddedMassCoefficient() { return 1.0; }

double StripAddedMassPerLength(double fluid_density, double width_normal,
                               double coefficient) {
  RequirePositiveFinite("fluid_density", fluid_density, "kg/m^3");
  RequirePositiveFinite("width_normal", width_normal, "m");
  RequirePositiveFinite("coefficient", coefficient, "dimensionless C_A");
  const double a = 0.5 * width_normal;
  return coefficient * fluid_density * kPi * a * a;
}

SparseMatrix WetTransverseAddedMass(const Structure& s, double mass_per_length,
                                    double water_depth, double fade_length) {
  RequirePositiveFinite("mass_per_length", mass_per_length, "kg/m");
  if (!(water_depth >= 0) || !std::isfinite(water_depth)) {
    throw InputError("water_depth",
                     "must be finite and >= 0 (m), got " + Str(water_depth));
  }
  if (!(fade_length >= 0) || !std::isfinite(fade_length)) {
    throw InputError("fade_length",
                     "must be finite and >= 0 (m), got " + Str(fade_length));
  }
  const std::vector<Node> nodes = CantileverNodes(s);
  const int n = static_cast<int>(s.dof_labels.size());
  // Below z_fade the full mass per length; from z_fade to the surface it falls
  // linearly to 0. With no fade, z_fade is the surface.
  const double z_fade = water_depth - fade_length;
  const auto m_at = [&](double z) {
    if (z >= water_depth) return 0.0;
    if (z <= z_fade) return mass_per_length;
    return mass_per_length * (water_depth - z) / fade_length;
  };
  Triplets t;
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const double z0 = s.elements[e].x0, z1 = s.elements[e].x1;
    if (z0 >= water_depth) break;  // this and all above are dry
    const double length = z1 - z0;
    Matrix6 me = Matrix6::Zero();
    // Full part [z0, min(z1, z_fade)], faded part [max(z0, z_fade), min(z1, depth)].
    const double full_hi = std::min(z1, z_fade);
    AddPiece(z0, length, z0, full_hi, mass_per_length, mass_per_length, &me);
    if (fade_length > 0) {
      const double lo = std::max(z0, z_fade), hi = std::min(z1, water_depth);
      AddPiece(z0, length, lo, hi, m_at(lo), m_at(hi), &me);
    }
    const Node& a = nodes[e];
    const Node& b = nodes[e + 1];
    const std::array<int, 6> dof = {a.dof[0], a.dof[1], a.dof[2],
                                    b.dof[0], b.dof[1], b.dof[2]};
    Scatter(0.5 * (me + me.transpose()), dof, &t);
  }
  return FromTriplets(n, t);
}

}  // namespace femup
