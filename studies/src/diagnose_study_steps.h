// Private to femup_studies: the steps of RunDiagnosis (diagnose_study.cc), each
// defined in the diagnose_study_*.cc file of its concept: the data and its
// noise, the classes' fits, their evidence and probabilities, the localisation
// scan, and the number format the outputs and the verdict share.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/diagnose_study.h"

namespace femup::diagnose_steps {

// A family's effect with its stated priors (RunDiagnosis's make_effect).
using EffectFactory = std::function<std::unique_ptr<Effect>(const std::string&)>;

// diagnose_study_data.cc: the measured states as observed modes at their
// sensors, their noise (stated, mesh and form error), the fitted and held-out
// modes (r.fitted_data, r.held_out_data, r.degrees_of_freedom) and the nominal
// model's modes paired with them (r.nominal_fitted, r.nominal_held_out).
void PrepareData(const Study& study, const DiagnosisSpec& spec,
                 const CantileverSpec& nominal, DiagnosisResult* result);

// diagnose_study_fit.cc: the classes' multi-start fits.
std::vector<const Effect*> Pointers(const std::vector<std::unique_ptr<Effect>>& effects);

struct FitOutcome {
  bool ok = false;
  bool converged = false;
  std::string message;
  Eigen::VectorXd theta;
  Eigen::MatrixXd jacobian;
  double chi2 = 0;
  std::vector<LocalOptimum> optima;  // every start's answer, distinct ones only
};

// Multi-start fit of one class on `data` (the definition says more).
FitOutcome FitClass(const EffectFitData& data, const std::vector<const Effect*>& effects,
                    const std::vector<Eigen::VectorXd>& starts,
                    const NonlinearSolver& solver, int* runs);

// Fits every candidate class (none first, then the singles, then the pairs,
// whose starts use the singles' answers) into r.candidates, with their
// predictions of the fitted and held-out modes, locations and magnitudes.
void FitClasses(const std::vector<std::vector<std::string>>& classes,
                const CantileverSpec& nominal, const EffectFactory& make_effect,
                const NonlinearSolver& solver, DiagnosisResult* result);

// diagnose_study_evidence.cc: every candidate's evidence (Laplace, tempered when
// even the best class fails, sampled when the study asks), the posterior
// probabilities (sorted, most probable first) and each kind's probability.
void ScoreClasses(const DiagnosisSpec& spec, const std::vector<std::string>& kinds,
                  std::size_t num_singles, std::size_t num_pairs,
                  const EffectFactory& make_effect, DiagnosisResult* result);

// diagnose_study_localise.cc: with diagnosis.localise, the chi2 drop of
// changing one element's stiffness or mass alone (r.localisation).
void LocaliseByElement(const DiagnosisSpec& spec, const CantileverSpec& nominal,
                       const NonlinearSolver& solver, DiagnosisResult* result);

// diagnose_study.cc: `v` with `digits` decimals.
std::string Fixed(double v, int digits);

}  // namespace femup::diagnose_steps
