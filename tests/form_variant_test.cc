// A model's form variants on DOFs of their own (a finer mesh), made
// comparable with the model (femup/core/fe/form_variant.h).
#include "femup/core/fe/form_variant.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/model_effects.h"
#include "structure_specs.h"

namespace femup {
namespace {

// A one-bay, one-storey frame with a heavy beam (a floor's mass on it), two
// elements per member: its higher modes are the beam's and the columns' own
// bending, which two elements resolve poorly (plane_frame_026 of the blind
// suite, rounded).
PlaneFrameSpec HeavyPortal(int elements_per_member) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, elements_per_member, 3.9, 6.8);
  spec.column = {210e9, 3.0e-3, 1.0e-5, 7850};
  spec.beam = {210e9, 6.9e-3, 1.4e-4, 2.6e5};
  return spec;
}

TEST(MatchDofs, FindsEachDofAtItsPlaceOnTheFinerMesh) {
  PlaneFrameSpec spec = HeavyPortal(2);
  spec.base.rotation = 4e6;  // base DOFs: labelled without a node of the frame
  const Structure model = BuildPlaneFrameStructure(spec);
  spec.elements_per_member = 6;
  const Structure finer = BuildPlaneFrameStructure(spec);
  const std::vector<int> dofs = MatchDofs(model, finer);
  ASSERT_EQ(dofs.size(), model.dof_labels.size());
  auto position = [](const Structure& s, const std::string& label) {
    const std::string node = label.substr(0, label.find(':'));
    for (const ModelNode& n : s.nodes)
      if (n.name == node) return n.xyz;
    return Eigen::Vector3d(-1, -1, -1);
  };
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const std::string& a = model.dof_labels[i];
    const std::string& b = finer.dof_labels[static_cast<std::size_t>(dofs[i])];
    EXPECT_EQ(a.substr(a.find(':')), b.substr(b.find(':'))) << a << " " << b;
    EXPECT_LT((position(model, a) - position(finer, b)).norm(), 1e-12) << a << " " << b;
  }
  // The model's own DOFs match themselves.
  const std::vector<int> self = MatchDofs(model, model);
  for (std::size_t i = 0; i < self.size(); ++i) EXPECT_EQ(self[i], static_cast<int>(i));
}

TEST(MatchDofs, NamesWhatHasNoMatch) {
  const Structure model = BuildPlaneFrameStructure(HeavyPortal(2));
  // Odd elements per member: the members' middles are not nodes of the finer mesh.
  const Structure odd = BuildPlaneFrameStructure(HeavyPortal(3));
  testing::ExpectInputError([&] { MatchDofs(model, odd); }, {"has no DOF at its place"});
  ChainSpec chain;
  chain.masses = {1.0, 1.0};
  chain.springs = {10.0, 10.0};
  testing::ExpectInputError([&] { MatchDofs(BuildSpringMassChain(chain), model); },
                            {"no node coordinates"});
}

// The variant on the model's DOFs moves each of the model's lowest modes, to
// first order, by its eigenvalue on the finer mesh. And that change is the
// mesh's discretisation error: checked against the converged frame (32
// elements per member), not against the variant's own solve.
TEST(OnModelDofs, MovesEachModeAsTheFinerMeshDoes) {
  const Structure model = BuildPlaneFrameStructure(HeavyPortal(2));
  ASSERT_EQ(model.form_variants.size(), 2u);
  const FormVariant& mesh = model.form_variants[1];
  ASSERT_FALSE(mesh.dofs.empty());
  constexpr int kModes = 5;
  const FormVariant on = OnModelDofs(model, mesh, kModes);
  EXPECT_TRUE(on.dofs.empty());
  EXPECT_EQ(on.name, mesh.name);
  EXPECT_EQ(on.stiffness.rows(), model.stiffness.rows());
  EXPECT_LT(Eigen::MatrixXd(on.mass - model.mass).cwiseAbs().maxCoeff(), 1e-30);
  const Modes m = SolveModes(model.stiffness, model.mass);
  const Modes converged = SolveModes(BuildPlaneFrameStructure(HeavyPortal(32)).stiffness,
                                     BuildPlaneFrameStructure(HeavyPortal(32)).mass);
  const SparseMatrix dk = on.stiffness - model.stiffness;
  int resolved = 0;
  for (int i = 0; i < kModes; ++i) {
    const Eigen::VectorXd phi = m.shapes.col(i);
    const double change = phi.dot(dk * phi);
    const double error = converged.eigenvalues[i] - m.eigenvalues[i];
    EXPECT_LE(change, 1e-9 * m.eigenvalues[i]) << i;  // a finer mesh is softer
    if (std::abs(error) > 1e-3 * m.eigenvalues[i]) {
      // 8 elements per member close at least 95 % of the coarse mesh's error.
      EXPECT_NEAR(change / error, 1.0, 0.05) << i;
      ++resolved;
    }
  }
  EXPECT_GE(resolved, 2);  // the higher modes' errors are several per cent here
  // A variant already on the model's DOFs comes back as it is.
  const FormVariant same = OnModelDofs(model, on, kModes);
  EXPECT_EQ(same.stiffness.nonZeros(), on.stiffness.nonZeros());
  testing::ExpectInputError([&] { OnModelDofs(model, mesh, 0); }, {"modes must be in"});
  FormVariant short_map = mesh;
  short_map.dofs.pop_back();
  testing::ExpectInputError([&] { OnModelDofs(model, short_map, kModes); },
                            {"entries for a model of"});
}

