// Eigenvalue and eigenvector derivatives
// (core/include/femup/core/linalg/eigen_derivatives.h), checked against closed-form
// derivatives of a 2-dof system and a mass scaling, and against central finite
// differences of SolveModes on a chain and a cantilever.
#include "femup/core/linalg/eigen_derivatives.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/structure.h"
#include "femup/core/linalg/modal.h"
#include "paper_beam.h"

namespace femup {
namespace {

SparseMatrix Sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }

// K = [a b; b c], M = I, p = b. With R = sqrt(((a - c) / 2)^2 + b^2) and
// theta = atan2(2 b, a - c) / 2, the larger eigenvalue is (a + c) / 2 + R with
// eigenvector (cos theta, sin theta), the smaller (a + c) / 2 - R with
// (-sin theta, cos theta); dR/db = b / R, dtheta/db = (a - c) / ((a - c)^2 + 4 b^2).
TEST(EigenDerivatives, TwoDofClosedForm) {
  const double a = 5.0, b = 1.5, c = 2.0;
  Eigen::Matrix2d k;
  k << a, b, b, c;
  const SparseMatrix ks = Sparse(k), ms = Sparse(Eigen::Matrix2d::Identity());
  Eigen::Matrix2d dk;
  dk << 0, 1, 1, 0;
  const SparseMatrix dks = Sparse(dk);
  const double r = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double theta = 0.5 * std::atan2(2 * b, a - c);
  const double dr = b / r;
  const double dtheta = (a - c) / ((a - c) * (a - c) + 4 * b * b);

  const Eigen::Vector2d upper(std::cos(theta), std::sin(theta));
  const Eigen::Vector2d lower(-std::sin(theta), std::cos(theta));
  const double lambda_upper = 0.5 * (a + c) + r, lambda_lower = 0.5 * (a + c) - r;
  // (d/dtheta of each eigenvector) * dtheta/db.
  const Eigen::Vector2d dupper =
      dtheta * Eigen::Vector2d(-std::sin(theta), std::cos(theta));
  const Eigen::Vector2d dlower =
      dtheta * Eigen::Vector2d(-std::cos(theta), -std::sin(theta));

  const NelsonSolver su(ks, ms, lambda_upper, upper);
  ASSERT_TRUE(su.ok()) << su.message();
  const EigenpairDerivative du = su.Derivative(dks, SparseMatrix());
  EXPECT_NEAR(du.eigenvalue, dr, 1e-14);
  EXPECT_LT((du.eigenvector - dupper).norm(), 1e-14);

  const NelsonSolver sl(ks, ms, lambda_lower, lower);
  ASSERT_TRUE(sl.ok()) << sl.message();
  const EigenpairDerivative dl = sl.Derivative(dks, SparseMatrix());
  EXPECT_NEAR(dl.eigenvalue, -dr, 1e-14);
  EXPECT_LT((dl.eigenvector - dlower).norm(), 1e-14);
  EXPECT_NEAR(EigenvalueDerivative(lower, lambda_lower, dks, SparseMatrix()), -dr, 1e-14);
}

// M(p) = (1 + p) M0: lambda(p) = lambda0 / (1 + p), phi(p) = phi0 / sqrt(1 + p),
// so at p = 0 dlambda = -lambda0 and dphi = -phi0 / 2, for any pencil.
TEST(EigenDerivatives, MassScalingClosedForm) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  const int n = 6;
  Eigen::MatrixXd x(n, n), y(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      x(i, j) = g(rng);
      y(i, j) = g(rng);
    }
  }
  const SparseMatrix k = Sparse(x * x.transpose() + n * Eigen::MatrixXd::Identity(n, n));
  const SparseMatrix m =
      Sparse(0.2 * y * y.transpose() + Eigen::MatrixXd::Identity(n, n));
  const Modes modes = SolveModes(k, m);
  for (int j = 0; j < n; ++j) {
    const NelsonSolver solver(k, m, modes.eigenvalues[j], modes.shapes.col(j));
    ASSERT_TRUE(solver.ok()) << solver.message();
    const EigenpairDerivative d = solver.Derivative(SparseMatrix(), m);
    EXPECT_NEAR(d.eigenvalue, -modes.eigenvalues[j], 1e-12 * modes.eigenvalues[j]);
    EXPECT_LT((d.eigenvector + 0.5 * modes.shapes.col(j)).norm(), 1e-10) << "mode " << j;
  }
}

