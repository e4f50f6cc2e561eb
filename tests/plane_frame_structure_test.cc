// The plane frame as a Structure of members (study model type plane_frame):
// its sway frequency against the portal frame's closed form (a rigid, heavy
// beam on two fixed-guided, axially rigid columns: omega^2 = 24 E I / (h^3 m)),
// the members' matrices summing to the whole, and a column's stiffness loss found by the
// effect fit from modes of a frame built with the weaker column's section.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/fe/fe.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/model_effect_pencil.h"
#include "femup/problems/model_effects.h"
#include "femup/solvers/nonlinear_solver.h"
#include "femup/studies/study.h"
#include "structure_specs.h"

namespace femup {
namespace {

PlaneFrameSpec Portal() {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 4, 3.0, 5.0);
  // Nearly massless columns, axially rigid (A large: no rocking of the beam,
  // which the closed form leaves out; with A = 0.01 it costs 0.46 %).
  spec.column = {210e9, 1.0, 8e-5, 1e-5};
  spec.beam = {210e9, 0.05, 8e-1, 2e4};  // rigid (I 1e4 times) and heavy
  return spec;
}

TEST(PlaneFrameStructure, PortalSwayMatchesTheClosedForm) {
  const PlaneFrameSpec spec = Portal();
  const Structure s = BuildPlaneFrameStructure(spec);
  EXPECT_EQ(s.type, "plane_frame");
  ASSERT_EQ(s.elements.size(), 3u);
  EXPECT_EQ(s.elements[0].label, "s1:col1");
  EXPECT_EQ(s.elements[2].label, "s1:beam1");
  const Modes modes = SolveModes(s.stiffness, s.mass);
  const double beam_mass = spec.beam.rho * spec.beam.A * spec.bay_width;
  const double ei = spec.column.E * spec.column.I;
  const double exact = 24 * ei / std::pow(spec.storey_height, 3) / beam_mass;
  EXPECT_NEAR(modes.eigenvalues[0] / exact, 1.0, 2e-3);
}

TEST(PlaneFrameStructure, MembersSumToTheWholeAndMatchTheFactorModel) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(3, 2, 2);
  spec.wet_storeys = 1;
  const Structure s = BuildPlaneFrameStructure(spec);
  ASSERT_EQ(s.elements.size(), 3u * 3 + 3 * 2);
  SparseMatrix k(s.stiffness.rows(), s.stiffness.cols()), m = k;
  int wet = 0;
  for (const ElementMatrices& e : s.elements) {
    k += e.stiffness;
    m += e.mass;
    wet += e.wet ? 1 : 0;
  }
  EXPECT_EQ(wet, 3);  // the three columns of storey 1
  EXPECT_LT((Eigen::MatrixXd(k - s.stiffness)).cwiseAbs().maxCoeff(), 1e-6);
  // The large builder's nominal matrices are the same frame.
  const ParametrisedModel big = BuildPlaneFrame(spec);
  EXPECT_EQ(big.dof_labels(), s.dof_labels);
  EXPECT_LT((Eigen::MatrixXd(big.stiffness() - s.stiffness)).cwiseAbs().maxCoeff(),
            1e-9 * Eigen::MatrixXd(s.stiffness).cwiseAbs().maxCoeff());
  EXPECT_LT((Eigen::MatrixXd(big.mass() - m)).cwiseAbs().maxCoeff(),
            1e-9 * Eigen::MatrixXd(m).cwiseAbs().maxCoeff());
  EXPECT_EQ(s.nodes.size(), s.dof_labels.size() / 3);
}

