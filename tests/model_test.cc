// ParametrisedModel (core/include/femup/core/fe/model.h) and the parameter plans that
// build it from a Structure (core/include/femup/core/fe/structure.h), checked against
// hand-assembled matrices.
#include "femup/core/fe/model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

#include "enum_names.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/structure.h"
#include "paper_beam.h"

namespace femup {
namespace {

SparseMatrix Sparse(const Eigen::MatrixXd& a) { return a.sparseView(); }
Eigen::MatrixXd Dense(const SparseMatrix& a) { return Eigen::MatrixXd(a); }
Eigen::MatrixXd Dense(const BasisMatrix& b) { return Eigen::MatrixXd(b.ToSparse()); }

// A 3-DOF model: K, M and three hand-made bases.
class SmallModel : public ::testing::Test {
 protected:
  void SetUp() override {
    k_ << 5, -2, 0, -2, 4, -1, 0, -1, 1;
    m_ << 2, 0.5, 0, 0.5, 3, 0, 0, 0, 1;
    model_ = ParametrisedModel(Sparse(k_), Sparse(m_), {"a", "b", "c"});
  }
  Parameter Make(const std::string& name, ParameterKind kind,
                 const Eigen::MatrixXd& basis) {
    Parameter p;
    p.name = name;
    p.kind = kind;
    p.basis = Sparse(basis);
    return p;
  }
  std::string WhatOfAdd(Parameter p) {
    try {
      model_.AddParameter(std::move(p));
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no exception)";
  }

