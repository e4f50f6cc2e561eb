// Timing of the paper-sized linear update: assembly of Z d = F and its SVD
// solve, per form. Run: ./build/bench/paper_chain_bench
#include <benchmark/benchmark.h>

#include "femup/measurement.h"
#include "femup/modal.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"

namespace {

void BM_AssembleAndSolve(benchmark::State& state) {
  const femup::PaperChainScenario s = femup::PaperChain(3);
  const femup::Modes fem = femup::SolveModes(s.model.stiffness(), s.model.mass());
  const std::vector<femup::ModalData> measured = {
      femup::PredictModes(s.model, s.preset, femup::Immersion::kDry, 2, "air"),
      femup::PredictModes(s.model, s.preset, femup::Immersion::kWet, 2, "water")};
  femup::CorrectionSystemOptions options;
  options.form =
      state.range(0) ? femup::SystemForm::kSummed : femup::SystemForm::kStacked;
  const auto solver = femup::CreateLinearSolver("lstsq");
  for (auto _ : state) {
    femup::LinearProblem p =
        femup::BuildCorrectionSystem(s.model, fem, measured, options);
    p.Fix("mass[4]", 0.0058);
    benchmark::DoNotOptimize(solver->Solve(p).x);
  }
}
BENCHMARK(BM_AssembleAndSolve)->Arg(0)->Arg(1)->ArgName("summed");

}  // namespace
