// Stated engineering priors on the unmodelled-effect families (`diagnosis.priors`
// of a study; docs/diagnosis.md, "Stated priors"): what the user knows of a
// family's physical quantities, where it can act and how likely it is
// beforehand. Where nothing is stated, the families' defaults hold.
//
// Each family parameter names the physical quantity behind its coordinate
// (EffectParameter::quantity in effects.h: "mass_kg", "loss", "factor", ...).
// Stated values are in that quantity's units and are converted here:
//   range [lower, upper]  replaces the parameter's prior range: uniform in its
//                         coordinate (in ln q for a log coordinate) from
//                         theta(lower) to theta(upper). It must lie within the
//                         values the quantity can take.
//   normal [mean, sigma]  a Gaussian on q: the fit gets the residual
//                         (q(theta) - mean) / sigma (so the estimate moves
//                         towards the mean), the evidence the Gaussian's Occam
//                         factor instead of the uniform range's; the fit's
//                         bounds become mean +- 6 sigma, clipped to the
//                         default range when the mean lies in it, and to the
//                         values q can take (in a log coordinate, at least 1 %
//                         of the mean).
//   regions               the family's instances kept (model_effects.h): those
//                         acting on a named element (its 1-based id or its
//                         label) or node (the prefix of its DOF labels, "n7").
//   weights               a family's prior probability relative to the other
//                         families' and to "none"'s (1 each by default).
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/structure.h"
#include "femup/core/invalid.h"
#include "femup/problems/effects.h"
#include "femup/problems/model_effects.h"
#include "femup/problems/nonlinear_problem.h"

namespace femup {

// What is stated about one physical quantity of a family.
struct QuantityPrior {
  std::string quantity;  // an EffectParameter::quantity of the family: "mass_kg"
  bool normal = false;   // false: a range
  double lower = 0;      // the range, in the quantity's units (lower < upper)
  double upper = 0;
  double mean = 0;  // the Gaussian, in the quantity's units (sigma > 0)
  double sigma = 0;
};

// What is stated about one family.
struct FamilyPrior {
  std::string kind;  // "attached_mass"
  std::vector<QuantityPrior> quantities;
  std::vector<std::string> regions;  // where it may act; empty: anywhere
};

struct StatedPriors {
  std::vector<FamilyPrior> families;      // at most one per kind
  std::map<std::string, double> weights;  // "none" or a kind -> weight; absent: 1

  bool empty() const { return families.empty() && weights.empty(); }
  // The family's stated prior, or null.
  const FamilyPrior* Find(const std::string& kind) const;
  // The weight of "none" or a kind (1 unless stated).
  double Weight(const std::string& kind) const;
  // Ok when valid, else the field "priors.<kind>[.<quantity>]" or
  // "weights.<kind>" and what is wrong: a kind or quantity given twice, a number that is
  // not finite, lower >= upper, sigma <= 0, an empty region name, a weight <= 0. Whether
  // the quantities and regions exist is the model's to say (ApplyFamilyPrior,
  // KeepStatedRegions).
  Invalid Validate() const;
};

// The prior probability of one explanation by its families (none: empty; one
// effect; a pair: two). The classes lie on levels, none, one effect and two
// effects, a third each (a half each on none and one effect where no pair is
// tried, num_pairs 0), equal within a level among the num_singles families or
// the num_pairs pairs, times the stated weights (none's; the family's; a pair's
// the product of its two's). A family's places then split its share.
double LevelPrior(const StatedPriors& priors, const std::vector<std::string>& families,
                  std::size_t num_singles, std::size_t num_pairs);

// q at theta and theta at q for a parameter (EffectParameter's map).
double QuantityAt(const EffectParameter& p, double theta);
double CoordinateOf(const EffectParameter& p, double quantity);

// A family's parameters (in order) with `prior`'s quantities applied. Throws
// InputError("<quantity>", ...) for a quantity none of them measures (listing
// those they do) and for a range or mean outside the values the quantity can
// take.
std::vector<EffectParameter> ApplyFamilyPrior(std::vector<EffectParameter> params,
                                              const FamilyPrior& prior);

// The effect with its parameters as `prior` states them, and its starts moved
// into the stated ranges (each start clipped, plus one at the middle of the
// stated ranges or the normal priors' means). Checks the quantities on
// creation (throws as ApplyFamilyPrior); prior.regions is not looked at.
std::unique_ptr<Effect> WithFamilyPrior(std::unique_ptr<Effect> effect,
                                        const FamilyPrior& prior,
                                        const CantileverSpec& nominal);
std::unique_ptr<ModelEffect> WithFamilyPrior(std::unique_ptr<ModelEffect> effect,
                                             const FamilyPrior& prior);

// The instances prior.regions keeps (every one when it names none): those
// acting on a named element (1-based id or label) or on a node named by the
// prefix of its DOF labels. Throws InputError("regions", ...) for a family with
// a single instance (it acts on the whole: nothing to choose), and
// InputError("regions[k]", ...) for a name that no instance of this family acts
// on (saying whether it names an element or node of the model at all).
std::vector<std::unique_ptr<ModelEffect>> KeepStatedRegions(
    std::vector<std::unique_ptr<ModelEffect>> instances, const Structure& structure,
    const FamilyPrior& prior);

// The normal priors' residuals: one per parameter with normal_sigma > 0,
// (q(theta_i) - mean) / sigma, appended after `problem`'s own (its parameters
// are `params`, in order). The problem is returned as it is when there is none.
int NumPriorResiduals(const std::vector<EffectParameter>& params);
NonlinearProblem WithPriorResiduals(NonlinearProblem problem,
                                    const std::vector<EffectParameter>& params);

// The normal priors as Gaussians in the parameters' own coordinates, linearised
// at theta: per parameter a mean and sigma (sigma 0 where the prior is
// uniform), for LaplaceEvidence; its Laplace evidence is then that of the
// Gaussian on q. Both empty when no parameter has a normal prior.
void LocalNormalPriors(const std::vector<EffectParameter>& params,
                       const Eigen::VectorXd& theta, Eigen::VectorXd* mean,
                       Eigen::VectorXd* sigma);

}  // namespace femup
