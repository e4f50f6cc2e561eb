// Sensors between nodes (femup/sensor.h): checked against closed forms, not
// against the code's own output.
#include "femup/core/fe/sensor.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <random>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "paper_beam.h"
#include "structure_specs.h"

namespace femup {
namespace {

double Read(const SensorRow& row, const Eigen::VectorXd& u) {
  double v = 0;
  for (const auto& [dof, w] : row.weights) v += w * u[dof];
  return v;
}

int Dof(const Structure& s, const std::string& label) {
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i)
    if (s.dof_labels[i] == label) return static_cast<int>(i);
  return -1;
}

// A clamped cantilever of 3 unequal elements under a transverse tip load P:
// the Euler-Bernoulli deflection w(y) = P y^2 (3 L - y) / (6 EI) is a cubic in
// each element, so the Hermite interpolation between nodes is exact.
TEST(Sensor, CantileverTipLoadDeflectionBetweenNodesIsTheClosedForm) {
  CantileverSpec spec = fixtures::PaperCantilever({0.0, 0.2, 0.55, 0.9});
  const Structure s = BuildCantilever(spec);
  const double length = 0.9, load = 3.0;
  const double ei = spec.section.E * spec.section.I;
  Eigen::VectorXd f =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.dof_labels.size()));
  f[Dof(s, "n3:ux")] = load;
  const Eigen::SimplicialLDLT<SparseMatrix> solver(s.stiffness);
  const Eigen::VectorXd u = solver.solve(f);
  SensorSpec at_clamp;
  at_clamp.has_x = true;
  SensorRow none;
  const Invalid clamped = LocateSensor(s, at_clamp, &none);
  EXPECT_EQ(clamped.field, "x");
  EXPECT_NE(clamped.message.find("rigid support"), std::string::npos) << clamped.message;
  for (double y : {0.05, 0.2, 0.31, 0.55, 0.7, 0.9}) {
    SensorSpec sensor;
    sensor.has_x = true;
    sensor.x = y;
    SensorRow row;
    ASSERT_FALSE(LocateSensor(s, sensor, &row)) << y;
    const double w = load * y * y * (3 * length - y) / (6 * ei);
    EXPECT_NEAR(Read(row, u), w, 1e-9 * std::abs(load * length * length * length / ei))
        << "y = " << y << " (" << row.name << ")";
    // Rotation about z at y: rz = -dw/dy = -P y (2 L - y) / (2 EI).
    const LineSegment* seg = nullptr;
    double xi = 0;
    for (const LineSegment& g : s.segments) {
      if (y >= g.a.y() - 1e-12 && y <= g.b.y() + 1e-12) {
        seg = &g;
        xi = (y - g.a.y()) / (g.b.y() - g.a.y());
        break;
      }
    }
    ASSERT_NE(seg, nullptr);
    SensorRow rot;
    rot.weights = SegmentWeights(s, *seg, xi, Eigen::Vector3d::UnitZ(), true);
    EXPECT_NEAR(Read(rot, u), -load * y * (2 * length - y) / (2 * ei),
                1e-9 * load * length * length / ei)
        << "y = " << y;
  }
}

// Any rigid motion u(p) = t + w x (p - p0), theta = w is in the span of the
// shape functions: the interpolation must give it back exactly at every point
// of every member of a 3D frame (the slope term's sign and the axial part).
TEST(Sensor, RigidMotionOfASpaceFrameIsInterpolatedExactly) {
  SpaceFrameSpec spec = fixtures::SpaceFrame(2, 1, 1, 2, 8, 12, 10);
  const Structure s = BuildSpaceFrameStructure(spec);
  const Eigen::Vector3d t(0.3, -0.2, 0.1), w(0.02, -0.05, 0.03), p0(1, 2, 3);
  Eigen::VectorXd u =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.dof_labels.size()));
  for (const ModelNode& n : s.nodes) {
    const Eigen::Vector3d v = t + w.cross(n.xyz - p0);
    const char* names[6] = {":ux", ":uy", ":uz", ":rx", ":ry", ":rz"};
    for (int k = 0; k < 6; ++k) {
      const int d = Dof(s, n.name + names[k]);
      ASSERT_GE(d, 0);
      u[d] = k < 3 ? v[k] : w[k - 3];
    }
  }
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (const LineSegment& g : s.segments) {
    if (g.node_a < 0 || g.node_b < 0) continue;  // the clamped base is not rigid motion
    const double xi = unit(rng);
    const Eigen::Vector3d p = g.a + xi * (g.b - g.a);
    Eigen::Vector3d d(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
    d.normalize();
    SensorSpec sensor;
    sensor.has_at = true;
    sensor.at = p;
    sensor.direction = d;
    SensorRow row;
    ASSERT_FALSE(LocateSensor(s, sensor, &row));
    EXPECT_NEAR(Read(row, u), d.dot(t + w.cross(p - p0)), 1e-12);
    SensorRow rot;
    rot.weights = SegmentWeights(s, g, xi, d, true);
    EXPECT_NEAR(Read(rot, u), d.dot(w), 1e-12);
    // The same weights from an index of the segment's two nodes made once
    // (IndexDofLabels), for translation and rotation and their slopes.
    const DofLabelIndex own =
        IndexDofLabels(s, {s.nodes[static_cast<std::size_t>(g.node_a)].name,
                           s.nodes[static_cast<std::size_t>(g.node_b)].name});
    EXPECT_EQ(own.size(), 12u);
    for (bool rotation : {false, true}) {
      for (bool slope : {false, true}) {
        EXPECT_EQ(SegmentWeights(s, own, g, xi, d, rotation, slope),
                  SegmentWeights(s, g, xi, d, rotation, slope));
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 20);
  const DofLabelIndex all = IndexDofLabels(s);
  ASSERT_EQ(all.size(), s.dof_labels.size());
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i)
    EXPECT_EQ(all.at(s.dof_labels[i]), static_cast<int>(i));
}

TEST(Sensor, OnANodeItReadsThatDof) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(2, 1, 2);
  const Structure s = BuildPlaneFrameStructure(spec);
  SensorSpec by_node;
  by_node.node = "n2";
  by_node.direction = Eigen::Vector3d::UnitX();
  SensorRow row;
  ASSERT_FALSE(LocateSensor(s, by_node, &row));
  EXPECT_EQ(row.SingleDof(), Dof(s, "n2:ux"));
  EXPECT_EQ(row.name, "n2:ux");
  SensorSpec at;
  at.has_at = true;
  at.at = s.nodes[1].xyz;
  at.direction = -Eigen::Vector3d::UnitY();
  ASSERT_FALSE(LocateSensor(s, at, &row));
  ASSERT_EQ(row.weights.size(), 1u);
  EXPECT_EQ(row.weights[0].first, Dof(s, s.nodes[1].name + ":uy"));
  EXPECT_DOUBLE_EQ(row.weights[0].second, -1.0);
  SensorSpec label;
  label.dof = "-n3:uy";
  ASSERT_FALSE(LocateSensor(s, label, &row));
  EXPECT_EQ(row.weights, (std::vector<std::pair<int, double>>{{Dof(s, "n3:uy"), -1.0}}));
}