TEST(EigenDerivatives, SingleDof) {
  // K = [k], M = [m]: phi = 1 / sqrt(m); with dM = [1], dphi = -m^(-3/2) / 2.
  const double kk = 3.0, mm = 2.0;
  const SparseMatrix k = Sparse(Eigen::MatrixXd::Constant(1, 1, kk));
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Constant(1, 1, mm));
  const Eigen::VectorXd phi = Eigen::VectorXd::Constant(1, 1 / std::sqrt(mm));
  const Eigen::VectorXd dphi = EigenvectorDerivative(k, m, kk / mm, phi, SparseMatrix(),
                                                     Sparse(Eigen::MatrixXd::Ones(1, 1)));
  EXPECT_NEAR(dphi[0], -0.5 * std::pow(mm, -1.5), 1e-15);
}

// Errors relative to the largest derivative of the same mode over parameters (a
// parameter that barely moves a mode is compared on that mode's scale).
struct FdAgreement {
  double eigenvalue = 0;     // max_p |fd - analytic dlambda_p| / max_p |dlambda_p|
  double eigenvector = 0;    // max_p ||fd - analytic dphi_p|| / max_p ||dphi_p||
  double normalisation = 0;  // max |2 phi' M dphi + phi' dM phi|
};

// Compares Nelson derivatives with extrapolated central differences (steps h
// and h/2) of SolveModes, for every parameter of `model` and the lowest
// `num_modes` modes of the wet (or dry) pencil at factors d.
FdAgreement CompareWithFiniteDifferences(const ParametrisedModel& model,
                                         const Eigen::VectorXd& d, bool wet,
                                         int num_modes, double h) {
  auto pencil = [&](const Eigen::VectorXd& f, SparseMatrix* k, SparseMatrix* m) {
    *k = model.UpdatedStiffness(f);
    *m = wet ? model.UpdatedWetMass(f) : model.UpdatedDryMass(f);
  };
  SparseMatrix k, m;
  pencil(d, &k, &m);
  const Modes modes = SolveModes(k, m);
  FdAgreement worst;
  for (int j = 0; j < num_modes; ++j) {
    const Eigen::VectorXd phi = modes.shapes.col(j);
    const NelsonSolver solver(k, m, modes.eigenvalues[j], phi);
    EXPECT_TRUE(solver.ok()) << solver.message();
    std::vector<EigenpairDerivative> analytic;
    std::vector<Eigen::VectorXd> fd_vec;
    std::vector<double> fd_val;
    double mode_scale = 0;    // largest ||dphi|| over parameters, for this mode
    double lambda_scale = 0;  // largest |dlambda| over parameters, for this mode
    for (int p = 0; p < model.num_parameters(); ++p) {
      const Parameter& par = model.parameter(p);
      const bool in_k = par.kind == ParameterKind::kStiffness;
      const bool in_m = par.kind == ParameterKind::kMass ||
                        (par.kind == ParameterKind::kAddedMass && wet);
      const SparseMatrix none;
      const SparseMatrix basis = par.basis.ToSparse();
      analytic.push_back(solver.Derivative(in_k ? basis : none, in_m ? basis : none));
      // The overload that takes the model's basis as it is held: the same answer.
      const EigenpairDerivative held =
          solver.Derivative(in_k ? &par.basis : nullptr, in_m ? &par.basis : nullptr);
      EXPECT_NEAR(held.eigenvalue, analytic.back().eigenvalue,
                  1e-12 * std::abs(analytic.back().eigenvalue) + 1e-300);
      EXPECT_LE((held.eigenvector - analytic.back().eigenvector).norm(),
                1e-10 * analytic.back().eigenvector.norm() + 1e-300);
      EXPECT_NEAR(
          EigenvalueDerivative(phi, modes.eigenvalues[j], in_k ? &par.basis : nullptr,
                               in_m ? &par.basis : nullptr),
          analytic.back().eigenvalue,
          1e-12 * std::abs(analytic.back().eigenvalue) + 1e-300);
      mode_scale = std::max(mode_scale, analytic.back().eigenvector.norm());
      lambda_scale = std::max(lambda_scale, std::abs(analytic.back().eigenvalue));
      // Central differences with steps h and h/2, combined by Richardson
      // extrapolation: error O(h^4), so a step large enough to keep the
      // eigensolver's rounding small (it grows as 1/h) still gives an accurate
      // reference.
      Eigen::VectorXd dphi[2];
      double dlambda[2];
      for (int level = 0; level < 2; ++level) {
        const double step = level == 0 ? h : h / 2;
        Eigen::VectorXd shifted[2];
        double lambdas[2];
        for (int side = 0; side < 2; ++side) {
          Eigen::VectorXd f = d;
          f[p] += side == 0 ? step : -step;
          SparseMatrix kf, mf;
          pencil(f, &kf, &mf);
          const Modes mf_modes = SolveModes(kf, mf);
          shifted[side] = mf_modes.shapes.col(j);
          // Same sign as the nominal eigenvector.
          if (shifted[side].dot(m * phi) < 0) shifted[side] *= -1;
          lambdas[side] = mf_modes.eigenvalues[j];
        }
        dphi[level] = (shifted[0] - shifted[1]) / (2 * step);
        dlambda[level] = (lambdas[0] - lambdas[1]) / (2 * step);
      }
      fd_vec.push_back((4 * dphi[1] - dphi[0]) / 3);
      fd_val.push_back((4 * dlambda[1] - dlambda[0]) / 3);

      const double norm_change = 2 * phi.dot(m * analytic.back().eigenvector) +
                                 (in_m ? phi.dot(basis * phi) : 0.0);
      worst.normalisation = std::max(worst.normalisation, std::abs(norm_change));
    }
    for (int p = 0; p < model.num_parameters(); ++p) {
      worst.eigenvalue = std::max(
          worst.eigenvalue, std::abs(fd_val[p] - analytic[p].eigenvalue) / lambda_scale);
      worst.eigenvector = std::max(
          worst.eigenvector, (fd_vec[p] - analytic[p].eigenvector).norm() / mode_scale);
    }
  }
  return worst;
}

