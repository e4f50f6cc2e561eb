#include "femup/core/fe/beam_modifications.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fe/assembly.h"
#include "fe/cantilever_geometry.h"
#include "femup/core/errors.h"
#include "femup/core/fe/fe.h"
#include "text_util.h"

namespace femup {

using internal::CantileverNodes;
using internal::ElementDofs;
using internal::FromTriplets;
using internal::kGaussW;
using internal::kGaussX;
using internal::Node;
using internal::Scatter;
using internal::Triplets;
using internal::Vector6;

namespace {

std::string Str(double v) { return internal::ShortestDecimal(v); }

void RequireFinite(const char* field, double v, const char* unit) {
  if (!std::isfinite(v)) {
    throw InputError(field, "must be finite (" + std::string(unit) + "), got " + Str(v));
  }
}

void RequireNonNegative(const char* field, double v, const char* unit) {
  if (!(v >= 0) || !std::isfinite(v)) {
    throw InputError(
        field, "must be finite and >= 0 (" + std::string(unit) + "), got " + Str(v));
  }
}

// z0 in [0, tip) and z1 > z0; with `z1_within_tip`, also z1 <= tip.
void RequireInterval(double z0, double z1, double tip, bool z1_within_tip) {
  RequireFinite("z0", z0, "m");
  RequireFinite("z1", z1, "m");
  if (!(z0 >= 0 && z0 < tip)) {
    throw InputError("z0", "got " + Str(z0) + " m; expected a height in [0, " + Str(tip) +
                               ") (base to below the tip)");
  }
  if (!(z1 > z0)) {
    throw InputError("z1",
                     "got " + Str(z1) + " m; expected a height above z0 = " + Str(z0));
  }
  if (z1_within_tip && z1 > tip) {
    throw InputError("z1", "got " + Str(z1) + " m; expected a height in (z0, " +
                               Str(tip) + "] (at most the tip)");
  }
}

double Tip(const Structure& s) { return s.elements.back().x1; }

// Adds the integral over [lo, hi] (heights, within the element [z0, z0 + length])
// of N N^T m(z), N the transverse shape, with m(z) = m_lo at lo varying linearly
// to m_hi at hi. The integrand has degree <= 7: the Gauss rule is exact.
void AddMassPiece(double z0, double length, double lo, double hi, double m_lo,
                  double m_hi, Matrix6* out) {
  if (!(hi > lo)) return;
  const double half = 0.5 * (hi - lo);
  for (std::size_t q = 0; q < kGaussX.size(); ++q) {
    const double t = 0.5 * (1 + kGaussX[q]);  // 0..1 along the piece
    const double z = lo + t * (hi - lo);
    const double m = m_lo + t * (m_hi - m_lo);
    const Vector6 n = internal::TransverseShape((z - z0) / length, length);
    *out += (kGaussW[q] * half * m) * (n * n.transpose());
  }
}

// Calls f(e, ze0, length, lo, hi) for each element e of the cantilever that
// overlaps [z0, z1]: its start ze0 and length, and [lo, hi] the overlap.
template <typename F>
void ForEachOverlap(const Structure& s, double z0, double z1, F f) {
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const double ze0 = s.elements[e].x0, ze1 = s.elements[e].x1;
    const double lo = std::max(z0, ze0), hi = std::min(z1, ze1);
    if (hi > lo) f(e, ze0, ze1 - ze0, lo, hi);
  }
}

}  // namespace

SparseMatrix TransverseMassOverInterval(const Structure& s, double z0, double z1,
                                        double mass_per_length, double fade_length) {
  RequireNonNegative("mass_per_length", mass_per_length, "kg/m");
  RequireNonNegative("fade_length", fade_length, "m");
  const std::vector<Node> nodes = CantileverNodes(s);
  const double tip = Tip(s);
  RequireInterval(z0, z1, tip, /*z1_within_tip=*/false);
  const int n = static_cast<int>(s.dof_labels.size());
  // Full mass per length below z_fade; from z_fade up to z1 it falls linearly to
  // 0. With no fade, z_fade is z1.
  const double z_fade = z1 - fade_length;
  const auto m_at = [&](double z) {
    return z <= z_fade ? mass_per_length : mass_per_length * (z1 - z) / fade_length;
  };
  const double top = std::min(z1, tip);
  Triplets t;
  ForEachOverlap(s, z0, top,
                 [&](std::size_t e, double ze0, double length, double lo, double hi) {
                   Matrix6 me = Matrix6::Zero();
                   // Full part [lo, min(hi, z_fade)], faded part [max(lo, z_fade), hi].
                   AddMassPiece(ze0, length, lo, std::min(hi, z_fade), mass_per_length,
                                mass_per_length, &me);
                   if (fade_length > 0) {
                     const double flo = std::max(lo, z_fade);
                     AddMassPiece(ze0, length, flo, hi, m_at(flo), m_at(hi), &me);
                   }
                   Scatter(0.5 * (me + me.transpose()), ElementDofs(nodes, e), &t);
                 });
  return FromTriplets(n, t);
}