// A square jacket's x and y sway modes are equal pairs in the model and in a
// finer Timoshenko variant, each in an arbitrary rotation from its solver: the
// variant's pairs are turned to the model's before pairing by MAC, so both of
// a pair move, and by the same amount (the symmetry's). (On the Intel Xeon of
// session 41 the two solvers' rotations agreed closely enough that this held
// without the turn too; AlignRepeatedModes' own test turns pairs on purpose.)
TEST(PairedModeChanges, EqualPairsOfASquareJacketMoveTogether) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 1, 1, 1, 10, 12, 12);
  spec.bracing = FaceBracing::kX;
  const Structure model = BuildSpaceFrameStructure(spec);
  SpaceFrameSpec fine = spec;
  fine.elements_per_member = 3;
  fine.theory = BeamTheory::kTimoshenko;
  const FormVariant v = FinerMeshVariant(model, BuildSpaceFrameStructure(fine), "finer");
  const ModeChanges c = PairedModeChanges(model, v, 6);
  ASSERT_NEAR(c.modes.eigenvalues[1] / c.modes.eigenvalues[0], 1.0, 1e-9);
  int pairs = 0;
  for (int first = 0; first < c.modes.size(); ++first) {
    const int last = static_cast<int>(LastOfRepeated(c.modes, first));
    if (last == first || last + 1 >= c.modes.size()) continue;
    ++pairs;
    for (int k = first; k <= last; ++k) {
      EXPECT_LT(c.eigenvalue_change[k], -1e-4 * c.modes.eigenvalues[k]) << k;
      EXPECT_NEAR(c.eigenvalue_change[k], c.eigenvalue_change[first],
                  1e-6 * c.modes.eigenvalues[k])
          << k;
    }
    first = last;
  }
  EXPECT_GE(pairs, 1);
}

// The finer mesh as a model the diagnosis can run on: the same matrices as the
// finer frame built directly, its nodes at the model's places named as the
// model's, and the model's attached-mass candidates (its nodes, and one line
// of finer segments per model segment).
TEST(RefinedModel, NamesTheFinerMeshAsTheModel) {
  const Structure model = BuildPlaneFrameStructure(HeavyPortal(2));
  ASSERT_EQ(model.form_variants.size(), 2u);
  const FormVariant& mesh = model.form_variants[1];
  ASSERT_NE(mesh.model, nullptr);
  EXPECT_EQ(model.form_variants[0].model, nullptr);  // the shear variant is no model
  const Structure& fine = *mesh.model;
  const Structure direct = BuildPlaneFrameStructure(HeavyPortal(8));
  ASSERT_EQ(fine.stiffness.rows(), direct.stiffness.rows());
  EXPECT_EQ(Eigen::MatrixXd(fine.stiffness - direct.stiffness).cwiseAbs().maxCoeff(), 0);
  EXPECT_EQ(Eigen::MatrixXd(fine.mass - direct.mass).cwiseAbs().maxCoeff(), 0);
  for (std::size_t i = 0; i < model.dof_labels.size(); ++i)
    EXPECT_EQ(fine.dof_labels[static_cast<std::size_t>(mesh.dofs[i])],
              model.dof_labels[i]);
  int inner = 0;
  for (const ModelNode& n : fine.nodes) {
    bool named = false;
    for (const ModelNode& m : model.nodes) named = named || m.name == n.name;
    if (!named) {
      EXPECT_EQ(n.name[0], 'f') << n.name;
      ++inner;
    }
  }
  EXPECT_EQ(inner, static_cast<int>(fine.nodes.size() - model.nodes.size()));
  EXPECT_EQ(fine.attached_mass_nodes.size(), model.nodes.size());
  ASSERT_EQ(fine.attached_mass_lines.size(), model.segments.size());
  for (std::size_t i = 0; i < model.segments.size(); ++i) {
    const std::vector<int>& line = fine.attached_mass_lines[i];
    ASSERT_EQ(line.size(), 4u);
    const LineSegment& first = fine.segments[static_cast<std::size_t>(line.front())];
    const LineSegment& last = fine.segments[static_cast<std::size_t>(line.back())];
    EXPECT_LT((first.a - model.segments[i].a).norm(), 1e-12);
    EXPECT_LT((last.b - model.segments[i].b).norm(), 1e-12);
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      EXPECT_EQ(fine.segments[static_cast<std::size_t>(line[k])].node_b,
                fine.segments[static_cast<std::size_t>(line[k + 1])].node_a);
  }
  // The attached-mass candidates are the model's, by name.
  std::set<std::string> on_model, on_fine;
  for (const auto& e : CreateModelEffects("attached_mass", model))
    on_model.insert(e->region().name);
  for (const auto& e : CreateModelEffects("attached_mass", fine))
    on_fine.insert(e->region().name);
  EXPECT_EQ(on_fine, on_model);
  // Its own form variant: shear deformation on its own DOFs.
  ASSERT_EQ(fine.form_variants.size(), 1u);
  EXPECT_TRUE(fine.form_variants[0].dofs.empty());
  EXPECT_EQ(fine.form_variants[0].name.find("finer mesh"), std::string::npos);
  EXPECT_NE(fine.form_variants[0].name.find("shear deformation"), std::string::npos);
  // A Timoshenko frame's finer mesh carries no variant of its own.
  PlaneFrameSpec timoshenko = HeavyPortal(2);
  timoshenko.theory = BeamTheory::kTimoshenko;
  const Structure t = BuildPlaneFrameStructure(timoshenko);
  ASSERT_EQ(t.form_variants.size(), 1u);
  ASSERT_NE(t.form_variants[0].model, nullptr);
  EXPECT_TRUE(t.form_variants[0].model->form_variants.empty());
  // A finer model that does not hold the model's nodes.
  testing::ExpectInputError(
      [&] { RefinedModel(model, BuildPlaneFrameStructure(HeavyPortal(3))); },
      {"has no DOF at its place"});
}

