// PreparedFactorSolve (studies/include/femup/studies/factor_solve.h): on its
// prepared path and on every fallback it returns the factors SolveFactors
// returns with diagnostics off, draw after draw with reused work space.
#include "femup/studies/factor_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "femup/counter_rng.h"
#include "femup/problems/noise.h"
#include "femup/studies/study.h"

namespace femup {
namespace {

std::string Example(const std::string& name) {
  return std::string(FEMUP_EXAMPLES_DIR) + "/" + name;
}

std::vector<ModalData> NoisyDraw(const std::vector<ModalData>& clean, double level,
                                 int draw) {
  NoiseModel noise;
  noise.level = level;
  CounterRng rng(99, 0, static_cast<std::uint64_t>(draw));
  std::vector<ModalData> out;
  for (const ModalData& m : clean) out.push_back(Corrupt(m, noise, &rng));
  return out;
}

// Relative agreement of two factor vectors (both finite).
double Difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / (1.0 + b.cwiseAbs().maxCoeff());
}

TEST(PreparedFactorSolve, LstsqDrawsEqualSolveFactors) {
  for (const char* form : {"summed", "stacked"}) {
    Study study = LoadStudy(Example("paper_chain_noise.yaml"));
    SystemFormFromString(form, &study.system.form);
    const Modes fem = FemModesFor(study);
    const std::vector<ModalData> clean = MeasuredStates(study);
    const PreparedFactorSolve prepared(study, study.solver, fem);
    EXPECT_TRUE(prepared.prepared());
    PreparedFactorSolve::Workspace work;
    FactorSolveOptions lean;
    lean.diagnostics = false;
    Eigen::VectorXd x(study.model.num_parameters());
    for (int draw = 0; draw < 40; ++draw) {
      const std::vector<ModalData> noisy = NoisyDraw(clean, 0.05, draw);
      const PreparedFactorSolve::Outcome outcome = prepared.Solve(noisy, &work, x);
      const FactorSolve reference = SolveFactors(study, study.solver, fem, noisy, lean);
      ASSERT_TRUE(outcome.usable) << form << " draw " << draw;
      EXPECT_LT(Difference(x, reference.solution.x), 1e-11) << form << " draw " << draw;
      EXPECT_EQ(x[3], 0.0058) << "mass[4] is fixed";
      EXPECT_GE(outcome.seconds, 0.0);
    }
  }
}

// No constraint: the common scaling leaves Z rank deficient, the prepared
// path cannot prove full rank, and the SVD path's minimum-norm answer comes
// back, as SolveFactors gives it.
TEST(PreparedFactorSolve, RankDeficientDrawsFallBackToTheSvdPath) {
  Study study = LoadStudy(Example("paper_chain_noise.yaml"));
  study.fixed.clear();
  const Modes fem = FemModesFor(study);
  const std::vector<ModalData> clean = MeasuredStates(study);
  const PreparedFactorSolve prepared(study, study.solver, fem);
  PreparedFactorSolve::Workspace work;
  FactorSolveOptions lean;
  lean.diagnostics = false;
  Eigen::VectorXd x(study.model.num_parameters());
  const PreparedFactorSolve::Outcome outcome = prepared.Solve(clean, &work, x);
  const FactorSolve reference = SolveFactors(study, study.solver, fem, clean, lean);
  EXPECT_EQ(reference.solution.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_EQ(outcome.usable, reference.solution.summary.usable());
  EXPECT_EQ(x, reference.solution.x);
}

// Other solvers are not prepared: every draw is SolveFactors.
TEST(PreparedFactorSolve, OtherSolversGoThroughSolveFactors) {
  Study study = LoadStudy(Example("paper_chain_solver_comparison.yaml"));
  const Modes fem = FemModesFor(study);
  const std::vector<ModalData> clean = MeasuredStates(study);
  const std::vector<ModalData> noisy = NoisyDraw(clean, 0.01, 3);
  FactorSolveOptions lean;
  lean.diagnostics = false;
  for (const SolverSpec& spec : study.noise_study->compare) {
    if (spec.name == "ipopt") continue;  // slow here; the same code path as ceres
    const PreparedFactorSolve prepared(study, spec, fem);
    EXPECT_EQ(prepared.prepared(), spec.method == "linear" && spec.name == "lstsq")
        << spec.label;
    PreparedFactorSolve::Workspace work;
    Eigen::VectorXd x(study.model.num_parameters());
    const PreparedFactorSolve::Outcome outcome = prepared.Solve(noisy, &work, x);
    const FactorSolve reference = SolveFactors(study, spec, fem, noisy, lean);
    EXPECT_EQ(outcome.usable, reference.solution.summary.usable()) << spec.label;
    if (prepared.prepared()) {
      EXPECT_LT(Difference(x, reference.solution.x), 1e-11) << spec.label;
    } else {
      EXPECT_EQ(x, reference.solution.x) << spec.label;
    }
  }
}

}  // namespace
}  // namespace femup
