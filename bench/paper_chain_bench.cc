// Timing of the paper-sized linear update: assembly of Z d = F and its SVD
// solve, per form. Run: ./build/bench/paper_chain_bench
#include <benchmark/benchmark.h>

#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/noise.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/lstsq.h"

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

// The phases of one draw of the paper's noise study (summed form, mass[4]
// fixed, 2 + 2 modes corrupted at 5 %), each on its own: what
// RunNoiseStudy's per-draw cost is made of.
struct NoiseDraw {
  femup::PaperChainScenario s = femup::PaperChain(3);
  femup::Modes fem = femup::SolveModes(s.model.stiffness(), s.model.mass());
  std::vector<femup::ModalData> clean = {
      femup::PredictModes(s.model, s.preset, femup::Immersion::kDry, 2, "air"),
      femup::PredictModes(s.model, s.preset, femup::Immersion::kWet, 2, "water")};
  femup::NoiseModel noise;
  femup::CorrectionSystemOptions options;
  NoiseDraw() {
    noise.level = 0.05;
    options.form = femup::SystemForm::kSummed;
    options.row_labels = false;
  }
};

void BM_NoiseDrawCorrupt(benchmark::State& state) {
  NoiseDraw d;
  std::vector<femup::ModalData> noisy = d.clean;
  std::uint64_t draw = 0;
  for (auto _ : state) {
    femup::CounterRng rng(1, 0, draw++);
    for (std::size_t i = 0; i < noisy.size(); ++i)
      femup::Corrupt(d.clean[i], d.noise, &rng, &noisy[i]);
    benchmark::DoNotOptimize(noisy[0].shapes.data());
  }
}
BENCHMARK(BM_NoiseDrawCorrupt);

void BM_NoiseDrawFill(benchmark::State& state) {
  NoiseDraw d;
  const femup::PreparedCorrectionSystem system(d.s.model, d.fem, d.options);
  femup::PreparedCorrectionSystem::Workspace work;
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  for (auto _ : state) {
    system.Fill(d.clean, &work, &a, &b);
    benchmark::DoNotOptimize(a.data());
  }
}
BENCHMARK(BM_NoiseDrawFill);

// The draw's least-squares problem: the 12 free columns (mass[4] fixed).
void BM_NoiseDrawLeastSquares(benchmark::State& state) {
  NoiseDraw d;
  const femup::LinearProblem p =
      femup::BuildCorrectionSystem(d.s.model, d.fem, d.clean, d.options);
  Eigen::MatrixXd free(p.A.rows(), 12);
  free << p.A.leftCols(3), p.A.rightCols(9);
  femup::FullRankLeastSquares qr(1e-10, true);
  Eigen::VectorXd z;
  for (auto _ : state) {
    benchmark::DoNotOptimize(qr.Solve(free, p.b, &z));
  }
}
BENCHMARK(BM_NoiseDrawLeastSquares);

}  // namespace
