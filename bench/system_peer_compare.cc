// The linear correction-factor system of a large model, femup against a
// SciPy implementation of the same computation, in one run of this program.
//
// The model: a jacket-like space frame (space_frame.h) of about 10^5 DOF with
// about 10^3 correction factors (mass per level; leg, brace and horizontal
// stiffness and added mass per level and block). "Measured" modes: the lowest
// modes of the model with random preset factors (fixed seed), in air and in
// water, with shapes on every DOF. Both sides then build the least-squares
// problem of the linear method with the "all FEM modes" weighting M^-1
// (problems/normal_correction_system.h),
//   G = sum_j Z_j' M^-1 Z_j,  h = sum_j Z_j' M^-1 F_j,
// and solve it for the factors:
//   femup: BuildNormalCorrectionSystem (sparse Cholesky of M, sparse half
//          solves L^-1 P Z_j) and the "lstsq" linear solver (column-scaled
//          SVD, with its identifiability report and covariance);
//   scipy: bench/peer/normal_system_peer.py (Z_j assembled from the basis
//          matrices, M^-1 Z_j by SuperLU with a symmetric ordering, G and h
//          by products, numpy.linalg.lstsq on G d = h).
// Both fix the first factor (a mass factor) at its preset value: scaling K and
// M together changes no residual, so one factor must be fixed.
// The matrices (K, M, every basis, the modes) are built once and written as
// Matrix Market files; femup runs in a fork()ed child (its peak resident set
// is its own), scipy reads the files.
//
// The bound: the time to read every stored entry of K, M and the bases once
// from memory (values and indices, best of 3 passes): no method that looks at
// the whole model can beat it. Reported as femup's time over that bound.
//
// Usage: femup_system_peer_compare [--size 1e5] [--air-modes 5] [--water-modes 5]
//                                  [--python /usr/bin/python3] [--script path]
//                                  [--markdown file] [--keep dir] [--threads 1]
// --size: 1e5 (4 x 4 bays, 40 levels, 4 blocks, all wet: 102,720 DOF, 1000
// factors), 1e4 (2 x 2 bays, 10 levels, 2 blocks, all wet) or BXxBYxLEVELSxBLOCKS
// (all wet).
#include <malloc.h>
#include <stdlib.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/fe/space_frame.h"
#include "femup/core/io/matrix_market.h"
#include "femup/core/linalg/blas.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/normal_correction_system.h"
#include "femup/solvers/linear_solver.h"
#include "peer_runner.h"

// The BLAS's dgemm (Fortran; the lengths of the character arguments follow,
// as core/src/linalg/banded_eigen.cc explains).
extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc, std::size_t transa_length,
                       std::size_t transb_length);

namespace {

namespace fs = std::filesystem;
using femup_bench::Clock;
using femup_bench::Format;
using femup_bench::PeerResult;

constexpr std::uint64_t kSeed = 20261124;

using femup_bench::Seconds;

femup::SpaceFrameSpec ParseSize(const std::string& item) {
  femup::SpaceFrameSpec spec;
  spec.elements_per_member = 4;
  if (item == "1e5") {
    spec.bays_x = 4;
    spec.bays_y = 4;
    spec.levels = 40;
    spec.blocks_per_level = 4;
  } else if (item == "1e4") {
    spec.bays_x = 2;
    spec.bays_y = 2;
    spec.levels = 10;
    spec.blocks_per_level = 2;
  } else {
    char x1 = 0, x2 = 0, x3 = 0;
    std::stringstream in(item);
    if (!(in >> spec.bays_x >> x1 >> spec.bays_y >> x2 >> spec.levels >> x3 >>
          spec.blocks_per_level) ||
        x1 != 'x' || x2 != 'x' || x3 != 'x' || !in.eof()) {
      throw CLI::ValidationError("--size",
                                 "'" + item + "' is not 1e4, 1e5 or BXxBYxLEVELSxBLOCKS");
    }
  }
  spec.water_depth = spec.levels * spec.level_height + 1;  // every member wet
  if (const femup::Invalid bad = spec.Validate())
    throw CLI::ValidationError("--size", item + ": " + bad.ToString());
  return spec;
}

// One pass over every stored value and index of the matrices and of the index
// lists (the bases' DOFs); returns the best time of three and a checksum (so
// the reads are not optimised away).
double ReadBound(const std::vector<const femup::SparseMatrix*>& matrices,
                 const std::vector<const std::vector<int>*>& lists, double* checksum) {
  double best = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = Clock::now();
    double sum = 0;
    long long index_sum = 0;
    for (const femup::SparseMatrix* a : matrices) {
      const double* v = a->valuePtr();
      const int* inner = a->innerIndexPtr();
      const int* outer = a->outerIndexPtr();
      for (Eigen::Index k = 0; k < a->nonZeros(); ++k) {
        sum += v[k];
        index_sum += inner[k];
      }
      for (Eigen::Index k = 0; k <= a->outerSize(); ++k) index_sum += outer[k];
    }
    for (const std::vector<int>* list : lists) {
      for (int i : *list) index_sum += i;
    }
    best = std::min(best, Seconds(start));
    *checksum = sum + static_cast<double>(index_sum);
  }
  return best;
}

