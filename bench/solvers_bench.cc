// Every solver of the framework on test problems, timed by Google Benchmark,
// with each answer's accuracy reported beside its time. Run all of them with
// scripts/bench.sh, or: ./build-bench/bench/solvers_bench --benchmark_min_time=0.05
//
// Benchmarks, named <problem>/<solver>:
//   paper_fixed/*     the paper's chain (3 wet masses, 2 air + 2 water modes,
//                     stacked system) with mass[4] fixed at its preset value;
//                     known answer: the preset factors.
//   paper_free/*      the same system without the fix: rank deficient by the
//                     common scaling of mass and stiffness (problems/
//                     eigen_sensitivity.h explains the null direction).
//   paper_noisy/*     paper_fixed with measured eigenvalues and shapes corrupted
//                     by 1 % Gaussian noise (seed kNoiseSeed).
//   illposed_<name>/* Hansen's problems at n = 64, b with 0.1 % relative noise
//                     (seed kNoiseSeed); tikhonov and tsvd choose their
//                     parameter by GCV.
//   bounded_2000x200/*  bench/bounded_problem.h: 2000 x 200 dense, box [-1, 1].
//   eigen_sensitivity/* the nonlinear update on the paper chain (noise-free
//                     modes, shapes at every DOF) from the nominal model, mass[4]
//                     fixed.
//   frame_large/*     the large sparse correction-factor problem: a 2D plane
//                     frame of 100 storeys x 50 bays, 4 elements per member
//                     (core/include/femup/core/fe/plane_frame.h: 106,200 DOF), 1,200
//                     factors (100 storey masses, 1,000 column/beam stiffness
//                     blocks, 100 added-mass blocks in the 20 wet storeys),
//                     preset factors drawn with seed kNoiseSeed, 5 air + 5 water
//                     modes with shapes at every DOF (noise-free), mass[s50]
//                     fixed. frame_large/build times building the model, the 10
//                     modes (sparse shift-invert) and the compressed
//                     M^-1-weighted system (problems/normal_correction_system.h)
//                     once, with counters per stage; the solvers then run on the
//                     1,200 x 1,200 compressed system, bvls/ceres/ipopt with
//                     bounds [-0.5, 1] on every factor.
//
// Counters (also in --benchmark_out JSON), from the last solve:
//   solver_iters  iterations the solver reports (1 for the direct solvers; bvls
//                 counts active-set changes, so 0 when no bound is involved)
//   error         paper_fixed, eigen_sensitivity: max |x - preset|;
//                 paper_noisy: the same, so it includes the noise's effect;
//                 paper_free: max |component of x - preset orthogonal to the
//                 null direction| (0 for any exact solution)
//   rel_error     illposed: ||x - x_exact|| / ||x_exact||
//                 frame_large: max |x - preset| (error), counters dofs,
//                 factors, data_rows
//   kkt           the solver's KKT residual, where it checks one
//   cost          0.5 ||W (A x - b)||^2 (0.5 ||r||^2 for the nonlinear update)
//   active        bounded: unknowns on a bound at the answer
//   peak_rss_kib  growth of the process's peak resident set (VmHWM, reset
//                 through /proc/self/clear_refs) over its resident set at the
//                 start, across every solve of the benchmark: the largest
//                 working set of one solve, to within the heap. Blocks under
//                 256 KiB come from a heap that earlier benchmarks may already
//                 have grown, so small problems read 0. Absent when the peak
//                 cannot be reset (not Linux >= 4.0) or mallopt failed.
// The label is the solver's status; FEMUP_BENCH_VERBOSE=1 prints each
// solver's message and warnings to stderr.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bounded_problem.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/blas.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/evaluation/ill_posed.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/noise.h"
#include "femup/problems/normal_correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"

