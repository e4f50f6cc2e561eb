// The linear correction-factor equations Z d = F
// (problems/include/femup/problems/correction_system.h), checked entry by entry
// against the formulas of method.md section 2 evaluated here with dense
// matrices, and by the residual of the exact factors.
#include "femup/problems/correction_system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "enum_names.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/structure.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/paper_chain.h"
#include "paper_beam.h"

namespace femup {
namespace {

struct PaperSetup {
  PaperChainScenario s = PaperChain(3);
  Modes fem;
  ModalData air, water;
  PaperSetup() {
    fem = SolveModes(s.model.stiffness(), s.model.mass());
    air = PredictModes(s.model, s.preset, Immersion::kDry, 2, "air");
    water = PredictModes(s.model, s.preset, Immersion::kWet, 2, "water");
  }
};

// Expected stacked row for FEM mode i and measured pair (lambda, phi), from
// method.md: mass -lambda Phi_i' M_a phi, stiffness Phi_i' K_b phi, added mass
// -lambda Phi_i' Mw phi (wet only); right-hand side -(Phi_i' K phi - lambda
// Phi_i' M phi).
void ExpectedRow(const ParametrisedModel& model, const Eigen::VectorXd& fem_i,
                 double lambda, const Eigen::VectorXd& phi, bool wet,
                 Eigen::RowVectorXd* z, double* f) {
  z->resize(model.num_parameters());
  for (int k = 0; k < model.num_parameters(); ++k) {
    const Parameter& p = model.parameter(k);
    const Eigen::MatrixXd basis(p.basis.ToSparse());
    const double proj = fem_i.dot(basis * phi);
    switch (p.kind) {
      case ParameterKind::kMass:
        (*z)[k] = -lambda * proj;
        break;
      case ParameterKind::kStiffness:
        (*z)[k] = proj;
        break;
      case ParameterKind::kAddedMass:
        (*z)[k] = wet ? -lambda * proj : 0.0;
        break;
    }
  }
  const Eigen::MatrixXd k(model.stiffness()), m(model.mass());
  *f = -(fem_i.dot(k * phi) - lambda * fem_i.dot(m * phi));
}

// For each row r = j * 5 + i of the stacked system of `state` alone (its modes
// j = 0, 1 against FEM modes i = 0..4), calls check(r, i, j, z, f) with
// ExpectedRow's row z and right-hand side f.
template <typename Check>
void ForEachExpectedRow(const PaperSetup& ps, const ModalData& state, bool wet,
                        Check check) {
  const Eigen::VectorXd lambdas = state.Eigenvalues();
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 5; ++i) {
      Eigen::RowVectorXd z;
      double f = 0;
      ExpectedRow(ps.s.model, ps.fem.shapes.col(i), lambdas[j], state.shapes.col(j), wet,
                  &z, &f);
      check(j * 5 + i, i, j, z, f);
    }
  }
}

double RelativeResidual(const LinearProblem& p, const Eigen::VectorXd& d) {
  return (p.A * d - p.b).norm() / p.b.norm();
}

TEST(CorrectionSystem, StackedAirOnly) {
  const PaperSetup ps;
  CorrectionSystemOptions options;
  const LinearProblem p = BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air}, options);
  ASSERT_EQ(p.num_rows(), 5 * 2);
  ASSERT_EQ(p.num_unknowns(), 13);
  EXPECT_EQ(p.b.size(), 10);
  EXPECT_EQ(p.row_labels.size(), 10u);
  EXPECT_EQ(p.names, ps.s.model.ParameterNames());
  ASSERT_EQ(p.groups.size(), 13u);
  EXPECT_EQ(p.groups[0], "mass");
  EXPECT_EQ(p.groups[5], "stiffness");
  EXPECT_EQ(p.groups[10], "added_mass");
  EXPECT_EQ(p.A.rightCols(3).cwiseAbs().maxCoeff(), 0.0) << "no added mass in air";
  ForEachExpectedRow(
      ps, ps.air, false, [&](int r, int i, int j, const Eigen::RowVectorXd& z, double f) {
        EXPECT_LE((p.A.row(r) - z).cwiseAbs().maxCoeff(), 1e-12 * z.cwiseAbs().maxCoeff())
            << p.row_labels[r];
        EXPECT_NEAR(p.b[r], f, 1e-9 * z.cwiseAbs().maxCoeff()) << p.row_labels[r];
        EXPECT_NE(p.row_labels[r].find("air mode " + std::to_string(j + 1)),
                  std::string::npos)
            << p.row_labels[r];
        EXPECT_NE(p.row_labels[r].find("FEM mode " + std::to_string(i + 1)),
                  std::string::npos)
            << p.row_labels[r];
      });
}

