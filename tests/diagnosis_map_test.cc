// The diagnosis map: a plane frame drawn to scale from its nodes (members as
// the segments their stiffness couples, clamped column feet reaching the
// ground), a chain drawn as a column, and the probability of each local
// explanation placed where it lies.
#include "femup/studies/diagnosis_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/reporting/diagnosis_map_figure.h"
#include "scratch_dir.h"
#include "structure_specs.h"

namespace femup {
namespace {

PlaneFrameSpec Portal() { return fixtures::PlaneFrame(1, 1, 2, 3.0, 5.0); }

const DiagnosisMap::Element& ElementOf(const DiagnosisMap& map,
                                       const std::string& region) {
  for (const auto& e : map.elements)
    if (e.region == region) return e;
  ADD_FAILURE() << "no " << region;
  return map.elements.front();
}

DiagnosisMap::Node NodeOf(const DiagnosisMap& map, const std::string& name) {
  for (const auto& n : map.nodes)
    if (n.region == "node " + name) return n;
  ADD_FAILURE() << name;
  return DiagnosisMap::Node();
}

TEST(DiagnosisMap, DrawsAPlaneFrameToScale) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EXPECT_TRUE(map.to_scale);
  ASSERT_EQ(map.elements.size(), 4u);  // two columns, one beam, its connections
  const auto& column = ElementOf(map, "element s1:col2");
  // Segments: joint n2 to its middle node n4, then from the clamped foot (no
  // DOF, so reached by the member's start height) up to n4.
  EXPECT_EQ(column.x, (std::vector<double>{5.0, 5.0, 5.0, 5.0}));
  EXPECT_EQ(column.y, (std::vector<double>{3.0, 1.5, 0.0, 1.5}));
  const auto& beam = ElementOf(map, "element s1:beam1");  // n1-n5, n2-n5
  EXPECT_EQ(beam.x, (std::vector<double>{0.0, 2.5, 5.0, 2.5}));
  EXPECT_EQ(beam.y, (std::vector<double>{3.0, 3.0, 3.0, 3.0}));
  // Its end connections: stubs from n1 and n2 a quarter of its end elements
  // (2.5 m) towards its middle.
  const auto& connections = ElementOf(map, "connections of s1:beam1");
  EXPECT_EQ(connections.x, (std::vector<double>{0.0, 0.625, 5.0, 4.375}));
  EXPECT_EQ(connections.y, (std::vector<double>{3.0, 3.0, 3.0, 3.0}));
  // Every free node is a place for an attached mass; the clamped feet are
  // supports too (rigid ones, which support flexibility may release).
  EXPECT_EQ(map.nodes.size(), 5u);
  ASSERT_EQ(map.supports.size(), 2u);
  EXPECT_EQ(map.supports[1].x, 5.0);
  EXPECT_EQ(map.supports[1].y, 0.0);
  PlaneFrameSpec sprung = Portal();
  sprung.base.rotation = 1e8;
  const DiagnosisMap on_springs = MapGeometry(BuildPlaneFrameStructure(sprung));
  ASSERT_EQ(on_springs.supports.size(), 2u);
  EXPECT_EQ(on_springs.supports[1].x, 5.0);
  EXPECT_EQ(on_springs.supports[1].y, 0.0);
}

TEST(DiagnosisMap, DrawsAChainAsAColumn) {
  ChainSpec spec;
  spec.masses = {1, 1, 1};
  spec.springs = {10, 10, 10};
  const DiagnosisMap map = MapGeometry(BuildSpringMassChain(spec));
  EXPECT_FALSE(map.to_scale);
  ASSERT_EQ(map.elements.size(), 3u);
  EXPECT_EQ(map.elements[2].y, (std::vector<double>{2.0, 3.0}));
  ASSERT_EQ(map.nodes.size(), 3u);
  EXPECT_EQ(map.nodes[0].region, "node x1");
  EXPECT_EQ(map.nodes[2].y, 3.0);
}

RankedClass Class(const std::string& kind, const std::string& region, double p) {
  RankedClass c;
  c.kind = kind;
  c.region = region;
  c.probability = p;
  return c;
}

TEST(DiagnosisMap, PlacesEachExplanationWhereItLiesByItsProbability) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EffectRanking r;
  r.classes = {Class("stiffness_loss", "element s1:beam1", 0.62),
               Class("attached_mass", "node n5", 0.2),
               Class("stiffness_loss", "element s1:col1", 0.005),
               Class("material_scaling", "all elements", 0.175)};
  r.kind_probabilities = {
      {"stiffness_loss", 0.625}, {"attached_mass", 0.2}, {"material_scaling", 0.175}};
  const Figure f = DiagnosisMapFigure(map, r, "portal");
  ASSERT_EQ(f.panels.size(), 1u);
  const Plot& p = f.panels[0];
  EXPECT_TRUE(p.equal_axes);
  EXPECT_NE(p.title.find("everywhere: material_scaling P 0.17"), std::string::npos)
      << p.title;
  ASSERT_EQ(p.series.size(), 3u);  // the model, the beam, the node; not col1 (< 0.01)
  EXPECT_EQ(p.series[0].title, "model");
  EXPECT_EQ(p.series[1].title, "stiffness loss, P >= 0.5");
  EXPECT_EQ(p.series[1].y[0], 3.0);
  EXPECT_TRUE(std::isnan(p.series[1].x.back()));  // polylines broken apart
  EXPECT_EQ(p.series[2].title, "attached mass, P 0.1-0.5");
  EXPECT_EQ(p.series[2].style, PlotSeries::Style::kPoints);
}

