// Measured modal data (core/include/femup/core/sysid/measurement.h): validation messages,
// reordering of sensor rows, and the modes predicted for the paper's chain
// (values from method.md, section 4).
#include "femup/core/sysid/measurement.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "femup/core/errors.h"
#include "femup/core/linalg/modal.h"
#include "femup/problems/paper_chain.h"

namespace femup {
namespace {

const double kPi = std::acos(-1.0);
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two modes measured at sensors on DOFs 3, 0, 1 of a 4-DOF model.
ModalData ThreeSensors() {
  ModalData d;
  d.state = "air";
  d.frequencies_hz = Eigen::Vector2d(2.0, 5.0);
  d.shapes.resize(3, 2);
  d.shapes << 1.0, -0.5,  //
      2.0, 0.25,          //
      3.0, 1.0;
  d.sensor_dofs = {3, 0, 1};
  return d;
}

// The message of the InputError thrown by Validate, or "(no exception)".
std::string WhatOfValidate(const ModalData& d, int num_dofs, const std::string& where) {
  try {
    d.Validate(num_dofs, where);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().rfind(where, 0), 0u) << "where() starts with the location";
    return e.what();
  }
  return "(no exception)";
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ModalData, ValidInputPasses) {
  EXPECT_EQ(WhatOfValidate(ThreeSensors(), 4, "study.yaml: measurements.air"),
            "(no exception)");
  ModalData frequencies_only;
  frequencies_only.frequencies_hz = Eigen::Vector3d(1, 2, 3);
  EXPECT_EQ(WhatOfValidate(frequencies_only, 4, "m"), "(no exception)");
  EXPECT_FALSE(frequencies_only.HasShapes());
}

TEST(ModalData, ValidateCatchesBadFrequencies) {
  const std::string where = "study.yaml: measurements.water";
  for (double bad : {0.0, -3.0, kNaN, std::numeric_limits<double>::infinity()}) {
    ModalData d = ThreeSensors();
    d.frequencies_hz[1] = bad;
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "mode 2")) << what;
    EXPECT_TRUE(Contains(what, "frequencies")) << what;
  }
  ModalData none;
  EXPECT_TRUE(Contains(WhatOfValidate(none, 4, where), where));
}

TEST(ModalData, ValidateCatchesShapeProblems) {
  const std::string where = "meas[air]";
  {
    ModalData d = ThreeSensors();
    d.shapes.conservativeResize(3, 1);  // one shape for two frequencies
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "1 mode shapes for 2 frequencies")) << what;
  }
  {
    ModalData d = ThreeSensors();
    d.sensor_dofs = {3, 0};  // three rows, two sensors
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "one per sensor")) << what;
  }
  {
    ModalData d = ThreeSensors();
    d.sensor_dofs.clear();  // then rows must equal the model's DOF count
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "one per model DOF")) << what;
    EXPECT_EQ(WhatOfValidate(d, 3, where), "(no exception)");
  }
  {
    ModalData d = ThreeSensors();
    d.shapes(2, 1) = kNaN;
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "NaN")) << what;
  }
  {
    ModalData d = ThreeSensors();
    d.shapes.col(0).setZero();
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "mode 1 is all zero")) << what;
  }
}

TEST(ModalData, ValidateCatchesBadSensors) {
  const std::string where = "measurements.air";
  {
    ModalData d = ThreeSensors();
    d.sensor_dofs = {3, 4, 1};  // DOF 4 of a 4-DOF model
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where + ".sensors")) << what;
    EXPECT_TRUE(Contains(what, "sensor 2")) << what;
  }
  {
    ModalData d = ThreeSensors();
    d.sensor_dofs = {3, -1, 1};
    EXPECT_TRUE(Contains(WhatOfValidate(d, 4, where), "sensor 2"));
  }
  {
    ModalData d = ThreeSensors();
    d.sensor_dofs = {3, 0, 3};
    const std::string what = WhatOfValidate(d, 4, where);
    EXPECT_TRUE(Contains(what, where)) << what;
    EXPECT_TRUE(Contains(what, "sensors 1 and 3")) << what;
  }
}

TEST(ModalData, EigenvaluesAndCompleteness) {
  const ModalData d = ThreeSensors();
  EXPECT_NEAR(d.Eigenvalues()[0], std::pow(4 * kPi, 2), 1e-12);
  EXPECT_NEAR(d.Eigenvalues()[1], std::pow(10 * kPi, 2), 1e-11);
  EXPECT_EQ(d.num_modes(), 2);
  EXPECT_FALSE(d.IsComplete(4));  // DOF 2 has no sensor
  ModalData full = d;
  full.shapes.conservativeResize(4, 2);
  full.shapes.row(3) << 4.0, -2.0;
  full.sensor_dofs = {3, 0, 1, 2};
  EXPECT_TRUE(full.IsComplete(4));
  ModalData no_shapes;
  no_shapes.frequencies_hz = Eigen::Vector2d(1, 2);
  EXPECT_FALSE(no_shapes.IsComplete(4));
}

