#include "femup/problems/effects.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "femup/core/errors.h"
#include "vector_of.h"

namespace femup {

namespace {

using internal::VectorOf;

// The location of an effect acting along the whole beam.
EffectLocation WholeLength(const CantileverSpec& s) {
  EffectLocation l;
  l.x0 = 0;
  l.x1 = BeamLength(s);
  return l;
}

// Extra transverse mass per length over [0, depth], fading linearly to zero over
// its top `fade` fraction (water added mass decays towards the free surface).
class AddedMassEffect : public Effect {
 public:
  static constexpr double kMaxFade = 0.5;  // of the depth
  std::string kind() const override { return "added_mass"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    return {LogQuantity({"ln_mass_ratio", "ln(added mass per length / rho A)",
                         std::log(1e-3), std::log(5.0), false},
                        "kg_per_m", BeamMassPerLength(s)),
            LinearQuantity({"depth", "height above the support it reaches (m)",
                            0.05 * length, length, true},
                           "level_m", 1.0, 0.0, length),
            LinearQuantity(
                {"fade", "fraction of the depth over which it fades to zero at the top",
                 0.0, kMaxFade, false},
                "fade", 1.0, 0.0, kMaxFade)};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    std::vector<Eigen::VectorXd> out;
    for (double f : {0.3, 0.6, 0.95})
      out.push_back(VectorOf({std::log(0.05), f * length, 0.0}));
    return out;
  }
  void Apply(const Eigen::VectorXd& t, Immersion immersion, bool wet_only,
             const CantileverSpec& nominal, CantileverSpec* spec) const override {
    if (wet_only && immersion != Immersion::kWet) return;
    // A level at (or below) the support: no water (a stated prior may reach it).
    if (!(t[1] > 0)) return;
    CantileverSpec::DistributedMass m;
    m.z0 = 0;
    m.z1 = std::min(t[1], BeamLength(nominal));
    m.mass_per_length = std::exp(t[0]) * BeamMassPerLength(nominal);
    m.fade = std::clamp(t[2], 0.0, kMaxFade) * m.z1;
    spec->distributed_masses.push_back(m);
  }
  EffectLocation Location(const CantileverSpec&,
                          const Eigen::VectorXd& t) const override {
    EffectLocation l;
    l.depth = t[1];
    l.x0 = 0;
    l.x1 = t[1];
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& s,
                                          const Eigen::VectorXd& t) const override {
    const double m = std::exp(t[0]) * BeamMassPerLength(s);
    const double fade = std::clamp(t[2], 0.0, kMaxFade) * t[1];
    return {{"added_mass_per_length", "kg/m", m},
            {"added_mass_ratio", "1 (per rho A)", std::exp(t[0])},
            {"fade_length", "m", fade},
            {"added_mass_total", "kg", m * (t[1] - 0.5 * fade)}};
  }
};

// Springs at the base in series with the nominal support (rigid when 0).
class SupportFlexibilityEffect : public Effect {
 public:
  std::string kind() const override { return "support_flexibility"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec&) const override {
    return {LogQuantity({"ln_rotation_compliance", "ln(EI / (k_rotation L))",
                         std::log(1e-6), std::log(10.0), false},
                        "rotation_compliance_ratio", 1.0),
            LogQuantity({"ln_translation_compliance", "ln(3 EI / (k_translation L^3))",
                         std::log(1e-6), std::log(10.0), false},
                        "translation_compliance_ratio", 1.0)};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec&) const override {
    return {VectorOf({std::log(1e-3), std::log(1e-5)}),
            VectorOf({std::log(1e-5), std::log(1e-3)}),
            VectorOf({std::log(0.03), std::log(0.03)})};
  }
  static double Series(double nominal, double added) {
    // 0 in a CantileverSpec means rigid.
    return nominal > 0 ? 1.0 / (1.0 / nominal + 1.0 / added) : added;
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    const double ei = BeamBendingStiffness(nominal), length = BeamLength(nominal);
    const double k_rot = ei / (length * std::exp(t[0]));
    const double k_tr = 3 * ei / (length * length * length * std::exp(t[1]));
    spec->support_rotation = Series(spec->support_rotation, k_rot);
    spec->support_transverse = Series(spec->support_transverse, k_tr);
  }
  EffectLocation Location(const CantileverSpec&, const Eigen::VectorXd&) const override {
    EffectLocation l;
    l.x = 0;
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& s,
                                          const Eigen::VectorXd& t) const override {
    const double ei = BeamBendingStiffness(s), length = BeamLength(s);
    return {{"rotational_stiffness", "N m/rad", ei / (length * std::exp(t[0]))},
            {"translational_stiffness", "N/m",
             3 * ei / (length * length * length * std::exp(t[1]))},
            {"rotation_compliance_ratio", "1 (EI / (k L))", std::exp(t[0])},
            {"translation_compliance_ratio", "1 (3 EI / (k L^3))", std::exp(t[1])}};
  }
};

// A point mass at height x, with its rotary inertia m r^2 where fitted.
class AttachedMassEffect : public Effect {
 public:
  explicit AttachedMassEffect(bool rotary) : rotary_(rotary) {}
  std::string kind() const override { return "attached_mass"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    std::vector<EffectParameter> p = {
        LogQuantity(
            {"ln_mass_ratio", "ln(mass / rho A L)", std::log(1e-4), std::log(2.0), false},
            "mass_kg", BeamMassPerLength(s) * length),
        LinearQuantity({"x", "height above the support (m)", 0.02 * length, length, true},
                       "x_m", 1.0, 0.0, length)};
    if (rotary_) {
      p.push_back(RadiusOfGyrationParameter(length));
    }
    return p;
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    std::vector<Eigen::VectorXd> out;
    for (double f : {0.25, 0.5, 0.75, 1.0}) {
      out.push_back(rotary_ ? VectorOf({std::log(0.02), f * length, std::log(0.01)})
                            : VectorOf({std::log(0.02), f * length}));
    }
    // A mass at the top whose inertia matters (a tip body of a tenth of L).
    if (rotary_) out.push_back(VectorOf({std::log(0.1), length, std::log(0.1)}));
    return out;
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    CantileverSpec::PointMass p;
    p.height = std::min(t[1], BeamLength(nominal));
    p.mass = std::exp(t[0]) * BeamMassPerLength(nominal) * BeamLength(nominal);
    if (rotary_) {
      const double r = std::exp(t[2]) * BeamLength(nominal);
      p.rotary_inertia = p.mass * r * r;
    }
    spec->point_masses.push_back(p);
  }
  EffectLocation Location(const CantileverSpec&,
                          const Eigen::VectorXd& t) const override {
    EffectLocation l;
    l.x = t[1];
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& s,
                                          const Eigen::VectorXd& t) const override {
    const double m = std::exp(t[0]) * BeamMassPerLength(s) * BeamLength(s);
    std::vector<EffectMagnitude> out = {
        {"mass", "kg", m}, {"mass_ratio", "1 (per beam mass)", std::exp(t[0])}};
    if (rotary_) {
      const double r = std::exp(t[2]) * BeamLength(s);
      out.push_back({"radius_of_gyration", "m", r});
      out.push_back({"rotary_inertia", "kg m^2", m * r * r});
    }
    return out;
  }

