// femup_validate: scores femup's solvers against references nobody here wrote
// (NIST's certified values for the StRD datasets, Hansen's ill-posed test
// problems with their exact solutions, the paper's preset correction factors)
// and prints each result as a Markdown table. With --out DIR it also writes the
// table and a JSON file of the numbers into DIR, all at once: files are staged
// and renamed into place only when every table has been computed.
//
// This file: the helpers of validate.h and the command line; each table is in
// its validate_<table>.cc.
#include "validate.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/linalg/blas.h"
#include "femup/evaluation/nist_strd.h"
#include "femup/reporting/output_dir.h"

namespace femup_validate {

std::string Format(const char* format, double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}
std::string Digits(double lre) { return Format("%.1f", lre); }
std::string Sci(double value) { return Format("%.2e", value); }

std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n' || c == '\r') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double MinLre(const femup::VectorLD& x, const femup::VectorLD& certified) {
  if (x.size() != certified.size()) return 0;
  double lre = 15;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    lre = std::min(lre, femup::LogRelativeError(x[j], certified[j]));
  }
  return lre;
}
double MinLre(const Eigen::VectorXd& x, const femup::VectorLD& certified) {
  return MinLre(femup::VectorLD(x.cast<long double>()), certified);
}

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

std::string NistFolder(const std::string& data, const std::string& kind) {
  const fs::path folder = fs::path(data) / kind;
  std::error_code ec;
  if (!fs::is_directory(data, ec)) {
    throw InputError("--data " + data,
                     "folder not found (expected NIST StRD data with "
                     "linear/ and nonlinear/ inside)");
  }
  if (!fs::is_directory(folder, ec)) {
    throw InputError(folder.string(),
                     "folder not found (the NIST " + kind + " .dat files belong there)");
  }
  return folder.string();
}

namespace {

// Prints every report and, with an output folder, writes <name>.md and
// <name>.json for each (and `combined` when not empty) in one commit.
void Emit(const std::vector<Report>& reports, const std::string& out,
          const std::string& combined) {
  std::string all;
  for (const auto& r : reports) all += (all.empty() ? "" : "\n") + r.markdown;
  std::cout << all;
  if (out.empty()) return;
  std::error_code ec;
  const fs::path parent = fs::path(out).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  femup::OutputDir dir(out);
  for (const auto& r : reports) {
    dir.WriteText(r.name + ".md", r.markdown);
    dir.WriteText(r.name + ".json", r.json.dump(2) + "\n");
  }
  if (!combined.empty()) dir.WriteText(combined, "# femup validation\n\n" + all);
  dir.Commit();
  std::cerr << "femup_validate: wrote " << Join(dir.files(), ", ") << " to " << out
            << "\n";
}

const std::vector<std::string> kSubcommands = {"nist-linear", "nist-nonlinear",
                                               "ill-posed", "paper-chain", "all"};

}  // namespace

}  // namespace femup_validate

using femup_validate::Check;
using femup_validate::Emit;
using femup_validate::Format;
using femup_validate::IllPosed;
using femup_validate::IllPosedSettings;
using femup_validate::InputError;
using femup_validate::Join;
using femup_validate::kSubcommands;
using femup_validate::NistFolder;
using femup_validate::NistLinear;
using femup_validate::NistNonlinear;
using femup_validate::PaperChain;
using femup_validate::Report;
using femup_validate::Seconds;

int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  // CLI11 reports an unknown subcommand as an unexpected argument; name it.
  if (argc > 1 && argv[1][0] != '-' &&
      std::find(kSubcommands.begin(), kSubcommands.end(), argv[1]) ==
          kSubcommands.end()) {
    std::cerr << "femup_validate: error: unknown subcommand '" << argv[1] << "' (choose "
              << Join(kSubcommands, ", ") << ")\n";
    return 1;
  }
  CLI::App app{
      "femup_validate: femup's solvers on references nobody here wrote (NIST StRD, "
      "Hansen's ill-posed problems, the paper's preset factors), as Markdown tables"};
  app.require_subcommand(1);

  std::string data = FEMUP_NIST_DATA_DIR;
  std::string out;
  IllPosedSettings ill;
  const auto add_out = [&out](CLI::App* cmd) {
    cmd->add_option("--out", out,
                    "also write the table (.md) and its numbers (.json) to this folder");
  };
  const auto add_data = [&data](CLI::App* cmd) {
    cmd->add_option("--data", data,
                    "NIST StRD folder holding linear/ and nonlinear/ (default: the "
                    "copy in tests/data/nist)");
  };
  const auto add_ill = [&ill](CLI::App* cmd) {
    cmd->add_option("--n", ill.n, "problem size (a multiple of 4)");
    cmd->add_option("--noise", ill.noise, "relative noise level ||e|| / ||b||");
    cmd->add_option("--seed", ill.seed, "seed of the noise");
  };
  CLI::App* linear = app.add_subcommand(
      "nist-linear", "the 11 NIST linear datasets on every linear solver");
  add_data(linear);
  add_out(linear);
  CLI::App* nonlinear = app.add_subcommand(
      "nist-nonlinear", "the 27 NIST nonlinear datasets, 2 starts, on ceres and ipopt");
  add_data(nonlinear);
  add_out(nonlinear);
  CLI::App* ill_posed = app.add_subcommand(
      "ill-posed", "parameter-choice rules on Hansen's test problems with noise");
  add_ill(ill_posed);
  add_out(ill_posed);
  CLI::App* chain =
      app.add_subcommand("paper-chain", "the paper's 5-dof chain on every linear solver");
  add_out(chain);
  CLI::App* all = app.add_subcommand("all", "every table, plus a combined Markdown file");
  add_data(all);
  add_ill(all);
  add_out(all);

  CLI11_PARSE(app, argc, argv);

  try {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Report> reports;
    std::string combined;
    if (*linear) reports.push_back(NistLinear(data));
    if (*nonlinear) reports.push_back(NistNonlinear(data));
    if (*ill_posed) reports.push_back(IllPosed(ill));
    if (*chain) reports.push_back(PaperChain());
    if (*all) {
      // Bad options fail before the long runs.
      Check(ill);
      NistFolder(data, "linear");
      NistFolder(data, "nonlinear");
      reports = {NistLinear(data), NistNonlinear(data), IllPosed(ill), PaperChain()};
      combined = "validation.md";
    }
    Emit(reports, out, combined);
    std::cerr << "femup_validate: " << app.get_subcommands().front()->get_name()
              << " took " << Format("%.1f", Seconds(start)) << " s\n";
  } catch (const InputError& e) {
    std::cerr << "femup_validate: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "femup_validate: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
