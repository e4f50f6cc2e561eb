// The blind benchmark generator's effects (blind_benchmark.cc), shared with its
// Bayes oracle (benchmark_oracle.cc) so that both use one definition: the
// true effects' forms, the ranges their properties are drawn from, and how a
// drawn size sets an effect's strength. Internal to the studies layer.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/problems/effect_fit.h"

namespace femup {
namespace benchmark_generator {

// The kinds the generator draws from, in its order.
inline const std::vector<std::string>& Kinds() {
  static const std::vector<std::string> kinds = {"added_mass", "support_flexibility",
                                                 "attached_mass", "stiffness_loss",
                                                 "material_scaling"};
  return kinds;
}

// The ranges the generator draws an effect's properties from (uniform unless
// said otherwise). Lengths are fractions of the beam's length L.
struct Ranges {
  // The single suite: no effect with probability kSingleNoneShare, else one
  // effect of a kind drawn uniformly.
  static constexpr double kSingleNoneShare = 1.0 / 6;
  // material_scaling: E lower than modelled with probability kLowerShare.
  static constexpr double kLowerShare = 0.5;
  // added_mass: depth; with probability kFadeShare a linear fade over the top
  // fraction (of the depth) in [kFadeMin, kFadeMax], else none.
  static constexpr double kDepthMin = 0.3, kDepthMax = 1.0;
  static constexpr double kFadeShare = 0.5, kFadeMin = 0.05, kFadeMax = 0.3;
  // support_flexibility: with probability kBothShare rotation and translation
  // (translational compliance = a x rotational, a in [kRatioMin, kRatioMax]),
  // else rotation only.
  static constexpr double kBothShare = 0.5, kRatioMin = 0.2, kRatioMax = 2.0;
  // attached_mass: in diagnosis element k (0-based) from kFirstElement to the
  // last, uniformly, at a fraction [kInElementMin, kInElementMax] of it; radius
  // of gyration (m) in [kGyrationMin, kGyrationMax].
  static constexpr int kFirstElement = 6;
  static constexpr double kInElementMin = 0.2, kInElementMax = 0.8;
  static constexpr double kGyrationMin = 0.01, kGyrationMax = 0.05;
  // stiffness_loss: width and centre.
  static constexpr double kWidthMin = 0.02, kWidthMax = 0.2;
  static constexpr double kCentreMin = 0.1, kCentreMax = 0.9;
  // Sizes "noise": the largest frequency shift in noise units, log-uniform in
  // [kStrongMin, kStrongMax] with probability kStrongShare, else in
  // [kWeakMin, kWeakMax]. Sizes "absolute": log-uniform relative shift in
  // [kAbsoluteMin, kAbsoluteMax].
  static constexpr double kStrongShare = 0.8, kStrongMin = 5, kStrongMax = 50;
  static constexpr double kWeakMin = 1, kWeakMax = 5;
  static constexpr double kAbsoluteMin = 0.005, kAbsoluteMax = 0.2;
};

// A true effect of a given kind with a strength s in (0, 1] that sets its size;
// the other properties (where, form) are drawn once.
struct TrueEffect {
  std::string kind;
  double a = 0, b = 0, c = 0;  // kind-specific draws
  int variant = 0;
  double strength = 0;

  void Apply(double s, CantileverSpec* spec) const {
    const double length = spec->node_heights.back();
    const double rho_a = spec->section.rho * spec->section.A;
    const double ei = spec->section.E * spec->section.I;
    if (kind == "added_mass") {
      CantileverSpec::DistributedMass m;
      m.z0 = 0;
      m.z1 = a;    // depth
      m.fade = b;  // fade length
      m.mass_per_length = 3 * s * rho_a;
      spec->distributed_masses.push_back(m);
    } else if (kind == "support_flexibility") {
      const double c_rot = 5 * s;     // EI / (k L)
      const double c_tr = c_rot * a;  // 3 EI / (k L^3) relative
      if (variant != 2) spec->support_rotation = ei / (length * c_rot);
      if (variant != 1)
        spec->support_transverse = 3 * ei / (length * length * length * c_tr);
    } else if (kind == "attached_mass") {
      CantileverSpec::PointMass p;
      p.height = a;
      p.mass = s * rho_a * length;
      p.rotary_inertia = p.mass * b * b;  // radius of gyration b
      spec->point_masses.push_back(p);
    } else if (kind == "stiffness_loss") {
      CantileverSpec::StiffnessChange ch;
      ch.z0 = std::max(0.0, a - 0.5 * b);
      ch.z1 = std::min(length, a + 0.5 * b);
      ch.factor = -0.9 * s;
      spec->stiffness_changes.push_back(ch);
    } else if (kind == "material_scaling") {
      spec->section.E *= 1 + a * 0.5 * s;  // a = +-1
    }
  }
};

// The lowest `modes` bending frequencies of `spec` (empty where it cannot be
// solved).
inline Eigen::VectorXd BendingFrequencies(const CantileverSpec& spec, int modes) {
  Eigen::VectorXd f;
  Eigen::MatrixXd unused;
  std::string why;
  if (!BendingModesAtSensors(spec, {}, modes, &f, &unused, &why)) return {};
  return f;
}

// The largest relative shift of the bending frequencies `f0` of `fine` that
// effect `e` at strength s causes (1 where the changed model cannot be solved).
inline double FrequencyShift(const TrueEffect& e, const CantileverSpec& fine,
                             const Eigen::VectorXd& f0, double s) {
  CantileverSpec spec = fine;
  e.Apply(s, &spec);
  const Eigen::VectorXd f1 = BendingFrequencies(spec, static_cast<int>(f0.size()));
  if (f1.size() != f0.size()) return 1.0;
  return (f1.array() / f0.array() - 1).abs().maxCoeff();
}

// The generator's strength for a target shift of the frequencies f0 of `fine`:
// bisection on (0, 1], 1 where even that falls short of the target.
inline double CalibrateStrength(const TrueEffect& e, const CantileverSpec& fine,
                                const Eigen::VectorXd& f0, double target) {
  auto shift = [&](double s) { return FrequencyShift(e, fine, f0, s); };
  double lo = 0, hi = 1;
  if (shift(hi) <= target) return hi;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (shift(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace benchmark_generator
}  // namespace femup
