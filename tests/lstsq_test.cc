// Linear least squares (solvers/include/femup/solvers/{linear_solver,lstsq,
// identifiability}.h) and LinearProblem
// (problems/include/femup/problems/linear_problem.h), checked against normal
// equations in long double, pseudo-inverses from Eigen's complete orthogonal
// decomposition, and hand-made rank-deficient examples.
#include "femup/solvers/lstsq.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/errors.h"
#include "femup/evaluation/nist_strd.h"
#include "femup/problems/linear_problem.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/linear_solver.h"
#include "solver_problems.h"

namespace femup {
namespace {

using MatrixLd = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using VectorLd = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

Eigen::MatrixXd RandomMatrix(int rows, int cols, unsigned seed) {
  return fixtures::RandomGaussian(rows, cols, seed);
}

// Least-squares solution by the normal equations in long double.
Eigen::VectorXd NormalEquations(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const MatrixLd al = a.cast<long double>();
  const VectorLd bl = b.cast<long double>();
  const MatrixLd ata = al.transpose() * al;
  const VectorLd atb = al.transpose() * bl;
  return Eigen::LLT<MatrixLd>(ata).solve(atb).cast<double>();
}

LinearProblem Problem(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return fixtures::NamedProblem(a, b);
}

double MaxRelativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& ref) {
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

TEST(LstsqSolver, OverdeterminedMatchesNormalEquations) {
  const Eigen::MatrixXd a = RandomMatrix(30, 5, 1);
  const Eigen::VectorXd b = RandomMatrix(30, 1, 2);
  const LinearProblem p = Problem(a, b);
  const auto solver = CreateLinearSolver("lstsq");
  ASSERT_NE(solver, nullptr);
  EXPECT_EQ(solver->name(), "lstsq");
  const LinearSolution sol = solver->Solve(p);
  const Eigen::VectorXd ref = NormalEquations(a, b);
  EXPECT_EQ(sol.summary.status, SolverStatus::kSolved);
  EXPECT_TRUE(sol.summary.usable());
  EXPECT_LE(MaxRelativeError(sol.x, ref), 1e-13);
  // Residual and cost are of the returned x; the residual is orthogonal to A.
  EXPECT_LE((sol.residual - (a * sol.x - b)).norm(), 1e-14 * b.norm());
  EXPECT_NEAR(sol.summary.cost, 0.5 * (a * ref - b).squaredNorm(),
              1e-12 * b.squaredNorm());
  EXPECT_LE((a.transpose() * sol.residual).norm(), 1e-12 * a.norm() * b.norm());
  EXPECT_EQ(sol.identifiability.rank, 5);
  EXPECT_TRUE(sol.identifiability.null_directions.empty());
  EXPECT_FALSE(sol.summary.message.empty());
}

TEST(LstsqSolver, WithoutColumnScalingSameFullRankSolution) {
  const Eigen::MatrixXd a = RandomMatrix(30, 5, 15);
  const Eigen::VectorXd b = RandomMatrix(30, 1, 16);
  LinearSolverOptions options;
  options.scale_columns = false;
  const LinearSolution sol = CreateLinearSolver("lstsq", options)->Solve(Problem(a, b));
  EXPECT_EQ(sol.summary.status, SolverStatus::kSolved);
  EXPECT_LE(MaxRelativeError(sol.x, NormalEquations(a, b)), 1e-13);
}

TEST(LstsqSolver, MinimumNormWithoutColumnScalingNamesTheDirections) {
  // lstsq.h: when A is rank deficient the minimum-norm solution comes "with a
  // warning that names the directions the data cannot determine". Without
  // column scaling, columns of norm 1e-9 and 1e9 make the solver's own rank
  // decision (on the unscaled A) rank deficient; the summary must then say
  // which direction, and the identifiability it returns must agree.
  Eigen::MatrixXd a(4, 3);
  // clang-format off
  a <<  1e-9,  1.0,  1e9,
        2e-9, -1.0,  3e9,
       -1e-9,  0.5,  1e9,
        3e-9,  2.0, -2e9;
  // clang-format on
  const Eigen::VectorXd b = a * Eigen::Vector3d(1e9, 1.0, 1e-9);
  LinearSolverOptions options;
  options.scale_columns = false;
  const LinearSolution sol = CreateLinearSolver("lstsq", options)->Solve(Problem(a, b));
  if (sol.summary.status == SolverStatus::kMinimumNorm) {
    EXPECT_FALSE(sol.identifiability.null_directions.empty())
        << "status minimum_norm but identifiability rank " << sol.identifiability.rank
        << " of 3 and no null direction; message: " << sol.summary.message;
    const std::string tail = "Add a constraint: ";
    const std::string& msg = sol.summary.message;
    EXPECT_FALSE(msg.size() >= tail.size() &&
                 msg.compare(msg.size() - tail.size(), tail.size(), tail) == 0)
        << "the message names no direction: " << msg;
  }
}

TEST(LstsqSolver, FixedValuesAreHonoured) {
  const Eigen::MatrixXd a = RandomMatrix(25, 4, 3);
  const Eigen::VectorXd b = RandomMatrix(25, 1, 4);
  LinearProblem p = Problem(a, b);
  p.Fix("x3", 0.7);
  EXPECT_TRUE(p.IsFixed(2));
  EXPECT_EQ(p.FreeUnknowns(), (std::vector<int>{0, 1, 3}));
  const LinearSolution sol = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_EQ(sol.x[2], 0.7);
  // Reference: least squares of the other three on b - 0.7 a3.
  Eigen::MatrixXd reduced(25, 3);
  reduced << a.col(0), a.col(1), a.col(3);
  const Eigen::VectorXd ref = NormalEquations(reduced, b - 0.7 * a.col(2));
  const Eigen::Vector3d free(sol.x[0], sol.x[1], sol.x[3]);
  EXPECT_LE(MaxRelativeError(free, ref), 1e-13);
  EXPECT_EQ(sol.summary.status, SolverStatus::kSolved);
  EXPECT_LE((sol.residual - (a * sol.x - b)).norm(), 1e-14 * b.norm());
}

TEST(LstsqSolver, RankDeficientGivesScaledMinimumNorm) {
  Eigen::MatrixXd a = RandomMatrix(20, 4, 5);
  a.col(1) *= 50.0;                      // unequal column norms
  a.col(3) = 2.0 * a.col(0) - a.col(1);  // rank 3
  const Eigen::VectorXd b = RandomMatrix(20, 1, 6);
  const LinearProblem p = Problem(a, b);
  const LinearSolution sol = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_EQ(sol.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_TRUE(sol.summary.usable());
  EXPECT_NE(sol.summary.message.find("rank 3 of 4"), std::string::npos)
      << sol.summary.message;
  EXPECT_EQ(sol.identifiability.rank, 3);
  ASSERT_EQ(sol.identifiability.null_directions.size(), 1u);
  // Reference: pseudo-inverse solution of the column-scaled matrix, mapped back.
  const Eigen::VectorXd scale = a.colwise().norm().transpose();
  const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(as);
  cod.setThreshold(1e-10);
  ASSERT_EQ(cod.rank(), 3);
  const Eigen::VectorXd ref = scale.cwiseInverse().asDiagonal() * cod.solve(b);
  EXPECT_LE(MaxRelativeError(sol.x, ref), 1e-11);
  // A (2, -1, 0, -1) = 0: the null direction, in the unknowns' own units.
  const Eigen::VectorXd v = sol.identifiability.null_directions[0].coefficients;
  EXPECT_LE((a * v).norm(), 1e-10 * a.norm());
  EXPECT_NEAR(std::abs(v.normalized().dot(Eigen::Vector4d(2, -1, 0, -1).normalized())),
              1.0, 1e-10);
  EXPECT_NEAR(v[2], 0.0, 1e-10);
}

TEST(LstsqSolver, WithoutDiagnosticsSameAnswerByQr) {
  Eigen::MatrixXd a = RandomMatrix(40, 6, 21);
  a.col(2) *= 1e4;  // unequal column norms
  const Eigen::VectorXd b = RandomMatrix(40, 1, 22);
  LinearProblem p = Problem(a, b);
  p.fixed = {{4, 0.25}};
  LinearSolverOptions lean;
  lean.diagnostics = false;
  const LinearSolution fast = CreateLinearSolver("lstsq", lean)->Solve(p);
  const LinearSolution full = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_EQ(fast.summary.status, SolverStatus::kSolved);
  EXPECT_NE(fast.summary.message.find("QR"), std::string::npos) << fast.summary.message;
  EXPECT_LE(MaxRelativeError(fast.x, full.x), 1e-13);
  EXPECT_EQ(fast.x[4], 0.25);
  EXPECT_LE((fast.residual - (a * fast.x - b)).norm(), 1e-14 * b.norm());
  EXPECT_NEAR(fast.summary.cost, full.summary.cost, 1e-12 * full.summary.cost);
  // No diagnostics: no covariance, no identifiability report.
  EXPECT_EQ(fast.covariance.size(), 0);
  EXPECT_EQ(fast.identifiability.rank, 0);  // not analysed
  EXPECT_EQ(full.identifiability.rank, 5);
}

TEST(LstsqSolver, WithoutDiagnosticsRankDeficientGoesTheSvdPath) {
  Eigen::MatrixXd a = RandomMatrix(20, 4, 5);
  a.col(3) = 2.0 * a.col(0) - a.col(1);  // rank 3
  const Eigen::VectorXd b = RandomMatrix(20, 1, 6);
  LinearSolverOptions lean;
  lean.diagnostics = false;
  const LinearSolution fast = CreateLinearSolver("lstsq", lean)->Solve(Problem(a, b));
  const LinearSolution full = CreateLinearSolver("lstsq")->Solve(Problem(a, b));
  EXPECT_EQ(fast.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_EQ(fast.x, full.x);  // the very same computation
}

TEST(LstsqSolver, ZeroColumnIsUnseen) {
  Eigen::MatrixXd a = RandomMatrix(10, 3, 7);
  a.col(1).setZero();
  const Eigen::VectorXd b = RandomMatrix(10, 1, 8);
  const LinearSolution sol = CreateLinearSolver("lstsq")->Solve(Problem(a, b));
  EXPECT_EQ(sol.identifiability.unseen, std::vector<std::string>{"x2"});
  EXPECT_EQ(sol.summary.status, SolverStatus::kMinimumNorm);
  EXPECT_EQ(sol.x[1], 0.0);  // minimum norm: nothing is put where no data is
  Eigen::MatrixXd reduced(10, 2);
  reduced << a.col(0), a.col(2);
  const Eigen::VectorXd ref = NormalEquations(reduced, b);
  EXPECT_LE(MaxRelativeError(Eigen::Vector2d(sol.x[0], sol.x[2]), ref), 1e-13);
  bool warned = false;
  for (const auto& w : sol.identifiability.warnings)
    warned |= w.find("x2") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(LstsqSolver, BadlyScaledColumnsSolvedToFullAccuracy) {
  Eigen::MatrixXd a = RandomMatrix(15, 3, 9);
  a.col(0) *= 1e-8;
  a.col(2) *= 1e8;
  const Eigen::Vector3d x_true(3e7, -0.25, 4e-9);  // each term of order 1
  const Eigen::VectorXd b = a * x_true;
  const LinearSolution sol = CreateLinearSolver("lstsq")->Solve(Problem(a, b));
  EXPECT_EQ(sol.summary.status, SolverStatus::kSolved);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(sol.x[j], x_true[j], 1e-12 * std::abs(x_true[j])) << j;
  }
  EXPECT_GT(sol.identifiability.condition_number_unscaled, 1e14);
  EXPECT_LT(sol.identifiability.condition_number, 1e3);
}

// NIST's Wampler4 and Wampler5 (exact design, x = 0..20, large residuals) are
// where the kappa^2 |r| term of the least-squares sensitivity dominates: a plain
// SVD solve gets 8.4 and 6.4 digits of the certified values, the refined one the
// least-squares answer of the data. On Filip the double-rounded design itself
// allows 7.65 digits (its exact least-squares answer, docs/validation.md).
TEST(LstsqSolver, RefinementReachesNistCertifiedDigits) {
  const std::vector<std::pair<std::string, double>> sets = {
      {"Wampler4", 12.0}, {"Wampler5", 12.0}, {"Longley", 13.0}, {"Filip", 7.5}};
  for (const auto& [name, digits] : sets) {
    const NistLinearDataset d = ReadNistLinear(std::string(FEMUP_TEST_DATA_DIR) +
                                               "/nist/linear/" + name + ".dat");
    const LinearSolution s = CreateLinearSolver("lstsq")->Solve(d.Problem());
    double lre = 15;
    for (int j = 0; j < d.num_parameters(); ++j) {
      lre = std::min(lre,
                     LogRelativeError(static_cast<long double>(s.x[j]), d.certified[j]));
    }
    EXPECT_GE(lre, digits) << name;
    RecordProperty(name + "_digits", std::to_string(lre));
  }
}

TEST(LinearSolverFactory, NamesAndErrors) {
  EXPECT_EQ(
      AvailableLinearSolvers(),
      (std::vector<std::string>{"lstsq", "tsvd", "tikhonov", "bvls", "ceres", "ipopt"}));
  EXPECT_NE(CreateLinearSolver("lstsq"), nullptr);
  try {
    CreateLinearSolver("qr");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solver.name");
    const std::string what = e.what();
    EXPECT_NE(what.find("qr"), std::string::npos) << what;
    for (const std::string& name : AvailableLinearSolvers()) {
      EXPECT_NE(what.find(name), std::string::npos) << what;
    }
  }
  for (double tol : {0.0, -1e-3, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    LinearSolverOptions options;
    options.relative_rank_tolerance = tol;
    EXPECT_NE(options.Validate().ToString(), "") << tol;
    try {
      CreateLinearSolver("lstsq", options);
      ADD_FAILURE() << "no exception for tolerance " << tol;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("rank_tolerance"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(LinearSolverOptions().Validate().ToString(), "");
}

TEST(LinearSolverFactory, InvalidOptionErrorNamesTheField) {
  // linear_solver.h: "InputError("solver.<field>", ...) for invalid options".
  LinearSolverOptions options;
  options.relative_rank_tolerance = 2.0;
  try {
    CreateLinearSolver("lstsq", options);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().rfind("solver.", 0), 0u) << "where() = '" << e.where() << "'";
  }
}

TEST(SolverStatus, Names) {
  EXPECT_STREQ(ToString(SolverStatus::kSolved), "solved");
  EXPECT_STREQ(ToString(SolverStatus::kMinimumNorm), "minimum_norm");
  EXPECT_STREQ(ToString(SolverStatus::kNoConvergence), "no_convergence");
  EXPECT_STREQ(ToString(SolverStatus::kFailed), "failed");
}

// ---------------------------------------------------------------------------
// LinearProblem.

TEST(LinearProblem, ValidateMessages) {
  const LinearProblem good = Problem(RandomMatrix(4, 3, 10), RandomMatrix(4, 1, 11));
  EXPECT_EQ(good.Validate().ToString(), "");

  LinearProblem p = good;
  p.b = Eigen::VectorXd::Zero(5);
  EXPECT_NE(p.Validate().ToString().find("4 rows but b has 5"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.names.pop_back();
  EXPECT_NE(p.Validate().ToString().find("2 names for 3 unknowns"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.groups = {"mass"};
  EXPECT_NE(p.Validate().ToString().find("groups"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.row_labels = {"r1"};
  EXPECT_NE(p.Validate().ToString().find("row labels"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.A(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(p.Validate().ToString().find("A has a NaN"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.b[0] = std::numeric_limits<double>::infinity();
  EXPECT_NE(p.Validate().ToString().find("b has a NaN"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.fixed = {{3, 1.0}};
  EXPECT_NE(p.Validate().ToString().find("index 3 is outside 0..2"), std::string::npos)
      << p.Validate().ToString();
  p.fixed = {{-1, 1.0}};
  EXPECT_NE(p.Validate().ToString().find("outside"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.fixed = {{1, 1.0}, {1, 2.0}};
  EXPECT_NE(p.Validate().ToString().find("x2 is fixed twice"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.fixed = {{0, std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_NE(p.Validate().ToString().find("not finite"), std::string::npos)
      << p.Validate().ToString();

  p = good;
  p.fixed = {{0, 1.0}, {1, 1.0}, {2, 1.0}};
  EXPECT_NE(p.Validate().ToString(), "");

  // The solver refuses an invalid problem before any work.
  p = good;
  p.b = Eigen::VectorXd::Zero(5);
  EXPECT_THROW(CreateLinearSolver("lstsq")->Solve(p), InputError);
}

TEST(LinearProblem, FixUnknownNameListsNames) {
  LinearProblem p = Problem(RandomMatrix(4, 3, 12), RandomMatrix(4, 1, 13));
  try {
    p.Fix("mass[4]", 0.0058);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mass[4]"), std::string::npos) << what;
    for (const char* name : {"x1", "x2", "x3"}) {
      EXPECT_NE(what.find(name), std::string::npos) << what;
    }
  }
  EXPECT_TRUE(p.fixed.empty());
  p.Fix("x2", 1.5);
  ASSERT_EQ(p.fixed.size(), 1u);
  EXPECT_EQ(p.fixed[0].first, 1);
  EXPECT_EQ(p.fixed[0].second, 1.5);
  EXPECT_FALSE(p.IsFixed(0));
}

// ---------------------------------------------------------------------------
// Identifiability.

// Two groups: column 0 ("mass[1]") and column 1 ("stiffness[1]") enter every
// equation as m * c - s * c, so only their difference is seen: (K~ - lambda M~)
// is unchanged when both factors grow together.
TEST(AnalyseIdentifiability, CommonScalingOnTwoGroups) {
  Eigen::MatrixXd a(4, 3);
  // clang-format off
  a << -2.0,  2.0, 1.0,
       -1.0,  1.0, 0.0,
        3.0, -3.0, 2.0,
        0.5, -0.5, 1.0;
  // clang-format on
  const std::vector<std::string> names = {"mass[1]", "stiffness[1]", "added_mass[1]"};
  const std::vector<std::string> groups = {"mass", "stiffness", "added_mass"};
  const Identifiability id = AnalyseIdentifiability(a, names, groups, 1e-10);
  EXPECT_EQ(id.rank, 2);
  ASSERT_EQ(id.singular_values.size(), 3);
  EXPECT_NEAR(id.singular_values[2], 0.0, 1e-14);
  EXPECT_GT(id.condition_number, 1e14);  // s_min is zero to rounding
  ASSERT_EQ(id.null_directions.size(), 1u);
  const NullDirection& nd = id.null_directions[0];
  // Null vector (1, 1, 0) / sqrt(2), sign with the largest entry positive.
  EXPECT_NEAR(nd.coefficients[0], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(nd.coefficients[1], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(nd.coefficients[2], 0.0, 1e-12);
  EXPECT_TRUE(nd.common_scaling) << nd.description;
  EXPECT_NE(nd.description.find("common scaling"), std::string::npos) << nd.description;
  EXPECT_NE(nd.description.find("mass[1]"), std::string::npos) << nd.description;
  EXPECT_NE(nd.description.find("stiffness[1]"), std::string::npos) << nd.description;
  EXPECT_TRUE(nd.best_to_fix == "mass[1]" || nd.best_to_fix == "stiffness[1]")
      << nd.best_to_fix;
  EXPECT_FALSE(id.warnings.empty());
}

// The overload that reuses the caller's column-scaled SVD (as LstsqSolver does)
// reports what the one that factorises itself does, on the common-scaling
// example above with a zero column added.
TEST(AnalyseIdentifiability, FromTheCallersSvdSameAnalysis) {
  Eigen::MatrixXd a(5, 4);
  // clang-format off
  a << -2.0,  2.0, 1.0, 0.0,
       -1.0,  1.0, 0.0, 0.0,
        3.0, -3.0, 2.0, 0.0,
        0.5, -0.5, 1.0, 0.0,
        1.0, -1.0, 4.0, 0.0;
  // clang-format on
  const std::vector<std::string> names = {"mass[1]", "stiffness[1]", "added_mass[1]",
                                          "mass[2]"};
  const std::vector<std::string> groups = {"mass", "stiffness", "added_mass", "mass"};
  for (const bool scale_columns : {true, false}) {
    const Eigen::VectorXd scale = IdentifiabilityScale(a, scale_columns);
    for (int j = 0; j < 3; ++j)
      EXPECT_DOUBLE_EQ(scale[j], scale_columns ? a.col(j).norm() : 1.0);
    EXPECT_EQ(scale[3], 1.0);  // a zero column keeps scale 1
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(a * scale.cwiseInverse().asDiagonal(),
                                             Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Identifiability own =
        AnalyseIdentifiability(a, names, groups, 1e-10, scale_columns);
    const Identifiability given =
        AnalyseIdentifiability(a, svd, names, groups, 1e-10, scale_columns);
    EXPECT_EQ(given.rank, 2);
    EXPECT_EQ(given.rank, own.rank);
    EXPECT_LE((given.singular_values - own.singular_values).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_EQ(given.unseen, own.unseen);
    EXPECT_EQ(given.warnings.size(), own.warnings.size());
    ASSERT_EQ(given.null_directions.size(), own.null_directions.size());
    // The null space is two-dimensional (the common scaling and the zero
    // column): compare the spans, not the basis vectors.
    const Eigen::Index dims = static_cast<Eigen::Index>(own.null_directions.size());
    Eigen::MatrixXd p_own(4, dims), p_given(4, dims);
    for (Eigen::Index q = 0; q < dims; ++q) {
      p_own.col(q) = own.null_directions[static_cast<std::size_t>(q)].coefficients;
      p_given.col(q) = given.null_directions[static_cast<std::size_t>(q)].coefficients;
    }
    const Eigen::MatrixXd projector =
        p_own * p_own.completeOrthogonalDecomposition().pseudoInverse();
    EXPECT_LE((projector * p_given - p_given).norm(), 1e-12);
  }
  // An SVD without V, or of another width, is refused by name.
  const Eigen::BDCSVD<Eigen::MatrixXd> values_only(a);
  EXPECT_THROW(AnalyseIdentifiability(a, values_only, names, groups, 1e-10), InputError);
  const Eigen::BDCSVD<Eigen::MatrixXd> narrow(a.leftCols(3), Eigen::ComputeThinV);
  EXPECT_THROW(AnalyseIdentifiability(a, narrow, names, groups, 1e-10), InputError);
}

TEST(AnalyseIdentifiability, OppositeSignsAreNotCommonScaling) {
  Eigen::MatrixXd a(3, 2);
  a << 1.0, 1.0, 2.0, 2.0, -1.0, -1.0;  // only m + s is seen: null (1, -1)
  const Identifiability id = AnalyseIdentifiability(a, {"mass[1]", "stiffness[1]"},
                                                    {"mass", "stiffness"}, 1e-10);
  EXPECT_EQ(id.rank, 1);
  ASSERT_EQ(id.null_directions.size(), 1u);
  const NullDirection& nd = id.null_directions[0];
  EXPECT_FALSE(nd.common_scaling) << nd.description;
  EXPECT_NEAR(std::abs(nd.coefficients[0]), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(nd.coefficients[0], -nd.coefficients[1], 1e-12);
  EXPECT_NE(nd.description.find("mass[1]"), std::string::npos) << nd.description;
  EXPECT_NE(nd.description.find("stiffness[1]"), std::string::npos) << nd.description;
}

TEST(AnalyseIdentifiability, NullDirectionInUnknownUnits) {
  // Columns of very different norm: the direction is reported in the
  // unknowns' own units, so A v = 0 holds for it.
  Eigen::MatrixXd a(3, 2);
  a << 1e6, -1.0, 2e6, -2.0, 3e6, -3.0;  // null vector (1, 1e6)
  const Identifiability id = AnalyseIdentifiability(a, {}, {}, 1e-10);
  ASSERT_EQ(id.null_directions.size(), 1u);
  const Eigen::VectorXd v = id.null_directions[0].coefficients;
  EXPECT_NEAR(v.norm(), 1.0, 1e-14);
  EXPECT_LE((a * v).norm(), 1e-9 * a.norm());
  EXPECT_EQ(id.null_directions[0].best_to_fix, "x2");  // default names
}

TEST(AnalyseIdentifiability, FullRankSingularValuesAndConditionNumbers) {
  const Eigen::MatrixXd a = RandomMatrix(8, 3, 14);
  const Identifiability id = AnalyseIdentifiability(a, {}, {}, 1e-10);
  EXPECT_EQ(id.rank, 3);
  EXPECT_TRUE(id.null_directions.empty());
  EXPECT_TRUE(id.unseen.empty());
  const Eigen::MatrixXd as = a * a.colwise().norm().cwiseInverse().asDiagonal();
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(as).singularValues();
  EXPECT_LE((id.singular_values - s).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(id.condition_number, s[0] / s[2], 1e-12 * s[0] / s[2]);
  const Eigen::VectorXd raw = Eigen::JacobiSVD<Eigen::MatrixXd>(a).singularValues();
  EXPECT_NEAR(id.condition_number_unscaled, raw[0] / raw[2], 1e-12 * raw[0] / raw[2]);
  EXPECT_NEAR(id.tolerance, 1e-10 * s[0], 1e-24);
}

TEST(AnalyseIdentifiability, BadInputThrows) {
  EXPECT_THROW(AnalyseIdentifiability(Eigen::MatrixXd(3, 0), {}, {}, 1e-10), InputError);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Ones(2, 2);
  nan(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(AnalyseIdentifiability(nan, {}, {}, 1e-10), InputError);
  EXPECT_THROW(AnalyseIdentifiability(Eigen::MatrixXd::Ones(2, 2), {}, {}, 0.0),
               InputError);
  EXPECT_THROW(AnalyseIdentifiability(Eigen::MatrixXd::Ones(2, 2), {}, {}, 1.0),
               InputError);
}

}  // namespace
}  // namespace femup

namespace femup {
namespace {

// FullRankLeastSquares (lstsq.h): the least-squares answer of a full-rank
// problem, on its loop path (<= 32 columns) and on Eigen's QR (more), against
// the normal equations in long double; and every case it must hand back.
TEST(FullRankLeastSquares, MatchesLongDoubleNormalEquationsOnBothPaths) {
  for (const auto& [rows, cols] : {std::pair<int, int>{20, 12}, {33, 32}, {90, 40}}) {
    Eigen::MatrixXd a = RandomMatrix(rows, cols, 20261124u + rows);
    // Columns of very different sizes: the scaling must not change the answer.
    for (int j = 0; j < cols; ++j) a.col(j) *= std::pow(10.0, (j % 7) - 3);
    const Eigen::VectorXd b = RandomMatrix(rows, 1, 7u + rows).col(0);
    const Eigen::VectorXd expected = NormalEquations(a, b);
    FullRankLeastSquares solver(1e-10, true);
    Eigen::VectorXd z;
    ASSERT_TRUE(solver.Solve(a, b, &z)) << rows << " x " << cols;
    ASSERT_EQ(z.size(), cols);
    for (int j = 0; j < cols; ++j)
      EXPECT_NEAR(z[j], expected[j], 1e-10 * std::abs(expected[j])) << j;
    // Again with the same work space: the same answer.
    Eigen::VectorXd again;
    ASSERT_TRUE(solver.Solve(a, b, &again));
    EXPECT_EQ(again, z);
  }
}

TEST(FullRankLeastSquares, ReachesNistLongleyCertifiedDigits) {
  // Longley: unscaled condition number about 5e7; certified to 15 digits.
  const NistLinearDataset d =
      ReadNistLinear(std::string(FEMUP_TEST_DATA_DIR) + "/nist/linear/Longley.dat");
  const LinearProblem p = d.Problem();
  FullRankLeastSquares solver(1e-10, true);
  Eigen::VectorXd z;
  ASSERT_TRUE(solver.Solve(p.A, p.b, &z));
  double lre = 15;
  for (int j = 0; j < d.num_parameters(); ++j)
    lre = std::min(lre, LogRelativeError(static_cast<long double>(z[j]), d.certified[j]));
  EXPECT_GE(lre, 8.0);
  RecordProperty("Longley_digits", std::to_string(lre));
}

TEST(FullRankLeastSquares, HandsBackWhatItCannotProveFullRank) {
  const Eigen::MatrixXd a = RandomMatrix(10, 4, 3u);
  const Eigen::VectorXd b = RandomMatrix(10, 1, 4u).col(0);
  FullRankLeastSquares solver(1e-10, true);
  Eigen::VectorXd z;
  Eigen::MatrixXd repeated = a;
  repeated.col(3) = repeated.col(1);  // rank 3
  EXPECT_FALSE(solver.Solve(repeated, b, &z));
  Eigen::MatrixXd zero = a;
  zero.col(2).setZero();
  EXPECT_FALSE(solver.Solve(zero, b, &z));
  EXPECT_FALSE(solver.Solve(a.topRows(3), b.head(3), &z));  // fewer rows than columns
  EXPECT_FALSE(solver.Solve(a, b.head(9), &z));             // sizes disagree
  // Nearly dependent (a small step out of the span of the others): s_min /
  // s_max about 1e-12, below the tolerance 1e-10.
  Eigen::MatrixXd near = a;
  near.col(3) = a.col(1) + 1e-12 * RandomMatrix(10, 1, 99u).col(0);
  EXPECT_FALSE(solver.Solve(near, b, &z));
  // The same matrix passes a tolerance it meets (the proof allows for up to
  // k ||R||_F ||R^-1||_F / cond, here within 1e2).
  FullRankLeastSquares loose(1e-16, true);
  EXPECT_TRUE(loose.Solve(near, b, &z));
}

// The no-diagnostics lstsq goes through it and agrees with the SVD path.
TEST(FullRankLeastSquares, IsLstsqWithoutDiagnostics) {
  LinearProblem p;
  p.A = RandomMatrix(20, 12, 11u);
  p.b = RandomMatrix(20, 1, 12u).col(0);
  LinearSolverOptions lean;
  lean.diagnostics = false;
  const LinearSolution fast = CreateLinearSolver("lstsq", lean)->Solve(p);
  const LinearSolution full = CreateLinearSolver("lstsq")->Solve(p);
  EXPECT_NE(fast.summary.message.find("Householder QR"), std::string::npos)
      << fast.summary.message;
  for (int j = 0; j < 12; ++j)
    EXPECT_NEAR(fast.x[j], full.x[j], 1e-12 * (1 + std::abs(full.x[j]))) << j;
}

}  // namespace
}  // namespace femup