// Each member of several finite elements carries them as its parts (what a
// loss over part of its length acts on): they sum to the member, which is its
// element; spans in fractions from its first joint (a column's foot, a beam's
// left end), extents as the elements' heights.
TEST(PlaneFrameStructure, MembersOfSeveralElementsCarryThemAsParts) {
  const PlaneFrameSpec spec = fixtures::PlaneFrame(2, 2, 2, 3.0, 5.0);
  const Structure s = BuildPlaneFrameStructure(spec);
  ASSERT_EQ(s.members.size(), s.elements.size());
  for (std::size_t i = 0; i < s.members.size(); ++i) {
    const ElementMember& m = s.members[i];
    const ElementMatrices& e = s.elements[static_cast<std::size_t>(m.element)];
    EXPECT_EQ(m.element, static_cast<int>(i));
    EXPECT_EQ(m.label, e.label);
    EXPECT_EQ(m.x0, e.x0);
    EXPECT_EQ(m.x1, e.x1);
    ASSERT_EQ(m.parts.size(), 2u) << m.label;
    EXPECT_EQ(m.parts[0].from, 0.0);
    EXPECT_EQ(m.parts[0].to, 0.5);
    EXPECT_EQ(m.parts[1].from, 0.5);
    EXPECT_EQ(m.parts[1].to, 1.0);
    const Eigen::MatrixXd whole(e.stiffness);
    const Eigen::MatrixXd sum = Eigen::MatrixXd(m.parts[0].stiffness.ToSparse() +
                                                m.parts[1].stiffness.ToSparse());
    EXPECT_LT((sum - whole).cwiseAbs().maxCoeff(), 1e-9 * whole.cwiseAbs().maxCoeff());
    EXPECT_LT((Eigen::MatrixXd(m.stiffness.ToSparse()) - whole).cwiseAbs().maxCoeff(),
              1e-9 * whole.cwiseAbs().maxCoeff());
  }
  // Storey 1's first column: its lower half from 0 to 1.5 m, its upper half to 3 m.
  EXPECT_EQ(s.members[0].label, "s1:col1");
  EXPECT_DOUBLE_EQ(s.members[0].parts[0].x0, 0.0);
  EXPECT_DOUBLE_EQ(s.members[0].parts[0].x1, 1.5);
  EXPECT_DOUBLE_EQ(s.members[0].parts[1].x1, 3.0);
  // One element per member: nothing to add.
  EXPECT_TRUE(BuildPlaneFrameStructure(fixtures::PlaneFrame(2, 2, 1)).members.empty());
}

// A loss over half a beam: the beam's left element alone, its stiffness
// that of a 2D frame element from the beam's left joint to its middle
// (Frame2dStiffness on those coordinates, scattered by DOF label); the
// member's own instance is its element's, not listed twice.
TEST(PlaneFrameStructure, StiffnessLossOverHalfABeamIsItsLeftElement) {
  const PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 2, 3.0, 5.0);
  const Structure s = BuildPlaneFrameStructure(spec);
  std::vector<std::string> regions;
  for (const auto& e : CreateModelEffects("stiffness_loss", s))
    regions.push_back(e->region().name);
  EXPECT_EQ(std::count(regions.begin(), regions.end(), "element s1:beam1"), 1);
  EXPECT_EQ(std::count(regions.begin(), regions.end(), "member s1:beam1"), 0);
  for (const char* part : {"member s1:beam1 (0.00-0.50)", "member s1:beam1 (0.50-1.00)",
                           "member s1:col1 (0.00-0.50)", "member s1:col2 (0.50-1.00)"}) {
    EXPECT_EQ(std::count(regions.begin(), regions.end(), part), 1) << part;
  }
  std::unique_ptr<ModelEffect> left;
  for (auto& e : CreateModelEffects("stiffness_loss", s))
    if (e->region().name == "member s1:beam1 (0.00-0.50)") left = std::move(e);
  ASSERT_TRUE(left);
  const double loss = 0.3;
  Eigen::VectorXd theta(1);
  theta << std::log(loss);
  const Eigen::MatrixXd change(left->Change(theta, Immersion::kDry).stiffness);
  // The beam's joints are the column tops; its middle node the one at (2.5, 3).
  auto node_at = [&](double x, double y) {
    for (const ModelNode& n : s.nodes)
      if (std::abs(n.xyz.x() - x) < 1e-12 && std::abs(n.xyz.y() - y) < 1e-12)
        return n.name;
    ADD_FAILURE() << "no node at " << x << ", " << y;
    return std::string();
  };
  const std::string a = node_at(0, 3), b = node_at(2.5, 3);
  std::vector<int> dofs;
  for (const std::string& node : {a, b})
    for (const char* d : {":ux", ":uy", ":rz"}) {
      const auto it = std::find(s.dof_labels.begin(), s.dof_labels.end(), node + d);
      ASSERT_NE(it, s.dof_labels.end());
      dofs.push_back(static_cast<int>(it - s.dof_labels.begin()));
    }
  const Matrix6 k6 = Frame2dStiffness(spec.beam, 0, 3, 2.5, 3);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(change.rows(), change.cols());
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) expected(dofs[i], dofs[j]) = -loss * k6(i, j);
  EXPECT_LT((change - expected).cwiseAbs().maxCoeff(), 1e-9 * k6.cwiseAbs().maxCoeff());
  EXPECT_DOUBLE_EQ(left->Location(theta).x0, 3.0);  // a beam: at its storey's height
}

