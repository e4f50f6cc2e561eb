// The compressed (normal-equation) correction system
// (problems/normal_correction_system.h), checked against the dense stacked
// form of correction_system.h with every FEM mode, which weights the same
// physical residuals by M^-1: same normal matrix, same residual norm for any x
// (with the offset), same least-squares factors; and, on noise-free data, the
// preset factors themselves.
#include "femup/problems/normal_correction_system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "femup/core/errors.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/paper_chain.h"
#include "femup/solvers/linear_solver.h"
#include "structure_specs.h"

namespace femup {
namespace {

struct Case {
  ParametrisedModel model;
  Eigen::VectorXd truth;
  std::vector<ModalData> states;
};

Case Frame() {
  PlaneFrameSpec spec = fixtures::PlaneFrame(3, 2, 2);
  spec.blocks_per_storey = 2;
  spec.wet_storeys = 1;
  Case c{BuildPlaneFrame(spec), {}, {}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  c.truth = Eigen::VectorXd(c.model.num_parameters());
  for (Eigen::Index i = 0; i < c.truth.size(); ++i) c.truth[i] = u(rng);
  for (int k : c.model.ParametersOfKind(ParameterKind::kAddedMass)) c.truth[k] = 0.3;
  c.states = {PredictModes(c.model, c.truth, Immersion::kDry, 6, "air"),
              PredictModes(c.model, c.truth, Immersion::kWet, 6, "water")};
  return c;
}

Case Chain() {
  const PaperChainScenario s = PaperChain(3);
  return {s.model,
          s.preset,
          {PredictModes(s.model, s.preset, Immersion::kDry, 2, "air"),
           PredictModes(s.model, s.preset, Immersion::kWet, 3, "water")}};
}

TEST(NormalCorrectionSystem, SameLeastSquaresProblemAsTheStackedFormWithEveryFemMode) {
  for (const Case& c : {Chain(), Frame()}) {
    const Modes fem = SolveModes(c.model.stiffness(), c.model.mass());
    const LinearProblem dense = BuildCorrectionSystem(c.model, fem, c.states, {});
    NormalCorrectionStats stats;
    const LinearProblem compact = BuildNormalCorrectionSystem(c.model, c.states, &stats);
    ASSERT_EQ(compact.num_unknowns(), dense.num_unknowns());
    EXPECT_EQ(compact.num_rows(), dense.num_unknowns());
    EXPECT_EQ(compact.data_rows(), dense.num_rows());
    EXPECT_EQ(compact.names, dense.names);

    const Eigen::MatrixXd g = dense.A.transpose() * dense.A;
    EXPECT_LT((compact.A.transpose() * compact.A - g).cwiseAbs().maxCoeff(),
              1e-9 * g.cwiseAbs().maxCoeff());
    std::mt19937_64 rng(3);
    std::normal_distribution<double> normal(0.0, 0.1);
    for (int trial = 0; trial < 3; ++trial) {
      Eigen::VectorXd x(dense.num_unknowns());
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = normal(rng);
      const double full = (dense.A * x - dense.b).squaredNorm();
      const double reduced =
          (compact.A * x - compact.b).squaredNorm() + compact.residual_offset;
      EXPECT_NEAR(reduced, full, 1e-8 * full);
    }
    // Noise-free data: with one mass factor fixed (the common scaling), the
    // preset factors.
    LinearProblem fixed = compact;
    fixed.fixed = {{0, c.truth[0]}};
    const LinearSolution s = CreateLinearSolver("lstsq")->Solve(fixed);
    EXPECT_LT((s.x - c.truth).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_EQ(stats.dropped, 1);  // the common scaling
  }
}

// Data the factors cannot fit (the paper chain's modes, made with all its
// factors, for a model with its first two only): the offset carries the
// residual the compact form's rows cannot, so that its smallest residual,
// offset included, is the dense form's.
TEST(NormalCorrectionSystem, OffsetCarriesTheResidualOfInconsistentData) {
  const Case c = Chain();
  ParametrisedModel few(c.model.stiffness(), c.model.mass(), c.model.dof_labels());
  few.AddParameter(c.model.parameter(0));
  few.AddParameter(c.model.parameter(1));
  const Modes fem = SolveModes(few.stiffness(), few.mass());
  const LinearProblem dense = BuildCorrectionSystem(few, fem, c.states, {});
  const LinearProblem compact = BuildNormalCorrectionSystem(few, c.states);
  const Eigen::VectorXd x = dense.A.completeOrthogonalDecomposition().solve(dense.b);
  const double dense_min = (dense.A * x - dense.b).squaredNorm();
  ASSERT_GT(dense_min, 1e-6 * dense.b.squaredNorm());
  EXPECT_GT(compact.residual_offset, 0.0);
  const double compact_min =
      (compact.A * x - compact.b).squaredNorm() + compact.residual_offset;
  EXPECT_NEAR(compact_min, dense_min, 1e-8 * dense_min);
}

// A small 3D space frame (space_frame.h), every member wet: the sparse half
// solves of the Cholesky factor against the dense stacked form with every FEM
// mode.
TEST(NormalCorrectionSystem, SpaceFrameMatchesTheDenseStackedForm) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2);
  spec.water_depth = 15;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  ASSERT_LT(model.num_dofs(), 1000);
  Eigen::VectorXd truth(model.num_parameters());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (Eigen::Index i = 0; i < truth.size(); ++i) truth[i] = u(rng);
  for (int k : model.ParametersOfKind(ParameterKind::kAddedMass)) truth[k] = 0.4;
  const std::vector<ModalData> states = {
      PredictModes(model, truth, Immersion::kDry, 4, "air"),
      PredictModes(model, truth, Immersion::kWet, 4, "water")};
  const Modes fem = SolveModes(model.stiffness(), model.mass());
  const LinearProblem dense = BuildCorrectionSystem(model, fem, states, {});
  NormalCorrectionStats stats;
  const LinearProblem compact = BuildNormalCorrectionSystem(model, states, &stats);
  const Eigen::MatrixXd g = dense.A.transpose() * dense.A;
  EXPECT_LT((compact.A.transpose() * compact.A - g).cwiseAbs().maxCoeff(),
            1e-9 * g.cwiseAbs().maxCoeff());
  const Eigen::VectorXd h = dense.A.transpose() * dense.b;
  EXPECT_LT((compact.A.transpose() * compact.b - h).cwiseAbs().maxCoeff(),
            1e-9 * h.cwiseAbs().maxCoeff());
  const double full = dense.b.squaredNorm();
  EXPECT_NEAR(compact.b.squaredNorm() + compact.residual_offset, full, 1e-9 * full);
  EXPECT_GT(stats.nnz_l, 0);
  EXPECT_GE(stats.nnz_w, stats.nnz_z);
  EXPECT_GT(stats.nnz_z, 0);
  // Consistent data: no residual of rounding size.
  EXPECT_EQ(compact.residual_offset, 0.0);
}

// The half solves and G's products on threads: the same bits for 1 and 2
// threads and one per core; negative threads refused by name.
TEST(NormalCorrectionSystem, ThreadCountDoesNotChangeTheSystem) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 1, 1, 2);
  spec.water_depth = 15;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  Eigen::VectorXd truth = Eigen::VectorXd::Constant(model.num_parameters(), 0.05);
  const std::vector<ModalData> states = {
      PredictModes(model, truth, Immersion::kDry, 4, "air"),
      PredictModes(model, truth, Immersion::kWet, 4, "water")};
  const LinearProblem one = BuildNormalCorrectionSystem(model, states, nullptr, {1});
  for (const int threads : {2, 0}) {
    const LinearProblem other =
        BuildNormalCorrectionSystem(model, states, nullptr, {threads});
    EXPECT_EQ(other.A, one.A) << threads;
    EXPECT_EQ(other.b, one.b) << threads;
    EXPECT_EQ(other.residual_offset, one.residual_offset) << threads;
  }
  try {
    BuildNormalCorrectionSystem(model, states, nullptr, {-1});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "threads");
  }
}

