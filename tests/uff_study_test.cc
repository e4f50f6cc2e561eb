// Study measurements from UFF mode shapes (modes_file: X.uff): the keys
// uff_dofs, geometry_file, geometry_tolerance, uff_directions and modes, read
// and checked at load time; the modes placed on the model's DOFs by
// PrepareMeasurements equal the model's own modes written with WriteUff; bad
// input names the study file or the UFF file and line. Also `femup identify`
// on a file of mode shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "expect_error.h"
#include "femup/core/errors.h"
#include "femup/core/io/uff.h"
#include "femup/core/linalg/modal.h"
#include "femup/studies/identify_study.h"
#include "femup/studies/study.h"
#include "scratch_dir.h"

namespace femup {
namespace {

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The paper's Model A beam, 30 DOFs; one state measured from beam.uff.
const std::string kStudy = R"(
model:
  type: cantilever
  length: 1.9
  elements: 10
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
parameters: {mass: none, stiffness: single}
measurements:
  - state: air
    modes_file: beam.uff
    geometry_file: beam.uff
    uff_directions: [X]
    uff_dofs: {"100": skip}
    modes: [1, 3]
    expansion: {method: serep, modes: 3}
)";

// Nodes 100..110 at the beam's nodes n0..n10, (0, height, 0), and the model's
// four lowest modes as normal modes (X = ux, Y = uy; zero at the clamp), in
// reverse order.
void WriteBeamUff(const Study& study, const Modes& modes, const std::string& path) {
  UffNodes nodes;
  for (std::size_t k = 0; k < study.structure.nodes.size(); ++k) {
    const Eigen::Vector3d& p = study.structure.nodes[k].xyz;
    nodes.nodes.push_back({100 + static_cast<int>(k), 0, 0, 0, {p.x(), p.y(), p.z()}});
  }
  std::vector<UffDataset> datasets = {nodes};
  for (int j = 3; j >= 0; --j) {
    UffModeShape s;
    s.mode_number = j + 1;
    s.frequency_hz = modes.FrequenciesHz()[j];
    s.values = Eigen::MatrixXcd::Zero(11, 3);  // node 100, the clamp: zero
    s.nodes.push_back(100);
    for (int k = 1; k <= 10; ++k) {
      s.nodes.push_back(100 + k);
      const std::string n = "n" + std::to_string(k);
      s.values(k, 0) = modes.shapes(study.model.FindDof(n + ":ux"), j);
      s.values(k, 1) = modes.shapes(study.model.FindDof(n + ":uy"), j);
    }
    datasets.push_back(s);
  }
  WriteUff(path, datasets);
}

using testing::ExpectError;

TEST(UffStudy, ModesPlacedByGeometryAreTheModelsOwn) {
  testing::ScratchDir dir;
  WriteText(dir.File("s.yaml"), kStudy);
  const Study study = LoadStudy(dir.File("s.yaml"));
  ASSERT_TRUE(study.measurements[0].uff_map.has_value());
  const UffDofMap& map = *study.measurements[0].uff_map;
  EXPECT_TRUE(map.by_geometry);
  EXPECT_EQ(map.geometry_file, dir.File("beam.uff"));
  EXPECT_NEAR(map.tolerance, 0.019, 1e-12);  // 1 % of the 1.9 m beam
  EXPECT_EQ(map.directions, std::vector<int>{1});
  ASSERT_EQ(map.skipped.size(), 1u);
  EXPECT_EQ(map.skipped[0].node, 100);
  EXPECT_EQ(study.measurements[0].use_modes, (std::vector<int>{1, 3}));
  ASSERT_EQ(study.structure.nodes.size(), 11u);
  EXPECT_EQ(study.structure.nodes[3].name, "n3");
  EXPECT_NEAR(study.structure.nodes[3].xyz.y(), 0.57, 1e-12);

  const Modes modes = SolveModes(study.model.stiffness(), study.model.mass());
  WriteBeamUff(study, modes, dir.File("beam.uff"));
  const std::vector<PreparedState> p = PrepareMeasurements(study);
  ASSERT_EQ(p.size(), 1u);
  ASSERT_TRUE(p[0].uff.has_value());
  EXPECT_EQ(p[0].source, dir.File("beam.uff"));
  EXPECT_EQ(p[0].identified_modes, (std::vector<int>{1, 3}));
  const ModalData& s = p[0].at_sensors;
  ASSERT_EQ(s.sensor_dofs.size(), 10u);
  ASSERT_EQ(s.num_modes(), 2);
  const Eigen::VectorXd hz = modes.FrequenciesHz();
  const int used[2] = {0, 2};
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(s.frequencies_hz[j] / hz[used[j]], 1.0, 1e-5);
    const double scale = modes.shapes.col(used[j]).cwiseAbs().maxCoeff();
    for (int k = 1; k <= 10; ++k) {
      const int dof = study.model.FindDof("n" + std::to_string(k) + ":ux");
      EXPECT_EQ(s.sensor_dofs[k - 1], dof);
      EXPECT_NEAR(s.shapes(k - 1, j), modes.shapes(dof, used[j]), 1e-5 * scale);
    }
  }
  // SEREP on the model's own modes: the expanded shapes are the model's.
  for (int j = 0; j < 2; ++j) {
    const Eigen::VectorXd e = p[0].data.shapes.col(j);
    const Eigen::VectorXd m = modes.shapes.col(used[j]);
    EXPECT_GT(std::pow(e.dot(m), 2) / (e.squaredNorm() * m.squaredNorm()), 1 - 1e-8);
  }
}