 private:
  bool rotary_;
};

// EI times (1 - fraction) over a region a tenth of the length wide.
class StiffnessLossEffect : public Effect {
 public:
  // Region widths, as fractions of the length: "a short region".
  static constexpr double kMinWidth = 0.02, kMaxWidth = 0.4, kStartWidth = 0.1;
  // The largest loss a stated prior may reach (all of it leaves no beam).
  static constexpr double kMaxLoss = 0.99;
  std::string kind() const override { return "stiffness_loss"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    return {LogQuantity({"ln_loss", "ln(fraction of EI lost)", std::log(3e-3),
                         std::log(0.9), false},
                        "loss", 1.0, kMaxLoss),
            LinearQuantity({"x", "centre of the region (m)", 0.0, length, true}, "x_m",
                           1.0, 0.0, length),
            LogQuantity({"ln_width", "ln(width of the region / L)", std::log(kMinWidth),
                         std::log(kMaxWidth), false},
                        "width_m", length, length)};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec& s) const override {
    const double length = BeamLength(s);
    std::vector<Eigen::VectorXd> out;
    for (double f : {0.05, 0.25, 0.45, 0.65, 0.85})
      out.push_back(VectorOf({std::log(0.1), f * length, std::log(kStartWidth)}));
    return out;
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    const double length = BeamLength(nominal);
    const double half = 0.5 * std::exp(t[2]) * length;
    CantileverSpec::StiffnessChange c;
    c.z0 = std::max(0.0, t[1] - half);
    c.z1 = std::min(length, t[1] + half);
    c.factor = -std::exp(t[0]);
    spec->stiffness_changes.push_back(c);
  }
  EffectLocation Location(const CantileverSpec& s,
                          const Eigen::VectorXd& t) const override {
    const double length = BeamLength(s);
    const double half = 0.5 * std::exp(t[2]) * length;
    EffectLocation l;
    l.x0 = std::max(0.0, t[1] - half);
    l.x1 = std::min(length, t[1] + half);
    l.x = 0.5 * (l.x0 + l.x1);
    return l;
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& s,
                                          const Eigen::VectorXd& t) const override {
    const double length = BeamLength(s);
    const double half = 0.5 * std::exp(t[2]) * length;
    const double width = std::min(length, t[1] + half) - std::max(0.0, t[1] - half);
    return {{"ei_loss_fraction", "1", std::exp(t[0])}, {"region_width", "m", width}};
  }
};

// Young's modulus (the E / rho ratio) off by a uniform factor.
class MaterialScalingEffect : public Effect {
 public:
  std::string kind() const override { return "material_scaling"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec&) const override {
    return {LogQuantity({"ln_e_factor", "ln(E_real / E_model)", -0.7, 0.7, false},
                        "factor", 1.0)};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec&) const override {
    return {VectorOf({0.0})};
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    spec->section.E = nominal.section.E * std::exp(t[0]);
  }
  EffectLocation Location(const CantileverSpec& s,
                          const Eigen::VectorXd&) const override {
    return WholeLength(s);
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec&,
                                          const Eigen::VectorXd& t) const override {
    return {{"e_factor", "1", std::exp(t[0])}};
  }
};

// A uniform axial force along the beam (a riser's or tendon's tension, a
// pile's compression), as a fraction of the nominal cantilever's Euler load
// pi^2 E I / (4 L^2): its geometric stiffness on the bending modes.
class AxialLoadEffect : public Effect {
 public:
  // Compression up to 0.8 of the buckling load (K stays positive definite even
  // with other effects softening the beam a little), tension up to 10 times it.
  static constexpr double kMaxCompression = 0.8;
  static constexpr double kMaxTension = 10.0;
  std::string kind() const override { return "axial_load"; }
  std::vector<EffectParameter> Parameters(const CantileverSpec& s) const override {
    const double euler = EulerLoad(s);
    return {LinearQuantity(
        {"force_ratio",
         "axial force / (pi^2 E I / (4 L^2)), tension positive, compression negative",
         -kMaxCompression, kMaxTension, false},
        "force_n", euler, -kMaxCompression * euler,
        std::numeric_limits<double>::infinity())};
  }
  std::vector<Eigen::VectorXd> Starts(const CantileverSpec&) const override {
    return {VectorOf({0.0}), VectorOf({-0.4}), VectorOf({2.0})};
  }
  void Apply(const Eigen::VectorXd& t, Immersion, bool, const CantileverSpec& nominal,
             CantileverSpec* spec) const override {
    spec->axial_force += t[0] * EulerLoad(nominal);
  }
  EffectLocation Location(const CantileverSpec& s,
                          const Eigen::VectorXd&) const override {
    return WholeLength(s);
  }
  std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& s,
                                          const Eigen::VectorXd& t) const override {
    return {{"axial_force", "N", t[0] * EulerLoad(s)}, {"force_ratio", "1", t[0]}};
  }
  static double EulerLoad(const CantileverSpec& s) {
    const double length = BeamLength(s);
    return M_PI * M_PI * BeamBendingStiffness(s) / (4 * length * length);
  }
};

}  // namespace