  Eigen::Matrix3d k_, m_;
  ParametrisedModel model_;
};

TEST_F(SmallModel, AddParameterAndLookups) {
  Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
  b(0, 0) = 1;
  EXPECT_EQ(model_.AddParameter(Make("mass[1]", ParameterKind::kMass, b)), 0);
  EXPECT_EQ(model_.AddParameter(Make("stiffness[1]", ParameterKind::kStiffness, b)), 1);
  EXPECT_EQ(model_.AddParameter(Make("mass[2]", ParameterKind::kMass, b)), 2);
  EXPECT_EQ(model_.num_parameters(), 3);
  EXPECT_EQ(model_.num_dofs(), 3);
  EXPECT_EQ(model_.FindParameter("mass[2]"), 2);
  EXPECT_EQ(model_.FindParameter("mass[3]"), -1);
  EXPECT_EQ(model_.ParametersOfKind(ParameterKind::kMass), (std::vector<int>{0, 2}));
  EXPECT_EQ(model_.ParametersOfKind(ParameterKind::kAddedMass), std::vector<int>{});
  EXPECT_EQ(model_.ParameterNames(),
            (std::vector<std::string>{"mass[1]", "stiffness[1]", "mass[2]"}));
  EXPECT_EQ(model_.FindDof("b"), 1);
  EXPECT_EQ(model_.FindDof("z"), -1);
  EXPECT_EQ(model_.parameter(1).name, "stiffness[1]");
  EXPECT_THROW(model_.parameter(3), std::out_of_range);
}

TEST_F(SmallModel, AddParameterRejectsBadInput) {
  Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
  b(1, 1) = 1;
  model_.AddParameter(Make("mass[1]", ParameterKind::kMass, b));

  const std::string duplicate = WhatOfAdd(Make("mass[1]", ParameterKind::kStiffness, b));
  EXPECT_NE(duplicate.find("mass[1]"), std::string::npos) << duplicate;
  EXPECT_NE(duplicate.find("twice"), std::string::npos) << duplicate;

  const std::string size =
      WhatOfAdd(Make("p", ParameterKind::kMass, Eigen::Matrix2d::Identity()));
  EXPECT_NE(size.find("2 x 2"), std::string::npos) << size;

  Eigen::Matrix3d asym = b;
  asym(0, 2) = 1.0;
  const std::string symmetric = WhatOfAdd(Make("q", ParameterKind::kMass, asym));
  EXPECT_NE(symmetric.find("not symmetric"), std::string::npos) << symmetric;

  Eigen::Matrix3d nan = b;
  nan(2, 2) = std::numeric_limits<double>::quiet_NaN();
  const std::string finite = WhatOfAdd(Make("r", ParameterKind::kMass, nan));
  EXPECT_NE(finite.find("NaN"), std::string::npos) << finite;

  Eigen::Matrix3d inf = b;
  inf(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_NE(WhatOfAdd(Make("s", ParameterKind::kMass, inf)), "(no exception)");

  EXPECT_NE(WhatOfAdd(Make("", ParameterKind::kMass, b)), "(no exception)");
  // Nothing bad was added.
  EXPECT_EQ(model_.num_parameters(), 1);
}

TEST_F(SmallModel, UpdatedMatricesAreHandSums) {
  Eigen::Matrix3d bm1 = Eigen::Matrix3d::Zero(), bm2 = bm1, bk = bm1, ba1 = bm1,
                  ba2 = bm1;
  bm1(0, 0) = 2;
  bm2 << 0, 0, 0, 0, 1, 0.25, 0, 0.25, 1;
  bk << 1, -1, 0, -1, 1, 0, 0, 0, 0;
  ba1(2, 2) = 4;
  ba2 << 1, 0, 1, 0, 0, 0, 1, 0, 1;
  model_.AddParameter(Make("m1", ParameterKind::kMass, bm1));
  model_.AddParameter(Make("a1", ParameterKind::kAddedMass, ba1));
  model_.AddParameter(Make("k1", ParameterKind::kStiffness, bk));
  model_.AddParameter(Make("m2", ParameterKind::kMass, bm2));
  model_.AddParameter(Make("a2", ParameterKind::kAddedMass, ba2));
  Eigen::VectorXd d(5);
  d << 0.1, 0.3, -0.2, 0.05, 0.7;

  const Eigen::Matrix3d k = k_ - 0.2 * bk;
  const Eigen::Matrix3d mdry = m_ + 0.1 * bm1 + 0.05 * bm2;
  const Eigen::Matrix3d added = 0.3 * ba1 + 0.7 * ba2;
  EXPECT_LE((Dense(model_.UpdatedStiffness(d)) - k).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((Dense(model_.UpdatedDryMass(d)) - mdry).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((Dense(model_.AddedMass(d)) - added).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((Dense(model_.UpdatedWetMass(d)) - (mdry + added)).cwiseAbs().maxCoeff(),
            1e-15);

  // Zero factors give the baseline; a wrong-size or NaN factor vector throws.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(5);
  EXPECT_EQ(Dense(model_.UpdatedStiffness(zero)), Eigen::MatrixXd(k_));
  EXPECT_EQ(Dense(model_.UpdatedWetMass(zero)), Eigen::MatrixXd(m_));
  EXPECT_EQ(Dense(model_.AddedMass(zero)).norm(), 0.0);
  EXPECT_THROW(model_.UpdatedStiffness(Eigen::VectorXd::Zero(4)), InputError);
  Eigen::VectorXd bad = d;
  bad[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(model_.UpdatedDryMass(bad), InputError);
}

// DOFs that share a label's node part ("n1:ux", "n1:rz") share a node; a
// label without ':' is its own node even when repeated.
TEST(ParametrisedModel, DofNodesFromTheLabels) {
  const Eigen::MatrixXd k = Eigen::MatrixXd::Identity(6, 6);
  const ParametrisedModel model(Sparse(k), Sparse(k),
                                {"n1:ux", "n1:uy", "n2:ux", "b", "n1:rz", "b"});
  EXPECT_EQ(model.DofNodes(), (std::vector<int>{0, 0, 1, 2, 0, 3}));
  EXPECT_TRUE(ParametrisedModel().DofNodes().empty());
}

TEST(ParametrisedModel, ConstructorRejectsBadMatrices) {
  const Eigen::Matrix2d k = (Eigen::Matrix2d() << 2, -1, -1, 1).finished();
  const Eigen::Matrix2d m = Eigen::Matrix2d::Identity();
  EXPECT_NO_THROW(ParametrisedModel(Sparse(k), Sparse(m), {"x1", "x2"}));
  EXPECT_THROW(ParametrisedModel(Sparse(k), Sparse(m), {"x1"}), InputError);
  EXPECT_THROW(
      ParametrisedModel(Sparse(k), Sparse(Eigen::Matrix3d::Identity()), {"x1", "x2"}),
      InputError);
  Eigen::Matrix2d asym = k;
  asym(0, 1) = -3;
  EXPECT_THROW(ParametrisedModel(Sparse(asym), Sparse(m), {"x1", "x2"}), InputError);
  Eigen::Matrix2d nan = m;
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ParametrisedModel(Sparse(k), Sparse(nan), {"x1", "x2"}), InputError);
}

TEST_F(SmallModel, ManyParametersKeepEveryFieldAsTheListGrows) {
  // More parameters than the list's first capacities (16, 32, ...): each keeps
  // its name, kind, basis, elements and tags when the list is regrown.
  for (int i = 0; i < 40; ++i) {
    Eigen::Matrix3d b = Eigen::Matrix3d::Zero();
    b(i % 3, i % 3) = i + 1.0;
    Parameter p = Make("p[" + std::to_string(i) + "]",
                       i % 2 ? ParameterKind::kStiffness : ParameterKind::kMass, b);
    p.elements = {i, i + 1};
    p.tags = {"tag" + std::to_string(i)};
    ASSERT_EQ(model_.AddParameter(std::move(p)), i);
  }
  for (int i = 0; i < 40; ++i) {
    const Parameter& p = model_.parameter(i);
    EXPECT_EQ(p.name, "p[" + std::to_string(i) + "]");
    EXPECT_EQ(p.kind, i % 2 ? ParameterKind::kStiffness : ParameterKind::kMass);
    EXPECT_EQ(p.elements, (std::vector<int>{i, i + 1}));
    EXPECT_TRUE(p.HasTag("tag" + std::to_string(i)));
    ASSERT_EQ(p.basis.rows(), 3);
    EXPECT_EQ(p.basis.nonZeros(), 1);
    EXPECT_EQ(p.basis.ToSparse().coeff(i % 3, i % 3), i + 1.0);
  }
}

TEST(ParametrisedModel, IsSymmetricFindsAMissingMirrorCompressedOrNot) {
  // An entry whose mirror is not stored at all, in a compressed matrix and in
  // one built by insert() (uncompressed).
  SparseMatrix a(4, 4);
  a.insert(0, 0) = 1;
  a.insert(3, 1) = 2;
  a.insert(1, 3) = 2;
  a.insert(2, 2) = 5;
  EXPECT_TRUE(IsSymmetric(a, 0.0));
  a.insert(3, 0) = 1e-3;  // a(0, 3) missing
  EXPECT_FALSE(IsSymmetric(a, 1e-6));
  EXPECT_TRUE(IsSymmetric(a, 1e-3));  // relative to the largest entry, 5
  a.makeCompressed();
  EXPECT_FALSE(IsSymmetric(a, 1e-6));
  EXPECT_TRUE(IsSymmetric(a, 1e-3));
  a.coeffRef(0, 3) = 1e-3;
  EXPECT_TRUE(IsSymmetric(a, 0.0));
}

TEST(ParametrisedModel, KindNamesAndMatrixPredicates) {
  const ParameterKind kind = testing::ExpectEnumNames<ParameterKind>(
      {{ParameterKind::kMass, "mass"},
       {ParameterKind::kStiffness, "stiffness"},
       {ParameterKind::kAddedMass, "added_mass"}},
      ParameterKindFromString, ParameterKind::kMass,
      {{"added_mass", ParameterKind::kAddedMass}}, "damping");
  EXPECT_EQ(kind, ParameterKind::kAddedMass);  // the refusal leaves it as it was

  Eigen::Matrix2d a;
  a << 1, 2, 2 + 1e-12, 3;
  EXPECT_TRUE(IsSymmetric(Sparse(a), 1e-10));
  EXPECT_FALSE(IsSymmetric(Sparse(a), 1e-14));
  EXPECT_FALSE(IsSymmetric(SparseMatrix(2, 3)));
  EXPECT_TRUE(AllFinite(Sparse(a)));
  a(1, 0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(AllFinite(Sparse(a)));
}

// ---------------------------------------------------------------------------
// BuildModel on the paper's chain: masses 1-3 wet.

Structure PaperChainStructure() {
  ChainSpec spec;
  spec.masses = {50, 50, 50, 50, 50};
  spec.springs = {2.9e7, 2.9e7, 2.9e7, 2.9e7, 2.9e7};
  spec.wet = {true, true, true, false, false};
  return BuildSpringMassChain(spec);
}

TEST(BuildModel, PaperPlanOnChain) {
  const Structure s = PaperChainStructure();
  const ParametrisedModel model = BuildModel(s, PaperParameterPlan());
  ASSERT_EQ(model.num_parameters(), 13);
  const std::vector<std::string> expected = {
      "mass[1]",       "mass[2]",       "mass[3]",      "mass[4]",      "mass[5]",
      "stiffness[1]",  "stiffness[2]",  "stiffness[3]", "stiffness[4]", "stiffness[5]",
      "added_mass[1]", "added_mass[2]", "added_mass[3]"};
  EXPECT_EQ(model.ParameterNames(), expected);
  for (int i = 0; i < 13; ++i) {
    const Parameter& p = model.parameter(i);
    const int id = i < 10 ? i % 5 + 1 : i - 9;
    const ParameterKind kind = i < 5    ? ParameterKind::kMass
                               : i < 10 ? ParameterKind::kStiffness
                                        : ParameterKind::kAddedMass;
    EXPECT_EQ(p.kind, kind) << p.name;
    EXPECT_EQ(p.elements, std::vector<int>{id}) << p.name;
    EXPECT_TRUE(p.HasTag("element:" + std::to_string(id))) << p.name;
    EXPECT_EQ(p.HasTag("wet"), id <= 3) << p.name;
    EXPECT_EQ(p.HasTag("dry"), id > 3) << p.name;
    EXPECT_FALSE(p.HasTag("element:" + std::to_string(id + 1))) << p.name;
    // Bases are the element's own matrices.
    const ElementMatrices& e = s.elements[id - 1];
    const SparseMatrix& expected_basis = kind == ParameterKind::kStiffness ? e.stiffness
                                         : kind == ParameterKind::kMass
                                             ? e.mass
                                             : e.added_mass_basis;
    EXPECT_EQ(Dense(p.basis), Dense(expected_basis)) << p.name;
  }
  // Hand-written: stiffness[2] couples x1 and x2 with 2.9e7 [1 -1; -1 1].
  Eigen::MatrixXd k2 = Eigen::MatrixXd::Zero(5, 5);
  k2.block<2, 2>(0, 0) << 2.9e7, -2.9e7, -2.9e7, 2.9e7;
  EXPECT_EQ(Dense(model.parameter(6).basis), k2);
  Eigen::MatrixXd a3 = Eigen::MatrixXd::Zero(5, 5);
  a3(2, 2) = 50;
  EXPECT_EQ(Dense(model.parameter(12).basis), a3);
}

TEST(BuildModel, BasesSumToKAndMSoCommonScalingIsANullSpace) {
  const Structure s = PaperChainStructure();
  const ParametrisedModel model = BuildModel(s, PaperParameterPlan());
  Eigen::MatrixXd mass_sum = Eigen::MatrixXd::Zero(5, 5), stiffness_sum = mass_sum;
  for (int i : model.ParametersOfKind(ParameterKind::kMass)) {
    mass_sum += Dense(model.parameter(i).basis);
  }
  for (int i : model.ParametersOfKind(ParameterKind::kStiffness)) {
    stiffness_sum += Dense(model.parameter(i).basis);
  }
  EXPECT_EQ(mass_sum, Dense(model.mass()));
  EXPECT_EQ(stiffness_sum, Dense(model.stiffness()));
  // Every mass and stiffness factor equal to c scales K and M by (1 + c).
  const double c = 0.37;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(13);
  d.head(10).setConstant(c);
  EXPECT_LE((Dense(model.UpdatedStiffness(d)) - (1 + c) * Dense(model.stiffness()))
                .cwiseAbs()
                .maxCoeff(),
            1e-14 * 2.9e7 * 2);
  EXPECT_LE((Dense(model.UpdatedDryMass(d)) - (1 + c) * Dense(model.mass()))
                .cwiseAbs()
                .maxCoeff(),
            1e-13);
}

TEST(BuildModel, SingleScopeLayouts) {
  const Structure s = PaperChainStructure();
  ParameterPlan plan;
  plan.mass.scope = ParameterFamily::Scope::kSingle;
  plan.stiffness.scope = ParameterFamily::Scope::kSingle;
  plan.stiffness.selection = ParameterFamily::Selection::kDry;
  plan.added_mass.scope = ParameterFamily::Scope::kSingle;
  const ParametrisedModel model = BuildModel(s, plan);
  EXPECT_EQ(model.ParameterNames(),
            (std::vector<std::string>{"mass[all]", "stiffness[dry]", "added_mass[wet]"}));
  EXPECT_EQ(Dense(model.parameter(0).basis), Dense(s.mass));
  EXPECT_EQ(model.parameter(0).elements, (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_TRUE(model.parameter(0).HasTag("mixed"));
  // Springs 4 and 5: 2.9e7 on (x3,x3), 2 x 2.9e7 on (x4,x4), 2.9e7 on (x5,x5).
  Eigen::MatrixXd kdry = Eigen::MatrixXd::Zero(5, 5);
  kdry.block<3, 3>(2, 2) << 1, -1, 0, -1, 2, -1, 0, -1, 1;
  kdry *= 2.9e7;
  EXPECT_EQ(Dense(model.parameter(1).basis), kdry);
  EXPECT_TRUE(model.parameter(1).HasTag("dry"));
  Eigen::MatrixXd wet = Eigen::MatrixXd::Zero(5, 5);
  wet.diagonal().head(3).setConstant(50);
  EXPECT_EQ(Dense(model.parameter(2).basis), wet);
  EXPECT_EQ(model.parameter(2).elements, (std::vector<int>{1, 2, 3}));
  EXPECT_TRUE(model.parameter(2).HasTag("wet"));
}

TEST(BuildModel, NoneScopeAndEmptySelection) {
  ChainSpec spec;
  spec.masses = {1, 1};
  spec.springs = {1, 1};
  const Structure dry = BuildSpringMassChain(spec);  // nothing wet
  ParameterPlan plan;
  plan.stiffness.scope = ParameterFamily::Scope::kPerElement;
  EXPECT_EQ(BuildModel(dry, plan).ParameterNames(),
            (std::vector<std::string>{"stiffness[1]", "stiffness[2]"}));
  try {
    BuildModel(dry, PaperParameterPlan());
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "parameters.added_mass");
    EXPECT_NE(std::string(e.what()).find("wet"), std::string::npos) << e.what();
  }
}

CantileverSpec PaperCantilever() {
  CantileverSpec spec = fixtures::PaperCantilever(UniformHeights(1.9, 10));
  spec.water_depth = 1.5;  // elements 1..8 wet
  return spec;
}

TEST(BuildModel, GroupLayoutsOnCantilever) {
  const Structure s = BuildCantilever(PaperCantilever());
  ParameterPlan plan;
  plan.stiffness.scope = ParameterFamily::Scope::kGroups;
  plan.stiffness.groups = {{1, 2, 3}, {4, 6}, {5}, {8, 10}, {7, 9}};
  plan.added_mass.scope = ParameterFamily::Scope::kGroups;
  plan.added_mass.groups = {{1, 2, 3, 4}, {5, 7}};
  const ParametrisedModel model = BuildModel(s, plan);
  EXPECT_EQ(
      model.ParameterNames(),
      (std::vector<std::string>{"stiffness[e1-e3]", "stiffness[e4+e6]", "stiffness[e5]",
                                "stiffness[e8+e10]", "stiffness[e7+e9]",
                                "added_mass[e1-e4]", "added_mass[e5+e7]"}));
  const Parameter& g = model.parameter(0);
  EXPECT_EQ(g.elements, (std::vector<int>{1, 2, 3}));
  EXPECT_TRUE(g.HasTag("wet"));
  for (int id : {1, 2, 3}) EXPECT_TRUE(g.HasTag("element:" + std::to_string(id)));
  const Eigen::MatrixXd expected = Dense(s.elements[0].stiffness) +
                                   Dense(s.elements[1].stiffness) +
                                   Dense(s.elements[2].stiffness);
  EXPECT_LE((Dense(g.basis) - expected).cwiseAbs().maxCoeff(),
            1e-15 * expected.cwiseAbs().maxCoeff());
  EXPECT_TRUE(model.parameter(3).HasTag("mixed"));  // e8 wet, e10 dry
  EXPECT_TRUE(model.parameter(4).HasTag("mixed"));  // e7 wet, e9 dry
  EXPECT_TRUE(model.parameter(6).HasTag("wet"));
}

TEST(BuildModel, BadGroupsThrow) {
  const Structure s = BuildCantilever(PaperCantilever());
  ParameterPlan plan;
  plan.mass.scope = ParameterFamily::Scope::kGroups;
  plan.mass.groups = {{1, 2}, {11}};
  try {
    BuildModel(s, plan);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "parameters.mass.groups");
    EXPECT_NE(std::string(e.what()).find("11"), std::string::npos) << e.what();
  }

  ParameterPlan added;
  added.added_mass.scope = ParameterFamily::Scope::kGroups;
  added.added_mass.groups = {{1, 2}, {8, 9}};  // element 9 is dry
  try {
    BuildModel(s, added);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "parameters.added_mass.groups");
    EXPECT_NE(std::string(e.what()).find("not wet"), std::string::npos) << e.what();
  }

  ParameterPlan empty;
  empty.stiffness.scope = ParameterFamily::Scope::kGroups;
  EXPECT_THROW(BuildModel(s, empty), InputError);
  empty.stiffness.groups = {{}};
  EXPECT_THROW(BuildModel(s, empty), InputError);
}

TEST(BuildModel, FindElement) {
  const Structure s = PaperChainStructure();
  EXPECT_EQ(s.FindElement(1), 0);
  EXPECT_EQ(s.FindElement(5), 4);
  EXPECT_EQ(s.FindElement(6), -1);
  EXPECT_EQ(s.FindElement(0), -1);
}

}  // namespace
}  // namespace femup