// A beam's connections named (stiffness loss "connections of s1:beam1") are
// drawn at the beam's two ends, in the stiffness loss's colours.
TEST(DiagnosisMap, DrawsABeamsConnectionsAtItsEnds) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EffectRanking r;
  r.classes = {Class("stiffness_loss", "connections of s1:beam1", 0.93),
               Class("none", "", 0.07)};
  r.kind_probabilities = {{"stiffness_loss", 0.93}, {"none", 0.07}};
  const Plot p = DiagnosisMapFigure(map, r, "portal").panels.at(0);
  ASSERT_EQ(p.series.size(), 2u);  // the model, the connections
  EXPECT_EQ(p.series[1].title, "stiffness loss, P >= 0.5");
  EXPECT_EQ(p.series[1].x.size(), 6u);  // two stubs, each broken by a NaN
  EXPECT_EQ(p.series[1].x[0], 0.0);
  EXPECT_EQ(p.series[1].x[3], 5.0);
}

// A mass between nodes ("n1-n5", its position xi fitted) is drawn at its
// fitted point on the line between the two nodes.
TEST(DiagnosisMap, DrawsAMassBetweenNodesAtItsFittedPoint) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EffectRanking r;
  RankedClass c = Class("attached_mass", "n1-n5", 0.7);
  c.names = {"ln_mass_ratio", "xi"};
  c.theta = Eigen::Vector2d(std::log(0.01), 0.25);
  r.classes = {c, Class("none", "", 0.3)};
  r.kind_probabilities = {{"attached_mass", 0.7}, {"none", 0.3}};
  const Figure f = DiagnosisMapFigure(map, r, "portal");
  const Plot& p = f.panels[0];
  ASSERT_EQ(p.series.size(), 2u);
  EXPECT_EQ(p.series[1].title, "attached mass, P >= 0.5");
  ASSERT_EQ(p.series[1].x.size(), 1u);
  const auto node = [&](const std::string& name) { return NodeOf(map, name); };
  EXPECT_DOUBLE_EQ(p.series[1].x[0], 0.75 * node("n1").x + 0.25 * node("n5").x);
  EXPECT_DOUBLE_EQ(p.series[1].y[0], 0.75 * node("n1").y + 0.25 * node("n5").y);
}