// This machine's arithmetic rate: a dense 1000 x 1000 product (2 n^3 flops,
// blocked and vectorised: near the core's peak), best of 3, in flop/s, by
// Eigen (built for any x86-64, so SSE2) and by the BLAS's dgemm (OpenBLAS's
// kernels for this processor: AVX2 or AVX-512); the floor takes the faster.
// With the flops a computation must make, it gives a time that no
// implementation of that computation on this machine can beat.
struct DenseRates {
  double eigen = 0, blas = 0;
  double best() const { return std::max(eigen, blas); }
};

DenseRates MeasureDenseRates() {
  const int n = 1000;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd a(n, n), b(n, n), c(n, n), d(n, n);
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    a.data()[k] = u(rng);
    b.data()[k] = u(rng);
  }
  double best_eigen = 1e300, best_blas = 1e300;
  const double one = 1, zero = 0;
  for (int pass = 0; pass < 3; ++pass) {
    auto start = Clock::now();
    c.noalias() = a * b;
    best_eigen = std::min(best_eigen, Seconds(start));
    start = Clock::now();
    dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, d.data(), &n, 1,
           1);
    best_blas = std::min(best_blas, Seconds(start));
  }
  if (!std::isfinite(c.sum()) ||
      !((c - d).cwiseAbs().maxCoeff() <= 1e-9 * c.cwiseAbs().maxCoeff()))
    throw std::runtime_error("dense products not finite or not equal");
  const double flops = 2.0 * n * n * n;
  return {flops / best_eigen, flops / best_blas};
}

