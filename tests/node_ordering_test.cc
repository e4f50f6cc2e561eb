// The eigensolver's options from a model's DOF labels (node_ordering.h).
#include "femup/core/linalg/node_ordering.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "femup/core/fe/space_frame.h"
#include "femup/core/linalg/modal.h"
#include "structure_specs.h"

namespace femup {
namespace {

TEST(NodeOrdering, NodesFromTheLabelsInOrderOfFirstAppearance) {
  EXPECT_EQ(DofNodesFromLabels({"n1:ux", "n1:uy", "n2:ux", "b", "n1:rz", "b"}),
            (std::vector<int>{0, 0, 1, 2, 0, 3}));
  EXPECT_TRUE(DofNodesFromLabels({}).empty());
}

// A frame's labels (several DOFs to a node) set the groups and leave every
// other option as it was; a chain's (one DOF to a node), no labels and fewer
// labels than the size asked for leave the options alone.
TEST(NodeOrdering, GroupsOnlyWhereANodeHoldsSeveralDofs) {
  EigenOptions base;
  base.num_modes = 4;
  base.shift = -2.5;
  base.tolerance = 1e-9;
  base.threads = 1;
  const std::vector<std::string> frame_labels = {"n1:ux", "n1:uy", "n1:rz", "n2:ux"};
  const EigenOptions frame = WithNodeOrdering(base, frame_labels, 0);
  EXPECT_EQ(frame.dof_groups, (std::vector<int>{0, 0, 0, 1}));
  EXPECT_EQ(frame.num_modes, 4);
  EXPECT_EQ(frame.shift, -2.5);
  EXPECT_EQ(frame.tolerance, 1e-9);
  EXPECT_EQ(frame.threads, 1);
  EXPECT_TRUE(WithNodeOrdering(base, {"x1", "x2", "x3"}, 0).dof_groups.empty());
  EXPECT_TRUE(WithNodeOrdering(base, {}, 0).dof_groups.empty());
  // Below the size where the node graph pays (the default): unchanged.
  EXPECT_TRUE(WithNodeOrdering(base, frame_labels).dof_groups.empty());
  EXPECT_TRUE(WithNodeOrdering(base, frame_labels, 5).dof_groups.empty());
}

// On a space frame (6 DOFs to a node) the node-ordered sparse solve gives the
// dense solver's lowest modes: the eigenvalues to 1e-9, and every shape inside
// the dense solver's eigenspace of its eigenvalue to 1e-6 (a pair of equal
// frequencies may come in any rotation, so shapes are compared by subspace).
TEST(NodeOrdering, SpaceFrameSolvedOnItsNodeGraphMatchesTheDenseSolver) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(3, 2, 1, 2);
  spec.bay_width_y = 12.0;
  const ParametrisedModel model = BuildSpaceFrame(spec);
  ASSERT_GT(model.num_dofs(), 600);
  EigenOptions sparse;
  sparse.method = EigenOptions::Method::kSparseShiftInvert;
  sparse.num_modes = 8;
  sparse = WithNodeOrdering(sparse, model.dof_labels(), 0);
  ASSERT_EQ(sparse.dof_groups.size(), static_cast<std::size_t>(model.num_dofs()));
  const Modes by_nodes = SolveModes(model.stiffness(), model.mass(), sparse);
  EigenOptions dense;
  dense.method = EigenOptions::Method::kDense;
  const Modes all = SolveModes(model.stiffness(), model.mass(), dense);
  ASSERT_EQ(by_nodes.size(), 8);
  const Eigen::MatrixXd m = Eigen::MatrixXd(model.mass());
  for (int j = 0; j < 8; ++j) {
    SCOPED_TRACE(j);
    EXPECT_NEAR(by_nodes.eigenvalues[j] / all.eigenvalues[j], 1.0, 1e-9);
    // The part of the shape outside the dense solver's eigenspace of the same
    // eigenvalue (M-orthogonal projection): zero up to the tolerance.
    Eigen::VectorXd rest = by_nodes.shapes.col(j);
    for (int i = 0; i < all.size(); ++i) {
      if (std::abs(all.eigenvalues[i] / all.eigenvalues[j] - 1.0) > 1e-6) continue;
      rest -= all.shapes.col(i) * all.shapes.col(i).dot(m * rest);
    }
    EXPECT_LT(std::sqrt(rest.dot(m * rest)), 1e-6);
  }
}

}  // namespace
}  // namespace femup