TEST(PlaneFrameStructure, FindsAWeakerColumn) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(2, 2, 3);
  auto nominal = std::make_shared<const Structure>(BuildPlaneFrameStructure(spec));
  // The truth: column line 2 of storey 1 with 30 % less E I (its own section).
  Structure truth = *nominal;
  const int weak = 1;  // "s1:col2"
  ASSERT_EQ(truth.elements[weak].label, "s1:col2");
  truth.stiffness -= 0.3 * truth.elements[weak].stiffness;
  // Bending and axial both scale with E: the member's E 30 % lower.
  const Modes modes = SolveModes(truth.stiffness, truth.mass);
  ModalData measured;
  measured.state = "test";
  measured.frequencies_hz = modes.FrequenciesHz().head(4);
  for (int i = 0; i < static_cast<int>(nominal->dof_labels.size()); ++i) {
    if (nominal->dof_labels[i].find(":ux") != std::string::npos)
      measured.sensor_dofs.push_back(i);
  }
  measured.shapes = modes.shapes(measured.sensor_dofs, Eigen::seqN(0, 4));
  std::shared_ptr<const ModelEffect> loss;
  for (auto& e : CreateModelEffects("stiffness_loss", *nominal)) {
    if (e->region().name == "element s1:col2") loss.reset(e.release());
  }
  ASSERT_TRUE(loss);
  const NonlinearProblem problem =
      BuildModelEffectFitProblem(nominal, {loss}, {measured}, EigenSensitivityOptions{});
  const NonlinearSolution fit = CreateNonlinearSolver("ceres")->Solve(problem);
  ASSERT_TRUE(fit.summary.usable()) << fit.summary.message;
  EXPECT_NEAR(std::exp(fit.x[0]), 0.3, 1e-6);
}

// A column on a base rotation spring kr, its top held by the rigid beam: by
// slope-deflection, lateral stiffness 12 E I / h^3 (1 - 3 E I / (4 E I + kr h))
// (kr -> infinity: fixed-guided, 12 E I / h^3; kr = 0: 3 E I / h^3), and a base
// horizontal spring kh in series with it.
double ColumnSwayStiffness(double ei, double h, double kr, double kh) {
  const double k = 12 * ei / std::pow(h, 3) * (1 - 3 * ei / (4 * ei + kr * h));
  return kh > 0 ? 1 / (1 / k + 1 / kh) : k;
}

TEST(PlaneFrameStructure, BaseSpringsMatchTheSlopeDeflectionClosedForm) {
  PlaneFrameSpec spec = Portal();
  const double ei = spec.column.E * spec.column.I, h = spec.storey_height;
  const double beam_mass = spec.beam.rho * spec.beam.A * spec.bay_width;
  for (const auto& [kr, kh] : {std::pair<double, double>{4 * ei / h, 0.0},
                               {0.5 * ei / h, 0.0},
                               {20 * ei / h, 12 * ei / std::pow(h, 3)}}) {
    spec.base = {kh, 0.0, kr};
    const Structure s = BuildPlaneFrameStructure(spec);
    const Modes modes = SolveModes(s.stiffness, s.mass);
    const double exact = 2 * ColumnSwayStiffness(ei, h, kr, kh) / beam_mass;
    EXPECT_NEAR(modes.eigenvalues[0] / exact, 1.0, 3e-3) << "kr " << kr << " kh " << kh;
  }
}

