// Unmodelled effects: parametrised families of changes to a nominal cantilever
// model, each with few parameters, used to explain the gap between a model and
// measured modes (`femup diagnose`). An effect changes the model's
// CantileverSpec (supports, material, the exact distributed and point changes of
// beam_modifications.h), so its matrices live in the same model interface as the
// correction factors and every effect works with every structure BuildCantilever
// makes.
//
// Each parameter has a range, which is also its prior: uniform in the
// parameter's own coordinate (log coordinates for magnitudes that span decades),
// unless a study states another (effect_priors.h).
// Locations are in metres from the support.
//
// The library (CreateEffect):
//   added_mass          extra transverse mass per length from the base up to a
//                       depth (water, soil, marine growth), fading linearly to
//                       zero over its top part: ln(m_a / rho A), depth, fade
//                       (fraction of the depth, 0 to 0.5).
//   support_flexibility rotational and translational springs at the base, as
//                       compliances relative to the beam's own: ln(EI / (k_r L)),
//                       ln(3 EI / (k_t L^3)).
//   attached_mass       a point mass at a height: ln(m / (rho A L)), x, and
//                       its rotary inertia m r^2: ln(r / L) from a negligible
//                       1e-3 to 0.1 (EffectOptions::rotary_inertia).
//   stiffness_loss      EI reduced by a fraction over a short region (2 % to 40 %
//                       of the length) centred at x: ln(loss fraction), x,
//                       ln(width / L).
//   material_scaling    uniform error of the E/rho ratio: ln(E factor).
//   axial_load          a uniform axial force (tension positive: a riser's or
//                       tendon's tension; negative: a pile's compression), its
//                       geometric stiffness on the bending modes: the force over
//                       the nominal cantilever's Euler load pi^2 E I / (4 L^2),
//                       from -0.8 to 10. Not among the default candidates
//                       (DefaultEffects): a study lists it where a load is
//                       plausible.
// Several effects at once are a list of effects whose parameter vectors are
// concatenated (effect_fit.h). To add a kind, derive from Effect and register it
// in CreateEffect (effects.cc).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/core/sysid/measurement.h"

namespace femup {

struct EffectParameter {
  EffectParameter() = default;
  // A parameter with no stated quantity ({name, description, lower, upper,
  // location}; LogQuantity and LinearQuantity below add one).
  EffectParameter(std::string name_in, std::string description_in, double lower_in,
                  double upper_in, bool location_in)
      : name(std::move(name_in)),
        description(std::move(description_in)),
        lower(lower_in),
        upper(upper_in),
        location(location_in) {}

