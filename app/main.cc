// femup: the command line. Each subcommand reads a study file, runs one
// pipeline from studies/, and writes its JSON, matrices and plots into an
// output folder all at once (nothing is left behind when a run fails).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "femup/errors.h"
#include "femup/output_dir.h"
#include "femup/studies/modes_study.h"
#include "femup/studies/noise_study.h"
#include "femup/studies/study.h"
#include "femup/studies/update_study.h"

namespace {

struct Common {
  std::string study;
  std::string out;
  bool no_plots = false;
  bool quiet = false;
};

void AddCommon(CLI::App* cmd, Common* c) {
  cmd->add_option("study", c->study, "study file (YAML or JSON)")->required();
  cmd->add_option("-o,--out", c->out, "output folder (default: out/<study name>)");
  cmd->add_flag("--no-plots", c->no_plots, "write JSON and matrices only");
  cmd->add_flag("-q,--quiet", c->quiet, "print nothing but errors and warnings");
}

std::string OutputFolder(const Common& c, const femup::Study& study) {
  if (!c.out.empty()) return c.out;
  std::filesystem::create_directories("out");
  return "out/" + study.name;
}

void Finish(femup::OutputDir* dir, const std::vector<std::string>& warnings,
            const Common& c) {
  dir->Commit();
  for (const auto& w : warnings) std::cerr << "femup: warning: " << w << "\n";
  if (!c.quiet) {
    std::cout << "\nwrote to " << dir->directory() << ":";
    for (const auto& f : dir->files()) {
      if (std::filesystem::exists(std::filesystem::path(dir->directory()) / f)) {
        std::cout << " " << f;
      }
    }
    std::cout << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "femup: find where a finite element model is wrong, and by how much, from "
      "vibration measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "femup 0.1.0");

  Common run_opts, noise_opts, modes_opts, check_opts;
  int num_modes = 0;
  CLI::App* run = app.add_subcommand(
      "run", "identify correction factors (Z d = F), build the updated model, compare");
  AddCommon(run, &run_opts);
  CLI::App* noise = app.add_subcommand(
      "noise", "the noise study: Rm of the added-mass factors vs corruption");
  AddCommon(noise, &noise_opts);
  CLI::App* modes =
      app.add_subcommand("modes", "modal analysis of the study's nominal model");
  AddCommon(modes, &modes_opts);
  modes->add_option("-n,--modes", num_modes,
                    "number of lowest modes (default: all, or 10)");
  CLI::App* check =
      app.add_subcommand("check", "read and check a study file, do no work");
  check->add_option("study", check_opts.study, "study file (YAML or JSON)")->required();

  CLI11_PARSE(app, argc, argv);

  try {
    std::vector<std::string> warnings;
    if (*check) {
      const femup::Study study = femup::LoadStudy(check_opts.study);
      std::cout << check_opts.study << ": ok: " << study.structure.description << ", "
                << study.model.num_dofs() << " DOFs, " << study.model.num_parameters()
                << " parameters, " << study.measurements.size() << " measured state(s)\n";
      return 0;
    }
    if (*run) {
      const femup::Study study = femup::LoadStudy(run_opts.study);
      const femup::UpdateResult result = femup::RunUpdate(study);
      femup::OutputDir dir(OutputFolder(run_opts, study));
      femup::WriteUpdateOutputs(result, study.plots && !run_opts.no_plots, &dir,
                                &warnings);
      if (!run_opts.quiet) std::cout << femup::UpdateReport(result);
      for (const auto& w : result.solution.identifiability.warnings) {
        warnings.push_back("solved system: " + w);
      }
      Finish(&dir, warnings, run_opts);
      return result.solution.summary.usable() ? 0 : 3;
    }
    if (*noise) {
      const femup::Study study = femup::LoadStudy(noise_opts.study);
      if (!study.noise_study) {
        throw femup::InputError(noise_opts.study,
                                "noise_study: the study has no noise_study "
                                "section (levels, draws, seed)");
      }
      const femup::NoiseStudyResult result = femup::RunNoiseStudy(study);
      femup::OutputDir dir(OutputFolder(noise_opts, study));
      femup::WriteNoiseOutputs(result, study.plots && !noise_opts.no_plots, &dir,
                               &warnings);
      if (!noise_opts.quiet) std::cout << femup::NoiseReport(result);
      Finish(&dir, warnings, noise_opts);
      return 0;
    }
    if (*modes) {
      const femup::Study study = femup::LoadStudy(modes_opts.study);
      const femup::ModesResult result = femup::RunModes(study, num_modes);
      femup::OutputDir dir(OutputFolder(modes_opts, study));
      femup::WriteModesOutputs(result, study.plots && !modes_opts.no_plots, &dir,
                               &warnings);
      if (!modes_opts.quiet) std::cout << femup::ModesReport(result);
      Finish(&dir, warnings, modes_opts);
      return 0;
    }
  } catch (const femup::InputError& e) {
    std::cerr << "femup: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "femup: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
