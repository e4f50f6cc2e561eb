// A model's form variants on DOFs of their own (a finer mesh), made
// comparable with the model (femup/core/fe/form_variant.h).
#include "femup/core/fe/form_variant.h"

#include <gtest/gtest.h>

#include <cmath>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/linalg/modal.h"
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

}  // namespace
}  // namespace femup