  std::string name;         // "ln_mass_ratio", "depth"
  std::string description;  // "ln(m_a / rho A)"
  double lower = 0;         // the prior range, uniform in this coordinate
  double upper = 1;
  bool location = false;  // a position along the structure (m)
  // The physical quantity behind the coordinate, on which a study states what
  // it knows (`diagnosis.priors`, effect_priors.h): its key in the study file,
  // unit included ("mass_kg", "loss"; empty: none can be stated), and the map
  // q = quantity_scale exp(theta) in a log coordinate, else q = quantity_scale
  // theta (quantity_scale > 0). [quantity_min, quantity_max] are the values q
  // can take (a log coordinate's are > 0 whatever quantity_min says).
  std::string quantity;
  bool log_coordinate = false;
  double quantity_scale = 1;
  double quantity_min = -std::numeric_limits<double>::infinity();
  double quantity_max = std::numeric_limits<double>::infinity();
  // A stated Gaussian prior on q, N(normal_mean, normal_sigma^2), when
  // normal_sigma > 0: it replaces the uniform prior on [lower, upper], which
  // then only bounds the fit.
  double normal_mean = 0;
  double normal_sigma = 0;
  // At its lower bound the effect is a simpler, nested one (a mass's radius of
  // gyration there: no rotary inertia to speak of). The fits also start once
  // with it held there, so that they end no worse than the simpler effect's.
  bool nested_at_lower = false;
};

// `p` measuring the quantity `key` as q = scale exp(theta), q in (0, max].
EffectParameter LogQuantity(EffectParameter p, const std::string& key, double scale,
                            double max = std::numeric_limits<double>::infinity());
// `p` measuring the quantity `key` as q = scale theta, q in [min, max].
EffectParameter LinearQuantity(EffectParameter p, const std::string& key, double scale,
                               double min, double max);

// An attached mass's radius of gyration r as the parameter ln(r / extent),
// measuring the quantity "radius_of_gyration_m" (r = extent exp(theta)); its
// prior range from a negligible 1e-3 of the structure's extent to 0.1 (a deck
// module of 7 m on a 30 m jacket: r = 7 / sqrt(6) m, about 0.1). A wider range
// let a point attachment take radii of 0.1-0.3 of a frame's extent (a body
// 0.25-0.7 of the frame across) and stand in for local stiffness losses at the
// joints (docs/diagnosis.md, "Session 61"). The one definition the
// cantilever's attached mass and the structures' share.
EffectParameter RadiusOfGyrationParameter(double extent);

// Where an effect acts, in metres from the support (NaN where not applicable).
struct EffectLocation {
  double depth = std::numeric_limits<double>::quiet_NaN();  // added_mass: 0..depth
  double x = std::numeric_limits<double>::quiet_NaN();      // attached_mass, centre
  double x0 = std::numeric_limits<double>::quiet_NaN();     // region start
  double x1 = std::numeric_limits<double>::quiet_NaN();     // region end
};

// The physical size of an effect: named quantities with units.
struct EffectMagnitude {
  std::string name;  // "added_mass_per_length", "rotational_stiffness"
  std::string unit;  // "kg/m", "N m/rad"
  double value = 0;
};

class Effect {
 public:
  virtual ~Effect() = default;
  // "added_mass", "support_flexibility", ...
  virtual std::string kind() const = 0;
  // Parameters and their ranges for this nominal model.
  virtual std::vector<EffectParameter> Parameters(
      const CantileverSpec& nominal) const = 0;
  // Starting points for a multi-start fit (each of size Parameters().size()).
  virtual std::vector<Eigen::VectorXd> Starts(const CantileverSpec& nominal) const = 0;
  // Applies the effect with parameters `theta` to `spec` (the nominal, possibly
  // changed by other effects already) for a state of the given immersion; sizes
  // refer to `nominal`. `wet_only_added_mass`: the study has wet states, so added
  // mass acts in those only.
  virtual void Apply(const Eigen::VectorXd& theta, Immersion immersion,
                     bool wet_only_added_mass, const CantileverSpec& nominal,
                     CantileverSpec* spec) const = 0;
  virtual EffectLocation Location(const CantileverSpec& nominal,
                                  const Eigen::VectorXd& theta) const = 0;
  virtual std::vector<EffectMagnitude> Magnitudes(const CantileverSpec& nominal,
                                                  const Eigen::VectorXd& theta) const = 0;
};

// The single kinds, in a fixed order (without "none"): every kind CreateEffect
// knows, and the ones `femup diagnose` tries when a study names no candidates
// (the list: every kind but axial_load).
std::vector<std::string> AvailableEffects();
std::vector<std::string> DefaultEffects();
struct EffectOptions {
  // attached_mass fits the mass's rotary inertia (a radius of gyration) as
  // well; false: a point mass on the transverse translation only.
  bool rotary_inertia = true;
};
// Throws InputError("effect", ...) for an unknown kind, listing the known ones.
std::unique_ptr<Effect> CreateEffect(const std::string& kind,
                                     const EffectOptions& options = {});

// The nominal beam's properties the ranges refer to (first element's section).
double BeamMassPerLength(const CantileverSpec& spec);     // rho A, kg/m
double BeamBendingStiffness(const CantileverSpec& spec);  // E I, N m^2
double BeamLength(const CantileverSpec& spec);            // m

}  // namespace femup
