// Which unmodelled effect explains the gap, on any structure: every instance of
// every candidate family (model_effects.h: a stiffness loss in each storey, an
// attached mass at each node, ...) is fitted to the measured modes by the one
// output-error engine (model_effect_pencil.h) from each of its starts, scored by
// its Laplace evidence (model_evidence.h), and given a posterior probability.
//
// Prior: "none" and each candidate family share equally (the benchmark's class
// prior), or in proportion to their stated weights; a family's share is split
// equally among its instances, so a family with many possible places pays for
// the choice (the discrete part of its Occam factor). Stated priors
// (effect_priors.h) replace a family's ranges, add Gaussian priors (a residual
// in the fit, their Occam factor in the evidence) and keep only the instances
// at the stated regions.
//
// Noise temperatures: where the best class (least chi2) leaves a misfit of the
// frequencies that their stated noise cannot explain (upper-tail p < 0.01),
// the frequencies' noise is scaled by chi2 / dof of their part of that misfit
// before the probabilities are formed; the shapes' noise likewise by theirs.
// Two temperatures, not one: a model's own form error (an idealised chain, an
// Euler-Bernoulli frame of stocky members) shows in its frequencies first, and
// one temperature for all residuals is diluted by shape residuals that fit, so
// a family that absorbs the form error (an E scaling) would still be named
// with confidence (docs/diagnosis.md, "Blind suites on other structures").
//
// The model's own form error: where the model's builder knows a richer
// formulation of it (Structure::form_variants: a frame of Euler-Bernoulli
// members with shear deformation), the change that formulation makes to the
// nominal frequencies (and shapes: form_error_on_shapes), u (in noise units),
// is allowed for as correlated noise: their covariance is I + u u' (one
// standard deviation of form error along u, every variant alike), and every
// class is judged with it. An
// effect that only mimics the model's own form error (an E scaling making
// every mode softer as shear deformation does) then earns little evidence over
// "none", and a real effect larger than the form error is still found. This
// comes before the temperatures, which then judge what is left.
//
// Probabilities that hold when no class is right (a bagged posterior,
// bagged_posterior.h): the Laplace posterior judges the classes as if one of
// them made the data up to the (tempered) noise. On data made by another
// formulation none does, and a difference in chi2 that a few residuals make
// was stated with the certainty of one spread over all of them (verdicts
// stated at >= 0.9 on the blind frame suite were right half the time). The
// probabilities are therefore averaged over bootstrap copies of the residuals
// (frequencies drawn among the frequencies, shape entries among the shape
// entries), every class scored on each copy at its fit; the Laplace
// probability is kept beside it (RankedClass::laplace_probability).
//
// Observational equivalence: two classes whose fits predict the data alike
// (their whitened residuals differ by at most 1 in squared norm: less than one
// standard deviation in all) and whose Jacobians at the fits span the same
// directions of the data (every cosine of their principal angles >= 0.999)
// cannot be told apart by these data, e.g. a chain's ground-spring flexibility
// and its first storey's stiffness loss. Each class lists the ones equivalent to
// it, and their summed probability is stated with them rather than read as a
// split between them.
//
// This is the step `femup diagnose` will run for every model type; today the
// command runs it for models other than the cantilever (whose diagnosis keeps
// its own pipeline, diagnose_study.h, until it moves here).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/core/invalid.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/model_effects.h"
#include "femup/solvers/model_evidence.h"