// A clamped frame's bases are rigid supports that support flexibility can
// release: at compliance ratios c_t (translations) and c_r (rotations) every
// restrained direction gets a spring of the column end's own stiffness over
// its ratio, condensed onto the frame's DOFs.
// K + dK is then the Schur complement of the same frame built on those base
// springs (its base DOFs condensed out), M + dM its Guyan-reduced mass, and the
// portal's sway the slope-deflection closed form with those springs.
TEST(PlaneFrameStructure, ClampedBasesAreRigidSupportsThatSpringsRelease) {
  PlaneFrameSpec spec = Portal();
  const Structure clamped = BuildPlaneFrameStructure(spec);
  EXPECT_TRUE(clamped.supports.empty());
  ASSERT_EQ(clamped.rigid_supports.size(), 2u);
  const RigidSupport& b2 = clamped.rigid_supports[1];
  EXPECT_EQ(b2.name, "b2");
  EXPECT_EQ(b2.xyz, Eigen::Vector3d(5.0, 0.0, 0.0));
  EXPECT_EQ(b2.directions, (std::vector<std::string>{"ux", "uy", "rz"}));
  // Its column's first element (h / 4 long) alone meets the foot: 4 E I / l
  // in rotation, 12 E I / l^3 sideways, E A / l along it.
  const double ei = spec.column.E * spec.column.I, h = spec.storey_height, l = h / 4;
  EXPECT_NEAR(b2.k_bb(2, 2) / (4 * ei / l), 1.0, 1e-12);
  EXPECT_NEAR(b2.k_bb(0, 0) / (12 * ei / std::pow(l, 3)), 1.0, 1e-12);
  EXPECT_NEAR(b2.k_bb(1, 1) / (spec.column.E * spec.column.A / l), 1.0, 1e-12);
  EXPECT_EQ(b2.rows.size(), 3u);  // the element's other node

  const auto effects = CreateModelEffects("support_flexibility", clamped);
  ASSERT_EQ(effects.size(), 1u);
  const double beam_mass = spec.beam.rho * spec.beam.A * spec.bay_width;
  const auto params = effects[0]->Parameters();
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[0].quantity, "translation_compliance_ratio");
  EXPECT_EQ(params[1].quantity, "rotation_compliance_ratio");
  for (const auto& [ct, cr] :
       {std::pair{0.05, 0.05}, std::pair{1.0, 1.0}, std::pair{8.0, 8.0},
        std::pair{1e-3, 2.0}, std::pair{3.0, 0.2}}) {
    const Eigen::VectorXd theta = Eigen::Vector2d(std::log(ct), std::log(cr));
    SparseMatrix k, m;
    ApplyModelEffects(clamped, {effects[0].get()}, {theta}, Immersion::kDry, &k, &m);
    const double kh = b2.k_bb(0, 0) / ct, kv = b2.k_bb(1, 1) / ct,
                 kr = b2.k_bb(2, 2) / cr;
    const std::string c = std::to_string(ct) + ", " + std::to_string(cr);
    PlaneFrameSpec sprung = spec;
    sprung.base = {kh, kv, kr};
    const Structure reference = BuildPlaneFrameStructure(sprung);
    const int n = static_cast<int>(clamped.dof_labels.size());
    const int nb = static_cast<int>(reference.dof_labels.size()) - n;
    ASSERT_EQ(nb, 6);
    for (int i = 0; i < n; ++i) ASSERT_EQ(reference.dof_labels[i], clamped.dof_labels[i]);
    const Eigen::MatrixXd k2(reference.stiffness), m2(reference.mass);
    const Eigen::MatrixXd kbb = k2.bottomRightCorner(nb, nb);
    const Eigen::MatrixXd t = -kbb.ldlt().solve(k2.bottomLeftCorner(nb, n));
    const Eigen::MatrixXd schur = k2.topLeftCorner(n, n) + k2.topRightCorner(n, nb) * t;
    const Eigen::MatrixXd guyan = m2.topLeftCorner(n, n) + m2.topRightCorner(n, nb) * t +
                                  t.transpose() * m2.bottomLeftCorner(nb, n) +
                                  t.transpose() * m2.bottomRightCorner(nb, nb) * t;
    EXPECT_LT((Eigen::MatrixXd(k) - schur).cwiseAbs().maxCoeff(),
              1e-9 * schur.cwiseAbs().maxCoeff())
        << "c " << c;
    EXPECT_LT((Eigen::MatrixXd(m) - guyan).cwiseAbs().maxCoeff(),
              1e-9 * guyan.cwiseAbs().maxCoeff())
        << "c " << c;
    // The sway against the closed form (the columns are axially rigid, so the
    // vertical springs leave it alone).
    const Modes modes = SolveModes(k, m);
    const double exact = 2 * ColumnSwayStiffness(ei, h, kr, kh) / beam_mass;
    EXPECT_NEAR(modes.eigenvalues[0] / exact, 1.0, 3e-3) << "c " << c;
  }
  // Its derivatives against central differences of the change.
  const Eigen::Vector2d t0(std::log(0.7), std::log(2.5));
  const double step = 1e-5;
  for (int i = 0; i < 2; ++i) {
    Eigen::VectorXd tu = t0, td = t0;
    tu[i] += step;
    td[i] -= step;
    const ModelChange d = effects[0]->Derivative(t0, i, Immersion::kDry);
    const ModelChange up = effects[0]->Change(tu, Immersion::kDry);
    const ModelChange down = effects[0]->Change(td, Immersion::kDry);
    for (const auto& [exact, a, b] :
         {std::tuple{&d.stiffness, &up.stiffness, &down.stiffness},
          std::tuple{&d.mass, &up.mass, &down.mass}}) {
      const Eigen::MatrixXd fd = (Eigen::MatrixXd(*a) - Eigen::MatrixXd(*b)) / (2 * step);
      EXPECT_LT((Eigen::MatrixXd(*exact) - fd).cwiseAbs().maxCoeff(),
                1e-6 * fd.cwiseAbs().maxCoeff())
          << "parameter " << i;
    }
  }
  // A frame on base springs keeps its springs as the supports it softens.
  PlaneFrameSpec on_springs = spec;
  on_springs.base.rotation = 1e7;
  EXPECT_TRUE(BuildPlaneFrameStructure(on_springs).rigid_supports.empty());
}