TEST(Sensor, BadPlacementsNameTheFieldAndWhatIsWrong) {
  PlaneFrameSpec spec = fixtures::PlaneFrame(1, 1, 2, 3, 6);
  const Structure frame = BuildPlaneFrameStructure(spec);
  SensorRow row;
  SensorSpec off;
  off.has_at = true;
  off.at = Eigen::Vector3d(3.0, 1.0, 0.0);  // inside the portal, on no member
  off.direction = Eigen::Vector3d::UnitX();
  Invalid bad = LocateSensor(frame, off, &row);
  EXPECT_EQ(bad.field, "at");
  EXPECT_NE(bad.message.find("is not on the structure"), std::string::npos)
      << bad.message;
  EXPECT_NE(bad.message.find("m away"), std::string::npos) << bad.message;

  SensorSpec out_of_plane = off;
  out_of_plane.at = Eigen::Vector3d(3.0, 3.0, 0.0);
  out_of_plane.direction = Eigen::Vector3d::UnitZ();
  bad = LocateSensor(frame, out_of_plane, &row);
  EXPECT_EQ(bad.field, "direction");
  EXPECT_NE(bad.message.find("no DOFs along z"), std::string::npos) << bad.message;

  SensorSpec no_direction = off;
  no_direction.at = Eigen::Vector3d(3.0, 3.0, 0.0);
  no_direction.direction.setZero();
  EXPECT_EQ(LocateSensor(frame, no_direction, &row).field, "direction");

  SensorSpec node;
  node.node = "n99";
  node.direction = Eigen::Vector3d::UnitX();
  bad = LocateSensor(frame, node, &row);
  EXPECT_EQ(bad.field, "node");
  EXPECT_NE(bad.message.find("'n99'"), std::string::npos);

  SensorSpec along;
  along.has_x = true;
  along.x = 1.0;
  bad = LocateSensor(frame, along, &row);
  EXPECT_EQ(bad.field, "x");
  EXPECT_NE(bad.message.find("cantilever"), std::string::npos) << bad.message;

  const Structure beam = BuildCantilever(fixtures::PaperCantilever({0.0, 0.3, 0.6}));
  along.x = 0.7;
  bad = LocateSensor(beam, along, &row);
  EXPECT_EQ(bad.field, "x");
  EXPECT_NE(bad.message.find("0..0.6"), std::string::npos) << bad.message;

  ChainSpec chain;
  chain.masses = {1.0, 1.0};
  chain.springs = {100.0, 100.0};
  const Structure c = BuildSpringMassChain(chain);
  node.node = "n1";
  bad = LocateSensor(c, node, &row);
  EXPECT_FALSE(bad.ok());
  SensorSpec two;
  two.dof = "x1";
  two.node = "n1";
  EXPECT_FALSE(LocateSensor(c, two, &row).ok());
  SensorSpec dof;
  dof.dof = "x7";
  bad = LocateSensor(c, dof, &row);
  EXPECT_EQ(bad.field, "dof");
  EXPECT_NE(bad.message.find("'x7'"), std::string::npos);

  Eigen::Vector3d d;
  EXPECT_FALSE(ParseSensorDirection("-y", &d));
  EXPECT_EQ(d, -Eigen::Vector3d::UnitY());
  EXPECT_EQ(ParseSensorDirection("up", &d).field, "direction");
}

TEST(Sensor, ReadSensorsAndSensorMatrixAgree) {
  std::vector<SensorRow> rows(2);
  rows[0].weights = {{0, 0.5}, {2, 0.25}};
  rows[1].weights = {{1, -1.0}};
  Eigen::MatrixXd shapes(3, 2);
  shapes << 1, 2, 3, 4, 5, 6;
  const Eigen::MatrixXd read = ReadSensors(rows, shapes);
  EXPECT_DOUBLE_EQ(read(0, 0), 0.5 * 1 + 0.25 * 5);
  EXPECT_DOUBLE_EQ(read(1, 1), -4.0);
  const Eigen::MatrixXd via_matrix = SensorMatrix(rows, 3) * shapes;
  EXPECT_TRUE(read.isApprox(via_matrix));
}

}  // namespace
}  // namespace femup