TEST(UffStudy, ExplicitMapWithSignsAndWildcardSkip) {
  testing::ScratchDir dir;
  const std::string text =
      Replace(Replace(kStudy,
                      "    geometry_file: beam.uff\n    uff_directions: [X]\n"
                      "    uff_dofs: {\"100\": skip}\n",
                      "    uff_dofs: {\"110:X\": n10:ux, \"105:-1\": n5:ux, \"103:+Y\": "
                      "-n3:uy, \"*\": skip}\n"),
              "    expansion: {method: serep, modes: 3}\n", "");
  WriteText(dir.File("s.yaml"), text);
  const Study study = LoadStudy(dir.File("s.yaml"));
  const UffDofMap& map = *study.measurements[0].uff_map;
  EXPECT_FALSE(map.by_geometry);
  EXPECT_TRUE(map.skip_unmapped);
  ASSERT_EQ(map.sensors.size(), 3u);
  EXPECT_NE(map.sensors[0].source.find(dir.File("s.yaml") + ":"), std::string::npos);
  EXPECT_NE(map.sensors[0].source.find("measurements[1].uff_dofs.110:X"),
            std::string::npos);
  const Modes modes = SolveModes(study.model.stiffness(), study.model.mass());
  WriteBeamUff(study, modes, dir.File("beam.uff"));
  const ModalData s = PrepareMeasurements(study)[0].at_sensors;
  ASSERT_EQ(s.sensor_dofs.size(), 3u);  // file order: 103, 105, 110
  const int n3 = study.model.FindDof("n3:uy"), n5 = study.model.FindDof("n5:ux"),
            n10 = study.model.FindDof("n10:ux");
  EXPECT_EQ(s.sensor_dofs, (std::vector<int>{n3, n5, n10}));
  const double scale = modes.shapes.col(2).cwiseAbs().maxCoeff();
  // "103:+Y": -n3:uy: the DOF is minus the +Y value; "105:-1": minus +X.
  EXPECT_NEAR(s.shapes(0, 1), -modes.shapes(n3, 2), 1e-5 * scale);
  EXPECT_NEAR(s.shapes(1, 1), -modes.shapes(n5, 2), 1e-5 * scale);
  EXPECT_NEAR(s.shapes(2, 1), modes.shapes(n10, 2), 1e-5 * scale);
}