TEST(EigenDerivatives, ChainMatchesFiniteDifferences) {
  ChainSpec spec;
  spec.masses = {50, 45, 60, 50, 40};
  spec.springs = {2.9e7, 2.5e7, 3.1e7, 2.9e7, 2.2e7};
  spec.wet = {true, true, true, false, false};
  const ParametrisedModel model =
      BuildModel(BuildSpringMassChain(spec), PaperParameterPlan());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.1, 0.2);
  Eigen::VectorXd d(model.num_parameters());
  for (int i = 0; i < d.size(); ++i) d[i] = u(rng);
  for (bool wet : {false, true}) {
    const FdAgreement a = CompareWithFiniteDifferences(model, d, wet, 5, 1e-3);
    // Measured: about 2e-11 and 6e-12.
    EXPECT_LT(a.eigenvalue, 1e-9) << (wet ? "wet" : "dry");
    EXPECT_LT(a.eigenvector, 1e-9) << (wet ? "wet" : "dry");
    EXPECT_LT(a.normalisation, 1e-14) << (wet ? "wet" : "dry");
  }
}

TEST(EigenDerivatives, CantileverMatchesFiniteDifferences) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(1.9, 10));
  spec.water_depth = 1.5;
  spec.added_mass_basis = AddedMassBasis::kTransverse;
  const ParametrisedModel model = BuildModel(BuildCantilever(spec), PaperParameterPlan());
  ASSERT_EQ(model.num_dofs(), 30);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.15);
  Eigen::VectorXd d(model.num_parameters());
  for (int i = 0; i < d.size(); ++i) d[i] = u(rng);
  // The eigensolver's rounding on this stiff pencil (axial and bending DOFs)
  // grows as 1/h in the differences: h = 0.02 balances it against O(h^4).
  const FdAgreement a = CompareWithFiniteDifferences(model, d, true, 6, 2e-2);
  EXPECT_LT(a.eigenvalue, 1e-6);   // measured: 7.5e-8
  EXPECT_LT(a.eigenvector, 1e-6);  // measured: 2.4e-8
  EXPECT_LT(a.normalisation, 1e-12);
}

TEST(EigenDerivatives, RepeatedEigenvalueIsReportedNotFactorised) {
  const SparseMatrix eye = Sparse(Eigen::MatrixXd::Identity(2, 2));
  const Eigen::VectorXd phi = Eigen::Vector2d(1, 0);
  const NelsonSolver solver(eye, eye, 1.0, phi);
  EXPECT_FALSE(solver.ok());
  EXPECT_NE(solver.message().find("singular"), std::string::npos) << solver.message();
  EXPECT_THROW(solver.Derivative(eye, SparseMatrix()), InputError);
  EXPECT_THROW(EigenvectorDerivative(eye, eye, 1.0, phi, eye, SparseMatrix()),
               InputError);
}

