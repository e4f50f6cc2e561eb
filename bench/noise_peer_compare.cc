// The paper's noise study (femup noise examples/paper_chain_noise.yaml: 11
// corruption levels x 1000 draws on the 5-dof chain, summed form, lstsq)
// against the same computation in numpy (bench/peer/noise_study_peer.py), all
// in one run of this program. The study is loaded once; what the Python side
// needs (K, M, each parameter's basis matrix, the clean measured modes per
// state as Matrix Market; parameter kinds, fixed and preset factors, levels,
// draws, seed as JSON) goes to a temporary directory. Each round times femup's
// RunNoiseStudy with 1 and with 2 threads, then the script twice (a Python
// loop over draws, and with the draws of a level batched). Prints Markdown
// tables: the times with the numpy/femup ratios (per round: median, min, max),
// and the mean Rm per level from both sides. The two sides draw from
// different random streams (a counter-based generator per draw vs numpy's
// PCG64 per level), so the Rm averages agree statistically, not to the digit:
// within a few percent at 1000 draws, both ~0 at level 0.
//
// Usage: femup_noise_peer_compare [--study FILE] [--draws N] [--repeat R] [--rounds K]
//                                 [--python /usr/bin/python3] [--script path]
//                                 [--markdown file] [--keep dir]
// When the script cannot run (no python, no numpy/scipy) the reason is printed
// and the numpy columns are left out.
#include <stdlib.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "femup/core/linalg/blas.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/study.h"
#include "peer_runner.h"

namespace {

namespace fs = std::filesystem;
using femup_bench::Clock;
using femup_bench::Format;
using femup_bench::PeerResult;
using femup_bench::RunPeerScript;
using femup_bench::Seconds;

// Writes the study's model, modes and noise settings for the script; throws
// femup::InputError when the study is not one the script implements (summed
// form, one dry and one wet state, linear lstsq, fixed factors only).
void WriteForPeer(const femup::Study& study, const fs::path& dir) {
  const femup::NoiseStudySpec& spec = *study.noise_study;
  const auto unsupported = [&](const std::string& field, const std::string& what) {
    throw femup::InputError(study.path, field + ": the numpy peer implements " + what);
  };
  if (study.system.form != femup::SystemForm::kSummed)
    unsupported("system.form", "the summed form only");
  if (!spec.compare.empty()) unsupported("noise_study.compare", "one solver only");
  if (study.solver.method != "linear" || study.solver.name != "lstsq")
    unsupported("solver", "linear lstsq only");
  if (study.lower.size() > 0 || study.upper.size() > 0 ||
      study.equality_matrix.size() > 0)
    unsupported("parameters", "fixed factors only (no bounds, no equalities)");
  if (spec.shape_noise != "entry") unsupported("noise_study.shape_noise", "entry only");

  const femup::ParametrisedModel& model = study.model;
  femup::WriteMatrixMarket((dir / "K.mtx").string(), model.stiffness(), true);
  femup::WriteMatrixMarket((dir / "M.mtx").string(), model.mass(), true);
  nlohmann::json j;
  j["form"] = "summed";
  j["parameters"] = model.ParameterNames();
  j["kinds"] = nlohmann::json::array();
  for (int k = 0; k < model.num_parameters(); ++k) {
    const femup::Parameter& p = model.parameter(k);
    j["kinds"].push_back(femup::ToString(p.kind));
    femup::WriteMatrixMarket((dir / ("basis_" + std::to_string(k) + ".mtx")).string(),
                             p.basis.ToSparse(), false);
  }
  const std::vector<std::string> names = model.ParameterNames();
  j["fixed"] = nlohmann::json::object();
  for (const auto& [name, value] : study.fixed) {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) unsupported("parameters.fix", "single named factors only");
    j["fixed"][std::to_string(at - names.begin())] = value;
  }
  j["preset"] =
      std::vector<double>(study.truth->data(), study.truth->data() + study.truth->size());
  j["added_mass_indices"] = model.ParametersOfKind(femup::ParameterKind::kAddedMass);
  j["levels"] = spec.levels;
  j["draws"] = spec.draws;
  j["seed"] = spec.seed;
  j["distribution"] = femup::ToString(spec.distribution);
  j["shape_noise"] = spec.shape_noise;
  j["shape_level_ratio"] = spec.shape_level_ratio;
  j["fem_modes"] =
      study.system.num_fem_modes < 0 ? model.num_dofs() : study.system.num_fem_modes;
  j["states"] = nlohmann::json::array();
  for (const femup::ModalData& m : femup::MeasuredStates(study)) {
    if (!m.IsComplete(model.num_dofs()))
      unsupported("measurements." + m.state, "shapes at every DOF only");
    const std::string file = "shapes_" + std::to_string(j["states"].size()) + ".mtx";
    femup::WriteMatrixMarket((dir / file).string(),
                             m.FullShapes(model.num_dofs(), m.state));
    j["states"].push_back(
        {{"state", m.state},
         {"immersion", femup::ToString(m.immersion)},
         {"frequencies_hz",
          std::vector<double>(m.frequencies_hz.data(),
                              m.frequencies_hz.data() + m.frequencies_hz.size())},
         {"shapes", file}});
  }
  std::ofstream out(dir / "study.json");
  out << j.dump(2) << "\n";
  if (!out) throw femup::InputError((dir / "study.json").string(), "cannot write");
}

