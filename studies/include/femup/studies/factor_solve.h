// One identification of the correction factors from a study's measured states:
// the paper's linear method (Z d = F on a linear solver) or iterative
// eigen-sensitivity updating (on a nonlinear solver), with the study's fixed
// values, bounds and equalities applied either way. The update and noise
// pipelines both go through here, so every solver is reachable from both.
#pragma once

#include <memory>
#include <vector>

#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/linear_problem.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/lstsq.h"
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

// SolveFactors for many sets of measured modes of one study and solver, with
// diagnostics off (a noise study's draws), when only x and whether it is usable
// are read. The lstsq solver on the linear method's Z d = F (fixed values, no
// equalities, not the normal system) is prepared once: Phi' B_k and the like
// by PreparedCorrectionSystem, the free columns and fixed values resolved, and
// each set solved by FullRankLeastSquares in per-worker work space, with no
// allocation once sizes have settled. Every other case, and a set whose full
// column rank cannot be proved, goes through SolveFactors: the answers are
// lstsq's either way. Holds references to the study and the FEM modes.
class PreparedFactorSolve {
 public:
  // Throws InputError as SolveFactors would for the study's set-up (a fixed
  // name that matches nothing, FEM modes that do not fit the model).
  PreparedFactorSolve(const Study& study, const SolverSpec& spec, const Modes& fem_modes);

  // One per thread; reused between calls.
  struct Workspace {
    PreparedCorrectionSystem::Workspace system;
    Eigen::MatrixXd a, a_free;
    Eigen::VectorXd b, b_free, z;
    std::unique_ptr<FullRankLeastSquares> qr;
  };
  struct Outcome {
    bool usable = false;  // solved (usable summary) and finite
    double seconds = 0;   // build and solve
  };
  // The factors into x (sized to the model's parameters; NaN when the solver
  // returned none).
  Outcome Solve(const std::vector<ModalData>& measured, Workspace* work,
                Eigen::Ref<Eigen::VectorXd> x) const;

  // True when sets are solved on the prepared path (before any fallback).
  bool prepared() const { return system_ != nullptr; }

 private:
  const Study* study_;
  const SolverSpec* spec_;
  const Modes* fem_modes_;
  std::unique_ptr<PreparedCorrectionSystem> system_;
  std::vector<int> free_;                      // free unknowns, ascending
  std::vector<std::pair<int, double>> fixed_;  // (index, value)
};

}  // namespace femup
