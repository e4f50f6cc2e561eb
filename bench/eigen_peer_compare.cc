// femup's sparse shift-invert eigensolver (SolveModes, kSparseShiftInvert:
// Spectra's SymGEigsShiftSolver on a CHOLMOD factorisation) against
// scipy.sparse.linalg.eigsh with shift-invert (ARPACK mode 3 on SuperLU) on the
// jacket-like space frames of space_frame.h, all in one run of this program.
// For each size the frame is built once and K and M are written as Matrix
// Market files to a temporary directory; femup's solve then runs in a fork()ed
// child that inherits K and M (so that its peak resident set is its own), and
// bench/peer/eigsh_peer.py times scipy on the same files and returns its
// eigenvalues as JSON. Prints Markdown tables: times with the scipy/femup
// ratio, peak memory and MB per 10^5 DOF, and the agreement of the answers.
//
// Usage: femup_eigen_peer_compare [--dofs 1e5,1e6] [--modes 10] [--shift 0]
//                                 [--tolerance 1e-10] [--python /usr/bin/python3]
//                                 [--script path] [--markdown file] [--keep dir]
// --dofs takes presets (1e4, 1e5, 1e6: the specs of docs/space_frame.md) or
// BXxBYxLEVELS (4 elements per member, one block, X bracing, dry).
// When the script cannot run (no python, no scipy) the reason is printed and
// the scipy columns are left out.
//
// Memory, both sides measured the same way: the peak resident set (VmHWM) of
// the process doing the solve, reset through /proc/self/clear_refs just before
// the solve, so it counts K and M as held in memory (and, for scipy, the
// interpreter and its modules) plus the solver's working memory. The forked
// child starts with the parent's resident pages (K and M; the model is freed
// and the heap trimmed before the fork). "growth" is that peak minus the
// resident set at the start of the solve: the solver's own working memory.
#include <malloc.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/fe/space_frame.h"
#include "femup/core/io/matrix_market.h"
#include "femup/core/linalg/blas.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/parallel.h"
#include "peer_runner.h"

namespace {

namespace fs = std::filesystem;
using femup_bench::Clock;
using femup_bench::Format;
using femup_bench::PeerResult;
using femup_bench::ResetPeakRss;
using femup_bench::RunInChild;
using femup_bench::RunPeerScript;
using femup_bench::Seconds;
using femup_bench::StatusMb;

// One size: a name for the table and the frame it builds.
struct Size {
  std::string name;
  femup::SpaceFrameSpec spec;
};

// "1e5", "1e6" (docs/space_frame.md), "1e4" (a small one for a quick run) or
// "BXxBYxLEVELS"; throws CLI::ValidationError otherwise.
Size ParseSize(const std::string& item) {
  // The named frames: bays in x and in y, levels, blocks per level, water depth.
  struct Preset {
    const char* name;
    int bays, levels, blocks;
    double water_depth;
  };
  static const Preset kPresets[] = {
      {"1e4", 2, 10, 1, 30},     // 10,560 DOF
      {"1e5", 4, 39, 2, 100},    // 100,152 DOF
      {"1e6", 10, 100, 1, 300},  // 998,400 DOF
  };
  Size s;
  s.name = item;
  const Preset* preset = nullptr;
  for (const Preset& p : kPresets) {
    if (item == p.name) preset = &p;
  }
  if (preset != nullptr) {
    s.spec.bays_x = s.spec.bays_y = preset->bays;
    s.spec.levels = preset->levels;
    s.spec.blocks_per_level = preset->blocks;
    s.spec.water_depth = preset->water_depth;
  } else {
    char x1 = 0, x2 = 0;
    std::stringstream in(item);
    if (!(in >> s.spec.bays_x >> x1 >> s.spec.bays_y >> x2 >> s.spec.levels) ||
        x1 != 'x' || x2 != 'x' || !in.eof()) {
      throw CLI::ValidationError("--dofs",
                                 "'" + item + "' is not 1e4, 1e5, 1e6 or BXxBYxLEVELS");
    }
    s.spec.blocks_per_level = 1;
  }
  s.spec.elements_per_member = 4;
  if (const femup::Invalid bad = s.spec.Validate())
    throw CLI::ValidationError("--dofs", item + ": " + bad.ToString());
  return s;
}

std::vector<Size> ParseSizes(const std::string& text) {
  std::vector<Size> sizes;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) sizes.push_back(ParseSize(item));
  if (sizes.empty()) throw CLI::ValidationError("--dofs", "no size given");
  return sizes;
}