SparseMatrix BendingStiffnessOverInterval(const Structure& s, double z0, double z1,
                                          double delta_ei) {
  RequireFinite("delta_ei", delta_ei, "N m^2");
  const std::vector<Node> nodes = CantileverNodes(s);
  RequireInterval(z0, z1, Tip(s), /*z1_within_tip=*/true);
  const int n = static_cast<int>(s.dof_labels.size());
  Triplets t;
  ForEachOverlap(
      s, z0, z1, [&](std::size_t e, double ze0, double length, double lo, double hi) {
        // N'' is linear in z: degree 2, exact with the Gauss rule.
        const double half = 0.5 * (hi - lo);
        Matrix6 ke = Matrix6::Zero();
        for (std::size_t q = 0; q < kGaussX.size(); ++q) {
          const double z = lo + 0.5 * (1 + kGaussX[q]) * (hi - lo);
          const Vector6 b = internal::TransverseCurvature((z - ze0) / length, length);
          ke += (kGaussW[q] * half * delta_ei) * (b * b.transpose());
        }
        Scatter(0.5 * (ke + ke.transpose()), ElementDofs(nodes, e), &t);
      });
  return FromTriplets(n, t);
}

SparseMatrix AxialForceStiffness(const Structure& s, double axial_force) {
  RequireFinite("axial_force", axial_force, "N");
  const std::vector<Node> nodes = CantileverNodes(s);
  const int n = static_cast<int>(s.dof_labels.size());
  Triplets t;
  if (axial_force == 0) return FromTriplets(n, t);
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const double ze0 = s.elements[e].x0, length = s.elements[e].x1 - ze0;
    // N' is quadratic in z: N' N'^T has degree 4, exact with the Gauss rule.
    const double half = 0.5 * length;
    Matrix6 kg = Matrix6::Zero();
    for (std::size_t q = 0; q < kGaussX.size(); ++q) {
      const Vector6 g = internal::TransverseSlope(0.5 * (1 + kGaussX[q]), length);
      kg += (kGaussW[q] * half * axial_force) * (g * g.transpose());
    }
    Scatter(0.5 * (kg + kg.transpose()), ElementDofs(nodes, e), &t);
  }
  return FromTriplets(n, t);
}

SparseMatrix PointMassAt(const Structure& s, double z, double mass,
                         double rotary_inertia) {
  RequireFinite("z", z, "m");
  RequireNonNegative("mass", mass, "kg");
  RequireNonNegative("rotary_inertia", rotary_inertia, "kg m^2");
  const std::vector<Node> nodes = CantileverNodes(s);
  const double tip = Tip(s);
  if (!(z >= 0 && z <= tip)) {
    throw InputError("z", "got " + Str(z) + " m; expected a height in [0, " + Str(tip) +
                              "] (base to tip)");
  }
  // The lowest element that reaches z: a node above the base is the top end
  // (xi = 1) of the element below it, where the shapes are exactly 0 or 1.
  std::size_t e = 0;
  while (e + 1 < s.elements.size() && z > s.elements[e].x1) ++e;
  const double ze0 = s.elements[e].x0, length = s.elements[e].x1 - ze0;
  const double xi = (z - ze0) / length;
  const Vector6 nt = internal::TransverseShape(xi, length);
  const Vector6 na = internal::AxialShape(xi);
  const Vector6 nr = internal::TransverseSlope(xi, length);
  const Matrix6 me = mass * (nt * nt.transpose()) + mass * (na * na.transpose()) +
                     rotary_inertia * (nr * nr.transpose());
  Triplets t;
  Scatter(0.5 * (me + me.transpose()), ElementDofs(nodes, e), &t);
  return FromTriplets(static_cast<int>(s.dof_labels.size()), t);
}

}  // namespace femup