TEST(NormalCorrectionSystem, CountsTheGramMatrixsFlopsFromTheBasesSupports) {
  // The chain's mass matrix is diagonal, so L^-1 P Z_j has Z_j's pattern: DOF
  // r's row holds one entry per factor entering the state whose basis touches
  // r, t_r of them, and G's lower triangle takes t_r (t_r + 1) / 2 products of
  // m-vectors (a multiplication and an addition per mode each).
  const Case c = Chain();
  double expected = 0;
  for (const ModalData& st : c.states) {
    std::vector<int> t(c.model.num_dofs(), 0);
    for (const Parameter& q : c.model.parameters()) {
      if (q.kind == ParameterKind::kAddedMass && st.immersion != Immersion::kWet)
        continue;
      for (int r : q.basis.dofs()) ++t[r];
    }
    for (int tr : t) expected += static_cast<double>(tr) * (tr + 1) * st.num_modes();
  }
  NormalCorrectionStats stats;
  BuildNormalCorrectionSystem(c.model, c.states, &stats);
  EXPECT_GT(expected, 0);
  EXPECT_EQ(stats.flops_gram, expected);
  EXPECT_EQ(stats.flops_factorise, static_cast<double>(c.model.num_dofs()));
}

TEST(NormalCorrectionSystem, MassThatIsNotPositiveDefiniteIsNamed) {
  const Case c = Chain();
  SparseMatrix mass = c.model.mass();
  mass.coeffRef(2, 2) = -mass.coeff(2, 2);
  ParametrisedModel broken(c.model.stiffness(), mass, c.model.dof_labels());
  for (const Parameter& q : c.model.parameters()) broken.AddParameter(q);
  try {
    BuildNormalCorrectionSystem(broken, c.states);
    ADD_FAILURE() << "an indefinite mass accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "model.mass");
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos)
        << e.what();
  }
}

// Shapes finite but too large to square: G overflows, and the error says so
// rather than returning a system of infinities.
TEST(NormalCorrectionSystem, NormalMatrixThatOverflowsIsNamed) {
  const Case c = Chain();
  std::vector<ModalData> huge = c.states;
  for (ModalData& st : huge) st.shapes *= 1e160;
  try {
    BuildNormalCorrectionSystem(c.model, huge);
    ADD_FAILURE() << "an overflowing system accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "measurements");
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
}

TEST(NormalCorrectionSystem, BadInputNamesTheField) {
  const Case c = Chain();
  EXPECT_THROW(BuildNormalCorrectionSystem(c.model, {}), InputError);
  std::vector<ModalData> partial = c.states;
  partial[0].sensor_dofs = {0, 1};
  partial[0].shapes = partial[0].shapes.topRows(2).eval();
  try {
    BuildNormalCorrectionSystem(c.model, partial);
    ADD_FAILURE() << "incomplete shapes accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("measurements.air"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace femup
