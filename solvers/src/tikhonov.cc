#include "femup/solvers/tikhonov.h"

#include <Eigen/QR>
#include <sstream>

#include "femup/core/errors.h"
#include "linear_common.h"

namespace femup {

namespace {

Eigen::MatrixXd Operator(const LinearProblem& problem, const std::string& op) {
  const int n = problem.num_unknowns();
  if (op == "identity") return Eigen::MatrixXd::Identity(n, n);
  if (op == "first_difference") return DifferenceOperator(n, 1, problem.groups);
  if (op == "second_difference") return DifferenceOperator(n, 2, problem.groups);
  if (problem.regulariser.size() == 0)
    throw InputError("solver.regularisation.operator",
                     "'problem' needs the problem to give a regulariser L");
  return problem.regulariser;
}

}  // namespace

LinearSolution TikhonovSolver::Solve(const LinearProblem& problem) const {
  const internal::Stopwatch clock;
  if (const Invalid bad = options_.regularisation.Validate())
    throw InputError("solver.regularisation", bad.ToString());
  const internal::ReducedProblem r = internal::Reduce(problem, name());
  const Eigen::MatrixXd l = Operator(problem, options_.regularisation.op);

  // ||L (x - x0)|| in the reduced coordinates: x = p + N z, so L N z - L (x0 - p);
  // z0 = (L N)^+ L (x0 - p) leaves only a constant outside range(L N).
  const Eigen::VectorXd x0 = problem.prior.size() > 0
                                 ? problem.prior
                                 : Eigen::VectorXd::Zero(problem.num_unknowns());
  const Eigen::MatrixXd ln = l * r.basis;
  const Eigen::VectorXd z0 =
      Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(ln).solve(
          l * (x0 - r.particular));

  LinearSolution solution;
  solution.identifiability = AnalyseIdentifiability(
      r.A, r.names, r.groups, options_.relative_rank_tolerance, true);
  const TikhonovPath path(r.A, r.b, ln, z0, problem.data_rows(), problem.residual_offset);
  RegularisationReport& rep = solution.regularisation;
  const double lambda = ChooseLambda(path, options_.regularisation, &rep);

  const Eigen::VectorXd z = path.Solve(lambda);
  const Eigen::VectorXd weighted_residual = internal::SetAnswer(problem, r, z, &solution);
  const Eigen::MatrixXd xz = path.Inverse(lambda);  // z - z0 = X (b - A z0)
  internal::FillUncertainty(problem, r.Lift(xz), weighted_residual,
                            path.EffectiveParameters(lambda), options_.confidence_level,
                            &solution);
  const Eigen::MatrixXd rz = xz * r.A;
  solution.resolution = r.basis * rz * r.basis.transpose();
  solution.bias_estimate =
      r.basis * ((rz - Eigen::MatrixXd::Identity(rz.rows(), rz.cols())) * (z - z0));

  std::ostringstream msg;
  msg << "Tikhonov (" << options_.regularisation.op << "), lambda = " << lambda << " by "
      << rep.parameter_choice << "; " << path.EffectiveParameters(lambda)
      << " effective parameters of " << r.A.cols();
  internal::FinishRegularised(msg.str(), r, clock.Seconds(), &solution);
  return solution;
}

}  // namespace femup
