#include "femup/studies/factor_solve.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "femup/core/errors.h"
#include "femup/core/linalg/node_ordering.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/normal_correction_system.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/solvers/uncertainty.h"

namespace femup {

namespace {

bool ShapesComplete(const std::vector<ModalData>& measured, int num_dofs) {
  for (const ModalData& m : measured) {
    if (!m.IsComplete(num_dofs)) return false;
  }
  return true;
}

}  // namespace

bool UsesNormalCorrectionSystem(const Study& study) {
  return study.system.form == SystemForm::kStacked && study.system.num_fem_modes < 0 &&
         study.model.num_dofs() > EigenOptions{}.dense_limit;
}

Modes FemModesFor(const Study& study) {
  if (UsesNormalCorrectionSystem(study)) return Modes{};
  const int n = study.model.num_dofs();
  EigenOptions options;
  if (study.system.num_fem_modes > 0 && study.system.num_fem_modes < n - 1) {
    options.num_modes = study.system.num_fem_modes;
  } else if (n > options.dense_limit) {
    const bool summed = study.system.form == SystemForm::kSummed;
    throw InputError(study.path,
                     std::string(summed ? "system.form: the summed form"
                                        : "system.fem_modes: this many FEM modes") +
                         " needs a dense eigen-solve of all " + std::to_string(n) +
                         " DOFs (the limit is " + std::to_string(options.dense_limit) +
                         "); use form: stacked without fem_modes (weighted by M^-1 "
                         "without the modes) or fewer system.fem_modes");
  }
  return SolveModes(study.model.stiffness(), study.model.mass(),
                    WithNodeOrdering(options, study.model.dof_labels()));
}

FactorSolve SolveFactors(const Study& study, const SolverSpec& spec,
                         const Modes& fem_modes, const std::vector<ModalData>& measured,
                         const FactorSolveOptions& options) {
  FactorSolve out;
  LinearProblem& p = out.problem;
  const int n = study.model.num_parameters();
  if (spec.method == "linear" || ShapesComplete(measured, study.model.num_dofs())) {
    CorrectionSystemOptions system = study.system;
    system.row_labels = study.system.row_labels && options.diagnostics;
    p = UsesNormalCorrectionSystem(study)
            ? BuildNormalCorrectionSystem(study.model, measured)
            : BuildCorrectionSystem(study.model, fem_modes, measured, system);
  } else {
    p.names = study.model.ParameterNames();
    for (const Parameter& q : study.model.parameters())
      p.groups.push_back(ToString(q.kind));
  }
  for (const auto& [name, value] : study.fixed) p.Fix(name, value);
  p.lower = study.lower;
  p.upper = study.upper;
  p.equality_matrix = study.equality_matrix;
  p.equality_rhs = study.equality_rhs;
  p.prior = spec.prior_mean;

  if (spec.method == "linear") {
    LinearSolverOptions linear = spec.linear;
    linear.diagnostics = spec.linear.diagnostics && options.diagnostics;
    out.solution = CreateLinearSolver(spec.name, linear)->Solve(p);
    return out;
  }

  NonlinearProblem np =
      BuildEigenSensitivityProblem(study.model, measured, spec.sensitivity);
  np.fixed = p.fixed;
  np.lower = study.lower;
  np.upper = study.upper;
  np.equality_matrix = study.equality_matrix;
  np.equality_rhs = study.equality_rhs;
  // Start at the nominal model, with fixed values in place, inside the bounds.
  for (const auto& [i, value] : np.fixed) np.initial[i] = value;
  for (int i = 0; i < n; ++i) {
    if (np.lower.size() > 0) np.initial[i] = std::max(np.initial[i], np.lower[i]);
    if (np.upper.size() > 0) np.initial[i] = std::min(np.initial[i], np.upper[i]);
  }
  out.nonlinear_residuals = np.num_residuals;
  const NonlinearSolution ns =
      CreateNonlinearSolver(spec.name, spec.nonlinear)->Solve(np);
  LinearSolution& s = out.solution;
  s.x = ns.x;
  s.summary = ns.summary;
  s.noise_estimated = false;  // residuals are divided by the stated sigmas
  s.confidence_level = spec.linear.confidence_level;
  if (p.A.size() > 0 && ns.x.size() == n) s.residual = p.A * ns.x - p.b;
  s.covariance = ns.covariance;
  // What the data fix: the sensitivity Jacobian at the answer, over the free
  // parameters (with frequencies only there are few rows: the report says
  // which combinations stay unseen).
  if (ns.jacobian.rows() > 0 && ns.jacobian.cols() == n) {
    std::vector<bool> is_fixed(n, false);
    for (const auto& f : p.fixed) is_fixed[f.first] = true;
    std::vector<int> free;
    for (int i = 0; i < n; ++i) {
      if (!is_fixed[i]) free.push_back(i);
    }
    Eigen::MatrixXd j(ns.jacobian.rows(), static_cast<Eigen::Index>(free.size()));
    std::vector<std::string> names, groups;
    for (std::size_t c = 0; c < free.size(); ++c) {
      j.col(static_cast<Eigen::Index>(c)) = ns.jacobian.col(free[c]);
      names.push_back(p.names[free[c]]);
      groups.push_back(p.groups[free[c]]);
    }
    s.identifiability =
        AnalyseIdentifiability(j, names, groups, spec.linear.relative_rank_tolerance);
  }
  SetIntervals(0.0, &s);  // known noise: normal quantile
  return out;
}

PreparedFactorSolve::PreparedFactorSolve(const Study& study, const SolverSpec& spec,
                                         const Modes& fem_modes)
    : study_(&study), spec_(&spec), fem_modes_(&fem_modes) {
  const bool eligible = spec.method == "linear" && spec.name == "lstsq" &&
                        !UsesNormalCorrectionSystem(study) &&
                        study.equality_matrix.size() == 0;
  if (!eligible) return;
  CorrectionSystemOptions system = study.system;
  system.row_labels = false;
  system_ = std::make_unique<PreparedCorrectionSystem>(study.model, fem_modes, system);
  LinearProblem names;  // resolves the fixed names as SolveFactors does
  names.names = study.model.ParameterNames();
  for (const auto& [name, value] : study.fixed) names.Fix(name, value);
  names.A.resize(0, static_cast<Eigen::Index>(names.names.size()));
  free_ = names.FreeUnknowns();
  fixed_ = names.fixed;
}

PreparedFactorSolve::Outcome PreparedFactorSolve::Solve(
    const std::vector<ModalData>& measured, Workspace* work,
    Eigen::Ref<Eigen::VectorXd> x) const {
  Outcome out;
  if (system_) {
    const auto start = std::chrono::steady_clock::now();
    system_->Fill(measured, &work->system, &work->a, &work->b);
    // As lstsq's reduction: the free columns gathered, the fixed ones moved
    // to the right-hand side.
    const Eigen::Index nfree = static_cast<Eigen::Index>(free_.size());
    work->a_free.resize(work->a.rows(), nfree);
    for (Eigen::Index k = 0; k < nfree; ++k) work->a_free.col(k) = work->a.col(free_[k]);
    work->b_free = work->b;
    for (const auto& [i, value] : fixed_) work->b_free -= value * work->a.col(i);
    if (!work->qr) {
      work->qr = std::make_unique<FullRankLeastSquares>(
          spec_->linear.relative_rank_tolerance, spec_->linear.scale_columns);
    }
    if (x.size() == study_->model.num_parameters() &&
        work->qr->Solve(work->a_free, work->b_free, &work->z)) {
      for (const auto& [i, value] : fixed_) x[i] = value;
      for (Eigen::Index k = 0; k < nfree; ++k) x[free_[k]] = work->z[k];
      out.usable = true;
      out.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return out;
    }
  }
  FactorSolveOptions lean;
  lean.diagnostics = false;
  const FactorSolve fs = SolveFactors(*study_, *spec_, *fem_modes_, measured, lean);
  out.seconds = fs.solution.summary.time_seconds;
  if (fs.solution.x.size() == x.size()) {
    x = fs.solution.x;
    out.usable = fs.solution.summary.usable() && fs.solution.x.allFinite();
  } else {
    x.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

}  // namespace femup