TEST(CorrectionSystem, StackedWaterOnly) {
  const PaperSetup ps;
  const LinearProblem p = BuildCorrectionSystem(ps.s.model, ps.fem, {ps.water}, {});
  ASSERT_EQ(p.num_rows(), 10);
  for (int c = 10; c < 13; ++c) {
    EXPECT_GT(p.A.col(c).cwiseAbs().maxCoeff(), 0.0) << p.names[c];
  }
  ForEachExpectedRow(ps, ps.water, true,
                     [&](int r, int, int, const Eigen::RowVectorXd& z, double f) {
                       EXPECT_LE((p.A.row(r) - z).cwiseAbs().maxCoeff(),
                                 1e-12 * z.cwiseAbs().maxCoeff());
                       EXPECT_NEAR(p.b[r], f, 1e-9 * z.cwiseAbs().maxCoeff());
                     });
}

TEST(CorrectionSystem, SummedIsAirRowPlusWaterRow) {
  const PaperSetup ps;
  const LinearProblem stacked =
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, {});
  CorrectionSystemOptions options;
  options.form = SystemForm::kSummed;
  // The order of the states does not matter to the summed form.
  const LinearProblem summed =
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.water, ps.air}, options);
  const int nf = 5, na = 2, nw = 2;
  ASSERT_EQ(stacked.num_rows(), nf * (na + nw));
  ASSERT_EQ(summed.num_rows(), nf * na * nw);
  ASSERT_EQ(summed.row_labels.size(), 20u);
  const double scale = stacked.A.cwiseAbs().maxCoeff();
  for (int i = 0; i < nf; ++i) {
    for (int j = 0; j < na; ++j) {
      for (int p = 0; p < nw; ++p) {
        const int r = (i * na + j) * nw + p;
        const int air_row = j * nf + i;
        const int water_row = na * nf + p * nf + i;
        const Eigen::RowVectorXd expected =
            stacked.A.row(air_row) + stacked.A.row(water_row);
        EXPECT_LE((summed.A.row(r) - expected).cwiseAbs().maxCoeff(), 1e-14 * scale)
            << summed.row_labels[r];
        EXPECT_NEAR(summed.b[r], stacked.b[air_row] + stacked.b[water_row],
                    1e-14 * stacked.b.cwiseAbs().maxCoeff());
      }
    }
  }
  // method.md's closed form of one entry: A_ijp = -Phi_i' M_a (lam_j phi_j +
  // lamw_p phiw_p) for mass factor a = mass[2], i = 3, j = 1, p = 2.
  const Eigen::MatrixXd m2(ps.s.model.parameter(1).basis.ToSparse());
  const Eigen::VectorXd combo = ps.air.Eigenvalues()[0] * ps.air.shapes.col(0) +
                                ps.water.Eigenvalues()[1] * ps.water.shapes.col(1);
  const double a = -ps.fem.shapes.col(2).dot(m2 * combo);
  EXPECT_NEAR(summed.A((2 * na + 0) * nw + 1, 1), a, 1e-12 * std::abs(a));
}

TEST(CorrectionSystem, FewerFemModesGiveFewerRows) {
  const PaperSetup ps;
  CorrectionSystemOptions options;
  options.num_fem_modes = 3;
  const LinearProblem all =
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, {});
  const LinearProblem stacked =
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, options);
  ASSERT_EQ(stacked.num_rows(), 3 * 4);
  // Each measured mode keeps its rows for FEM modes 1..3.
  for (int block = 0; block < 4; ++block) {
    EXPECT_EQ(stacked.A.middleRows(block * 3, 3), all.A.middleRows(block * 5, 3));
    EXPECT_EQ(stacked.b.segment(block * 3, 3), all.b.segment(block * 5, 3));
  }
  options.form = SystemForm::kSummed;
  EXPECT_EQ(
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, options).num_rows(),
      3 * 2 * 2);
  options.num_fem_modes = 1;
  EXPECT_EQ(
      BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, options).num_rows(),
      4);

  options.num_fem_modes = 6;
  EXPECT_THROW(BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air}, options), InputError);
  options.num_fem_modes = 0;
  EXPECT_THROW(BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air}, options), InputError);
}