TEST(PlaneFrameStructure, BaseSpringsAreSupportsWithTheirOwnDofs) {
  PlaneFrameSpec spec = Portal();
  const Structure clamped = BuildPlaneFrameStructure(spec);
  EXPECT_TRUE(clamped.supports.empty());
  EXPECT_NE(clamped.description.find("columns clamped"), std::string::npos);
  spec.base.rotation = 5e7;
  spec.base.vertical = 2e9;
  const Structure s = BuildPlaneFrameStructure(spec);
  // Two column bases, two sprung directions each, after the frame's own DOFs.
  ASSERT_EQ(s.dof_labels.size(), clamped.dof_labels.size() + 4);
  EXPECT_EQ(s.dof_labels[clamped.dof_labels.size()], "b1:uy");
  EXPECT_EQ(s.dof_labels.back(), "b2:rz");
  ASSERT_EQ(s.supports.size(), 4u);
  EXPECT_EQ(s.supports[1].name, "base rotation at b1");
  EXPECT_EQ(s.supports[1].unit, "N m/rad");
  EXPECT_EQ(s.supports[1].stiffness, 5e7);
  EXPECT_EQ(s.supports[0].unit, "N/m");
  EXPECT_EQ(s.stiffness.coeff(s.supports[1].dof, s.supports[1].dof) -
                s.elements[0].stiffness.coeff(s.supports[1].dof, s.supports[1].dof),
            5e7);
  EXPECT_EQ(s.nodes.back().name, "b2");
  EXPECT_EQ(s.nodes.back().xyz.x(), spec.bay_width);
  EXPECT_NE(
      s.description.find("on base springs (vertical 2e+09 N/m, rotation 5e+07 N m/rad"),
      std::string::npos)
      << s.description;
  // Stiff springs approach the clamp (steel columns: the base DOFs carry mass).
  spec.column.rho = 7850;
  spec.base = {};
  const Structure steel = BuildPlaneFrameStructure(spec);
  spec.base = {1e13, 1e15, 1e12};  // 10^5-10^6 times the members' own
  const Structure stiff = BuildPlaneFrameStructure(spec);
  const Modes near = SolveModes(stiff.stiffness, stiff.mass);
  const Modes exact = SolveModes(steel.stiffness, steel.mass);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(near.eigenvalues[k] / exact.eigenvalues[k], 1.0, 1e-4)
        << "mode " << k + 1;
}

