// Mode-shape expansion (core/include/femup/core/sysid/expansion.h) against full-DOF
// truth: a cantilever's own modes seen at a few sensors must expand back to the full mode
// (exactly, for serep/lsq when the mode is in the basis, and for dynamic expansion with
// the mode's eigenvalue); a shape outside the basis shows in the sensor MAC.
#include "femup/core/sysid/expansion.h"

#include <gtest/gtest.h>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/sensor.h"
#include "femup/core/fe/structure.h"

namespace femup {
namespace {

struct Beam {
  SparseMatrix k, m;
  Modes modes;
};

Beam MakeBeam() {
  CantileverSpec spec;
  spec.node_heights = UniformHeights(1.9, 10);
  spec.section = BeamSection{206e9, 8.8e-4, 8.53e-8, 7850};
  const Structure s = BuildCantilever(spec);
  Beam b{s.stiffness, s.mass, {}};
  b.modes = SolveModes(b.k, b.m);
  return b;
}

// Transverse DOFs of nodes 2, 4, 6, 8, 10 (labels n<k>:ux; 3 DOFs per node).
std::vector<int> Sensors() { return {3, 9, 15, 21, 27}; }

double Distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double s = a.dot(b) < 0 ? -1.0 : 1.0;
  return (a - s * b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(Expansion, ModesInTheBasisExpandExactly) {
  const Beam b = MakeBeam();
  const std::vector<int> sensors = Sensors();
  for (int j = 0; j < 3; ++j) {
    const Eigen::VectorXd truth = b.modes.shapes.col(j);
    const Eigen::VectorXd at_sensors = 2.5 * truth(sensors);  // any scaling
    for (const char* method : {"serep", "lsq"}) {
      ExpansionOptions o;
      o.method = method;
      o.num_modes = 4;
      const ExpandedShape e =
          ExpandShape(b.k, b.m, b.modes, sensors, at_sensors, b.modes.eigenvalues[j], o);
      EXPECT_LT(Distance(e.shape, 2.5 * truth), 1e-9) << method << " mode " << j + 1;
      EXPECT_NEAR(e.sensor_mac, 1.0, 1e-12);
      EXPECT_GT(e.condition_number, 1.0);
      if (std::string(method) == "lsq") {
        EXPECT_EQ(e.shape(sensors), at_sensors);  // measured entries kept
      } else {
        EXPECT_LT((e.shape(sensors) - at_sensors).cwiseAbs().maxCoeff(),
                  1e-9 * at_sensors.cwiseAbs().maxCoeff());  // fitted
      }
    }
    ExpansionOptions d;
    d.method = "dynamic";
    const ExpandedShape e = ExpandShape(b.k, b.m, b.modes, sensors, truth(sensors),
                                        b.modes.eigenvalues[j], d);
    EXPECT_LT(Distance(e.shape, truth), 1e-7) << "dynamic mode " << j + 1;
  }
}

// Sensors between nodes (a matrix of interpolation weights, femup/sensor.h):
// serep and lsq fit the modal coordinates to the interpolated rows, exact for
// a mode in the basis; dynamic needs DOFs and is refused naming the others.
TEST(Expansion, SensorsBetweenNodesExpandExactly) {
  CantileverSpec spec;
  spec.node_heights = UniformHeights(1.9, 10);
  spec.section = BeamSection{206e9, 8.8e-4, 8.53e-8, 7850};
  const Structure s = BuildCantilever(spec);
  const Beam b = MakeBeam();
  std::vector<SensorRow> rows;
  for (double x : {0.33, 0.71, 1.05, 1.42, 1.77}) {
    SensorSpec at;
    at.has_x = true;
    at.x = x;
    SensorRow row;
    ASSERT_FALSE(LocateSensor(s, at, &row));
    rows.push_back(row);
  }
  const SparseMatrix c = SensorMatrix(rows, static_cast<int>(s.dof_labels.size()));
  for (int j = 0; j < 3; ++j) {
    const Eigen::VectorXd truth = b.modes.shapes.col(j);
    const Eigen::VectorXd at_sensors = -1.7 * (c * truth);
    for (const char* method : {"serep", "lsq"}) {
      ExpansionOptions o;
      o.method = method;
      o.num_modes = 4;
      const ExpandedShape e =
          ExpandShape(b.k, b.m, b.modes, c, at_sensors, b.modes.eigenvalues[j], o);
      EXPECT_LT(Distance(e.shape, -1.7 * truth), 1e-9) << method << " mode " << j + 1;
      EXPECT_NEAR(e.sensor_mac, 1.0, 1e-12);
    }
  }
  ExpansionOptions d;
  d.method = "dynamic";
  try {
    ExpandShape(b.k, b.m, b.modes, c, c * b.modes.shapes.col(0), b.modes.eigenvalues[0],
                d);
    ADD_FAILURE() << "dynamic expansion from points accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("use serep or lsq"), std::string::npos)
        << e.what();
  }
}

TEST(Expansion, ShapeOutsideTheBasisShowsInTheSensorMac) {
  const Beam b = MakeBeam();
  const std::vector<int> sensors = Sensors();
  ExpansionOptions o;
  o.num_modes = 2;  // modes 1-2 cannot represent mode 4
  const Eigen::VectorXd measured = b.modes.shapes.col(3)(sensors);
  const ExpandedShape e =
      ExpandShape(b.k, b.m, b.modes, sensors, measured, b.modes.eigenvalues[3], o);
  EXPECT_LT(e.sensor_mac, 0.5);
  o.method = "lsq";
  const ExpandedShape l =
      ExpandShape(b.k, b.m, b.modes, sensors, measured, b.modes.eigenvalues[3], o);
  EXPECT_EQ(l.shape(sensors), measured);
  EXPECT_DOUBLE_EQ(l.sensor_mac, e.sensor_mac);
}

TEST(Expansion, BadInputNamesTheField) {
  const Beam b = MakeBeam();
  const Eigen::VectorXd v = Eigen::VectorXd::Ones(3);
  auto expect = [&](const std::vector<int>& sensors, const Eigen::VectorXd& m,
                    ExpansionOptions o, const std::string& field) {
    try {
      ExpandShape(b.k, b.m, b.modes, sensors, m, 100.0, o);
      ADD_FAILURE() << "no error for " << field;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect({3, 9, 9}, v, {}, "sensors");
  expect({3, 9, 999}, v, {}, "sensors");
  expect({3, 9}, v, {}, "measured");
  ExpansionOptions o;
  o.num_modes = 4;
  expect({3, 9, 15}, v, o, "num_modes");
  o = {};
  o.method = "guyan";
  expect({3, 9, 15}, v, o, "method");
}

}  // namespace
}  // namespace femup
