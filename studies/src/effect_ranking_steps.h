// Private to femup_studies: the steps of RankModelEffects (effect_ranking.cc),
// each defined in the effect_ranking_*.cc file of its concept: the families
// and their instances (effect_ranking_families.cc), an instance's fit and
// screen (effect_ranking_fit.cc), the noise temperatures and the classes'
// evidence and probabilities (effect_ranking_evidence.cc), and the ranked
// classes' order (effect_ranking_order.cc).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/model_effects.h"
#include "femup/solvers/model_evidence.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/effect_ranking.h"
#include "model_form_error.h"

namespace femup::effect_ranking_steps {

// effect_ranking_families.cc ------------------------------------------------

// Which measured modes are held out (held[state][mode] != 0;
// EffectRankingOptions::held_out). Throws InputError("diagnosis.held_out", ...)
// for a mode that is not measured or where every mode is held out.
std::vector<std::vector<char>> HeldOutModes(
    const std::vector<ModalData>& states,
    const std::vector<std::pair<int, int>>& held_out);

// The families tried (EffectRankingOptions::kinds, or every one that applies
// to the structure by default: those that do not are said in out->skipped)
// and each one's instances with their stated priors, made and checked before
// any fit: a stated prior or weight for a family not tried, or a region that
// names nothing, throws InputError naming the field. Where stiffness_loss is
// tried on groups rather than members, out->notes says so.
struct Families {
  std::vector<std::string> kinds;
  std::vector<std::vector<std::unique_ptr<ModelEffect>>> instances;  // per kind
};
Families TriedFamilies(const Structure& structure, const EffectRankingOptions& options,
                       ModelEffectOptions effect_options, EffectRanking* out);

// The engine's options for the fits: the stated noise, and the eigen-solver
// a model of this size and type is solved with.
EigenSensitivityOptions FitOptions(const Structure& structure,
                                   const EffectRankingOptions& options);

// effect_ranking_fit.cc -----------------------------------------------------

// One instance's best fit over its starts.
struct Fit {
  bool ok = false;
  bool converged = false;
  Eigen::VectorXd theta;
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residual;
  double chi2 = 0;
  bool fitted = true;  // false: one linearised step's end (ScreenInstance)
};

// The best start is the one with the least misfit, the stated normal priors'
// residuals included (the posterior's mode); chi2, the residual and the
// Jacobian kept are the data's alone. With `ritz`, each start is searched on a
// Ritz basis built there, and the full model's fits start where the searches
// ended (the best, and any other that ended elsewhere within 10 of its misfit).
Fit FitInstance(const std::shared_ptr<const Structure>& structure,
                const std::shared_ptr<const ModelEffect>& effect,
                const std::vector<ModalData>& states,
                const EigenSensitivityOptions& options, const NonlinearSolver& solver,
                bool ritz);

// One linearised step from each of the instance's starts, kept inside the
// parameters' ranges: a screen of the instance in one evaluation per start.
// `misfit` is the least misfit (data and stated priors) the steps predict,
// infinite where no start can be evaluated; `fit` is that step's end, with the
// data's predicted residual and the Jacobian at its start (not fitted).
struct Screen {
  double misfit = std::numeric_limits<double>::infinity();
  Fit fit;
};

Screen ScreenInstance(const std::shared_ptr<const Structure>& structure,
                      const std::shared_ptr<const ModelEffect>& effect,
                      const std::vector<ModalData>& states,
                      const EigenSensitivityOptions& options);

// The residuals of the nominal model (no effect), and which of them are
// eigenvalue (frequency) rows, from the engine's own row labels.
struct Nominal {
  Eigen::VectorXd residual;
  std::vector<char> is_frequency;
};

Nominal NominalResidual(const Structure& structure, const std::vector<ModalData>& states,
                        const EigenSensitivityOptions& options);

// How many two of kind k's places (the first `singles` effects) lie apart:
// the pairs of places one family can form (RegionsOverlap).
double PlacesApart(const std::vector<std::shared_ptr<const ModelEffect>>& effects,
                   const std::vector<std::size_t>& effect_kind, std::size_t singles,
                   std::size_t k);

// The verdict (or, where it is none, the most probable effect) fitted again
// without the held-out modes (held[state][mode] != 0), and both that fit's and
// the nominal model's predictions of them (EffectRankingOptions::held_out).
HeldOutCheck CheckOnHeldOutModes(
    const EffectRanking& ranking, const std::shared_ptr<const Structure>& structure,
    const std::vector<std::shared_ptr<const ModelEffect>>& effects,
    const std::vector<ModalData>& states, const std::vector<std::vector<char>>& held,
    const EigenSensitivityOptions& fit, const NonlinearSolver& solver, bool ritz);

// effect_ranking_evidence.cc ------------------------------------------------

// A class's evidence integrated over the frequencies' noise temperature
// (EffectRankingOptions::FrequencyTemperature::kMarginal): T = exp(u) on a
// grid of u in [0, log kMaxFrequencyTemperature], half the prior at T = 1 and
// half uniform in u; at each T the frequency rows' variances are T times
// their stated ones (the likelihood's normalisation, -n_f / 2 log T, with
// them) and the shapes' t_s. Returns the log of the integral, the evidence at
// the grid's most probable T (its Occam factor and covariance), and the
// posterior's harmonic mean temperature 1 / E[1 / T].
struct MarginalTemperature {
  ModelEvidence evidence;
  double log_evidence = 0;
  double temperature = 1;
};

MarginalTemperature MarginalFrequencyTemperature(
    const Eigen::VectorXd& residual, const Eigen::MatrixXd& jacobian,
    const std::vector<char>& is_frequency, int num_frequencies, double shape_temperature,
    const Eigen::VectorXd& theta, const ClassPriors& priors);

// Noise temperatures from the best fit's residual, one for the frequencies
// and one for the shapes: a model's form error shows in its frequencies
// first, and one temperature for both would be diluted by shape residuals
// that fit. Each is 1 unless its chi2 is improbable (p < 0.01) at the stated
// noise, then chi2 over its degrees of freedom (those of the frequencies less
// the fit's parameters; of the shapes less one scale per shape mode).
struct NoiseTemperatures {
  double frequency = 1, shape = 1;
  int num_frequencies = 0;
  double best_chi2_p_value = 1;  // of the whole residual
};
NoiseTemperatures NoiseTemperaturesOf(const Eigen::VectorXd& best_residual,
                                      int num_params,
                                      const std::vector<char>& is_frequency,
                                      int shape_modes);

// Every class's evidence (Laplace at the noise temperatures, or with
// `marginal` integrated over the frequencies' temperature:
// MarginalFrequencyTemperature) and probability (bagged over
// `bagging_copies` copies of the rows, frequencies drawn among frequencies
// and shape entries among shape entries, or the Laplace one where 0), into
// each class; returns each family's probability. row_scale is 1 / sqrt of
// each row's noise temperature.
std::map<std::string, double> Probabilities(const std::vector<Eigen::VectorXd>& residuals,
                                            const std::vector<Eigen::MatrixXd>& jacobians,
                                            const std::vector<ClassPriors>& priors,
                                            const std::vector<char>& is_frequency,
                                            const NoiseTemperatures& noise,
                                            const Eigen::VectorXd& row_scale,
                                            bool marginal, int bagging_copies,
                                            std::vector<RankedClass>* classes);

// effect_ranking_order.cc ---------------------------------------------------

// The classes in the ranking's order, into out->classes with the family
// probabilities (by_kind) and the gap's verdict (EffectRanking::gap_*): the
// most probable family first ("none" is a family of one class), and within it
// the fitted classes, the most probable first; "none" first where no gap is
// probable at options.gap_confidence, or where the first effect explains less
// than options.gap_explained of it. Screened classes more probable than every
// fitted one of their family are said in out->notes.
void PutInOrder(std::vector<RankedClass> classes,
                const std::map<std::string, double>& by_kind,
                const EffectRankingOptions& options, EffectRanking* out);

}  // namespace femup::effect_ranking_steps
