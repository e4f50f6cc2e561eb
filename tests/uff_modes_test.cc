// Measured modes from UFF dataset 55 (femup/uff_modes.h): a cantilever's own
// modes written with WriteUff (normal and complex) and read back at the model's
// DOFs, by an explicit map and by node coordinates; complex shapes and
// eigenvalues against hand computations; a pyuff mode-shape file and a complex
// mode of another exporter; every kind of bad input, named.
#include "femup/core/io/uff_modes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/linalg/modal.h"
#include "scratch_dir.h"

namespace femup {
namespace {

const std::string kData = std::string(FEMUP_TEST_DATA_DIR);

using testing::ExpectError;

// The paper's Model A beam: 10 elements over 1.9 m, clamped; 30 DOFs.
struct Beam {
  Structure structure;
  Modes modes;
  Beam() {
    CantileverSpec spec;
    spec.node_heights = UniformHeights(1.9, 10);
    spec.section = {206e9, 8.8e-4, 8.53e-8, 7850};
    structure = BuildCantilever(spec);
    modes = SolveModes(structure.stiffness, structure.mass);
  }
  int Dof(const std::string& label) const {
    for (std::size_t i = 0; i < structure.dof_labels.size(); ++i)
      if (structure.dof_labels[i] == label) return static_cast<int>(i);
    return -1;
  }
};

// UFF node 100 + k at model node n<k>, k = 0..10 (the base too), placed at
// (0, height, 0) in dataset 15.
UffNodes BeamNodes(const Beam& beam) {
  UffNodes nodes;
  for (std::size_t k = 0; k < beam.structure.nodes.size(); ++k) {
    const Eigen::Vector3d& p = beam.structure.nodes[k].xyz;
    nodes.nodes.push_back({100 + static_cast<int>(k), 0, 0, 0, {p.x(), p.y(), p.z()}});
  }
  return nodes;
}

// Mode j of the beam as dataset 55 at nodes 100..110 (translations: X = ux,
// Y = uy, Z = 0; zero at the clamp, node 100), normal or complex: the shape
// times e^{i phase} with the eigenvalue of damping ratio `zeta`.
UffModeShape BeamMode(const Beam& beam, int j, bool complex_mode, double zeta = 0.0,
                      double phase = 0.0) {
  UffModeShape s;
  s.analysis_type =
      complex_mode ? UffAnalysisType::kComplexFirstOrder : UffAnalysisType::kNormalMode;
  s.complex_data = complex_mode;
  s.mode_number = j + 1;
  const double f = beam.modes.FrequenciesHz()[j];
  if (complex_mode) {
    const double w = 2 * M_PI * f;
    s.eigenvalue = {-zeta * w, w * std::sqrt(1 - zeta * zeta)};
  } else {
    s.frequency_hz = f;
    s.modal_mass = 1.0;
  }
  s.values = Eigen::MatrixXcd::Zero(11, 3);
  s.nodes.push_back(100);
  const std::complex<double> rotation = std::polar(1.0, phase);
  for (int k = 1; k <= 10; ++k) {
    s.nodes.push_back(100 + k);
    const std::string n = "n" + std::to_string(k);
    s.values(k, 0) = rotation * beam.modes.shapes(beam.Dof(n + ":ux"), j);
    s.values(k, 1) = rotation * beam.modes.shapes(beam.Dof(n + ":uy"), j);
  }
  return s;
}

UffDofMap GeometryMap(const Beam& beam, const UffFile& file, const std::string& name) {
  UffDofMap map;
  map.by_geometry = true;
  map.geometry = UffNodeCoordinates(file, name);
  map.geometry_file = name;
  map.model_nodes = beam.structure.nodes;
  map.tolerance = 0.019;
  map.directions = {1};  // X: the transverse ux
  map.skipped = {{100, "base"}};
  return map;
}

TEST(UffDirection, NamesAndCodes) {
  int d = 0;
  EXPECT_TRUE(ParseUffDirection("+Y", &d));
  EXPECT_EQ(d, 2);
  EXPECT_TRUE(ParseUffDirection("-rz", &d));
  EXPECT_EQ(d, -6);
  EXPECT_TRUE(ParseUffDirection("X", &d));
  EXPECT_EQ(d, 1);
  EXPECT_TRUE(ParseUffDirection("5", &d));
  EXPECT_EQ(d, 5);
  EXPECT_TRUE(ParseUffDirection("-3", &d));
  EXPECT_EQ(d, -3);
  for (const char* bad : {"", "W", "7", "0", "+", "XY", "--X"})
    EXPECT_FALSE(ParseUffDirection(bad, &d)) << bad;
  EXPECT_EQ(UffDirectionName(1), "+X");
  EXPECT_EQ(UffDirectionName(-6), "-RZ");
  EXPECT_STREQ(FrameDofName(-2), "uy");
  EXPECT_STREQ(FrameDofName(6), "rz");
}

TEST(UffModes, BestRealShapeByHand) {
  // A monophase shape e^{i a} phi comes back as phi (largest entry positive).
  const Eigen::Vector3d phi(0.2, -1.0, 0.5);
  const Eigen::VectorXcd rotated =
      phi.cast<std::complex<double>>() * std::polar(1.0, 2.0);
  const RealShape r = BestRealShape(rotated);
  EXPECT_NEAR((r.shape - (-phi)).norm(), 0.0, 1e-14);  // -1.0 is the largest: flipped
  EXPECT_NEAR(r.mpc, 1.0, 1e-14);
  EXPECT_NEAR(r.imaginary_fraction, 0.0, 1e-14);
  // psi = [1, 0.5i]: psi^T psi = 0.75, psi^H psi = 1.25, MPC = 0.36, theta = 0,
  // real part [1, 0], imaginary share 0.25 / 1.25 = 0.2 = (1 - sqrt(0.36)) / 2.
  Eigen::VectorXcd psi(2);
  psi << 1.0, std::complex<double>(0.0, 0.5);
  const RealShape q = BestRealShape(psi);
  EXPECT_NEAR(q.mpc, 0.36, 1e-15);
  EXPECT_NEAR(q.imaginary_fraction, 0.2, 1e-15);
  EXPECT_NEAR(q.shape[0], 1.0, 1e-15);
  EXPECT_NEAR(q.shape[1], 0.0, 1e-15);
  // [1, i] is as far from real as a shape can be.
  psi << 1.0, std::complex<double>(0.0, 1.0);
  EXPECT_NEAR(BestRealShape(psi).mpc, 0.0, 1e-15);
  EXPECT_NEAR(BestRealShape(psi).imaginary_fraction, 0.5, 1e-15);
}

TEST(UffModes, ComplexEigenvalueByHand) {
  // lambda = -zeta w + i w sqrt(1 - zeta^2), w = 2 pi 10: 10 Hz, 2 %.
  const double w = 2 * M_PI * 10;
  double f = 0, zeta = 0;
  ComplexEigenvalueModes({-0.02 * w, w * std::sqrt(1 - 0.02 * 0.02)}, &f, &zeta, "x");
  EXPECT_NEAR(f, 10.0, 1e-12);
  EXPECT_NEAR(zeta, 0.02, 1e-15);
  // -0.1111111 + 41.11111 i rad/s: |lambda| = 41.1112601..., f = 6.5430603 Hz,
  // zeta = 0.1111111 / 41.1112601 = 0.00270269.
  ComplexEigenvalueModes({-0.1111111, 41.11111}, &f, &zeta, "x");
  EXPECT_NEAR(f, 6.543060269585478, 1e-9);
  EXPECT_NEAR(zeta, 0.0027026926344510377, 1e-12);
  ExpectError(
      [&] {
        ComplexEigenvalueModes({0.0, 0.0}, &f, &zeta, "m.uff: line 9");
      },
      {"m.uff: line 9", "nonzero complex eigenvalue"});
}

TEST(UffModes, NormalModesWrittenAndReadBackEqualTheModelsModes) {
  const Beam beam;
  testing::ScratchDir dir;
  const std::string path = dir.File("beam.uff");
  WriteUff(path, {BeamNodes(beam), BeamMode(beam, 2, false), BeamMode(beam, 0, false),
                  BeamMode(beam, 1, false)});
  const UffFile file = ReadUff(path);

  // By coordinates, X only: the ten ux DOFs, in node order.
  const UffModes u = ExtractUffModes(file, path, GeometryMap(beam, file, path),
                                     beam.structure.dof_labels, {});
  ASSERT_EQ(u.sensors.size(), 10u);
  ASSERT_EQ(u.all_frequencies_hz.size(), 3u);
  EXPECT_EQ(u.used, (std::vector<int>{1, 2, 3}));
  const Eigen::VectorXd hz = beam.modes.FrequenciesHz();
  for (int j = 0; j < 3; ++j) {
    // Written as E13.5: 6 significant digits.
    EXPECT_NEAR(u.modes[j].frequency_hz / hz[j], 1.0, 1e-5) << j;
    EXPECT_EQ(u.modes[j].mode_number, j + 1);  // sorted by frequency
    EXPECT_EQ(u.modes[j].mpc, 1.0);
    for (int k = 1; k <= 10; ++k) {
      const int dof = beam.Dof("n" + std::to_string(k) + ":ux");
      EXPECT_EQ(u.sensors[k - 1].dof, dof);
      EXPECT_EQ(u.sensors[k - 1].label, "n" + std::to_string(k) + ":ux");
      EXPECT_NEAR(u.shapes(k - 1, j), beam.modes.shapes(dof, j),
                  1e-5 * beam.modes.shapes.col(j).cwiseAbs().maxCoeff());
    }
  }
  // Mode lines: the 55 datasets after the 15 (which has 11 nodes, lines 1-14).
  EXPECT_GT(u.modes[0].line, 14);
  EXPECT_EQ(u.sensors[2].source.substr(0, 4), "n3, ");

  // The same by an explicit map with reversed and Y entries, selecting modes.
  UffDofMap map;
  map.sensors = {{105, 1, beam.Dof("n5:ux"), "", ""},
                 {110, -1, beam.Dof("n10:ux"), "", ""},
                 {110, 2, beam.Dof("n10:uy"), "", ""}};
  map.skip_unmapped = true;
  const UffModes e = ExtractUffModes(file, path, map, beam.structure.dof_labels, {3, 1});
  ASSERT_EQ(e.sensors.size(), 3u);
  EXPECT_EQ(e.used, (std::vector<int>{3, 1}));
  EXPECT_NEAR(e.modes[0].frequency_hz / hz[2], 1.0, 1e-5);
  const double scale = beam.modes.shapes.col(2).cwiseAbs().maxCoeff();
  EXPECT_NEAR(e.shapes(0, 0), beam.modes.shapes(beam.Dof("n5:ux"), 2), 1e-5 * scale);
  EXPECT_NEAR(e.shapes(1, 0), -beam.modes.shapes(beam.Dof("n10:ux"), 2), 1e-5 * scale);
  EXPECT_NEAR(e.shapes(2, 0), beam.modes.shapes(beam.Dof("n10:uy"), 2), 1e-5 * scale);
}

TEST(UffModes, ComplexModesGiveTheUndampedFrequencyAndTheRealShape) {
  const Beam beam;
  testing::ScratchDir dir;
  const std::string path = dir.File("complex.uff");
  // Proportionally damped modes (monophase, rotated by 0.7 rad), 1 % and 3 %,
  // and one with a non-proportional part: i 0.05 times mode 3's shape.
  UffModeShape m2 = BeamMode(beam, 1, true, 0.03, -2.5);
  const UffModeShape m3 = BeamMode(beam, 2, false);
  m2.values += std::complex<double>(0.0, 0.05) * m3.values;
  WriteUff(path, {BeamNodes(beam), BeamMode(beam, 0, true, 0.01, 0.7), m2});
  const UffFile file = ReadUff(path);
  const UffModes u = ExtractUffModes(file, path, GeometryMap(beam, file, path),
                                     beam.structure.dof_labels, {});
  ASSERT_EQ(u.modes.size(), 2u);
  const Eigen::VectorXd hz = beam.modes.FrequenciesHz();
  EXPECT_NEAR(u.modes[0].frequency_hz / hz[0], 1.0, 1e-5);
  EXPECT_NEAR(u.modes[1].frequency_hz / hz[1], 1.0, 1e-5);
  EXPECT_NEAR(u.modes[0].damping_ratio, 0.01, 1e-6);
  EXPECT_NEAR(u.modes[1].damping_ratio, 0.03, 1e-6);
  EXPECT_EQ(u.modes[0].analysis_type, UffAnalysisType::kComplexFirstOrder);
  // Mode 1: the model's shape exactly (up to its sign), MPC 1.
  Eigen::VectorXd phi1(10), phi2(10), phi3(10);
  for (int k = 1; k <= 10; ++k) {
    const int dof = beam.Dof("n" + std::to_string(k) + ":ux");
    phi1[k - 1] = beam.modes.shapes(dof, 0);
    phi2[k - 1] = beam.modes.shapes(dof, 1);
    phi3[k - 1] = beam.modes.shapes(dof, 2);
  }
  const double sign1 = u.shapes.col(0).dot(phi1) > 0 ? 1.0 : -1.0;
  EXPECT_NEAR((u.shapes.col(0) - sign1 * phi1).norm() / phi1.norm(), 0.0, 2e-5);
  EXPECT_NEAR(u.modes[0].mpc, 1.0, 1e-8);
  EXPECT_LT(u.modes[0].imaginary_fraction, 1e-9);
  // Mode 2: psi = e^{-2.5 i} phi2 + 0.05 i phi3 at the ux DOFs. Its best real
  // fit, MPC and imaginary share by the formulas of the header, from the
  // written values.
  const Eigen::VectorXcd psi = std::polar(1.0, -2.5) * phi2.cast<std::complex<double>>() +
                               std::complex<double>(0.0, 0.05) * phi3;
  const RealShape expect = BestRealShape(psi);
  EXPECT_NEAR(u.modes[1].mpc, expect.mpc, 1e-5);
  EXPECT_LT(u.modes[1].mpc, 0.999);
  EXPECT_NEAR(u.modes[1].imaginary_fraction, (1 - std::sqrt(u.modes[1].mpc)) / 2, 1e-12);
  EXPECT_NEAR((u.shapes.col(1) - expect.shape).norm() / expect.shape.norm(), 0.0, 1e-4);
  // ... which stays close to the model's mode 2 (MAC).
  const double mac = std::pow(u.shapes.col(1).dot(phi2), 2) /
                     (u.shapes.col(1).squaredNorm() * phi2.squaredNorm());
  EXPECT_GT(mac, 0.99);
}

TEST(UffModesRealData, PyuffNormalModeWithRotations) {
  // pyuff's uff55_translation_rotation.uff: one normal mode at 97.013 Hz, 43
  // nodes of 6 values; node 1 = (5.3569e-02, 2.0271e-02, 4.6623e-03, 0, 0, 0),
  // node 3 Y = 1.5260e-02.
  const std::string path = kData + "/realdata/uff55_translation_rotation.uff";
  const UffFile file = ReadUff(path);
  UffDofMap map;
  map.sensors = {
      {1, 1, 0, "", ""}, {1, 2, 1, "", ""}, {3, -2, 2, "", ""}, {3, 6, 3, "", ""}};
  map.skip_unmapped = true;
  const UffModes u = ExtractUffModes(file, path, map, {"a", "b", "c", "d"}, {});
  ASSERT_EQ(u.modes.size(), 1u);
  EXPECT_DOUBLE_EQ(u.modes[0].frequency_hz, 97.013);
  EXPECT_DOUBLE_EQ(u.shapes(0, 0), 5.3569e-02);
  EXPECT_DOUBLE_EQ(u.shapes(1, 0), 2.0271e-02);
  EXPECT_DOUBLE_EQ(u.shapes(2, 0), -1.5260e-02);
  EXPECT_DOUBLE_EQ(u.shapes(3, 0), 0.0);
  EXPECT_EQ(u.sensors[2].label, "c");
  // Without "*": skip, node 2 is the first node nothing maps: named with its line.
  map.skip_unmapped = false;
  ExpectError(
      [&] {
        ExtractUffModes(file, path, map, {"a", "b", "c", "d"}, {});
      },
      {path + ": line 13", "node 2 is not mapped", "\"2\": skip"});
}

TEST(UffModesRealData, ComplexModeOfAnotherExporter) {
  // tests/data/uff/pyuff_uff55_complex_mode.uff (README there): a complex mode
  // (analysis type 3), eigenvalue -0.1111111 + 41.11111 i rad/s, record 8 with
  // values run together ("4.111111E+03-3.111111E+03"); node 111111: Y =
  // 0.1111111 + 0.09111111 i, Z = 0.007111111 + 0.004111111 i; node 60101:
  // Z = -0.04111111 - 0.01111111 i. Expected, computed by hand (Python, the
  // header's formulas) with node 60101 mapped along -Z: f 6.5430603 Hz, zeta
  // 0.00270269, MPC 0.949949, imaginary share 0.0126733, shape 0.143619,
  // 0.00814335, 0.0393651.
  const std::string path = kData + "/uff/pyuff_uff55_complex_mode.uff";
  const UffFile file = ReadUff(path);
  UffDofMap map;
  map.sensors = {{111111, 2, 0, "", ""}, {111111, 3, 1, "", ""}, {60101, -3, 2, "", ""}};
  const UffModes u = ExtractUffModes(file, path, map, {"a", "b", "c"}, {});
  ASSERT_EQ(u.modes.size(), 1u);
  EXPECT_EQ(u.modes[0].mode_number, 1);
  EXPECT_NEAR(u.modes[0].frequency_hz, 6.543060269585478, 1e-9);
  EXPECT_NEAR(u.modes[0].damping_ratio, 0.0027026926344510377, 1e-12);
  EXPECT_NEAR(u.modes[0].mpc, 0.9499492374130875, 1e-12);
  EXPECT_NEAR(u.modes[0].imaginary_fraction, 0.01267330326230644, 1e-12);
  EXPECT_NEAR(u.shapes(0, 0), 0.1436194037061064, 1e-12);
  EXPECT_NEAR(u.shapes(1, 0), 0.008143347607059193, 1e-12);
  EXPECT_NEAR(u.shapes(2, 0), 0.039365076787893236, 1e-12);
  // No rotations in 3 values per node.
  map.sensors.push_back(
      {60101, 4, 3, "s.yaml:9:5: measurements[1].uff_dofs.60101:RX", ""});
  ExpectError(
      [&] {
        ExtractUffModes(file, path, map, {"a", "b", "c", "d"}, {});
      },
      {"s.yaml:9:5", "direction +RX is missing", "3 values per node"});
}

TEST(UffModesErrors, EveryProblemIsNamed) {
  const Beam beam;
  testing::ScratchDir dir;
  const std::vector<std::string>& labels = beam.structure.dof_labels;
  auto write = [&](const std::string& name, const std::vector<UffDataset>& d) {
    WriteUff(dir.File(name), d);
    return dir.File(name);
  };
  // No dataset 55: nodes and a function only.
  UffFunction f;
  f.function_type = 1;
  f.abscissa_increment = 0.01;
  f.y = Eigen::VectorXcd::Ones(4);
  const std::string none = write("none.uff", {BeamNodes(beam), f});
  {
    const UffFile file = ReadUff(none);
    ExpectError(
        [&] { ExtractUffModes(file, none, GeometryMap(beam, file, none), labels, {}); },
        {none, "no mode shape (dataset 55)", "1 x dataset 15, 1 x dataset 58",
         "identify:"});
  }
  // A frequency-response shape is not a mode.
  UffModeShape frf = BeamMode(beam, 0, false);
  frf.analysis_type = UffAnalysisType::kFrequencyResponse;
  const std::string odd = write("frf.uff", {frf});
  ExpectError([&] { ExtractUffModes(ReadUff(odd), odd, {}, labels, {}); },
              {odd + ": line 2", "frequency response shape (analysis type 5"});

  // Modes with other node sets: mode 2 lacks node 104; mode 3 has node 111 more.
  UffModeShape lacks = BeamMode(beam, 1, false);
  lacks.nodes.erase(lacks.nodes.begin() + 4);
  Eigen::MatrixXcd kept(10, 3);
  kept << lacks.values.topRows(4), lacks.values.bottomRows(6);
  lacks.values = kept;
  const std::string sets =
      write("sets.uff", {BeamNodes(beam), BeamMode(beam, 0, false), lacks});
  const UffFile sets_file = ReadUff(sets);
  const long long lacks_line = std::get<UffModeShape>(sets_file.datasets[2]).line;
  ExpectError(
      [&] {
        ExtractUffModes(sets_file, sets, GeometryMap(beam, sets_file, sets), labels, {});
      },
      {sets + ": line " + std::to_string(lacks_line), "node 104 is missing",
       "share one node set"});
  // ... used alone, mode 2 is fine.
  EXPECT_EQ(
      ExtractUffModes(sets_file, sets, GeometryMap(beam, sets_file, sets), labels, {2})
          .sensors.size(),
      9u);
  UffModeShape more = BeamMode(beam, 1, false);
  more.nodes.push_back(111);
  more.values.conservativeResize(12, 3);
  more.values.row(11).setConstant(0.5);
  const std::string extra =
      write("extra.uff", {BeamNodes(beam), BeamMode(beam, 0, false), more});
  {
    const UffFile file = ReadUff(extra);
    const UffModeShape& s = std::get<UffModeShape>(file.datasets[2]);
    ExpectError(
        [&] { ExtractUffModes(file, extra, GeometryMap(beam, file, extra), labels, {}); },
        {extra + ": line " + std::to_string(s.node_lines.back()),
         "node 111 is not in the other modes"});
  }

  const std::string good = write(
      "good.uff", {BeamNodes(beam), BeamMode(beam, 0, false), BeamMode(beam, 1, false)});
  const UffFile file = ReadUff(good);
  const UffModeShape& first = std::get<UffModeShape>(file.datasets[1]);
  // Unknown nodes: no map at all; a map naming a node the modes lack.
  ExpectError([&] { ExtractUffModes(file, good, {}, labels, {}); },
              {good + ": line " + std::to_string(first.node_lines[0]),
               "node 100 is not mapped", "uff_dofs", "geometry_file"});
  UffDofMap wrong;
  wrong.sensors = {{99, 1, 0, "s.yaml:7:3: measurements[1].uff_dofs.99:+X", ""}};
  ExpectError([&] { ExtractUffModes(file, good, wrong, labels, {}); },
              {"s.yaml:7:3", "node 99 is not in dataset 55 of " + good, "nodes 100-110"});
  // Skipped and mapped.
  UffDofMap both;
  both.sensors = {{101, 1, 0, "s.yaml:7:3", ""}};
  both.skipped = {{101, "s.yaml:8:3"}};
  ExpectError([&] { ExtractUffModes(file, good, both, labels, {}); },
              {"s.yaml:8:3", "skipped and also mapped"});
  // Two components on one DOF.
  UffDofMap twice;
  twice.sensors = {{101, 1, 0, "s.yaml:7:3", ""}, {102, 1, 0, "s.yaml:8:3", ""}};
  twice.skip_unmapped = true;
  ExpectError([&] { ExtractUffModes(file, good, twice, labels, {}); },
              {"model DOF n1:ux is measured twice", "s.yaml:7:3", "s.yaml:8:3"});
  // A mode the file does not have.
  ExpectError(
      [&] { ExtractUffModes(file, good, GeometryMap(beam, file, good), labels, {3}); },
      {good, "mode 3 is asked for", "2 mode(s)"});

  // Geometry: a node without coordinates, one off the model, one at the clamped
  // base, a tolerance that takes two model nodes, a direction the model lacks.
  UffDofMap g = GeometryMap(beam, file, good);
  g.geometry.erase(g.geometry.begin() + 5);  // node 105
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"node 105 has no coordinates in " + good, "line"});
  g = GeometryMap(beam, file, good);
  g.geometry[3].xyz[0] = 0.05;  // node 103 5 cm off the beam
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"node 103 at (0.05, 0.57, 0)", "0.05 m from the nearest model node n3",
               "tolerance 0.019 m", "\"103\": skip"});
  g.skip_unmapped = true;  // "*": skip leaves it out
  EXPECT_EQ(ExtractUffModes(file, good, g, labels, {}).sensors.size(), 9u);
  g = GeometryMap(beam, file, good);
  g.geometry[1].xyz = {0.0, 0.0, 0.0};  // node 101 moved onto the base n0
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"node 101", "model node n0, which has no DOF n0:ux", "\"101\": skip"});
  g = GeometryMap(beam, file, good);
  g.tolerance = 0.2;
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"within the tolerance 0.2 m of two model nodes", "geometry_tolerance"});
  g = GeometryMap(beam, file, good);
  g.directions = {3};
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"has no DOF n1:uz for direction +Z"});
  g.directions = {4};
  ExpectError([&] { ExtractUffModes(file, good, g, labels, {}); },
              {"direction +RX (uff_directions) is missing", "3 values per node"});
  // A shape that is zero at every mapped DOF (Z).
  UffDofMap zero;
  zero.sensors = {{101, 3, 0, "s", ""}};
  zero.skip_unmapped = true;
  ExpectError(
      [&] { ExtractUffModes(file, good, zero, labels, {}); },
      {good + ": line " + std::to_string(first.line), "zero at every mapped DOF"});
}

