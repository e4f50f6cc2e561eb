// femup's bounded least-squares solvers (bvls, ceres, ipopt) against
// scipy.optimize.lsq_linear ('bvls', 'trf') on the random bounded problems of
// bounded_problem.h, all timed in one run of this program. Each problem is
// written as Matrix Market files to a temporary directory, femup's solvers are
// timed in-process, then bench/peer/lsq_linear_peer.py times scipy on the same
// files and returns its solutions as JSON. Prints two Markdown tables: wall
// times with femup/scipy ratios, and the answers (status, iterations, cost,
// agreement with a reference solution).
//
// Usage: femup_peer_compare [--sizes 500x50,2000x200] [--repeat 3] [--budget 10]
//                           [--python /usr/bin/python3] [--script path]
//                           [--markdown file]
// When the script cannot run (no python, no scipy) the reason is printed and
// the scipy columns are left out.
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bounded_problem.h"
#include "femup/core/io/matrix_market.h"
#include "femup/core/linalg/blas.h"
#include "femup/solvers/linear_solver.h"
#include "peer_runner.h"

namespace {

namespace fs = std::filesystem;
using femup_bench::Format;
using femup_bench::PeerResult;
using femup_bench::RunPeerScript;

const char* const kFemupSolvers[] = {"bvls", "ceres", "ipopt"};
const char* const kScipyMethods[] = {"bvls", "trf"};
constexpr std::uint64_t kSeed = 20240601;

struct Size {
  int rows = 0, cols = 0;
};

// "500x50,2000x200" -> sizes; throws CLI::ValidationError on anything else.
std::vector<Size> ParseSizes(const std::string& text) {
  std::vector<Size> sizes;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    Size s;
    char x = 0;
    std::stringstream in(item);
    if (!(in >> s.rows >> x >> s.cols) || x != 'x' || !in.eof() || s.rows < s.cols ||
        s.cols < 1) {
      throw CLI::ValidationError("--sizes", "'" + item + "' is not MxN with M >= N >= 1");
    }
    sizes.push_back(s);
  }
  return sizes;
}

// One solver's best wall time over its runs and the answer of the last run
// (every run solves the same problem, so every run gives the same answer).
struct Timed {
  double seconds = 0;
  int runs = 0;
  femup::LinearSolution solution;
};

// Best of up to `repeat` runs; no further run starts once `budget` seconds are spent.
Timed TimeSolver(const femup::LinearSolver& solver, const femup::LinearProblem& p,
                 int repeat, double budget) {
  Timed out;
  double spent = 0;
  while (out.runs < repeat && (out.runs == 0 || spent < budget)) {
    const auto start = std::chrono::steady_clock::now();
    out.solution = solver.Solve(p);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    spent += seconds;
    out.seconds = out.runs == 0 ? seconds : std::min(out.seconds, seconds);
    ++out.runs;
  }
  return out;
}

// Runs the script on `dir` (one BLAS thread).
PeerResult RunPeer(const std::string& python, const std::string& script,
                   const fs::path& dir, int repeat, double budget) {
  return RunPeerScript(
      python, script, dir,
      "--repeat " + std::to_string(repeat) + " --budget " + std::to_string(budget));
}

// Everything measured on one size.
struct Row {
  Size size;
  int active = 0;  // unknowns on a bound in femup bvls's answer
  std::vector<Timed> femup;
  PeerResult peer;
};

