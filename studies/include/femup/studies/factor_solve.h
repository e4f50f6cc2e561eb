// One identification of the correction factors from a study's measured states:
// the paper's linear method (Z d = F on a linear solver) or iterative
// eigen-sensitivity updating (on a nonlinear solver), with the study's fixed
// values, bounds and equalities applied either way. The update and noise
// pipelines both go through here, so every solver is reachable from both.
#pragma once

#include <vector>

#include "femup/measurement.h"
#include "femup/modal.h"
#include "femup/problems/linear_problem.h"
#include "femup/solvers/linear_solver.h"
#include "femup/studies/study.h"

namespace femup {

struct FactorSolve {
  // Z d = F with the constraints (empty A when the method is sensitivity and
  // the shapes are not known at every DOF, so Z cannot be formed).
  LinearProblem problem;
  // The factors with status, message, uncertainty. For the sensitivity method:
  // x, summary and covariance come from the nonlinear solve (residual = Z x - F
  // when Z exists).
  LinearSolution solution;
  int nonlinear_residuals = 0;  // sensitivity: number of residuals fitted
};

// True when the study's linear system is built without the FEM eigenbasis:
// the stacked form with every FEM mode (system.fem_modes absent) on a model of
// more than EigenOptions{}.dense_limit DOFs. The weighting by all FEM modes is
// then M^-1, applied through a sparse Cholesky factor of M
// (normal_correction_system.h): the same least-squares problem, in O(nnz)
// memory instead of a dense eigenbasis.
bool UsesNormalCorrectionSystem(const Study& study);

// The FEM modes of the nominal model that SolveFactors needs: none when
// UsesNormalCorrectionSystem(study); the lowest system.fem_modes when that is
// given (by the sparse eigensolver above the dense limit); otherwise every
// mode (dense). Throws InputError naming "system.form" when the summed form
// would need every mode of a model above the dense limit.
Modes FemModesFor(const Study& study);

struct FactorSolveOptions {
  // false: the caller reads only solution.x and solution.summary, many times over
  // (a noise study's draws): the problem gets no row labels and linear solvers
  // run with LinearSolverOptions::diagnostics = false (lstsq: no identifiability
  // analysis, no covariance; QR when the rank is provably full).
  bool diagnostics = true;
};

// `fem_modes`: from FemModesFor(study). Throws InputError for unusable input
// (e.g. a fixed name that matches nothing).
FactorSolve SolveFactors(const Study& study, const SolverSpec& spec,
                         const Modes& fem_modes, const std::vector<ModalData>& measured,
                         const FactorSolveOptions& options = {});

}  // namespace femup