TEST(PlaneFrameStructure, BaseSpringsFromAStudyFileAndTheirErrors) {
  const std::string frame =
      "name: portal\nmodel:\n  type: plane_frame\n  storeys: 1\n  bays: 1\n"
      "  storey_height: 3\n  bay_width: 5\n"
      "  column: {E: 210e9, A: 0.01, I: 8e-5, rho: 7850}\n"
      "  beam: {E: 210e9, A: 0.01, I: 2e-4, rho: 7850}\n";
  const Study study = ParseStudyModel(frame + "  base: {rotation: 3e7}\n", "portal.yaml");
  ASSERT_EQ(study.structure.supports.size(), 2u);
  EXPECT_EQ(study.structure.supports[0].stiffness, 3e7);
  for (const auto& [bad, field] : {std::pair<std::string, std::string>{
                                       "  base: {rotation: -1}\n", "model.base.rotation"},
                                   {"  base: {}\n", "model.base"},
                                   {"  base: {spin: 1}\n", "spin"}}) {
    try {
      ParseStudyModel(frame + bad, "portal.yaml");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

// With shear deformation, a fixed-guided column's sway stiffness is
// 12 E I / (h^3 (1 + phi)), phi = 12 E I / (kappa A G h^2): the portal's sway
// frequency with a column shear area small enough that phi is about 2.8.
TEST(PlaneFrameStructure, TimoshenkoPortalSwayHasTheShearTerm) {
  PlaneFrameSpec spec = Portal();
  spec.theory = BeamTheory::kTimoshenko;
  spec.column_shear_area = 1e-4;
  const Structure s = BuildPlaneFrameStructure(spec);
  // Nothing richer to allow for than its own members on a finer mesh.
  ASSERT_EQ(s.form_variants.size(), 1u);
  EXPECT_EQ(s.form_variants[0].name,
            "a finer mesh (16 elements per member instead of 4)");
  EXPECT_NE(s.description.find("Timoshenko"), std::string::npos);
  const Modes modes = SolveModes(s.stiffness, s.mass);
  const double beam_mass = spec.beam.rho * spec.beam.A * spec.bay_width;
  const double ei = spec.column.E * spec.column.I, h = spec.storey_height;
  const double g = spec.column.E / 2.6;
  const double phi = 12 * ei / (spec.column_shear_area * g * h * h);
  ASSERT_GT(phi, 2.0);
  const double exact = 24 * ei / (std::pow(h, 3) * (1 + phi)) / beam_mass;
  EXPECT_NEAR(modes.eigenvalues[0] / exact, 1.0, 2e-3);
}

// An Euler-Bernoulli frame carries its shear-deformable self and its finer
// mesh as form variants: the same frame built with Timoshenko members of half
// the area as shear area on four times its elements per member, base springs
// included, and the same frame on that mesh. Each on its own DOFs, with the
// model's DOFs at their places.
TEST(PlaneFrameStructure, FormVariantsAreTheFrameWithShearDeformationAndOnAFinerMesh) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(2, 2, 2);
  spec.base.rotation = 5e7;
  const Structure s = BuildPlaneFrameStructure(spec);
  ASSERT_EQ(s.form_variants.size(), 2u);
  PlaneFrameSpec finer = spec;
  finer.elements_per_member = 8;
  const Structure mesh = BuildPlaneFrameStructure(finer);
  finer.theory = BeamTheory::kTimoshenko;
  finer.column_shear_area = 0.5 * spec.column.A;
  finer.beam_shear_area = 0.5 * spec.beam.A;
  const Structure t = BuildPlaneFrameStructure(finer);
  auto max_abs = [](const SparseMatrix& a) {
    return Eigen::MatrixXd(a).cwiseAbs().maxCoeff();
  };
  const FormVariant& v = s.form_variants[0];
  EXPECT_NE(v.name.find("shear deformation"), std::string::npos);
  EXPECT_NE(v.name.find("on a finer mesh (8 elements per member instead of 2)"),
            std::string::npos);
  EXPECT_LT(max_abs(v.stiffness - t.stiffness), 1e-12 * max_abs(t.stiffness));
  EXPECT_LT(max_abs(v.mass - t.mass), 1e-12 * max_abs(t.mass));
  const FormVariant& m = s.form_variants[1];
  EXPECT_EQ(m.name, "a finer mesh (8 elements per member instead of 2)");
  EXPECT_LT(max_abs(m.stiffness - mesh.stiffness), 1e-12 * max_abs(mesh.stiffness));
  EXPECT_LT(max_abs(m.mass - mesh.mass), 1e-12 * max_abs(mesh.mass));
  ASSERT_EQ(v.dofs.size(), s.dof_labels.size());
  EXPECT_EQ(m.dofs, v.dofs);
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
    const std::string& a = s.dof_labels[i];
    const std::string& b = t.dof_labels[static_cast<std::size_t>(v.dofs[i])];
    EXPECT_EQ(a.substr(a.find(':')), b.substr(b.find(':'))) << a << " " << b;
  }
  // Softer, and lower on the finer mesh: every one of the lowest modes.
  const Modes eb = SolveModes(s.stiffness, s.mass);
  const Modes sheared = SolveModes(v.stiffness, v.mass);
  const Modes refined = SolveModes(m.stiffness, m.mass);
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT(sheared.eigenvalues[k], refined.eigenvalues[k]) << k;
    EXPECT_LE(refined.eigenvalues[k], eb.eigenvalues[k] * (1 + 1e-12)) << k;
  }
}