// The reduced matrix is factorised as L D L' (no pivoting) where that is
// accurate: on a cantilever it is, and the derivative agrees with an LU solve
// of the same reduced system.
TEST(EigenDerivatives, SymmetricFactorIsUsedWhereItIsAccurate) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(1.9, 10));
  spec.water_depth = 1.5;
  const ParametrisedModel model = BuildModel(BuildCantilever(spec), PaperParameterPlan());
  const SparseMatrix k = model.stiffness(), m = model.mass();
  const Modes modes = SolveModes(k, m);
  int p = 0;
  while (model.parameter(p).kind != ParameterKind::kStiffness) ++p;
  const SparseMatrix dk = model.parameter(p).basis.ToSparse();
  for (int j : {0, 3}) {
    const Eigen::VectorXd phi = modes.shapes.col(j);
    const double lambda = modes.eigenvalues[j];
    const NelsonSolver solver(k, m, lambda, phi);
    ASSERT_TRUE(solver.ok()) << solver.message();
    EXPECT_FALSE(solver.uses_lu()) << "mode " << j + 1;
    // The same derivative from a dense solve of the bordered system
    // [K - lambda M, M phi; phi' M, 0] [v; mu] = [f; -0.5 phi' dM phi]
    // (Lee and Jung's algebraic method), an independent formulation.
    const Eigen::Index n = phi.size();
    const Eigen::MatrixXd a = Eigen::MatrixXd(k) - lambda * Eigen::MatrixXd(m);
    const Eigen::VectorXd mphi = m * phi;
    const double dlambda = phi.dot(dk * phi);
    Eigen::MatrixXd bordered = Eigen::MatrixXd::Zero(n + 1, n + 1);
    bordered.topLeftCorner(n, n) = a;
    bordered.topRightCorner(n, 1) = -mphi;
    bordered.bottomLeftCorner(1, n) = -mphi.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
    rhs.head(n) = -(dk * phi) + dlambda * mphi;
    const Eigen::VectorXd dense = bordered.fullPivLu().solve(rhs).head(n);
    const EigenpairDerivative d = solver.Derivative(dk, SparseMatrix());
    EXPECT_NEAR(d.eigenvalue, dlambda, 1e-12 * std::abs(dlambda));
    EXPECT_LT((d.eigenvector - dense).norm(), 1e-8 * dense.norm()) << "mode " << j + 1;
  }
}

// Where L D L' meets a zero pivot (it does not pivot), the reduced matrix is
// factorised by LU instead, and the derivative is still exact.
TEST(EigenDerivatives, ZeroPivotFallsBackToLu) {
  // K - 2 I = [0 0 0; 0 0 1; 0 1 0]: phi = e1 (lambda = 2), and the reduced
  // matrix [0 1; 1 0] has a zero first pivot in any symmetric order.
  Eigen::MatrixXd kd = 2 * Eigen::MatrixXd::Identity(3, 3);
  kd(1, 2) = kd(2, 1) = 1;
  const SparseMatrix k = Sparse(kd);
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Identity(3, 3));
  const Eigen::VectorXd phi = Eigen::Vector3d(1, 0, 0);
  const NelsonSolver solver(k, m, 2.0, phi);
  ASSERT_TRUE(solver.ok()) << solver.message();
  EXPECT_TRUE(solver.uses_lu());
  Eigen::MatrixXd dkd = Eigen::MatrixXd::Zero(3, 3);
  dkd(0, 1) = dkd(1, 0) = 3;
  dkd(0, 2) = dkd(2, 0) = 5;
  const EigenpairDerivative d = solver.Derivative(Sparse(dkd), SparseMatrix());
  // dlambda = phi' dK phi = 0; f = -dK phi = (0, -3, -5); [0 1; 1 0] v = f
  // gives v = (0, -5, -3); c = -phi' v = 0.
  EXPECT_NEAR(d.eigenvalue, 0.0, 1e-15);
  EXPECT_LT((d.eigenvector - Eigen::Vector3d(0, -5, -3)).norm(), 1e-14);
}