namespace {

constexpr std::uint64_t kNoiseSeed = 20240601;

// Blocks of 256 KiB and more are mmapped and returned to the system when
// freed. glibc otherwise raises this threshold after the first large free and
// keeps freed blocks in its heap, so a benchmark would reuse memory an earlier
// one left resident and its peak growth would read near zero. Set before any
// benchmark runs (static initialisation).
const bool kMallocConfigured = mallopt(M_MMAP_THRESHOLD, 256 * 1024) == 1;

// A "Vm...:" field of /proc/self/status in KiB, or -1.
double StatusKib(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  double value = 0;
  while (status >> key) {
    if (key == field && status >> value) return value;
    status.ignore(1 << 10, '\n');
  }
  return -1;
}

// Measures the growth of the peak resident set from construction on.
class PeakRss {
 public:
  PeakRss() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";  // resets VmHWM to the current resident set (Linux >= 4.0)
    clear.flush();
    reset_ = kMallocConfigured && static_cast<bool>(clear);
    start_kib_ = StatusKib("VmRSS:");
  }
  // Sets the counter when the peak could be reset.
  void Report(benchmark::State& state) const {
    const double peak = StatusKib("VmHWM:");
    if (reset_ && peak >= 0 && start_kib_ >= 0) {
      state.counters["peak_rss_kib"] = peak - start_kib_;
    }
  }

 private:
  bool reset_ = false;
  double start_kib_ = -1;
};

// The counters every solver's summary gives, and its status as the label.
void ReportSummary(benchmark::State& state, const femup::SolverSummary& s) {
  state.SetLabel(femup::ToString(s.status));
  state.counters["solver_iters"] = s.iterations;
  state.counters["cost"] = s.cost;
  if (std::isfinite(s.kkt_residual)) state.counters["kkt"] = s.kkt_residual;
}

// Measured modes of the paper chain at its preset factors: 2 air, 2 water,
// shapes at every DOF; corrupted when `noise_level` > 0.
std::vector<femup::ModalData> PaperData(const femup::PaperChainScenario& s,
                                        double noise_level) {
  std::vector<femup::ModalData> data = {
      femup::PredictModes(s.model, s.preset, femup::Immersion::kDry, 2, "air"),
      femup::PredictModes(s.model, s.preset, femup::Immersion::kWet, 2, "water")};
  if (noise_level > 0) {
    femup::NoiseModel noise;
    noise.level = noise_level;
    std::mt19937_64 rng(kNoiseSeed);
    for (femup::ModalData& d : data) d = femup::Corrupt(d, noise, &rng);
  }
  return data;
}

femup::LinearProblem PaperSystem(const femup::PaperChainScenario& s, double noise_level,
                                 bool fix) {
  const femup::Modes fem = femup::SolveModes(s.model.stiffness(), s.model.mass());
  femup::LinearProblem p =
      femup::BuildCorrectionSystem(s.model, fem, PaperData(s, noise_level), {});
  if (fix) p.Fix(s.fixed_parameter, s.preset[s.model.FindParameter(s.fixed_parameter)]);
  return p;
}

// The direction along which the paper chain's data do not change: (1 + d) of
// mass and stiffness factors and d of added-mass factors all scaled together.
Eigen::VectorXd NullDirection(const femup::PaperChainScenario& s) {
  Eigen::VectorXd v = s.preset;
  for (int i = 0; i < v.size(); ++i) {
    if (s.model.parameter(i).kind != femup::ParameterKind::kAddedMass) v[i] += 1.0;
  }
  return v.normalized();
}

// Times `solver` on `problem`; `accuracy` sets the accuracy counters from the answer.
void RunLinear(benchmark::State& state, const std::string& solver_name,
               const femup::LinearProblem& problem,
               const std::function<void(benchmark::State&, const femup::LinearSolution&)>&
                   accuracy) {
  const auto solver = femup::CreateLinearSolver(solver_name);
  femup::LinearSolution solution;
  const PeakRss rss;
  for (auto _ : state) {
    solution = solver->Solve(problem);
    benchmark::DoNotOptimize(solution.x.data());
  }
  rss.Report(state);
  ReportSummary(state, solution.summary);
  accuracy(state, solution);
  if (std::getenv("FEMUP_BENCH_VERBOSE") != nullptr) {
    std::cerr << solver_name << ": " << femup::ToString(solution.summary.status) << ": "
              << solution.summary.message << "\n";
    for (const std::string& w : solution.summary.warnings)
      std::cerr << "  warning: " << w << "\n";
  }
}