std::string Tables(const std::vector<Row>& rows, const std::string& peer_note) {
  const bool have_peer = std::all_of(rows.begin(), rows.end(),
                                     [](const Row& r) { return r.peer.error.empty(); });
  std::ostringstream md;
  md << "### Wall time (best of the runs, seconds)\n\n";
  if (!have_peer) md << "scipy columns skipped: " << peer_note << "\n\n";
  md << "| m x n | active bounds (femup bvls) |";
  if (have_peer) md << " scipy bvls | scipy trf |";
  for (const char* name : kFemupSolvers) {
    md << " femup " << name << (have_peer ? " (÷ scipy bvls, ÷ scipy trf)" : "") << " |";
  }
  md << "\n|---|---|" << (have_peer ? "---|---|" : "") << "---|---|---|\n";
  for (const Row& r : rows) {
    md << "| " << r.size.rows << " x " << r.size.cols << " | " << r.active << " |";
    double scipy_time[2] = {0, 0};
    if (have_peer) {
      for (int k = 0; k < 2; ++k) {
        scipy_time[k] = r.peer.json["results"][kScipyMethods[k]]["time"].get<double>();
        md << " " << Format("%.4g", scipy_time[k]) << " |";
      }
    }
    for (const Timed& t : r.femup) {
      md << " " << Format("%.4g", t.seconds);
      if (have_peer) {
        md << " (" << Format("%.2f", t.seconds / scipy_time[0]) << ", "
           << Format("%.2f", t.seconds / scipy_time[1]) << ")";
      }
      md << " |";
    }
    md << "\n";
  }

  md << "\n### Answers\n\nReference for the agreement column: "
     << (have_peer ? "scipy's bvls" : "femup's bvls") << ".\n\n"
     << "| m x n | solver | runs | status | iterations | cost | KKT residual | "
        "max abs difference from the reference |\n"
     << "|---|---|---|---|---|---|---|---|\n";

  for (const Row& r : rows) {
    Eigen::VectorXd reference = r.femup[0].solution.x;
    if (have_peer) {
      const auto x = r.peer.json["results"]["bvls"]["x"].get<std::vector<double>>();
      reference = Eigen::Map<const Eigen::VectorXd>(x.data(),
                                                    static_cast<Eigen::Index>(x.size()));
    }
    const std::string size =
        std::to_string(r.size.rows) + " x " + std::to_string(r.size.cols);
    for (std::size_t k = 0; k < r.femup.size(); ++k) {
      const femup::SolverSummary& s = r.femup[k].solution.summary;
      md << "| " << size << " | femup " << kFemupSolvers[k] << " | " << r.femup[k].runs
         << " | " << femup::ToString(s.status) << " | " << s.iterations << " | "
         << Format("%.12g", s.cost) << " | " << Format("%.1e", s.kkt_residual) << " | "
         << Format("%.1e", (r.femup[k].solution.x - reference).cwiseAbs().maxCoeff())
         << " |\n";
    }
    if (!have_peer) continue;
    for (const char* method : kScipyMethods) {
      const nlohmann::json& j = r.peer.json["results"][method];
      const auto x = j["x"].get<std::vector<double>>();
      const Eigen::Map<const Eigen::VectorXd> xs(x.data(),
                                                 static_cast<Eigen::Index>(x.size()));
      md << "| " << size << " | scipy " << method << " | " << j["runs"].get<int>()
         << " | " << j["termination"].get<std::string>() << " | " << j["nit"].get<int>()
         << " | " << Format("%.12g", j["cost"].get<double>()) << " | optimality "
         << Format("%.1e", j["optimality"].get<double>()) << " | "
         << Format("%.1e", (xs - reference).cwiseAbs().maxCoeff()) << " |\n";
    }
  }
  md << "\nKKT residual: femup's check, relative to |A'b|_inf; for scipy, its own "
        "first-order optimality measure (absolute). Status: femup's, or what stopped "
        "scipy.\n";
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  CLI::App app{"femup's bounded least-squares solvers against scipy's lsq_linear"};
  std::string sizes_text = "500x50,2000x200,5000x500";
  int repeat = 3;
  double budget = 10;
  std::string python = "/usr/bin/python3";
  std::string script = FEMUP_PEER_SCRIPT;
  std::string markdown;
  app.add_option("--sizes", sizes_text, "problem sizes, MxN, comma-separated");
  app.add_option("--repeat", repeat, "most runs per solver (the best is kept)")
      ->check(CLI::PositiveNumber);
  app.add_option("--budget", budget,
                 "seconds after which no further run of a solver starts")
      ->check(CLI::NonNegativeNumber);
  femup_bench::AddPeerOptions(app, python, script, markdown, "scipy",
                              "lsq_linear_peer.py");
  CLI11_PARSE(app, argc, argv);
  std::vector<Size> sizes;
  try {
    sizes = ParseSizes(sizes_text);
  } catch (const CLI::Error& e) {
    return app.exit(e);
  }

  const fs::path tmp = femup_bench::WorkDirectory("", "peer");
  if (tmp.empty()) return 1;

  std::vector<Row> rows;
  std::string peer_note, versions;
  for (const Size& size : sizes) {
    Row row;
    row.size = size;
    const femup::LinearProblem p =
        femup_bench::RandomBoundedProblem(size.rows, size.cols, kSeed);
    const fs::path dir =
        tmp / (std::to_string(size.rows) + "x" + std::to_string(size.cols));
    fs::create_directory(dir);
    femup::WriteMatrixMarket((dir / "A.mtx").string(), p.A);
    femup::WriteMatrixMarket((dir / "b.mtx").string(), Eigen::MatrixXd(p.b));
    femup::WriteMatrixMarket((dir / "lower.mtx").string(), Eigen::MatrixXd(p.lower));
    femup::WriteMatrixMarket((dir / "upper.mtx").string(), Eigen::MatrixXd(p.upper));

    for (const char* name : kFemupSolvers) {
      std::cerr << size.rows << "x" << size.cols << ": femup " << name << "\n";
      row.femup.push_back(
          TimeSolver(*femup::CreateLinearSolver(name), p, repeat, budget));
    }
    std::cerr << size.rows << "x" << size.cols << ": scipy\n";
    row.peer = RunPeer(python, script, dir, repeat, budget);
    if (!row.peer.error.empty()) {
      peer_note = row.peer.error;
    } else {
      versions = "scipy " + row.peer.json["scipy"].get<std::string>() + ", numpy " +
                 row.peer.json["numpy"].get<std::string>();
    }
    row.active = femup_bench::ActiveBounds(p, row.femup[0].solution.x);
    rows.push_back(std::move(row));
  }
  fs::remove_all(tmp);

  std::ostringstream out;
  out << "Problems: bench/bounded_problem.h (A Gaussian, box [-1, 1], seed " << kSeed
      << "); femup solvers with default options; best of up to " << repeat
      << " runs, no further run after " << budget << " s. "
      << (peer_note.empty() ? "Peer: " + versions + " (" + python + ", one BLAS thread)."
                            : "Peer: not run.")
      << "\n\n"
      << Tables(rows, peer_note);
  if (!femup_bench::PrintTables(out.str(), markdown)) return 1;
  return 0;
}
