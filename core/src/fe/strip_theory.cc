#include "femup/core/fe/strip_theory.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "fe/cantilever_geometry.h"
#include "femup/core/errors.h"
#include "femup/core/fe/beam_modifications.h"
#include "text_util.h"

namespace femup {

namespace {

const double kPi = std::acos(-1.0);

std::string Str(double v) { return internal::ShortestDecimal(v); }

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
  if (water_depth == 0) {
    internal::CantileverNodes(s);  // still a cantilever, or InputError
    const auto n = static_cast<Eigen::Index>(s.dof_labels.size());
    return SparseMatrix(n, n);
  }
  return TransverseMassOverInterval(s, 0, water_depth, mass_per_length, fade_length);
}

}  // namespace femup