void RegisterPaperChain() {
  const femup::PaperChainScenario s = femup::PaperChain(3);
  const Eigen::VectorXd preset = s.preset;
  const Eigen::VectorXd null = NullDirection(s);
  const auto max_error = [preset](benchmark::State& state,
                                  const femup::LinearSolution& x) {
    state.counters["error"] = (x.x - preset).cwiseAbs().maxCoeff();
  };
  const auto line_error = [preset, null](benchmark::State& state,
                                         const femup::LinearSolution& x) {
    const Eigen::VectorXd e = x.x - preset;
    state.counters["error"] = (e - e.dot(null) * null).cwiseAbs().maxCoeff();
  };
  const femup::LinearProblem fixed = PaperSystem(s, 0.0, true);
  const femup::LinearProblem free = PaperSystem(s, 0.0, false);
  const femup::LinearProblem noisy = PaperSystem(s, 0.01, true);
  for (const std::string& name : femup::AvailableLinearSolvers()) {
    benchmark::RegisterBenchmark(("paper_fixed/" + name).c_str(), RunLinear, name, fixed,
                                 max_error);
    benchmark::RegisterBenchmark(("paper_free/" + name).c_str(), RunLinear, name, free,
                                 line_error);
    benchmark::RegisterBenchmark(("paper_noisy/" + name).c_str(), RunLinear, name, noisy,
                                 max_error);
  }
}

void RegisterIllPosed() {
  for (const std::string& name : femup::IllPosedProblemNames()) {
    const femup::IllPosedProblem ip = femup::MakeIllPosedProblem(name, 64);
    femup::LinearProblem p;
    p.A = ip.A;
    p.b = femup::AddRelativeNoise(ip.b, 1e-3, kNoiseSeed);
    for (int j = 0; j < p.A.cols(); ++j) p.names.push_back("x" + std::to_string(j + 1));
    const Eigen::VectorXd exact = ip.x_exact;
    const auto rel_error = [exact](benchmark::State& state,
                                   const femup::LinearSolution& x) {
      state.counters["rel_error"] = (x.x - exact).norm() / exact.norm();
    };
    for (const std::string solver : {"tikhonov", "tsvd", "lstsq"}) {
      benchmark::RegisterBenchmark(("illposed_" + name + "/" + solver).c_str(), RunLinear,
                                   solver, p, rel_error);
    }
  }
}

void RegisterBounded() {
  const femup::LinearProblem p = femup_bench::RandomBoundedProblem(2000, 200, kNoiseSeed);
  const auto active = [p](benchmark::State& state, const femup::LinearSolution& x) {
    state.counters["active"] = femup_bench::ActiveBounds(p, x.x);
  };
  for (const std::string solver : {"bvls", "ceres", "ipopt"}) {
    benchmark::RegisterBenchmark(("bounded_2000x200/" + solver).c_str(), RunLinear,
                                 solver, p, active);
  }
}

void RunEigenSensitivity(benchmark::State& state, const std::string& solver_name) {
  const femup::PaperChainScenario s = femup::PaperChain(3);
  femup::NonlinearProblem p =
      femup::BuildEigenSensitivityProblem(s.model, PaperData(s, 0.0), {});
  p.fixed = {{s.model.FindParameter(s.fixed_parameter),
              s.preset[s.model.FindParameter(s.fixed_parameter)]}};
  const auto solver = femup::CreateNonlinearSolver(solver_name);
  femup::NonlinearSolution solution;
  const PeakRss rss;
  for (auto _ : state) {
    solution = solver->Solve(p);
    benchmark::DoNotOptimize(solution.x.data());
  }
  rss.Report(state);
  ReportSummary(state, solution.summary);
  state.counters["error"] = (solution.x - s.preset).cwiseAbs().maxCoeff();
}

void RegisterEigenSensitivity() {
  for (const std::string& name : femup::AvailableNonlinearSolvers()) {
    benchmark::RegisterBenchmark(("eigen_sensitivity/" + name).c_str(),
                                 RunEigenSensitivity, name);
  }
}

struct LargeFrame {
  femup::LinearProblem problem;  // compressed, mass[s50] fixed
  Eigen::VectorXd preset;
  int dofs = 0;
  double seconds_model = 0, seconds_modes = 0;
  femup::NormalCorrectionStats stats;
};

double SecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

LargeFrame BuildLargeFrame() {
  LargeFrame f;
  auto t0 = std::chrono::steady_clock::now();
  femup::PlaneFrameSpec spec;
  spec.storeys = 100;
  spec.bays = 50;
  spec.elements_per_member = 4;
  spec.blocks_per_storey = 5;
  spec.wet_storeys = 20;
  const femup::ParametrisedModel model = femup::BuildPlaneFrame(spec);
  f.dofs = model.num_dofs();
  std::mt19937_64 rng(kNoiseSeed);
  std::uniform_real_distribution<double> structural(-0.05, 0.05), added(0.3, 0.5);
  f.preset.resize(model.num_parameters());
  for (int i = 0; i < model.num_parameters(); ++i) {
    f.preset[i] = model.parameter(i).kind == femup::ParameterKind::kAddedMass
                      ? added(rng)
                      : structural(rng);
  }
  f.seconds_model = SecondsSince(t0);
  t0 = std::chrono::steady_clock::now();
  const std::vector<femup::ModalData> data = {
      femup::PredictModes(model, f.preset, femup::Immersion::kDry, 5, "air"),
      femup::PredictModes(model, f.preset, femup::Immersion::kWet, 5, "water")};
  f.seconds_modes = SecondsSince(t0);
  f.problem = femup::BuildNormalCorrectionSystem(model, data, &f.stats);
  const int fixed = model.FindParameter("mass[s50]");
  f.problem.fixed = {{fixed, f.preset[fixed]}};
  return f;
}

const LargeFrame& GetLargeFrame() {
  static const LargeFrame frame = BuildLargeFrame();
  return frame;
}

void RunLargeFrameBuild(benchmark::State& state) {
  const PeakRss rss;
  for (auto _ : state) benchmark::DoNotOptimize(GetLargeFrame().problem.A.data());
  rss.Report(state);
  const LargeFrame& f = GetLargeFrame();
  state.counters["dofs"] = f.dofs;
  state.counters["factors"] = f.problem.num_unknowns();
  state.counters["data_rows"] = f.problem.data_rows();
  state.counters["s_model"] = f.seconds_model;
  state.counters["s_modes"] = f.seconds_modes;
  state.counters["s_assembly"] = f.stats.seconds_assembly;
  state.counters["s_compress"] = f.stats.seconds_compress;
  state.counters["dropped"] = f.stats.dropped;
}

void RunLargeFrame(benchmark::State& state, const std::string& solver_name,
                   bool bounded) {
  const LargeFrame& f = GetLargeFrame();
  femup::LinearProblem p = f.problem;
  if (bounded) {
    p.lower = Eigen::VectorXd::Constant(p.num_unknowns(), -0.5);
    p.upper = Eigen::VectorXd::Constant(p.num_unknowns(), 1.0);
  }
  const Eigen::VectorXd preset = f.preset;
  RunLinear(state, solver_name, p,
            [preset](benchmark::State& st, const femup::LinearSolution& x) {
              if (x.x.size() == preset.size())
                st.counters["error"] = (x.x - preset).cwiseAbs().maxCoeff();
            });
}

void RegisterLargeFrame() {
  // One repetition each: the build is done once per process (the first run
  // pays for it), and each solve takes seconds.
  benchmark::RegisterBenchmark("frame_large/build", RunLargeFrameBuild)
      ->Iterations(1)
      ->Repetitions(1)
      ->Unit(benchmark::kSecond);
  for (const std::string& name : femup::AvailableLinearSolvers()) {
    const bool bounded = name == "bvls" || name == "ceres" || name == "ipopt";
    benchmark::RegisterBenchmark(("frame_large/" + name).c_str(), RunLargeFrame, name,
                                 bounded)
        ->Repetitions(1)
        ->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

// Google Benchmark's main, with the benchmarks registered at run time: their
// problems are built here, once, not at static initialisation.
int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RegisterPaperChain();
  RegisterIllPosed();
  RegisterBounded();
  RegisterEigenSensitivity();
  RegisterLargeFrame();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