TEST(UffStudy, LoadTimeErrorsNameTheStudyField) {
  testing::ScratchDir dir;
  const std::string path = dir.File("bad.yaml");
  auto expect = [&](const std::string& text, std::vector<std::string> needles) {
    WriteText(path, text);
    needles.insert(needles.begin(), path + ":");
    ExpectError([&] { LoadStudy(path); }, needles);
  };
  const std::string maps = "    uff_dofs: {\"100\": skip}\n";
  expect(Replace(kStudy, maps, maps + "    sensors: [n1:ux]\n"),
         {"measurements[1].sensors", "uff_dofs", "geometry_file"});
  expect(Replace(Replace(kStudy, maps, ""),
                 "    geometry_file: beam.uff\n    uff_directions: [X]\n", ""),
         {"measurements[1].modes_file", "needs uff_dofs"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"abc:+X\": n1:ux}"),
         {"uff_dofs.abc:+X", "<node>:<direction>", "'abc:+X'"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:+W\": n1:ux}"),
         {"uff_dofs.101:+W", "RX, RY or RZ"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:+X\": n99:ux}"),
         {"uff_dofs.101:+X", "no model DOF is labelled 'n99:ux'", "n1:ux"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:+X\": skip}"),
         {"uff_dofs.101:+X", "whole node", "\"101\": skip"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101\": n1:ux}"),
         {"uff_dofs.101", "takes skip"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:X\": n1:ux, \"101:+1\": n2:ux}"),
         {"uff_dofs.101:+1", "listed twice"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:X\": n1:ux, \"102:X\": n1:ux}"),
         {"uff_dofs.102:X", "DOF 'n1:ux' is listed twice"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"101:X\": n1:ux, \"101\": skip}"),
         {"skipped and also mapped"});
  expect(Replace(kStudy, "{\"100\": skip}", "{\"*\": n1:ux}"), {"\"*\" takes skip"});
  expect(Replace(kStudy, "{\"100\": skip}", "[1, 2]"),
         {"uff_dofs", "expected a mapping"});
  expect(Replace(kStudy, "uff_directions: [X]", "uff_directions: [X, -1]"),
         {"uff_directions[2]", "listed twice"});
  expect(Replace(kStudy, "uff_directions: [X]", "uff_directions: [Q]"),
         {"uff_directions[1]", "found 'Q'"});
  expect(
      Replace(kStudy, "    geometry_file: beam.uff\n", "    geometry_tolerance: 0.1\n"),
      {"geometry_tolerance", "needs geometry_file"});
  expect(Replace(kStudy, "modes_file: beam.uff", "modes_file: modes.json"),
         {"measurements[1].uff_dofs",
          "UFF modes_file (.uff, .unv); this measurement has none"});
  expect(Replace(
             kStudy,
             "    modes_file: beam.uff\n    geometry_file: beam.uff\n    uff_directions: "
             "[X]\n    uff_dofs: {\"100\": skip}\n    modes: [1, 3]\n    expansion: "
             "{method: serep, modes: 3}\n",
             "    frequencies_hz: [7.8]\n    uff_dofs: {\"100\": skip}\n"),
         {"measurements[1].uff_dofs", "this measurement has none"});
  const std::string chain = R"(
model: {type: chain, masses: [50, 50], springs: [2.9e7, 2.9e7]}
measurements:
  - {state: air, modes_file: m.uff, geometry_file: m.uff}
)";
  expect(chain, {"measurements[1].geometry_file", "no node coordinates", "uff_dofs"});
}

TEST(UffStudy, PrepareTimeErrorsNameTheUffFileAndLine) {
  testing::ScratchDir dir;
  WriteText(dir.File("s.yaml"), kStudy);
  const Study study = LoadStudy(dir.File("s.yaml"));
  ExpectError([&] { PrepareMeasurements(study); }, {dir.File("beam.uff"), "not found"});
  // Nodes only: no dataset 55.
  UffNodes nodes;
  nodes.nodes = {{100, 0, 0, 0, {0.0, 0.0, 0.0}}};
  WriteUff(dir.File("beam.uff"), {nodes});
  ExpectError([&] { PrepareMeasurements(study); },
              {dir.File("beam.uff"), "no mode shape (dataset 55)", "1 x dataset 15"});
  // Modes, but no dataset 15 for the geometry.
  const Modes modes = SolveModes(study.model.stiffness(), study.model.mass());
  WriteBeamUff(study, modes, dir.File("full.uff"));
  UffFile full = ReadUff(dir.File("full.uff"));
  full.datasets.erase(full.datasets.begin());
  WriteUff(dir.File("beam.uff"), full.datasets);
  ExpectError([&] { PrepareMeasurements(study); },
              {dir.File("beam.uff"), "no node coordinates", "dataset 15 or 2411"});
  // A node of the modes the explicit map does not know: file and line.
  std::string text = Replace(kStudy,
                             "    geometry_file: beam.uff\n    uff_directions: [X]\n"
                             "    uff_dofs: {\"100\": skip}\n",
                             "    uff_dofs: {\"101:X\": n1:ux}\n");
  WriteText(dir.File("t.yaml"),
            Replace(text, "    expansion: {method: serep, modes: 3}\n", ""));
  WriteBeamUff(study, modes, dir.File("beam.uff"));
  const long long line = std::get<UffModeShape>(ReadUff(dir.File("beam.uff")).datasets[4])
                             .node_lines[0];  // the lowest mode, node 100
  ExpectError([&] { PrepareMeasurements(LoadStudy(dir.File("t.yaml"))); },
              {dir.File("beam.uff") + ": line " + std::to_string(line),
               "node 100 is not mapped"});
  // A mode number the file does not have.
  WriteText(dir.File("u.yaml"), Replace(kStudy, "modes: [1, 3]", "modes: [1, 5]"));
  ExpectError([&] { PrepareMeasurements(LoadStudy(dir.File("u.yaml"))); },
              {dir.File("beam.uff"), "mode 5 is asked for", "4 mode(s)"});
}