// A pair of effects counts for each of its two: its local part drawn where it
// lies (a softer support; a mass between nodes at its fitted xi, whatever its
// place among the pair's parameters), its global part in the title, each with
// the probability of every class that holds it.
TEST(DiagnosisMap, DrawsEachPartOfAPairWhereItLies) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EffectRanking r;
  RankedClass mass_and_e =
      Class("material_scaling+attached_mass", "all elements + n1-n5", 0.15);
  mass_and_e.names = {"ln_e_factor", "ln_mass_ratio", "xi"};
  mass_and_e.theta = Eigen::Vector3d(0.01, std::log(0.01), 0.25);
  r.classes = {Class("added_mass+support_flexibility", "below 1.2 m + supports", 0.55),
               Class("added_mass", "below 1.2 m", 0.25), mass_and_e,
               Class("none", "", 0.05)};
  r.kind_probabilities = {{"added_mass+support_flexibility", 0.55},
                          {"added_mass", 0.25},
                          {"material_scaling+attached_mass", 0.15},
                          {"none", 0.05}};
  const Plot p = DiagnosisMapFigure(map, r, "portal").panels.at(0);
  // added_mass alone and in the pair; the pair's support part is drawn.
  EXPECT_NE(p.title.find(
                "(everywhere: added_mass P 0.8, material_scaling P 0.15, none P 0.05)"),
            std::string::npos)
      << p.title;
  EXPECT_EQ(p.title.find("support_flexibility"), std::string::npos) << p.title;
  ASSERT_EQ(p.series.size(), 3u);  // the model, the mass, the supports
  EXPECT_EQ(p.series[1].title, "attached mass, P 0.1-0.5");
  ASSERT_EQ(p.series[1].x.size(), 1u);
  const auto node = [&](const std::string& name) { return NodeOf(map, name); };
  EXPECT_DOUBLE_EQ(p.series[1].x[0], 0.75 * node("n1").x + 0.25 * node("n5").x);
  EXPECT_EQ(p.series[2].title, "softer supports, P 0.55");
}

// Two places of one family: both drawn, each mass between nodes at its own
// fitted xi, and two damaged members each in the pair's band.
TEST(DiagnosisMap, DrawsBothPlacesOfAPairOfOneFamily) {
  const DiagnosisMap map = MapGeometry(BuildPlaneFrameStructure(Portal()));
  EffectRanking r;
  RankedClass masses = Class("attached_mass+attached_mass", "n1-n5 + n5-n2", 0.6);
  masses.names = {"ln_mass_ratio", "xi", "ln_mass_ratio", "xi"};
  masses.theta = Eigen::Vector4d(std::log(0.01), 0.25, std::log(0.02), 0.5);
  r.classes = {
      masses,
      Class("stiffness_loss+stiffness_loss", "element s1:col1 + element s1:col2", 0.3),
      Class("none", "", 0.1)};
  r.kind_probabilities = {{"attached_mass+attached_mass", 0.6},
                          {"stiffness_loss+stiffness_loss", 0.3},
                          {"none", 0.1}};
  const Plot p = DiagnosisMapFigure(map, r, "portal").panels.at(0);
  EXPECT_NE(p.title.find("(everywhere: none P 0.1)"), std::string::npos) << p.title;
  ASSERT_EQ(p.series.size(), 3u);  // the model, the two columns, the two masses
  EXPECT_EQ(p.series[1].title, "stiffness loss, P 0.1-0.5");
  EXPECT_EQ(p.series[2].title, "attached mass, P >= 0.5");
  ASSERT_EQ(p.series[2].x.size(), 2u);
  const auto node = [&](const std::string& name) { return NodeOf(map, name); };
  EXPECT_DOUBLE_EQ(p.series[2].x[0], 0.75 * node("n1").x + 0.25 * node("n5").x);
  EXPECT_DOUBLE_EQ(p.series[2].x[1], 0.5 * node("n5").x + 0.5 * node("n2").x);
  const auto& columns = p.series[1].x;  // both columns, x 0 and 5
  EXPECT_NE(std::find(columns.begin(), columns.end(), 0.0), columns.end());
  EXPECT_NE(std::find(columns.begin(), columns.end(), 5.0), columns.end());
}

TEST(DiagnosisMap, RendersWithGnuplot) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot is not installed";
  testing::ScratchDir dir;
  PlaneFrameSpec spec = Portal();
  spec.base.rotation = 1e8;
  EffectRanking r;
  r.classes = {Class("support_flexibility", "supports", 0.7),
               Class("stiffness_loss", "element s1:col1", 0.3)};
  r.kind_probabilities = {{"support_flexibility", 0.7}, {"stiffness_loss", 0.3}};
  const Figure f =
      DiagnosisMapFigure(MapGeometry(BuildPlaneFrameStructure(spec)), r, "x");
  EXPECT_EQ(f.panels[0].series.back().title, "softer supports, P 0.7");
  const PlotStatus status = RenderFigure(f, dir.File("map"));
  ASSERT_TRUE(status.rendered) << status.message;
  std::ifstream script(dir.File("map.gp"));
  const std::string text((std::istreambuf_iterator<char>(script)), {});
  EXPECT_NE(text.find("set size ratio -1"), std::string::npos);
  EXPECT_NE(text.find("lc rgb '#e67e22'"), std::string::npos) << text;  // col1's band
}

}  // namespace
}  // namespace femup