TEST(UffNodeCoordinates, MergesDatasetsAndRefusesConflicts) {
  UffNodes a, b;
  a.nodes = {{1, 0, 0, 0, {0.0, 0.0, 0.0}}, {2, 0, 0, 0, {1.0, 0.0, 0.0}}};
  b.dataset = 2411;
  b.nodes = {{2, 0, 0, 0, {1.0, 0.0, 0.0}}, {3, 0, 0, 0, {2.0, 0.0, 0.0}}};
  const UffFile file = ParseUff(FormatUff({a, b}, "g.uff"), "g.uff");
  const std::vector<UffNode> nodes = UffNodeCoordinates(file, "g.uff");
  ASSERT_EQ(nodes.size(), 3u);
  EXPECT_EQ(nodes[2].label, 3);
  b.nodes[0].xyz[1] = 0.5;
  const UffFile bad = ParseUff(FormatUff({a, b}, "g.uff"), "g.uff");
  ExpectError([&] { UffNodeCoordinates(bad, "g.uff"); },
              {"g.uff: line", "node 2 at (1, 0.5, 0) is also at (1, 0, 0)"});
  ExpectError([&] { UffNodeCoordinates(UffFile{}, "e.uff"); },
              {"e.uff", "no node coordinates", "dataset 15 or 2411"});
}

}  // namespace
}  // namespace femup