// Writes every basis into one coordinate file of size n x (n * p): basis k's
// entry (r, c) at column k * n + c (1-based in the file).
void WriteBases(const fs::path& path, const femup::ParametrisedModel& model) {
  long long nnz = 0;
  for (const femup::Parameter& q : model.parameters()) nnz += q.basis.nonZeros();
  std::ofstream out(path);
  out << "%%MatrixMarket matrix coordinate real general\n"
      << "% femup_system_peer_compare: basis k's entry (r, c) at column k * n + c\n"
      << model.num_dofs() << " "
      << static_cast<long long>(model.num_dofs()) * model.num_parameters() << " " << nnz
      << "\n";
  char line[96];
  for (int k = 0; k < model.num_parameters(); ++k) {
    const femup::SparseMatrix& b = model.parameter(k).basis.local();
    const std::vector<int>& dofs = model.parameter(k).basis.dofs();
    const long long offset = static_cast<long long>(k) * model.num_dofs();
    for (Eigen::Index c = 0; c < b.outerSize(); ++c) {
      for (femup::SparseMatrix::InnerIterator it(b, c); it; ++it) {
        const int len = std::snprintf(line, sizeof line, "%lld %lld %.17g\n",
                                      static_cast<long long>(dofs[it.row()]) + 1,
                                      offset + dofs[c] + 1, it.value());
        out.write(line, len);
      }
    }
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The femup side, in the calling process: time, answer, memory.
nlohmann::json SolveFemup(const femup::ParametrisedModel& model,
                          const std::vector<femup::ModalData>& states,
                          const Eigen::VectorXd& truth, int threads) {
  nlohmann::json out;
  const bool have_peak = femup_bench::ResetPeakRss();
  out["rss_before_solve_mb"] = femup_bench::StatusMb("VmRSS");
  const auto start = Clock::now();
  femup::NormalCorrectionStats stats;
  femup::LinearProblem problem =
      femup::BuildNormalCorrectionSystem(model, states, &stats, {threads});
  // Scaling K and M together leaves every mode's residual zero: fix the first
  // factor (a mass factor) at its preset value, as the linear method does.
  problem.fixed = {{0, truth[0]}};
  const double assembly = Seconds(start);
  const auto solve_start = Clock::now();
  const femup::LinearSolution solution =
      femup::CreateLinearSolver("lstsq")->Solve(problem);
  out["solve_time"] = Seconds(solve_start);
  out["solve_route"] =
      solution.summary.message.substr(0, solution.summary.message.find(':'));
  out["assembly_time"] = assembly;
  out["time"] = Seconds(start);
  out["solve_peak_rss_mb"] =
      have_peak ? nlohmann::json(femup_bench::StatusMb("VmHWM")) : nlohmann::json();
  out["factorise_time"] = stats.seconds_factorise;
  out["analyse_time"] = stats.seconds_analyse;
  out["compress_time"] = stats.seconds_compress;
  out["half_solve_time"] = stats.seconds_half_solve;
  out["gram_time"] = stats.seconds_gram;
  out["nnz_l"] = stats.nnz_l;
  out["flops_factorise"] = stats.flops_factorise;
  out["flops_gram"] = stats.flops_gram;
  out["flops_half_solve"] = stats.flops_half_solve;
  out["nnz_z"] = stats.nnz_z;
  out["nnz_w"] = stats.nnz_w;
  out["dropped"] = stats.dropped;
  out["status"] = solution.summary.usable() ? "usable" : "not usable";
  out["error_vs_truth"] = (solution.x - truth).cwiseAbs().maxCoeff();
  out["x"] =
      std::vector<double>(solution.x.data(), solution.x.data() + solution.x.size());
  return out;
}

double MaxAbsDifference(const nlohmann::json& a, const nlohmann::json& b) {
  double out = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    out = std::max(out, std::abs(a[k].get<double>() - b[k].get<double>()));
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  CLI::App app{"the linear correction-factor system at scale: femup against scipy"};
  std::string size = "1e5";
  int air_modes = 5, water_modes = 5, threads = 1;
  std::string python = "/usr/bin/python3";
  std::string script = FEMUP_SYSTEM_PEER_SCRIPT;
  std::string markdown, keep;
  app.add_option("--size", size, "1e5, 1e4 or BXxBYxLEVELSxBLOCKS");
  app.add_option("--air-modes", air_modes, "measured modes in air")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--water-modes", water_modes, "measured modes in water")
      ->check(CLI::NonNegativeNumber);
  femup_bench::AddPeerOptions(app, python, script, markdown, "scipy",
                              "normal_system_peer.py");
  app.add_option("--keep", keep, "write the files under this directory and keep them");
  app.add_option("--threads", threads,
                 "femup's threads for the half solves and G (0 = one per core)")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  femup::SpaceFrameSpec spec;
  try {
    spec = ParseSize(size);
    if (air_modes + water_modes < 1)
      throw CLI::ValidationError("--air-modes", "no measured mode");
  } catch (const CLI::Error& e) {
    return app.exit(e);
  }

  const fs::path dir = femup_bench::WorkDirectory(keep, "system");
  if (dir.empty()) return 1;
  fs::create_directories(dir);

  std::cerr << size << ": building the frame\n";
  auto start = Clock::now();
  const femup::ParametrisedModel model = femup::BuildSpaceFrame(spec);
  const double build_time = Seconds(start);
  const int n = model.num_dofs(), p = model.num_parameters();

  // Preset factors: stiffness and mass within +-10 %, added mass 0.2 to 0.6.
  Eigen::VectorXd truth(p);
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> small(-0.1, 0.1), added(0.2, 0.6);
  for (int k = 0; k < p; ++k) {
    truth[k] = model.parameter(k).kind == femup::ParameterKind::kAddedMass ? added(rng)
                                                                           : small(rng);
  }
  std::cerr << size << ": " << n << " DOF, " << p << " factors; measured modes\n";
  // The measured modes come from a child process that writes them to `dir`:
  // CHOLMOD's OpenMP threads, once started, do not survive a fork(), so this
  // process must not start them before it forks femup's side.
  struct Measured {
    const char* name;
    femup::Immersion immersion;
    int modes;
  };
  std::vector<Measured> measured;
  if (air_modes > 0) measured.push_back({"air", femup::Immersion::kDry, air_modes});
  if (water_modes > 0) measured.push_back({"water", femup::Immersion::kWet, water_modes});
  start = Clock::now();
  const PeerResult simulated = femup_bench::RunInChild([&] {
    nlohmann::json out = nlohmann::json::array();
    for (const Measured& m : measured) {
      const femup::ModalData st =
          femup::PredictModes(model, truth, m.immersion, m.modes, m.name);
      femup::WriteMatrixMarket((dir / (std::string(m.name) + "_shapes.mtx")).string(),
                               Eigen::MatrixXd(st.shapes));
      const Eigen::VectorXd hz = st.frequencies_hz;
      out.push_back(std::vector<double>(hz.data(), hz.data() + hz.size()));
    }
    return out;
  });
  if (!simulated.error.empty()) {
    std::cerr << "the measured modes could not be computed: " << simulated.error << "\n";
    return 1;
  }
  std::vector<femup::ModalData> states;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    femup::ModalData st;
    st.state = measured[i].name;
    st.immersion = measured[i].immersion;
    st.frequencies_hz = Eigen::Map<const Eigen::VectorXd>(
        simulated.json[i].get<std::vector<double>>().data(), measured[i].modes);
    st.shapes = femup::ReadMatrixMarketDense(
        (dir / (std::string(measured[i].name) + "_shapes.mtx")).string());
    states.push_back(std::move(st));
  }
  const double modes_time = Seconds(start);

  std::vector<const femup::SparseMatrix*> matrices = {&model.stiffness(), &model.mass()};
  std::vector<const std::vector<int>*> lists;
  long long nnz_bases = 0;
  for (const femup::Parameter& q : model.parameters()) {
    matrices.push_back(&q.basis.local());
    lists.push_back(&q.basis.dofs());
    nnz_bases += q.basis.nonZeros();
  }
  double checksum = 0;
  const double bound = ReadBound(matrices, lists, &checksum);
  std::cerr << size << ": read bound " << bound << " s (checksum " << checksum << ")\n";
  const DenseRates rates = MeasureDenseRates();
  const double rate = rates.best();
  std::cerr << size << ": dense product " << rates.eigen / 1e9 << " GFLOP/s (Eigen), "
            << rates.blas / 1e9 << " GFLOP/s (BLAS)\n";
  long long bytes = 0;
  for (const femup::SparseMatrix* a : matrices)
    bytes += a->nonZeros() * 12LL + (a->outerSize() + 1) * 4LL;
  for (const std::vector<int>* list : lists)
    bytes += static_cast<long long>(list->size()) * 4LL;

  std::cerr << size << ": writing K, M, the bases and the modes\n";
  start = Clock::now();
  femup::WriteMatrixMarket((dir / "K.mtx").string(), model.stiffness(), true);
  femup::WriteMatrixMarket((dir / "M.mtx").string(), model.mass(), true);
  WriteBases(dir / "bases.mtx", model);
  {
    nlohmann::json meta;
    meta["kinds"] = nlohmann::json::array();
    for (const femup::Parameter& q : model.parameters())
      meta["kinds"].push_back(femup::ToString(q.kind));
    meta["truth"] = std::vector<double>(truth.data(), truth.data() + p);
    meta["fixed"] = {{"index", 0}, {"value", truth[0]}};
    meta["states"] = nlohmann::json::array();
    for (const femup::ModalData& st : states) {
      const std::string file = st.state + "_shapes.mtx";
      const Eigen::VectorXd lambdas = st.Eigenvalues();
      meta["states"].push_back(
          {{"name", st.state},
           {"wet", st.immersion == femup::Immersion::kWet},
           {"shapes", file},
           {"eigenvalues",
            std::vector<double>(lambdas.data(), lambdas.data() + lambdas.size())}});
    }
    std::ofstream(dir / "problem.json") << meta.dump() << "\n";
  }
  const double write_time = Seconds(start);
  ::malloc_trim(0);

  std::cerr << size << ": femup\n";
  const PeerResult femup_side =
      femup_bench::RunInChild([&] { return SolveFemup(model, states, truth, threads); });
  if (!femup_side.error.empty())
    std::cerr << "  femup failed: " << femup_side.error << "\n";
  std::cerr << size << ": scipy\n";
  const PeerResult peer = femup_bench::RunPeerScript(python, script, dir, "");
  if (!peer.error.empty()) std::cerr << "  scipy not run: " << peer.error << "\n";
  if (keep.empty()) fs::remove_all(dir);

  std::ostringstream md;
  const double per = n / 1e5;
  md << "Frame: space_frame.h, " << spec.bays_x << " x " << spec.bays_y << " bays, "
     << spec.levels << " levels, " << spec.blocks_per_level
     << " blocks per level, X bracing, 4 elements per member, all members wet: " << n
     << " DOF, " << p << " factors, nnz K " << model.stiffness().nonZeros()
     << ", all bases " << nnz_bases << ". Measured: " << air_modes << " modes in air, "
     << water_modes << " in water, of the model with random preset factors (seed "
     << kSeed << "), shapes on every DOF. Build " << Format("%.1f", build_time)
     << " s, modes " << Format("%.1f", modes_time) << " s, writing "
     << Format("%.1f", write_time) << " s.\n\n";
  md << "| side | assembly (s) | solve (s) | total (s) | scipy / femup | total / read "
        "bound | peak (MB) | MB per 10^5 DOF | max error vs preset |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  const auto peak = [](const nlohmann::json& j) {
    return j["solve_peak_rss_mb"].is_null() ? -1.0 : j["solve_peak_rss_mb"].get<double>();
  };
  double femup_total = 0;
  if (femup_side.error.empty()) {
    const nlohmann::json& f = femup_side.json;
    femup_total = f["time"].get<double>();
    md << "| femup | " << Format("%.2f", f["assembly_time"].get<double>()) << " | "
       << Format("%.2f", f["solve_time"].get<double>()) << " | "
       << Format("%.2f", femup_total) << " | 1 | " << Format("%.0f", femup_total / bound)
       << " | " << Format("%.0f", peak(f)) << " | " << Format("%.0f", peak(f) / per)
       << " | " << Format("%.1e", f["error_vs_truth"].get<double>()) << " |\n";
  } else {
    md << "| femup | failed: " << femup_side.error << " |\n";
  }
  if (peer.error.empty()) {
    const nlohmann::json& s = peer.json;
    const double total = s["time"].get<double>();
    md << "| scipy | " << Format("%.2f", s["assembly_time"].get<double>()) << " | "
       << Format("%.2f", s["solve_time"].get<double>()) << " | " << Format("%.2f", total)
       << " | "
       << (femup_total > 0 ? Format("%.1f", total / femup_total) : std::string("-"))
       << " | " << Format("%.0f", total / bound) << " | " << Format("%.0f", peak(s))
       << " | " << Format("%.0f", peak(s) / per) << " | "
       << Format("%.1e", s["error_vs_truth"].get<double>()) << " |\n";
  } else {
    md << "| scipy | not run: " << peer.error << " |\n";
  }
  md << "\nRead bound: one pass over the stored values and indices of K, M and every "
        "basis ("
     << Format("%.0f", bytes / 1e6) << " MB) takes " << Format("%.3f", bound) << " s ("
     << Format("%.1f", bytes / bound / 1e9) << " GB/s).";
  if (femup_side.error.empty()) {
    const nlohmann::json& f = femup_side.json;
    md << " femup: sparse Cholesky of M "
       << Format("%.2f", f["factorise_time"].get<double>())
       << " s (ordering and analysis " << Format("%.2f", f["analyse_time"].get<double>())
       << " s; nnz L " << f["nnz_l"].get<long long>() << "), nnz of all Z_j "
       << f["nnz_z"].get<long long>() << ", of all L^-1 P Z_j "
       << f["nnz_w"].get<long long>() << " ("
       << Format("%.1f", f["nnz_w"].get<double>() / f["nnz_z"].get<double>())
       << "x), half solves " << Format("%.2f", f["half_solve_time"].get<double>())
       << " s, G = sum W_j' W_j " << Format("%.2f", f["gram_time"].get<double>())
       << " s, pivoted Cholesky of G " << Format("%.2f", f["compress_time"].get<double>())
       << " s, " << f["dropped"].get<int>() << " directions dropped.";
    // The arithmetic the method cannot skip, at the dense product's rate: M's
    // factorisation (the M^-1 weighting) and G's lower triangle.
    const double flops_m = f["flops_factorise"].get<double>();
    const double flops_g = f["flops_gram"].get<double>();
    md << " lstsq on the " << f["x"].size() << "-column square root ("
       << f["solve_route"].get<std::string>() << ") "
       << Format("%.2f", f["solve_time"].get<double>()) << " s.";
    md << " Arithmetic floor: the Cholesky factorisation of M needs "
       << Format("%.2f", flops_m / 1e9) << " GFLOP and G's lower triangle "
       << Format("%.2f", flops_g / 1e9)
       << " GFLOP; at this machine's dense-product rate (" << Format("%.1f", rate / 1e9)
       << " GFLOP/s, 1000 x 1000, the faster of Eigen's "
       << Format("%.1f", rates.eigen / 1e9) << " and the BLAS's dgemm "
       << Format("%.1f", rates.blas / 1e9) << ") they take at least "
       << Format("%.3f", flops_m / rate) << " + " << Format("%.3f", flops_g / rate)
       << " s = " << Format("%.0f", (flops_m + flops_g) / rate / bound)
       << "x the read bound; femup took "
       << Format("%.0f", f["factorise_time"].get<double>() / (flops_m / rate)) << "x and "
       << Format("%.0f", f["gram_time"].get<double>() / (flops_g / rate))
       << "x that floor for them, and "
       << Format("%.0f", femup_total / ((flops_m + flops_g) / rate))
       << "x it for the whole solve (" << Format("%.2f", femup_total) << " s).";
    // The half solves are the method's too (the M^-1 weighting), but sparse
    // triangular solves: their operations at the dense rate are a bound no
    // implementation reaches, given beside the floor above.
    const double flops_h = f["flops_half_solve"].get<double>();
    md << " The half solves make " << Format("%.2f", flops_h / 1e9) << " GFLOP ("
       << Format("%.3f", flops_h / rate) << " s at that rate; femup took "
       << Format("%.0f", f["half_solve_time"].get<double>() / (flops_h / rate))
       << "x it): with them the method's arithmetic takes at least "
       << Format("%.3f", (flops_m + flops_g + flops_h) / rate)
       << " s, and femup's whole solve "
       << Format("%.0f", femup_total / ((flops_m + flops_g + flops_h) / rate))
       << "x that.";
    if (peer.error.empty()) {
      md << " Largest difference between the two answers: "
         << Format("%.1e", MaxAbsDifference(f["x"], peer.json["x"])) << ".";
    }
  }
  if (peer.error.empty()) {
    md << " Peer: scipy " << peer.json["scipy"].get<std::string>() << ", numpy "
       << peer.json["numpy"].get<std::string>() << " (" << python
       << ", one BLAS thread); reading its files took "
       << Format("%.1f", peer.json["read_time"].get<double>()) << " s (not counted).";
  }
  const char* omp = std::getenv("OMP_NUM_THREADS");
  md << " femup ran with OMP_NUM_THREADS=" << (omp != nullptr ? omp : "unset")
     << " (CHOLMOD's threads) and " << threads
     << " thread(s) for its half solves and G (--threads; 0 = one per core); "
     << femup::BlasSummary() << ".";
  md << " Peak: VmHWM of the solving process, reset just before the work starts (it "
        "counts the model held in memory; scipy: also the interpreter).\n";
  std::cout << md.str();
  if (!markdown.empty()) std::ofstream(markdown) << md.str();
  return femup_side.error.empty() ? 0 : 1;
}