// Where the finer mesh would be more than a few thousand DOFs, the shear
// variant stays on the model's own mesh and there is no mesh variant.
TEST(PlaneFrameStructure, FormVariantsStayOnTheModelsMeshWhereAFinerOneIsLarge) {
  const Structure s = BuildPlaneFrameStructure(fixtures::PlaneFrame(20, 5, 4));
  ASSERT_GT(s.stiffness.rows(), 2000);
  ASSERT_EQ(s.form_variants.size(), 1u);
  EXPECT_TRUE(s.form_variants[0].dofs.empty());
  EXPECT_EQ(s.form_variants[0].stiffness.rows(), s.stiffness.rows());
  EXPECT_EQ(s.form_variants[0].name.find(" on a finer mesh"), std::string::npos);
}

TEST(PlaneFrameStructure, TheoryAndShearAreasFromAStudyFileAndTheirErrors) {
  const std::string head =
      "name: portal\nmodel:\n  type: plane_frame\n  storeys: 1\n  bays: 1\n"
      "  storey_height: 3\n  bay_width: 5\n"
      "  beam: {E: 210e9, A: 0.01, I: 2e-4, rho: 7850}\n";
  const Study study = ParseStudyModel(
      head +
          "  theory: timoshenko\n  column: {E: 210e9, A: 0.01, I: 8e-5, rho: 7850, "
          "shear_area: 0.004}\n",
      "portal.yaml");
  ASSERT_EQ(study.structure.form_variants.size(), 1u);  // its finer mesh alone
  EXPECT_EQ(study.structure.form_variants[0].name.find("shear"), std::string::npos);
  for (const auto& [bad, field] :
       {std::pair<std::string, std::string>{
            "  theory: bernoulli\n  column: {E: 210e9, A: 0.01, I: 8e-5, rho: 7850}\n",
            "model.theory"},
        {"  column: {E: 210e9, A: 0.01, I: 8e-5, rho: 7850, shear_area: 0.02}\n",
         "model.column.shear_area"},
        {"  column: {E: 210e9, A: 0.01, I: 8e-5, rho: 7850, shear_area: -1}\n",
         "model.column.shear_area"}}) {
    try {
      ParseStudyModel(head + bad, "portal.yaml");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

TEST(PlaneFrameStructure, RefusesAnInvalidSpecNamingTheField) {
  PlaneFrameSpec spec = Portal();
  spec.bays = 0;
  try {
    BuildPlaneFrameStructure(spec);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model.bays"), std::string::npos) << e.what();
  }
  spec = Portal();
  spec.base.rotation = -1;
  EXPECT_NE(
      spec.Validate().ToString().find("base.rotation: a spring stiffness must be >= 0"),
      std::string::npos);
  spec.base.rotation = 1e7;
  EXPECT_THROW(BuildPlaneFrame(spec), InputError);  // the benchmark frame is clamped
  spec = Portal();
  spec.beam_shear_area = -1;
  EXPECT_NE(spec.Validate().ToString().find("beam.shear_area: must be >= 0"),
            std::string::npos)
      << spec.Validate().ToString();
}

}  // namespace
}  // namespace femup