// femup's run: best wall time of `repeat` runs of RunNoiseStudy.
struct FemupRun {
  double seconds = 0;
  femup::NoiseStudyResult result;
};

FemupRun TimeFemup(const femup::Study& study, int threads, int repeat) {
  FemupRun run;
  femup::NoiseRunOptions options;
  options.threads = threads;
  for (int r = 0; r < repeat; ++r) {
    const auto start = Clock::now();
    femup::NoiseStudyResult result = femup::RunNoiseStudy(study, options);
    const double t = Seconds(start);
    if (r == 0 || t < run.seconds) {
      run.seconds = t;
      run.result = std::move(result);
    }
  }
  return run;
}

std::string Cell(const PeerResult& p, const char* format, double value) {
  return p.error.empty() ? Format(format, value) : std::string("n/a");
}

}  // namespace

int main(int argc, char** argv) {
  femup::SetUpBlasForProgram(argv);  // as the command line (femup/core/linalg/blas.h)
  CLI::App app{"femup's noise study against the same computation in numpy"};
  std::string study_path = FEMUP_NOISE_STUDY;
  int draws = 0, repeat = 1, rounds = 1;
  std::string python = "/usr/bin/python3";
  std::string script = FEMUP_NOISE_PEER_SCRIPT;
  std::string markdown, keep;
  app.add_option("--study", study_path, "the noise study (default: the paper's)");
  app.add_option("--draws", draws, "draws per level (default: the study's)")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeat", repeat, "runs of each side, best kept (default 1)")
      ->check(CLI::PositiveNumber);
  app.add_option("--rounds", rounds,
                 "rounds of all four runs, interleaved (default 1); ratios per round")
      ->check(CLI::PositiveNumber);
  femup_bench::AddPeerOptions(app, python, script, markdown, "numpy and scipy",
                              "noise_study_peer.py");
  app.add_option("--keep", keep, "write the peer's input files here and keep them");
  CLI11_PARSE(app, argc, argv);

  femup::Study study;
  const fs::path dir = femup_bench::WorkDirectory(keep, "noise");
  if (dir.empty()) return 1;
  try {
    study = femup::LoadStudy(study_path);
    if (!study.noise_study || !study.truth)
      throw femup::InputError(study_path, "noise_study: missing (or truth missing)");
    if (draws > 0) study.noise_study->draws = draws;
    fs::create_directories(dir);
    WriteForPeer(study, dir);
  } catch (const femup::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    if (keep.empty()) fs::remove_all(dir);
    return 1;
  }
  const femup::NoiseStudySpec& spec = *study.noise_study;

  // Rounds interleave the sides (femup 1 thread, 2 threads, numpy loop, numpy
  // batched), so a machine whose speed drifts (a shared virtual machine)
  // slows both sides of a round alike; each round gives its own ratios.
  FemupRun one, two;
  PeerResult loop, batched;
  std::vector<std::array<double, 4>>
      round_ratios;  // loop/1, loop/2, batched/1, batched/2
  const std::string args = "--repeat " + std::to_string(repeat) + " --mode ";
  for (int round = 0; round < rounds; ++round) {
    std::cerr << "round " << round + 1 << " of " << rounds
              << ": femup 1 thread, 2 threads";
    FemupRun r1 = TimeFemup(study, 1, repeat);
    FemupRun r2 = TimeFemup(study, 2, repeat);
    std::cerr << ", numpy loop";
    PeerResult l = RunPeerScript(python, script, dir, args + "loop");
    PeerResult b;
    if (l.error.empty()) {
      std::cerr << ", numpy batched";
      b = RunPeerScript(python, script, dir, args + "vectorised");
    } else {
      b.error = l.error;
    }
    std::cerr << "\n";
    if (!l.error.empty()) std::cerr << "  numpy not run: " << l.error << "\n";
    if (l.error.empty() && b.error.empty()) {
      const double tl = l.json["time"].get<double>(), tb = b.json["time"].get<double>();
      round_ratios.push_back(
          {tl / r1.seconds, tl / r2.seconds, tb / r1.seconds, tb / r2.seconds});
    }
    if (round == 0 || r1.seconds < one.seconds) one = std::move(r1);
    if (round == 0 || r2.seconds < two.seconds) two = std::move(r2);
    // Keep the fastest successful run of each peer mode.
    const auto faster = [](const PeerResult& candidate, const PeerResult& kept) {
      return candidate.error.empty() &&
             (!kept.error.empty() ||
              candidate.json["time"].get<double>() < kept.json["time"].get<double>());
    };
    if (round == 0 || faster(l, loop)) loop = std::move(l);
    if (round == 0 || faster(b, batched)) batched = std::move(b);
  }
  const bool identical = one.result.rm_average == two.result.rm_average &&
                         one.result.usable_draws == two.result.usable_draws;
  if (keep.empty()) fs::remove_all(dir);

  const double t1 = one.seconds, t2 = two.seconds;
  // Median (min-max) over the rounds of one ratio column.
  const auto spread = [&](int column) {
    if (round_ratios.empty()) return std::string("n/a");
    std::vector<double> v;
    for (const auto& r : round_ratios) v.push_back(r[static_cast<std::size_t>(column)]);
    std::sort(v.begin(), v.end());
    const double median =
        v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    return Format("%.1f", median) + " (" + Format("%.1f", v.front()) + "-" +
           Format("%.1f", v.back()) + ")";
  };
  std::ostringstream md;
  md << "Study: " << study.name << " (" << spec.levels.size() << " levels x "
     << spec.draws << " draws, summed form, " << study.model.num_parameters()
     << " factors, lstsq), " << rounds << " round(s), each side run " << repeat
     << " time(s) per round; times are the best of all runs, ratios the median "
     << "(min-max) over the rounds of each round's best times. femup: "
     << "RunNoiseStudy with NoiseRunOptions::threads = 1 and 2 (hardware threads: "
     << std::thread::hardware_concurrency() << "); 1 and 2 threads give "
     << (identical ? "identical" : "DIFFERENT") << " results. numpy: "
     << (loop.error.empty() ? "numpy " + loop.json["numpy"].get<std::string>() +
                                  ", scipy " + loop.json["scipy"].get<std::string>() +
                                  ", one BLAS thread (" + python + ")"
                            : "not run (" + loop.error + ")")
     << ".\n\n";
  md << "| | femup 1 thread (s) | femup 2 threads (s) | numpy (s) | numpy / femup 1 "
        "thread | numpy / femup 2 threads |\n|---|---|---|---|---|---|\n";
  const auto row = [&](const char* label, const PeerResult& p, int column) {
    const double tp = p.error.empty() ? p.json["time"].get<double>() : 0.0;
    md << "| " << label << " | " << Format("%.3f", t1) << " | " << Format("%.3f", t2)
       << " | " << Cell(p, "%.3f", tp) << " | " << spread(column) << " | "
       << spread(column + 1) << " |\n";
  };
  row("numpy, Python loop over draws", loop, 0);
  row("numpy, draws of a level batched (lstsq looped)", batched, 2);

  md << "\nMean Rm (average over the added-mass factors, %), per level; relative "
        "difference = |numpy - femup| / femup (different random streams).\n\n"
     << "| level | femup | numpy loop | rel. diff. | numpy batched | rel. diff. | usable "
        "draws (femup / numpy) |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t l = 0; l < spec.levels.size(); ++l) {
    const double f = one.result.rm_average[l];
    md << "| " << Format("%g", spec.levels[l] * 100) << " % | " << Format("%.4g", f)
       << " |";
    const PeerResult* peers[] = {&loop, &batched};
    for (const PeerResult* p : peers) {
      if (!p->error.empty()) {
        md << " n/a | n/a |";
        continue;
      }
      const double n = p->json["rm_average"][l].is_number()
                           ? p->json["rm_average"][l].get<double>()
                           : std::nan("");
      md << " " << Format("%.4g", n) << " | "
         << (f > 1e-6 ? Format("%.1f %%", std::abs(n - f) / f * 100) : std::string("-"))
         << " |";
    }
    md << " " << one.result.usable_draws[l] << " / "
       << (loop.error.empty() ? std::to_string(loop.json["usable"][l].get<int>())
                              : std::string("n/a"))
       << " |\n";
  }
  if (!femup_bench::PrintTables(md.str(), markdown)) return 1;
  return identical ? 0 : 1;
}