TEST(UffStudy, SpaceFrameNodesPlacedFrom2411WithEveryTranslation) {
  // A small jacket: test nodes 7 and 8 (dataset 2411) at two of its free
  // nodes; without uff_directions every translation becomes that node's
  // ux, uy, uz (a space frame has them all), "5": skip leaves a node out.
  testing::ScratchDir dir;
  WriteText(dir.File("s.yaml"), R"(
model: {type: space_frame, levels: 2, bays_x: 1, bays_y: 1, level_height: 4,
        bay_width_x: 5, bay_width_y: 5, elements_per_member: 1, bracing: none}
measurements:
  - {state: air, modes_file: m.uff, geometry_file: m.uff, uff_dofs: {"5": skip}}
)");
  const Study study = LoadStudy(dir.File("s.yaml"));
  ASSERT_GE(study.structure.nodes.size(), 8u);
  const ModelNode& a = study.structure.nodes[2];
  const ModelNode& b = study.structure.nodes[7];
  // 1 % of the largest side of the free nodes' box: 5 m wide, 4 to 8 m high.
  EXPECT_NEAR(study.measurements[0].uff_map->tolerance, 0.05, 1e-12);
  UffNodes nodes;
  nodes.dataset = 2411;
  nodes.nodes = {{7, 0, 0, 0, {a.xyz.x(), a.xyz.y(), a.xyz.z()}},
                 {8, 0, 0, 0, {b.xyz.x() + 0.01, b.xyz.y(), b.xyz.z()}},
                 {5, 0, 0, 0, {-9.0, -9.0, -9.0}}};
  UffModeShape s;
  s.frequency_hz = 3.5;
  s.nodes = {5, 8, 7};
  s.values = Eigen::MatrixXcd::Zero(3, 3);
  s.values.row(1) << 0.1, 0.2, 0.3;
  s.values.row(2) << -1.0, 0.5, 0.25;
  WriteUff(dir.File("m.uff"), {nodes, s});
  const ModalData d = PrepareMeasurements(study)[0].at_sensors;
  ASSERT_EQ(d.sensor_dofs.size(), 6u);
  const std::vector<int> expected = {
      study.model.FindDof(b.name + ":ux"), study.model.FindDof(b.name + ":uy"),
      study.model.FindDof(b.name + ":uz"), study.model.FindDof(a.name + ":ux"),
      study.model.FindDof(a.name + ":uy"), study.model.FindDof(a.name + ":uz")};
  EXPECT_EQ(d.sensor_dofs, expected);
  EXPECT_NEAR(d.shapes(1, 0), 0.2, 1e-6);
  EXPECT_NEAR(d.shapes(3, 0), -1.0, 1e-6);
  EXPECT_NEAR(d.frequencies_hz[0], 3.5, 1e-5);
}

TEST(UffStudy, IdentifyOnModeShapesPointsToModesFile) {
  testing::ScratchDir dir;
  UffModeShape s;
  s.frequency_hz = 10;
  s.nodes = {1, 2};
  s.values = Eigen::MatrixXcd::Ones(2, 3);
  WriteUff(dir.File("modes.uff"), {s, s});
  IdentifyOptions o;
  o.file = dir.File("modes.uff");
  ExpectError([&] { RunIdentify(o); },
              {dir.File("modes.uff"), "holds 2 mode shape(s) (dataset 55)", "modes_file",
               "femup info"});
}

}  // namespace
}  // namespace femup