// The femup solve, in the calling process: time, answers, memory.
nlohmann::json SolveFemup(const femup::SparseMatrix& K, const femup::SparseMatrix& M,
                          const femup::EigenOptions& options) {
  nlohmann::json out;
  const bool have_peak = ResetPeakRss();
  out["rss_before_solve_mb"] = StatusMb("VmRSS");
  const auto start = Clock::now();
  const femup::Modes modes = femup::SolveModes(K, M, options);
  out["time"] = Seconds(start);
  if (have_peak) {
    out["solve_peak_rss_mb"] = StatusMb("VmHWM");
  } else {
    out["solve_peak_rss_mb"] = nullptr;
  }
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  out["maxrss_mb"] = usage.ru_maxrss / 1024.0;  // kB on Linux
  std::vector<double> values, residuals;
  for (int j = 0; j < modes.size(); ++j) {
    const Eigen::VectorXd phi = modes.shapes.col(j);
    const Eigen::VectorXd k_phi = K * phi;
    const double lambda = modes.eigenvalues[j];
    values.push_back(lambda);
    residuals.push_back((k_phi - lambda * (M * phi)).norm() / k_phi.norm());
  }
  out["eigenvalues"] = values;
  out["residuals"] = residuals;
  return out;
}

// Runs the script on `dir` (one BLAS thread) with one of its factorisations:
// "default" (eigsh's own SuperLU) or "symmetric" (a symmetric-ordering splu
// as OPinv).
PeerResult RunPeer(const std::string& python, const std::string& script,
                   const fs::path& dir, int modes, double shift, double tolerance,
                   const std::string& factorisation) {
  return RunPeerScript(
      python, script, dir,
      "--k " + std::to_string(modes) + " --shift " + Format("%.17g", shift) + " --tol " +
          Format("%.17g", tolerance) + " --factorisation " + factorisation);
}

// Column heading of a peer configuration.
std::string PeerName(const std::string& factorisation) {
  return factorisation == "symmetric" ? "scipy, symmetric splu as OPinv"
                                      : "scipy eigsh, defaults";
}

// Everything measured on one size.
struct Row {
  std::string name;
  long long dofs = 0;
  long long nnz_k = 0;  // full symmetric storage
  double build_time = 0, write_time = 0;
  PeerResult femup;
  std::vector<PeerResult> peers;  // one per configuration, in the order asked
};

double MaxOf(const nlohmann::json& values) {
  double out = 0;
  for (const auto& v : values) out = std::max(out, v.get<double>());
  return out;
}

// Max over modes of |lambda_femup - lambda_scipy| / |lambda_scipy|.
double MaxRelativeDifference(const nlohmann::json& a, const nlohmann::json& b) {
  double out = 0;
  for (std::size_t j = 0; j < std::min(a.size(), b.size()); ++j) {
    const double x = a[j].get<double>(), y = b[j].get<double>();
    out = std::max(out, std::abs(x - y) / std::abs(y));
  }
  return out;
}

// Peak resident set during the solve, or the whole process's when that could
// not be reset.
double PeakMb(const nlohmann::json& j) {
  return j["solve_peak_rss_mb"].is_null() ? j["maxrss_mb"].get<double>()
                                          : j["solve_peak_rss_mb"].get<double>();
}