TEST(ModalData, FullShapesReordersSensorRows) {
  ModalData d = ThreeSensors();
  d.shapes.conservativeResize(4, 2);
  d.shapes.row(3) << 4.0, -2.0;
  d.sensor_dofs = {3, 0, 1, 2};  // row r measures DOF sensor_dofs[r]
  const Eigen::MatrixXd full = d.FullShapes(4, "m");
  Eigen::MatrixXd expected(4, 2);
  expected << 2.0, 0.25,  // DOF 0: row 1
      3.0, 1.0,           // DOF 1: row 2
      4.0, -2.0,          // DOF 2: row 3
      1.0, -0.5;          // DOF 3: row 0
  EXPECT_EQ(full, expected);

  // Without sensor_dofs the shapes are already in model order.
  ModalData plain = d;
  plain.sensor_dofs.clear();
  EXPECT_EQ(plain.FullShapes(4, "m"), plain.shapes);
}

TEST(ModalData, FullShapesThrowsWhenIncomplete) {
  const ModalData d = ThreeSensors();
  try {
    d.FullShapes(4, "measurements.water");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "measurements.water.shapes");
    EXPECT_TRUE(Contains(e.what(), "3 of the model's 4 DOFs")) << e.what();
  }
  ModalData no_shapes;
  no_shapes.frequencies_hz = Eigen::Vector2d(1, 2);
  EXPECT_THROW(no_shapes.FullShapes(4, "x"), InputError);
}

TEST(Immersion, Names) {
  EXPECT_STREQ(ToString(Immersion::kDry), "dry");
  EXPECT_STREQ(ToString(Immersion::kWet), "wet");
}

TEST(PredictModes, PaperChainAirAndWater) {
  const PaperChainScenario s = PaperChain(3);
  const ModalData air = PredictModes(s.model, s.preset, Immersion::kDry, 2, "air");
  const ModalData water = PredictModes(s.model, s.preset, Immersion::kWet, 2, "water");
  EXPECT_EQ(air.state, "air");
  EXPECT_EQ(air.immersion, Immersion::kDry);
  EXPECT_EQ(water.state, "water");
  EXPECT_EQ(water.immersion, Immersion::kWet);
  ASSERT_EQ(air.num_modes(), 2);
  ASSERT_EQ(water.num_modes(), 2);
  EXPECT_NEAR(air.frequencies_hz[0], 34.808, 5e-4);
  EXPECT_NEAR(air.frequencies_hz[1], 102.008, 5e-4);
  EXPECT_NEAR(water.frequencies_hz[0], 33.588, 5e-4);
  EXPECT_NEAR(water.frequencies_hz[1], 95.673, 5e-4);
  EXPECT_TRUE(air.IsComplete(5));
  EXPECT_TRUE(air.sensor_dofs.empty());

  // Shapes are eigenvectors of the updated pencils, M~-normalised.
  const Eigen::MatrixXd k(s.model.UpdatedStiffness(s.preset));
  const Eigen::MatrixXd mdry(s.model.UpdatedDryMass(s.preset));
  const Eigen::MatrixXd mwet(s.model.UpdatedWetMass(s.preset));
  for (int j = 0; j < 2; ++j) {
    const double la = air.Eigenvalues()[j], lw = water.Eigenvalues()[j];
    EXPECT_LE((k * air.shapes.col(j) - la * mdry * air.shapes.col(j)).norm(),
              1e-9 * la * (mdry * air.shapes.col(j)).norm());
    EXPECT_LE((k * water.shapes.col(j) - lw * mwet * water.shapes.col(j)).norm(),
              1e-9 * lw * (mwet * water.shapes.col(j)).norm());
    EXPECT_NEAR(air.shapes.col(j).dot(mdry * air.shapes.col(j)), 1.0, 1e-12);
    EXPECT_NEAR(water.shapes.col(j).dot(mwet * water.shapes.col(j)), 1.0, 1e-12);
  }
  // Water adds mass only: every wet frequency is lower.
  const ModalData air5 = PredictModes(s.model, s.preset, Immersion::kDry, 5, "air");
  const ModalData water5 = PredictModes(s.model, s.preset, Immersion::kWet, 5, "water");
  for (int j = 0; j < 5; ++j) EXPECT_LT(water5.frequencies_hz[j], air5.frequencies_hz[j]);
}

}  // namespace
}  // namespace femup
