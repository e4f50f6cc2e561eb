// The large plane frame builder (core/include/femup/core/fe/plane_frame.h), checked
// against counts from its definition, the sums of its substructure matrices,
// the total mass, and the sway stiffness of a portal frame with a rigid beam
// (two fixed-guided columns: 24 E I / h^3).
#include "femup/core/fe/plane_frame.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <string>

#include "femup/core/errors.h"
#include "structure_specs.h"

namespace femup {
namespace {

TEST(PlaneFrame, CountsFollowTheSpec) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(4, 3, 2);
  spec.blocks_per_storey = 3;
  spec.wet_storeys = 2;
  const ParametrisedModel m = BuildPlaneFrame(spec);
  // Joints: 4 lines x 4 levels; one node inside each of 16 columns + 12 beams.
  EXPECT_EQ(m.num_dofs(), 3 * (16 + 28));
  // 4 mass + 4 x 3 x 2 stiffness + 2 x 3 added mass.
  EXPECT_EQ(m.num_parameters(), 4 + 24 + 6);
  EXPECT_EQ(m.parameter(0).name, "mass[s1]");
  EXPECT_EQ(m.parameter(4).name, "stiffness[s1:col1]");
  EXPECT_EQ(m.parameter(5).name, "stiffness[s1:beam1]");
  EXPECT_EQ(m.parameter(28).name, "added_mass[s1:col1]");
  EXPECT_EQ(m.dof_labels()[0], "n1:ux");

  // Stiffness blocks sum to K, storey masses to M.
  SparseMatrix k_sum(m.num_dofs(), m.num_dofs()), m_sum(m.num_dofs(), m.num_dofs());
  for (const Parameter& p : m.parameters()) {
    if (p.kind == ParameterKind::kStiffness) k_sum += p.basis.ToSparse();
    if (p.kind == ParameterKind::kMass) m_sum += p.basis.ToSparse();
  }
  EXPECT_LT(Eigen::MatrixXd(k_sum - m.stiffness()).cwiseAbs().maxCoeff(),
            1e-12 * Eigen::MatrixXd(m.stiffness()).cwiseAbs().maxCoeff());
  EXPECT_LT(Eigen::MatrixXd(m_sum - m.mass()).cwiseAbs().maxCoeff(), 1e-9);

  // A unit horizontal translation of every free node moves all beams rigidly
  // and the columns except at their clamped bases: u' M u lies between the
  // beams' mass plus half and plus all of the columns' mass.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(m.num_dofs());
  for (int i = 0; i < m.num_dofs(); i += 3) u[i] = 1.0;
  const double moved = u.dot(m.mass() * u);
  const double beams = spec.beam.rho * spec.beam.A * spec.bay_width * 3 * 4;
  const double columns = spec.column.rho * spec.column.A * spec.storey_height * 4 * 4;
  EXPECT_GT(moved, beams + columns * 0.5);
  EXPECT_LT(moved, beams + columns);
}

TEST(PlaneFrame, PortalSwayStiffnessWithARigidBeam) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 3);
  spec.storey_height = 3.0;
  spec.column = {210e9, 100.0, 1e-4, 7850};  // axially rigid
  spec.beam = {210e9, 1.0, 100.0, 7850};     // rigid in bending too
  const ParametrisedModel m = BuildPlaneFrame(spec);
  // Joint (line 0, level 1) is node 1; push it horizontally.
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m.num_dofs());
  f[m.FindDof("n1:ux")] = 1000.0;
  const Eigen::SimplicialLDLT<SparseMatrix> solver(m.stiffness());
  ASSERT_EQ(solver.info(), Eigen::Success);
  const Eigen::VectorXd x = solver.solve(f);
  const double expected = 1000.0 * 27.0 / (24.0 * 210e9 * 1e-4);
  const double left = x[m.FindDof("n1:ux")], right = x[m.FindDof("n2:ux")];
  EXPECT_NEAR(0.5 * (left + right), expected, 1e-5 * expected);
  // The beam carries half the load to the far column: it shortens by
  // (P / 2) L / (E A).
  EXPECT_NEAR(left - right, 500.0 * 6.0 / (210e9 * 1.0), 1e-3 * 500.0 * 6.0 / 210e9);
}

TEST(PlaneFrame, BadSpecNamesTheField) {
  auto expect = [](PlaneFrameSpec spec, const std::string& field) {
    try {
      BuildPlaneFrame(spec);
      ADD_FAILURE() << "no error for " << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  PlaneFrameSpec s;
  s.storeys = 0;
  expect(s, "storeys");
  s = {};
  s.blocks_per_storey = 9;
  expect(s, "blocks_per_storey");
  s = {};
  s.wet_storeys = 11;
  expect(s, "wet_storeys");
  s = {};
  s.beam.I = -1;
  expect(s, "beam");
  s = {};
  s.elements_per_member = 0;
  expect(s, "elements_per_member");
}

}  // namespace
}  // namespace femup