std::string Tables(const std::vector<Row>& rows, const std::vector<std::string>& configs,
                   const std::vector<std::string>& notes) {
  std::ostringstream md;
  md << "### Time and memory\n\n";
  for (std::size_t c = 0; c < configs.size(); ++c) {
    if (!notes[c].empty()) md << PeerName(configs[c]) << ": " << notes[c] << "\n\n";
  }
  md << "| DOF | nnz K | femup (s) | femup peak (MB) | femup MB per 10^5 DOF |";
  for (const std::string& c : configs) {
    md << " " << PeerName(c)
       << " (s) | / femup | peak (MB) | max rel. eigenvalue difference |";
  }
  md << "\n|---|---|---|---|---|";
  for (std::size_t c = 0; c < configs.size(); ++c) md << "---|---|---|---|";
  md << "\n";
  for (const Row& r : rows) {
    const double per = static_cast<double>(r.dofs) / 1e5;
    md << "| " << r.dofs << " | " << r.nnz_k << " |";
    if (!r.femup.error.empty()) {
      md << " failed: " << r.femup.error << " |\n";
      continue;
    }
    const double ft = r.femup.json["time"].get<double>();
    const double fm = PeakMb(r.femup.json);
    md << " " << Format("%.3g", ft) << " | " << Format("%.0f", fm) << " | "
       << Format("%.0f", fm / per) << " |";
    for (const PeerResult& p : r.peers) {
      if (!p.error.empty()) {
        md << " failed | | | |";
        continue;
      }
      const double st = p.json["time"].get<double>();
      md << " " << Format("%.3g", st) << " | " << Format("%.2f", st / ft) << " | "
         << Format("%.0f", PeakMb(p.json)) << " | "
         << Format("%.1e", MaxRelativeDifference(r.femup.json["eigenvalues"],
                                                 p.json["eigenvalues"]))
         << " |";
    }
    md << "\n";
  }

  md << "\n### Details\n\n"
     << "| DOF | build (s) | write K, M (s) | femup growth (MB) | femup max residual |";
  for (const std::string& c : configs) {
    md << " " << PeerName(c)
       << ": read (s) | growth (MB) | process peak incl. reading (MB) | max residual |";
  }
  md << " lowest, highest eigenvalue (femup, rad^2/s^2) |\n|---|---|---|---|---|";
  for (std::size_t c = 0; c < configs.size(); ++c) md << "---|---|---|---|";
  md << "---|\n";
  const auto growth = [](const nlohmann::json& j) {
    return j["solve_peak_rss_mb"].is_null()
               ? std::string("n/a")
               : Format("%.0f", j["solve_peak_rss_mb"].get<double>() -
                                    j["rss_before_solve_mb"].get<double>());
  };
  for (const Row& r : rows) {
    md << "| " << r.dofs << " | " << Format("%.1f", r.build_time) << " | "
       << Format("%.1f", r.write_time) << " |";
    if (!r.femup.error.empty()) {
      md << " failed |\n";
      continue;
    }
    const nlohmann::json& f = r.femup.json;
    md << " " << growth(f) << " | " << Format("%.1e", MaxOf(f["residuals"])) << " |";
    for (const PeerResult& p : r.peers) {
      if (!p.error.empty()) {
        md << " failed | | | |";
        continue;
      }
      md << " " << Format("%.1f", p.json["read_time"].get<double>()) << " | "
         << growth(p.json) << " | " << Format("%.0f", p.json["maxrss_mb"].get<double>())
         << " | " << Format("%.1e", MaxOf(p.json["residuals"])) << " |";
    }
    const auto& ev = f["eigenvalues"];
    md << " " << Format("%.6g", ev.front().get<double>()) << ", "
       << Format("%.6g", ev.back().get<double>()) << " |\n";
  }
  md << "\nPeak: VmHWM of the solving process, reset just before the solve, so it counts "
        "K and M as held (scipy: also the interpreter and its modules); growth: that "
        "peak minus the resident set at the start of the solve. Residual: max over "
        "modes of ||K phi - lambda M phi|| / ||K phi||, each side on its own vectors.\n";
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  CLI::App app{"femup's sparse shift-invert eigensolver against scipy's eigsh"};
  std::string sizes_text = "1e5";
  int modes = 10;
  double shift = 0;
  double tolerance = 1e-10;
  std::string python = "/usr/bin/python3";
  std::string script = FEMUP_EIGSH_PEER_SCRIPT;
  std::string markdown, keep;
  std::string peers_text = "default,symmetric";
  int threads = 0;
  bool dof_ordering = false;
  app.add_option("--dofs", sizes_text,
                 "frames, comma-separated: 1e4, 1e5, 1e6 (docs/space_frame.md) or "
                 "BXxBYxLEVELS");
  app.add_option("--modes", modes, "number of modes (lowest above the shift)")
      ->check(CLI::PositiveNumber);
  app.add_option("--shift", shift, "shift sigma (rad^2/s^2), both sides");
  app.add_option("--tolerance", tolerance,
                 "relative convergence tolerance, both sides (femup EigenOptions, "
                 "eigsh tol)")
      ->check(CLI::PositiveNumber);
  femup_bench::AddPeerOptions(app, python, script, markdown, "scipy", "eigsh_peer.py");
  app.add_option("--peers", peers_text,
                 "scipy configurations, comma-separated: default (eigsh factorises "
                 "with SuperLU's defaults), symmetric (splu with a symmetric ordering "
                 "and no pivoting, as OPinv)");
  app.add_flag(
      "--dof-ordering", dof_ordering,
      "order the DOF graph, not the node graph (EigenOptions::dof_groups empty)");
  app.add_option("--threads", threads,
                 "femup's EigenOptions::threads (M's check beside K - shift*M's "
                 "factorisation): 0 = one per core, 1 = one after the other")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--keep", keep,
                 "write K.mtx and M.mtx under this directory (one subdirectory per "
                 "size) and keep them, instead of a temporary directory");
  CLI11_PARSE(app, argc, argv);
  std::vector<Size> sizes;
  std::vector<std::string> configs;
  try {
    sizes = ParseSizes(sizes_text);
    std::stringstream list(peers_text);
    std::string item;
    while (std::getline(list, item, ',')) {
      if (item != "default" && item != "symmetric") {
        throw CLI::ValidationError("--peers",
                                   "'" + item + "' is not default or symmetric");
      }
      configs.push_back(item);
    }
  } catch (const CLI::Error& e) {
    return app.exit(e);
  }

  const fs::path tmp = femup_bench::WorkDirectory(keep, "eigsh");
  if (tmp.empty()) return 1;
  if (!keep.empty()) fs::create_directories(tmp);

  femup::EigenOptions options;
  options.method = femup::EigenOptions::Method::kSparseShiftInvert;
  options.num_modes = modes;
  options.shift = shift;
  options.tolerance = tolerance;
  options.threads = threads;

  std::vector<Row> rows;
  std::string versions;
  // Why a configuration first failed (no python or scipy, no memory), or empty.
  std::vector<std::string> notes(configs.size());
  for (const Size& size : sizes) {
    Row row;
    row.name = size.name;
    std::cerr << size.name << ": building the frame\n";
    femup::SparseMatrix K, M;
    femup::EigenOptions size_options = options;
    {
      auto start = Clock::now();
      femup::ParametrisedModel model = femup::BuildSpaceFrame(size.spec);
      row.build_time = Seconds(start);
      K = model.stiffness();
      M = model.mass();
      // The ordering on the node graph, as a caller with the model passes it.
      if (!dof_ordering) size_options.dof_groups = model.DofNodes();
    }
    ::malloc_trim(0);  // the model's memory back to the system before the fork
    row.dofs = K.rows();
    row.nnz_k = K.nonZeros();
    const fs::path dir = tmp / size.name;
    fs::create_directories(dir);
    std::cerr << size.name << ": " << row.dofs << " DOF, nnz K " << row.nnz_k
              << " (build " << Format("%.1f", row.build_time) << " s); writing K, M\n";
    auto start = Clock::now();
    femup::WriteMatrixMarket((dir / "K.mtx").string(), K, true);
    femup::WriteMatrixMarket((dir / "M.mtx").string(), M, true);
    row.write_time = Seconds(start);

    std::cerr << size.name << ": femup\n";
    row.femup = RunInChild([&] { return SolveFemup(K, M, size_options); });
    if (!row.femup.error.empty())
      std::cerr << "  femup failed: " << row.femup.error << "\n";
    K.resize(0, 0);  // not needed any more: leave the memory to the peer
    M.resize(0, 0);
    K.data().squeeze();
    M.data().squeeze();
    ::malloc_trim(0);

    for (std::size_t c = 0; c < configs.size(); ++c) {
      std::cerr << size.name << ": " << PeerName(configs[c]) << "\n";
      row.peers.push_back(
          RunPeer(python, script, dir, modes, shift, tolerance, configs[c]));
      const PeerResult& p = row.peers.back();
      if (!p.error.empty()) {
        std::cerr << "  " << PeerName(configs[c]) << " failed: " << p.error << "\n";
        if (notes[c].empty()) notes[c] = "failed on " + size.name + ": " + p.error;
      } else {
        versions = "scipy " + p.json["scipy"].get<std::string>() + ", numpy " +
                   p.json["numpy"].get<std::string>();
      }
    }
    if (keep.empty()) fs::remove_all(dir);
    rows.push_back(std::move(row));
  }
  if (keep.empty()) fs::remove_all(tmp);

  const char* omp = std::getenv("OMP_NUM_THREADS");
  std::ostringstream out;
  out << "Frames: space_frame.h (X bracing, 4 elements per member), K and M in full "
         "storage for femup, read from the same Matrix Market files by scipy. "
      << modes << " modes nearest above shift " << shift << ", tolerance " << tolerance
      << " on both sides; one run each. femup: SolveModes(kSparseShiftInvert) in a "
         "forked child (OMP_NUM_THREADS="
      << (omp != nullptr ? omp : "unset") << ", "
      << (dof_ordering ? "the DOF graph ordered (--dof-ordering)"
                       : "the node graph ordered (EigenOptions::dof_groups)")
      << ", EigenOptions::threads = " << threads
      << (threads == 0
              ? " (one per core: " + std::to_string(femup::DefaultThreadCount()) + ")"
              : std::string())
      << "; " << femup::BlasSummary() << "). "
      << (versions.empty()
              ? std::string("Peer: not run.")
              : "Peer: " + versions + " (" + python +
                    ", one BLAS thread): eigsh(K, k, M=M, sigma, which='LM', tol) with "
                    "its defaults, and with OPinv from splu(K - sigma M, "
                    "permc_spec='MMD_AT_PLUS_A', diag_pivot_thresh=0, "
                    "options={'SymmetricMode': True}), the factorisation timed with "
                    "the solve.")
      << "\n\n"
      << Tables(rows, configs, notes);
  if (!femup_bench::PrintTables(out.str(), markdown)) return 1;
  const bool all_solved = std::all_of(rows.begin(), rows.end(),
                                      [](const Row& r) { return r.femup.error.empty(); });
  return all_solved ? 0 : 1;
}