namespace femup {

struct EffectRankingOptions {
  std::vector<std::string> kinds;  // candidate families; empty: every one that applies
  double frequency_sigma = 0.002;  // relative, of a measured eigenvalue's frequency
  double shape_sigma = 0.02;       // of a shape entry, relative to the largest
  bool use_shapes = true;
  std::string solver = "ceres";  // a NonlinearSolver name
  // Instances fitted at once (0: every core). The ranking does not depend on it.
  int threads = 0;
  // Models with at least this many DOFs (negative: none) search each start's
  // fit on a Ritz basis built at that start (eigen_sensitivity.h: the lowest
  // modes and their static corrections for the instance's unknowns), then
  // finish the best start (and any other that ends elsewhere within a chi2 of
  // 10 of it) on the full model, from where the search ended: what is reported
  // is always the full model's fit.
  int ritz_min_dofs = 3000;
  // Allow for the model's form error where the structure carries form
  // variants (above); false: judge the classes on the stated noise alone.
  bool formulation_error = true;
  // Allow for the model's form error on the mode shapes at the sensors as well
  // as on the frequencies (model_form_error.h): every row's covariance gains
  // the variants' changes. It matters where the form variants move the shapes
  // (a tall shear building's flexural deformation: its false alarms halved);
  // on plane frames, the cantilever and the jacket no verdict changed
  // (docs/diagnosis.md, "Session 63"). false: on the frequencies alone.
  bool form_error_on_shapes = true;
  // Where the model's form error is allowed for, move each class to the mode
  // of the misfit its evidence is taken on (one Gauss-Newton step on the
  // whitened misfit) before its evidence; false: each class at its raw fit
  // (for comparison; docs/diagnosis.md, "Each class is moved to the mode").
  bool form_step = true;
  // With form_step, each fitted class is moved by a fit of the whitened misfit
  // to its mode (from its raw fit, on the full model), not by one Gauss-Newton
  // step (screened classes keep the step). Off by default: on the portal whose
  // only gap is its own form error (the test
  // EffectRanking.AllowsForTheModelsOwnShearDeformation) it lowers "none" from
  // P 0.94 to 0.47, every stiffness loss gaining as much as it pays; on 49 cases of the
  // soft-foundation suite it gained three kinds and lost none (p 0.25), with
  // no better calibration and one new confident miss where the form variants
  // are hundreds of noise units (docs/diagnosis.md).
  bool form_fit = false;
  // Bootstrap copies of the residuals the probabilities are averaged over
  // (above); 0: the Laplace posterior alone.
  int bagging_copies = 400;
  // Stiffness loss tries each member of a group on its own (a space frame's
  // braces, legs, horizontals) where the model has at most this many members
  // (-1: however many), or where the study states its regions: each member is
  // one more fit.
  int max_members = 200;
  // What the user knows of the nominal model's overall stiffness and mass, as
  // relative standard deviations (an E known to within 2 %: 0.02; 0: nothing
  // stated). Each is allowed for as a form variant of the model
  // (model_form_error.h: the frequencies' covariance gains one standard
  // deviation along the uniform change it makes), with or without
  // formulation_error: an overall change the model is already expected to be
  // off by is not named a gap, and a material scaling must exceed it. In
  // [0, 0.5).
  double stiffness_uncertainty = 0;
  double mass_uncertainty = 0;
  // Attached masses carry a fitted rotary inertia (a radius of gyration) where
  // the structure has rotational DOFs and node coordinates; false: point
  // masses on the translations only (ModelEffectOptions::rotary_inertia).
  bool rotary_inertia = true;
  // Where more members than this are tried, each is first screened by the
  // misfit one linearised (Gauss-Newton) step from each of its starts
  // predicts, its step kept in range: two evaluations where a fit takes tens.
  // Only the members the screen ranks best, this many, are then fitted; the
  // others are ranked on the Laplace evidence at the end of their screen's
  // step, listed after their family's fitted classes (RankedClass::fitted),
  // and a note says so. -1: every member is fitted.
  int members_fitted = 12;
  // What the study states about the families (empty: their defaults). Each
  // family it names must be among those tried.
  StatedPriors priors;
  // A gap is named only where its probability (1 - P(none): of any effect at
  // all) reaches this; below it the verdict is "none" (no significant gap),
  // first among the classes, with every probability as it is. The prior gives
  // none one share among the families' (the suites' base rate), which keeps the
  // stated probabilities calibrated but names a family on a case without an
  // effect whenever the model's own form error leaves several of its places a
  // little more probable than none. Asking for confidence before saying there
  // is a gap lowers those false alarms and misses weak real effects: on the
  // shear buildings it pays, on the plane frames it only costs
  // (docs/diagnosis.md, "Naming a gap only with confidence"), so it is the
  // user's choice. 0 (the default): the most probable family, whatever its
  // probability. In [0, 1).
  double gap_confidence = 0;
  // An effect is named the gap's cause only where it removes at least this
  // share of the nominal model's misfit beyond the noise (RankedClass::
  // explained); otherwise the verdict is "none" (no effect explains the gap),
  // first among the classes, with every probability as it is. A chain fitted
  // to a frame, or any model with a form error, leaves a misfit of many noise
  // units that the families can only nibble at: a place that removes 1 % of it,
  // shifting the misfit from the shapes to the frequencies, can still be the
  // most probable class, and naming it the gap's cause misleads. 0: the most
  // probable family, however little it explains. In [0, 1); a third by default:
  // the effect is at least a third of the gap (docs/diagnosis.md, "An effect
  // named only where it explains the gap", has the suites at 1/3 and 1/2).
  double gap_explained = 1.0 / 3;
  // How the frequencies' noise temperature (a model form error of unknown
  // shape: each mode's frequency off by about the same number of noise units,
  // its signs uneven) enters the evidence.
  // kThreshold: one temperature for every class, the best fit's chi2 per
  // degree of freedom, applied only where that fit fails at p < 0.01.
  // kMarginal: each class's evidence integrated over the temperature T =
  // 1 + d^2 (d: the discrepancy of each mode in noise units), half the prior
  // on d = 0 and half log-uniform in T up to 10^4 (d = 100), so a
  // class that needs no discrepancy is not charged for one, and one that
  // explains a misfit only as well as a discrepancy would is not preferred.
  // kAuto (the default): kMarginal where no form variant of the structure's
  // own (Structure::form_variants) is allowed for, kThreshold where one is.
  // A chain or an imported matrix has no description of its form error, and
  // one of unknown shape is all that can be assumed: on the blind shear
  // buildings kMarginal halved the false alarms (11 to 5 of 43 on both floor
  // kinds) with top-1 as good or better. A plane frame's shear deformation
  // and finer mesh are allowed for as their own changes, and there kMarginal
  // lost 3 of 50 verdicts and gained none (docs/diagnosis.md, "A marginal
  // frequency temperature").
  enum class FrequencyTemperature { kAuto, kThreshold, kMarginal };
  FrequencyTemperature frequency_temperature = FrequencyTemperature::kAuto;
  // 1: single effects. 2: also pairs of effects acting at once
  // (model_effect_pair.h): for every two families tried, the place of each
  // that fitted best alone, and for every family, each two of its
  // pair_places best-fitting places that lie apart (two damaged storeys, two masses),
  // fitted together from where the two fits ended (and from the families'
  // starts). The prior is then the cantilever pipeline's (LevelPrior): 1/3 on
  // none, 1/3 on one effect (the families by their weights), 1/3 on two (each
  // pair of families, one family twice included, by the product of their
  // weights), and a pair's share is split among every combination of its
  // places (for one family, every two of its places that lie apart), as a
  // family's is among its places. A pair's kind is "<first kind>+<second kind>" in the
  // families' order ("a+a" for one family's); it is a family of its own in
  // kind_probabilities (FamilyPresence sums each family over its pairs).
  int max_effects = 1;
  // With max_effects 2: among how many of a family's best-fitting places
  // (least chi2 alone) its pairs of places are formed, each two that lie apart
  // fitted; -1: every place. On blind shear buildings with two damaged storeys
  // (docs/diagnosis.md) the true pair was named in 21, 35, 49 and 57 cases of
  // 100 with 3, 6, 10 and every place, for 29, 34, 55 and 77 s.
  int pair_places = 10;
  // Modes the verdict is checked on, as (state index in the states given,
  // measured mode index from 0): its place is fitted again without them, and
  // what that fit predicts for them is reported beside the nominal model's
  // (EffectRanking::held_out). The ranking itself uses every mode. Where the
  // verdict is none, the most probable effect is checked. Empty: no check.
  std::vector<std::pair<int, int>> held_out;
  // Ok when valid, else the field and what is wrong.
  Invalid Validate() const;
};

// "auto", "threshold" or "marginal", and back (nullopt for any other name).
std::string ToString(EffectRankingOptions::FrequencyTemperature t);
std::optional<EffectRankingOptions::FrequencyTemperature> FrequencyTemperatureNamed(
    const std::string& name);

struct RankedClass {
  std::string kind;    // "none" or a family
  std::string region;  // the instance's region ("" for none)
  std::vector<std::string> names;
  Eigen::VectorXd theta;
  double chi2 = 0;
  ModelEvidence evidence;  // at the final temperature
  double log_prior = 0;
  double probability = 0;          // bagged (above), or Laplace where bagging is off
  double laplace_probability = 0;  // from the Laplace evidences alone
  // The frequencies' noise temperature the class's evidence was taken at (the
  // ranking's, or with FrequencyTemperature::kMarginal the class's posterior
  // harmonic mean).
  double frequency_temperature = 1;
  bool converged = true;
  // False for a member left out of the fits by the screen
  // (EffectRankingOptions::members_fitted): theta, chi2 and the evidence are
  // at the end of one linearised step from its best start.
  bool fitted = true;
  // "<kind> at <region>" of the classes observationally equivalent to this one
  // (see above), and the probability of the group (this class's included).
  std::vector<std::string> equivalent;
  double group_probability = 0;
  EffectLocation location;
  std::vector<EffectMagnitude> magnitudes;
  // What the class predicts at its fit, mode by mode in the measured order
  // (state by state): the paired model frequency and, where shapes were
  // compared, the MAC (eigen_sensitivity.h). For "none" the nominal model's:
  // how far the gap shrinks once the class is added.
  std::vector<PairedModeMisfit> modes;
  // The share of the nominal model's misfit beyond the noise that the class
  // removes, in [0, 1]: 1 - max(0, chi2 - (n - s - k)) / (chi2_none - (n - s)), with n
  // residuals, s modes whose shapes are scaled to fit and k parameters (0
  // where there is no gap beyond the noise, EffectRanking::gap_within_noise;
  // 1 where the nominal misfit is within the noise's expectation but the gap
  // sits in a few rows; 0 for none); chi2 at the
  // stated noise, whitened where the model's form error is allowed for
  // (form_errors: that error is not part of the gap).
  double explained = 0;
};

// A form variant's size on these data (see above).
struct FormErrorAllowance {
  std::string name;                 // FormVariant::name
  double max_frequency_change = 0;  // relative, largest over the measured modes
  double noise_units = 0;           // norm of its change of the frequency residuals
};

// The verdict checked on modes it was not fitted to (EffectRankingOptions::
// held_out): its place fitted again without them, and both that fit's and the
// nominal model's predictions of them.
struct HeldOutCheck {
  std::string kind;
  std::string region;
  Eigen::VectorXd theta;  // the fit without the held-out modes
  std::vector<PairedModeMisfit> nominal;
  std::vector<PairedModeMisfit> refit;
  bool ok = false;  // false: the refit failed (why says how)
  std::string why;
};

struct EffectRanking {
  // By family, the most probable family first (but "none" first where the
  // gap's probability is below EffectRankingOptions::gap_confidence, or the
  // effect explains too little of it: gap_explained), then by
  // class within it: the first is the verdict (the most probable class of the
  // most probable family).
  std::vector<RankedClass> classes;
  std::vector<std::pair<std::string, double>> kind_probabilities;  // most probable first
  // The probability of any gap (1 - P(none)), and whether it was below
  // EffectRankingOptions::gap_confidence (a positive one), so that "none" is
  // the verdict: also where none was the most probable family anyway, and the
  // rule changed nothing.
  double gap_probability = 0;
  bool gap_below_confidence = false;
  // Whether the most probable family's best class explained less than
  // EffectRankingOptions::gap_explained of the gap, so that "none" is the
  // verdict (the class that did not explain enough is the first of the rest).
  bool gap_unexplained = false;
  // None's misfit in the misfit the classes were ranked in (at the stated
  // noise; whitened where the model's form error is allowed for), and what
  // the noise alone gives it (its expectation: the residuals less one scale
  // per shape mode). Where the first is no larger and the most probable effect
  // gains less than 9 (3 noise standard deviations) over none
  // (gap_within_noise) there is no gap to explain: every class explains none
  // of it (RankedClass::explained 0), and "none" is the verdict wherever
  // gap_explained is positive (gap_unexplained), however the probabilities
  // fall: a family whose places can each fit a little of the noise (every
  // family holds effects too small to tell from none) is not named for it.
  // A gain of 9 or more is a gap in a few rows that the noise's spread over
  // many rows hides (the effect is then named as before).
  double nominal_misfit = 0, noise_misfit = 0;
  bool gap_within_noise = false;
  // Of the frequencies' noise: the one every class was judged at, or with a
  // marginal temperature the verdict's own (RankedClass::frequency_temperature).
  double temperature = 1;
  // How it was used: kThreshold or kMarginal (kAuto resolved).
  EffectRankingOptions::FrequencyTemperature frequency_temperature =
      EffectRankingOptions::FrequencyTemperature::kThreshold;
  double shape_temperature = 1;  // of the shapes' noise
  double best_chi2_p_value = 1;
  int bagging_copies = 0;  // the probabilities' bootstrap copies (0: Laplace)
  int num_residuals = 0;
  std::vector<std::string> skipped;  // "<kind>: why it does not apply"
  std::vector<std::string> notes;    // what was left untried, and how to try it
  std::vector<FormErrorAllowance> form_errors;  // allowed for, one per variant
  std::optional<HeldOutCheck> held_out;         // where options.held_out names modes
};

// The class the gap is shown with and the verdict is checked on: the verdict,
// or where the verdict is "none" the most probable class of another family
// (what the most probable effect would close); null where there is none.
const RankedClass* GapClass(const EffectRanking& ranking);
// The "none" class (the nominal model), null where it was not ranked.
const RankedClass* NoneClass(const EffectRanking& ranking);

// Throws InputError for invalid options, held-out modes that are not measured
// (or every mode), an unknown family, a named family that
// does not apply to the structure, a stated prior that does not fit the
// structure's families (a quantity they lack, a region that names none of their
// places; "diagnosis.priors.<kind>...", before any fit), or states the engine
// refuses.
EffectRanking RankModelEffects(const Structure& structure,
                               const std::vector<ModalData>& states,
                               const EffectRankingOptions& options);

// The families a class's kind holds: the kind itself, or both of a pair ("a+b",
// EffectRankingOptions::max_effects 2; "a+a", two places of one family: a).
std::vector<std::string> FamiliesOf(const std::string& kind);

// The probability that each family is part of the explanation: the sum of
// kind_probabilities over its own entry and every pair that holds it (so the
// figures can add up to more than 1 where pairs were tried; without pairs they
// are kind_probabilities). Most probable first.
std::vector<std::pair<std::string, double>> FamilyPresence(const EffectRanking& ranking);

// A kind's summed probability over its places (kind_probabilities; 0 for a kind
// the ranking does not hold). The verdict's kind need not be the most probable
// (EffectRankingOptions::gap_confidence, gap_explained).
double KindProbability(const EffectRanking& ranking, const std::string& kind);

// The root mean square of model / measured - 1 over a class's paired modes
// (RankedClass::modes; for "none" the nominal model's gap); NaN where it has
// none.
double RmsFrequencyError(const RankedClass& c);

}  // namespace femup