std::string WhatOfBuild(const PaperSetup& ps, const std::vector<ModalData>& states,
                        const CorrectionSystemOptions& options) {
  try {
    BuildCorrectionSystem(ps.s.model, ps.fem, states, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(CorrectionSystem, SummedFormNeedsOneDryAndOneWetState) {
  const PaperSetup ps;
  CorrectionSystemOptions options;
  options.form = SystemForm::kSummed;
  const std::string air_only = WhatOfBuild(ps, {ps.air}, options);
  EXPECT_NE(air_only.find("stacked"), std::string::npos) << air_only;
  const std::string water_only = WhatOfBuild(ps, {ps.water}, options);
  EXPECT_NE(water_only.find("stacked"), std::string::npos) << water_only;
  ModalData air2 = ps.air;
  air2.state = "air2";
  const std::string two_dry = WhatOfBuild(ps, {ps.air, air2, ps.water}, options);
  EXPECT_NE(two_dry.find("stacked"), std::string::npos) << two_dry;
  // The stacked form takes any number of states.
  options.form = SystemForm::kStacked;
  EXPECT_EQ(WhatOfBuild(ps, {ps.air, air2, ps.water}, options), "(no exception)");
}

TEST(CorrectionSystem, BadInputsThrow) {
  const PaperSetup ps;
  const CorrectionSystemOptions options;
  ModalData incomplete = ps.air;
  incomplete.shapes = ps.air.shapes.topRows(3);
  incomplete.sensor_dofs = {0, 1, 2};
  const std::string what = WhatOfBuild(ps, {incomplete}, options);
  EXPECT_NE(what.find("measurements.air"), std::string::npos) << what;
  EXPECT_NE(what.find("3 of the model's 5 DOFs"), std::string::npos) << what;

  ModalData no_shapes = ps.air;
  no_shapes.shapes.resize(0, 0);
  EXPECT_NE(WhatOfBuild(ps, {no_shapes}, options), "(no exception)");
  EXPECT_NE(WhatOfBuild(ps, {}, options), "(no exception)");

  Modes short_fem = ps.fem;
  short_fem.shapes = ps.fem.shapes.topRows(4);
  EXPECT_THROW(BuildCorrectionSystem(ps.s.model, short_fem, {ps.air}, options),
               InputError);
}

TEST(CorrectionSystem, PaperPresetSatisfiesBothForms) {
  const PaperSetup ps;
  for (SystemForm form : {SystemForm::kStacked, SystemForm::kSummed}) {
    CorrectionSystemOptions options;
    options.form = form;
    const LinearProblem p =
        BuildCorrectionSystem(ps.s.model, ps.fem, {ps.air, ps.water}, options);
    EXPECT_EQ(p.num_rows(), 20);
    EXPECT_LE(RelativeResidual(p, ps.s.preset), 1e-10) << ToString(form);
    // The baseline factors (all zero) do not.
    EXPECT_GT(RelativeResidual(p, Eigen::VectorXd::Zero(13)), 0.5) << ToString(form);
  }
}

TEST(CorrectionSystem, CantileverExactFactorsSatisfyBothForms) {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(1.9, 10));
  spec.water_depth = 1.5;
  for (AddedMassBasis basis :
       {AddedMassBasis::kElementMass, AddedMassBasis::kTransverse}) {
    spec.added_mass_basis = basis;
    const Structure s = BuildCantilever(spec);
    const ParametrisedModel model = BuildModel(s, PaperParameterPlan());
    ASSERT_EQ(model.num_parameters(), 10 + 10 + 8);
    Eigen::VectorXd d(model.num_parameters());
    for (int k = 0; k < 10; ++k) {
      d[k] = 0.03 * std::sin(1.0 + k);        // mass
      d[10 + k] = -0.04 * std::cos(2.0 * k);  // stiffness
    }
    for (int w = 0; w < 8; ++w) d[20 + w] = 0.1 + 0.02 * w;  // added mass
    const Modes fem = SolveModes(model.stiffness(), model.mass());
    const std::vector<ModalData> states = {
        PredictModes(model, d, Immersion::kDry, 3, "air"),
        PredictModes(model, d, Immersion::kWet, 3, "water")};
    for (SystemForm form : {SystemForm::kStacked, SystemForm::kSummed}) {
      CorrectionSystemOptions options;
      options.form = form;
      const LinearProblem p = BuildCorrectionSystem(model, fem, states, options);
      EXPECT_EQ(p.num_rows(), form == SystemForm::kStacked ? 30 * 6 : 30 * 9);
      EXPECT_LE(RelativeResidual(p, d), 1e-10)
          << ToString(form) << ", basis " << ToString(basis);
    }
  }
}

TEST(CorrectionSystem, WithoutRowLabelsTheSameSystem) {
  const PaperSetup setup;
  for (SystemForm form : {SystemForm::kStacked, SystemForm::kSummed}) {
    CorrectionSystemOptions options;
    options.form = form;
    const LinearProblem with = BuildCorrectionSystem(setup.s.model, setup.fem,
                                                     {setup.air, setup.water}, options);
    options.row_labels = false;
    const LinearProblem without = BuildCorrectionSystem(
        setup.s.model, setup.fem, {setup.air, setup.water}, options);
    EXPECT_EQ(with.A, without.A) << ToString(form);
    EXPECT_EQ(with.b, without.b);
    EXPECT_EQ(with.names, without.names);
    EXPECT_EQ(with.groups, without.groups);
    EXPECT_EQ(with.row_labels.size(), static_cast<std::size_t>(with.A.rows()));
    EXPECT_TRUE(without.row_labels.empty());
    EXPECT_TRUE(without.Validate().ok()) << without.Validate().ToString();
  }
}

// PreparedCorrectionSystem: one preparation, many sets of modes. Each Fill
// into reused storage gives the system a fresh build gives (entries checked
// against the formulas above by the other tests), whatever came before.
TEST(PreparedCorrectionSystem, RepeatedFillsEqualFreshBuilds) {
  const PaperSetup setup;
  ModalData air2 = setup.air, water2 = setup.water;
  air2.frequencies_hz *= 1.01;
  water2.shapes.col(1) *= -2.0;
  water2.shapes(3, 0) += 0.05;
  for (SystemForm form : {SystemForm::kStacked, SystemForm::kSummed}) {
    CorrectionSystemOptions options;
    options.form = form;
    const PreparedCorrectionSystem prepared(setup.s.model, setup.fem, options);
    PreparedCorrectionSystem::Workspace work;
    Eigen::MatrixXd a;
    Eigen::VectorXd b;
    for (const auto& states : {std::vector<ModalData>{setup.air, setup.water},
                               std::vector<ModalData>{air2, water2},
                               std::vector<ModalData>{setup.air, setup.water}}) {
      prepared.Fill(states, &work, &a, &b);
      const LinearProblem fresh =
          BuildCorrectionSystem(setup.s.model, setup.fem, states, options);
      EXPECT_EQ(a, fresh.A) << ToString(form);
      EXPECT_EQ(b, fresh.b) << ToString(form);
    }
  }
}

// Shapes given at sensors in any order (covering every DOF) are the same
// measurement as shapes in model order.
TEST(PreparedCorrectionSystem, SensorOrderDoesNotMatter) {
  const PaperSetup setup;
  std::vector<ModalData> reordered = {setup.air, setup.water};
  for (ModalData& m : reordered) {
    const Eigen::MatrixXd shapes = m.shapes;
    m.sensor_dofs = {4, 2, 0, 1, 3};
    for (int i = 0; i < 5; ++i) m.shapes.row(i) = shapes.row(m.sensor_dofs[i]);
  }
  CorrectionSystemOptions options;
  options.form = SystemForm::kSummed;
  const PreparedCorrectionSystem prepared(setup.s.model, setup.fem, options);
  const LinearProblem in_order = prepared.Build({setup.air, setup.water});
  const LinearProblem at_sensors = prepared.Build(reordered);
  EXPECT_EQ(in_order.A, at_sensors.A);
  EXPECT_EQ(in_order.b, at_sensors.b);
}

TEST(PreparedCorrectionSystem, RejectsWhatBuildRejects) {
  const PaperSetup setup;
  CorrectionSystemOptions options;
  options.num_fem_modes = 6;
  EXPECT_THROW(PreparedCorrectionSystem(setup.s.model, setup.fem, options), InputError);
  options.num_fem_modes = -1;
  options.form = SystemForm::kSummed;
  const PreparedCorrectionSystem prepared(setup.s.model, setup.fem, options);
  PreparedCorrectionSystem::Workspace work;
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  EXPECT_THROW(prepared.Fill({setup.air}, &work, &a, &b), InputError);
  ModalData broken = setup.water;
  broken.frequencies_hz[0] = -1.0;
  EXPECT_THROW(prepared.Fill({setup.air, broken}, &work, &a, &b), InputError);
}

TEST(SystemForm, Names) {
  testing::ExpectEnumNames<SystemForm>(
      {{SystemForm::kStacked, "stacked"}, {SystemForm::kSummed, "summed"}},
      SystemFormFromString, SystemForm::kStacked, {{"summed", SystemForm::kSummed}},
      "paper");
}

}  // namespace
}  // namespace femup