// A repeated eigenvalue: K = diag(1, 1, 4), M = I; lambda = 1 has the
// eigenspace {e1, e2}, and any phi = (cos t, sin t, 0) is an eigenvector. dK
// couples the eigenspace with e3 only, so to first order every phi stays an
// eigenvector and moves by v3 e3 with 3 v3 = -(dK phi)_3 (the closed form).
TEST(EigenDerivatives, RepeatedEigenvalueWithItsEigenspace) {
  const SparseMatrix k = Sparse(Eigen::Vector3d(1, 1, 4).asDiagonal().toDenseMatrix());
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Identity(3, 3));
  Eigen::MatrixXd cluster = Eigen::MatrixXd::Zero(3, 2);
  cluster(0, 0) = cluster(1, 1) = 1;
  Eigen::MatrixXd dkd = Eigen::MatrixXd::Zero(3, 3);
  dkd(0, 2) = dkd(2, 0) = 2;
  dkd(1, 2) = dkd(2, 1) = -5;
  const SparseMatrix dk = Sparse(dkd);
  for (double t : {0.0, 0.3, 1.2}) {
    const Eigen::Vector3d phi(std::cos(t), std::sin(t), 0);
    EXPECT_FALSE(NelsonSolver(k, m, 1.0, phi).ok()) << "one row removed is singular";
    const NelsonSolver solver(k, m, 1.0, phi, cluster);
    ASSERT_TRUE(solver.ok()) << solver.message();
    const EigenpairDerivative d = solver.Derivative(dk, SparseMatrix());
    EXPECT_NEAR(d.eigenvalue, 0.0, 1e-15);
    const double v3 = -(2 * std::cos(t) - 5 * std::sin(t)) / 3;
    EXPECT_LT((d.eigenvector - Eigen::Vector3d(0, 0, v3)).norm(), 1e-14) << t;
    // A mass change keeps phi' M phi = 1: -0.5 phi' dM phi phi inside.
    const SparseMatrix dm = Sparse(Eigen::MatrixXd::Identity(3, 3));
    const EigenpairDerivative dmass = solver.Derivative(SparseMatrix(), dm);
    EXPECT_NEAR(dmass.eigenvalue, -1.0, 1e-15);  // -lambda phi' dM phi
    EXPECT_LT((dmass.eigenvector + 0.5 * phi).norm(), 1e-14) << t;
  }
  // With a one-column "eigenspace" the solver is Nelson's own.
  const Eigen::Vector3d e3(0, 0, 1);
  const EigenpairDerivative a =
      NelsonSolver(k, m, 4.0, e3).Derivative(dk, SparseMatrix());
  const EigenpairDerivative b =
      NelsonSolver(k, m, 4.0, e3, Eigen::MatrixXd(e3)).Derivative(dk, SparseMatrix());
  EXPECT_GT(a.eigenvector.norm(), 1.0);
  EXPECT_LT((a.eigenvector - b.eigenvector).norm(), 1e-15);
  // Bad eigenspaces.
  EXPECT_THROW(NelsonSolver(k, m, 1.0, Eigen::Vector3d(1, 0, 0), 2 * cluster), InputError)
      << "not M-orthonormal";
  EXPECT_THROW(NelsonSolver(k, m, 4.0, Eigen::Vector3d(0, 0, 1), cluster), InputError)
      << "phi outside";
  EXPECT_THROW(NelsonSolver(k, m, 1.0, Eigen::Vector3d(1, 0, 0), Eigen::MatrixXd(2, 2)),
               InputError);
}

TEST(EigenDerivatives, BadInputThrows) {
  const SparseMatrix k = Sparse(Eigen::Vector2d(1, 4).asDiagonal().toDenseMatrix());
  const SparseMatrix m = Sparse(Eigen::MatrixXd::Identity(2, 2));
  const Eigen::VectorXd phi = Eigen::Vector2d(1, 0);
  const SparseMatrix wrong = Sparse(Eigen::MatrixXd::Identity(3, 3));
  EXPECT_THROW(NelsonSolver(k, m, 1.0, Eigen::Vector2d(2, 0)), InputError)
      << "not mass-normalised";
  EXPECT_THROW(NelsonSolver(wrong, m, 1.0, phi), InputError);
  EXPECT_THROW(NelsonSolver(k, m, 1.0, Eigen::VectorXd()), InputError);
  EXPECT_THROW(EigenvalueDerivative(phi, 1.0, wrong, SparseMatrix()), InputError);
  const NelsonSolver solver(k, m, 1.0, phi);
  ASSERT_TRUE(solver.ok());
  EXPECT_THROW(solver.Derivative(SparseMatrix(), wrong), InputError);
}

}  // namespace
}  // namespace femup