// A mass on a line of finer segments sits on the segment its position falls
// in: at a finer node, it is that node's point mass (and its rotary inertia
// that node's, on its rotation); its slope is the change's derivative with
// respect to the position.
TEST(RefinedModel, AMassAlongALineIsOnTheSegmentItFallsIn) {
  const Structure model = BuildPlaneFrameStructure(HeavyPortal(2));
  const Structure& fine = *model.form_variants[1].model;
  for (const bool rotary : {false, true}) {
    SCOPED_TRACE(rotary ? "with rotary inertia" : "translations only");
    ModelEffectOptions options;
    options.rotary_inertia = rotary;
    const auto effects = CreateModelEffects("attached_mass", fine, options);
    const ModelEffect* line = nullptr;
    for (const auto& e : effects)
      if (e->region().name == "n1-n5") line = e.get();  // the beam's first half
    ASSERT_NE(line, nullptr);
    // Half way along n1-n5: a finer node (4 segments on the line).
    const Eigen::Vector3d middle = 0.5 * (model.nodes[0].xyz + model.nodes[4].xyz);
    int node = -1;
    for (std::size_t k = 0; k < fine.nodes.size(); ++k)
      if ((fine.nodes[k].xyz - middle).norm() < 1e-9) node = static_cast<int>(k);
    ASSERT_GE(node, 0);
    const std::string name = fine.nodes[static_cast<std::size_t>(node)].name;
    Eigen::VectorXd theta(rotary ? 3 : 2);
    theta[0] = std::log(0.01);
    theta[1] = 0.5;
    if (rotary) theta[2] = std::log(0.1);  // r a tenth of the frame's extent
    ASSERT_EQ(line->Parameters().size(), static_cast<std::size_t>(theta.size()));
    const SparseMatrix dm = line->Change(theta, Immersion::kDry).mass;
    const double m = 0.01 * ReferenceMass(fine);
    const double j = rotary ? m * std::pow(0.1 * ReferenceLength(fine), 2) : 0.0;
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(dm.rows(), dm.cols());
    for (std::size_t i = 0; i < fine.dof_labels.size(); ++i) {
      const auto at = static_cast<Eigen::Index>(i);
      if (fine.dof_labels[i] == name + ":ux" || fine.dof_labels[i] == name + ":uy")
        expected(at, at) = m;
      if (fine.dof_labels[i] == name + ":rz") expected(at, at) = j;
    }
    EXPECT_LT((Eigen::MatrixXd(dm) - expected).cwiseAbs().maxCoeff(), 1e-9 * m);
    // d(dM)/dxi by central differences, inside a segment (xi = 0.4: the second).
    for (const double xi : {0.4, 0.8}) {
      theta[1] = xi;
      const double h = 1e-6;
      Eigen::VectorXd up = theta, down = theta;
      up[1] += h;
      down[1] -= h;
      const Eigen::MatrixXd numeric =
          Eigen::MatrixXd(line->Change(up, Immersion::kDry).mass -
                          line->Change(down, Immersion::kDry).mass) /
          (2 * h);
      const Eigen::MatrixXd analytic = line->Derivative(theta, 1, Immersion::kDry).mass;
      EXPECT_LT((numeric - analytic).cwiseAbs().maxCoeff(),
                1e-5 * analytic.cwiseAbs().maxCoeff())
          << xi;
    }
  }
}

}  // namespace
}  // namespace femup
