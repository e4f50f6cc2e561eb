// femup solve: a general linear inverse problem A x ~ b read from files.
#include "commands.h"
#include "femup/reporting/outputs.h"
#include "femup/solvers/linear_solver.h"
#include "femup/studies/solve_study.h"

namespace femup::cli {

namespace {

struct SolveOptions {
  femup::SolveFiles files;
  std::string solver = "lstsq";
  femup::LinearSolverOptions options;
  OutputOptions output;
};

void AddOptions(CLI::App* cmd, SolveOptions* o) {
  femup::SolveFiles& files = o->files;
  femup::RegularisationOptions& regularisation = o->options.regularisation;
  cmd->add_option("--A", files.a,
                  "matrix A (.mtx or .csv; a CSV header names the unknowns)")
      ->required();
  cmd->add_option("--b", files.b, "right-hand side b (.mtx or .csv)")->required();
  cmd->add_option("--lower", files.lower, "lower bounds (vector file)");
  cmd->add_option("--upper", files.upper, "upper bounds (vector file)");
  cmd->add_option("--truth", files.truth,
                  "a reference solution to report the error against");
  cmd->add_option("--sigma", files.data_sigma,
                  "noise standard deviation of b (known noise)");
  cmd->add_option("--solver", o->solver,
                  "lstsq, tsvd, tikhonov, bvls, ceres or ipopt (default lstsq)");
  cmd->add_option("--parameter-choice", regularisation.parameter_choice,
                  "tikhonov/tsvd: gcv, lcurve, discrepancy, quasi_optimality or fixed");
  cmd->add_option("--lambda", regularisation.lambda,
                  "tikhonov with --parameter-choice fixed: lambda");
  cmd->add_option("--noise-norm", regularisation.noise_norm,
                  "discrepancy principle: ||e||");
  cmd->add_option("--operator", regularisation.op,
                  "tikhonov: identity, first_difference or second_difference");
  cmd->add_option("--truncation", o->options.truncation, "tsvd: singular values kept");
  AddOutputOptions(cmd, &o->output, "JSON and CSV", "out/solve");
}

int Run(const Invocation& invocation, const SolveOptions& o) {
  const femup::SolveFiles& files = o.files;
  const femup::SolveResult result = femup::RunSolve(files, o.solver, o.options);
  std::vector<std::string> inputs{files.a, files.b};
  for (const std::string* f : {&files.lower, &files.upper, &files.truth}) {
    if (!f->empty()) inputs.push_back(*f);
  }
  Publish(invocation, RunInfo{"solve", o.solver + " on " + files.a, inputs}, o.output.out,
          !o.output.no_plots, o.output.quiet, result, femup::WriteSolveOutputs,
          femup::SolveReport);
  // An unusable solution (see SolutionSummary) is written, then exit 3.
  return result.solution.summary.usable() ? 0 : 3;
}

}  // namespace

Command SolveCommand() {
  auto o = std::make_shared<SolveOptions>();
  return {"solve",
          "solve a general linear inverse problem A x ~ b from files (.mtx or .csv)",
          [o](CLI::App* cmd) { AddOptions(cmd, o.get()); },
          [o](const Invocation& invocation) { return Run(invocation, *o); }};
}

}  // namespace femup::cli