std::vector<std::string> DefaultEffects() {
  return {"added_mass", "support_flexibility", "attached_mass", "stiffness_loss",
          "material_scaling"};
}

std::vector<std::string> AvailableEffects() {
  std::vector<std::string> out = DefaultEffects();
  out.push_back("axial_load");
  return out;
}

std::unique_ptr<Effect> CreateEffect(const std::string& kind,
                                     const EffectOptions& options) {
  if (kind == "added_mass") return std::make_unique<AddedMassEffect>();
  if (kind == "support_flexibility") return std::make_unique<SupportFlexibilityEffect>();
  if (kind == "attached_mass")
    return std::make_unique<AttachedMassEffect>(options.rotary_inertia);
  if (kind == "stiffness_loss") return std::make_unique<StiffnessLossEffect>();
  if (kind == "material_scaling") return std::make_unique<MaterialScalingEffect>();
  if (kind == "axial_load") return std::make_unique<AxialLoadEffect>();
  std::string known;
  for (const auto& k : AvailableEffects()) known += (known.empty() ? "" : ", ") + k;
  throw InputError("effect",
                   "unknown effect '" + kind + "' (expected none, " + known + ")");
}

EffectParameter LogQuantity(EffectParameter p, const std::string& key, double scale,
                            double max) {
  p.quantity = key;
  p.log_coordinate = true;
  p.quantity_scale = scale;
  p.quantity_min = 0;
  p.quantity_max = max;
  return p;
}

EffectParameter RadiusOfGyrationParameter(double extent) {
  EffectParameter p =
      LogQuantity({"ln_radius_ratio", "ln(radius of gyration / the structure's extent)",
                   std::log(1e-3), std::log(0.1), false},
                  "radius_of_gyration_m", extent);
  p.nested_at_lower = true;
  return p;
}

EffectParameter LinearQuantity(EffectParameter p, const std::string& key, double scale,
                               double min, double max) {
  p.quantity = key;
  p.log_coordinate = false;
  p.quantity_scale = scale;
  p.quantity_min = min;
  p.quantity_max = max;
  return p;
}

double BeamMassPerLength(const CantileverSpec& spec) {
  return spec.section.rho * spec.section.A;
}
double BeamBendingStiffness(const CantileverSpec& spec) {
  return spec.section.E * spec.section.I;
}
double BeamLength(const CantileverSpec& spec) {
  return spec.node_heights.empty() ? 0.0 : spec.node_heights.back();
}

}  // namespace femup
