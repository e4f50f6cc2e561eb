// Sim-to-real gap diagnosis (`femup diagnose`): given a nominal cantilever model
// and measured modes, where the gap lies, which unmodelled effect causes it and
// how far it shrinks once that effect is added.
//
//  1. Where: every element's bending stiffness and its mass are changed alone,
//     each by one fitted factor; the drop in chi2 each achieves, plotted along
//     the structure, localises the discrepancy (sensitivity-based subset
//     selection with subsets of one element).
//  2. Which effect: every candidate model class (none, each effect of
//     effects.h alone and, with max_effects 2, every pair) is fitted to the
//     fitted modes with the framework's nonlinear solver from several starts,
//     scored by its Laplace evidence (model_evidence.h) plus the predictive
//     log-likelihood of the held-out modes, and given a posterior probability
//     (prior: one third each on no effect, one effect and two effects, shared
//     equally within, times the stated weights: a pair's the product of its
//     two). Stated priors (effect_priors.h) replace the families' ranges and
//     add Gaussian priors (a residual in the fit, their Occam factor in the
//     evidence); regions do not apply (the effects are placed by a fitted
//     height: state x_m instead), nor normal priors with sampled evidence.
//     When even the best class leaves a chi2 the stated noise cannot explain
//     (p < 0.01), the noise is scaled up by chi2 / dof of that class (a noise
//     temperature) before the probabilities are formed, and the report says
//     so.
//  3. How far it shrinks: frequency errors and MACs of the nominal model and of
//     each class's fitted model, on fitted and on held-out modes.
//
// Frequency uncertainty per mode is the stated noise and the nominal mesh's
// discretisation error (the change of each frequency when every element is
// halved) added in quadrature.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "femup/problems/effect_fit.h"
#include "femup/problems/effect_priors.h"
#include "femup/problems/effects.h"
#include "femup/solvers/model_evidence.h"
#include "femup/studies/study.h"

namespace femup {

// One candidate model class: no effect, one, or two effects together.
// One start's answer of a class's multi-start fit.
struct LocalOptimum {
  Eigen::VectorXd theta;
  Eigen::MatrixXd jacobian;  // whitened, at theta
  double chi2 = 0;
  // The held-out modes predicted from theta (whitened residuals and their
  // Jacobian); `predicts` false where the model could not be evaluated there.
  bool predicts = false;
  Eigen::VectorXd held_out_residual;
  Eigen::MatrixXd held_out_jacobian;
};

struct DiagnosisCandidate {
  std::vector<std::string> kinds;  // empty = none
  std::string label;               // "none", "added_mass", "added_mass+stiffness_loss"
  bool converged = false;          // the best fit's solver status
  std::string message;
  Eigen::VectorXd theta;               // best fit, concatenated effect parameters
  std::vector<std::string> names;      // "<kind>.<parameter>"
  ModelEvidence evidence;              // at the final temperature
  Eigen::MatrixXd jacobian;            // whitened, at theta
  double chi2 = 0;                     // fitted modes
  double held_out_chi2 = 0;            // held-out modes, predicted from theta
  Eigen::VectorXd held_out_residual;   // whitened, at theta
  Eigen::MatrixXd held_out_jacobian;   // whitened, at theta
  double held_out_log_predictive = 0;  // LogPredictiveDensity, at the final temperature
  double score = 0;                    // log evidence + held-out log predictive density
  double laplace_score =
      0;  // the same by Laplace's approximation (at the final temperature)
  std::vector<LocalOptimum> optima;  // the multi-start fit's distinct answers
  int basins = 1;  // separated optima whose Laplace evidences were summed
  // "laplace" or "sampled": how the score was computed. Sampled (when the study
  // asks for it, the class has parameters and is within reach of the best) when
  // its standard error is at most 0.2; draws, Kish's effective number of them
  // and the standard error are reported whenever sampling ran.
  std::string evidence_method = "laplace";
  int evidence_draws = 0;
  double evidence_effective_draws = 0;
  double evidence_standard_error = 0;
  double probability = 0;  // posterior
  int starts = 0;          // fits run
  // Per effect: location and physical size.
  std::vector<EffectLocation> locations;
  std::vector<std::vector<EffectMagnitude>> magnitudes;
  // Predictions of the fitted model: for fitted data and held-out data.
  std::vector<PredictedState> fitted, held_out;
};

struct ElementIndicator {
  int element = 0;  // 1-based
  double x0 = 0, x1 = 0;
  double stiffness_factor = 0, stiffness_chi2_drop = 0;
  double mass_factor = 0, mass_chi2_drop = 0;
};

struct DiagnosisResult {
  std::string study_name;
  std::string description;
  double length = 0;
  EffectFitData fitted_data, held_out_data;  // held_out_data may have no states
  std::vector<PredictedState> nominal_fitted, nominal_held_out;
  double frequency_noise = 0, shape_noise = 0;
  std::vector<double> mesh_error;  // per state and mode (fitted then held out), relative
  // The families' form error in each frequency, the same order, relative.
  std::vector<double> form_error;
  double form_error_fraction = 0;  // DiagnosisSpec::form_error
  double temperature = 1;
  double best_chi2_p_value = 1;  // of the best class at the stated noise
  int degrees_of_freedom = 0;
  std::vector<DiagnosisCandidate> candidates;  // ranked, most probable first
  std::vector<std::pair<std::string, double>> kind_probabilities;  // "none" and kinds
  std::vector<ElementIndicator> localisation;
  // The verdict: the top class, its probability, and whether it is separated
  // from the others (the top class alone reaches `confidence`); when not, the
  // classes that together do.
  std::string verdict;
  double verdict_probability = 0;
  bool separated = false;
  std::vector<std::string> indistinguishable;
  double confidence = 0.9;
  StatedPriors priors;  // as the study states them (diagnosis.priors, weights)
  std::vector<std::string> warnings;
};

// Runs the diagnosis on `study`, which needs a cantilever model and a
// `diagnosis` section (defaults apply when it is absent). Throws InputError for
// a model that is not a cantilever, unusable measurements, bad options, or
// stated priors that do not apply (before any fit).
DiagnosisResult RunDiagnosis(const Study& study);

}  // namespace femup
