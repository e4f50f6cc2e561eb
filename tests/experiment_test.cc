// From records to factors: femup simulate's records (RunSimulate), measurements
// identified from them by ERA or read from identify's modes.json, channels
// mapped to DOFs, shapes expanded (PrepareMeasurements), the update and the
// comparison of several studies. References: the continuous cantilever's
// frequencies (beta L = 1.8751, 4.6941), full-DOF model modes, strip theory.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "femup/core/errors.h"
#include "femup/core/io/uff.h"
#include "femup/core/linalg/modal.h"
#include "femup/reporting/output_dir.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/compare_study.h"
#include "femup/studies/simulate_study.h"
#include "femup/studies/study.h"
#include "femup/studies/update_study.h"
#include "scratch_dir.h"

namespace femup {
namespace {

constexpr double kPi = 3.14159265358979323846;

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string Sensors(const std::string& first) {
  std::string s = "[" + first;
  for (int n = 9; n >= 1; --n) s += ", n" + std::to_string(n) + ":ux";
  return s + "]";
}

const std::string kBeam = R"(
model:
  type: cantilever
  length: 1.9
  elements: 10
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
  water_depth: 1.52
  added_mass_basis: transverse
)";

// The "real" beam: the nominal mesh, clamped; water by strip theory to 1.52 m.
std::string RealBeam(double noise) {
  return kBeam + R"(
parameters: {mass: none, stiffness: none, added_mass: none}
records:
  sample_rate_hz: 500
  duration_s: 8
  sensors: )" +
         Sensors("n10:ux") + R"(
  impulse: {dof: "n9:ux"}
  noise: )" +
         std::to_string(noise) + R"(
  seed: 3
  states:
    - {state: air, damping: [0.002, 0.005, 0.01], file: air.uff}
    - state: water
      immersion: wet
      damping: [0.007, 0.006, 0.01]
      water: {depth: 1.52, width: 0.0258, thickness: 0.0341}
      file: water.uff
)";
}

// Simulates the records into `dir`; returns the result.
SimulateResult Simulate(const testing::ScratchDir& dir, double noise) {
  WriteText(dir.File("real.yaml"), RealBeam(noise));
  const Study real = LoadStudy(dir.File("real.yaml"));
  SimulateResult r = RunSimulate(real);
  OutputDir out(dir.File("data"));
  std::vector<std::string> warnings;
  WriteSimulateOutputs(r, false, &out, &warnings);
  out.Commit();
  return r;
}

std::string Nominal(const std::string& measurement_extra, const std::string& sensors) {
  return kBeam + R"(
parameters: {mass: none, stiffness: per_element, added_mass: per_element}
measurements:
  - state: air
    identify: {file: data/air.uff, max_frequency_hz: 100}
    modes: 2
    sensors: )" +
         sensors + "\n" + measurement_extra + R"(
  - state: water
    immersion: wet
    identify: {file: data/water.uff, max_frequency_hz: 100}
    modes: 2
    sensors: )" +
         Sensors("n10:ux") + "\n" + measurement_extra + "\n";
}

double CantileverHz(double beta_l) {
  const double ei = 206e9 * 8.53e-8, rho_a = 7850 * 8.8e-4, l = 1.9;
  return beta_l * beta_l / (2 * kPi * l * l) * std::sqrt(ei / rho_a);
}

TEST(Simulate, RecordsAreUffTimeHistoriesOfTheStructure) {
  testing::ScratchDir dir;
  const SimulateResult r = Simulate(dir, 0.0);
  ASSERT_EQ(r.states.size(), 2u);
  // Modes in the records: the continuous beam's, to the mesh's accuracy.
  EXPECT_NEAR(r.states[0].frequencies_hz[0] / CantileverHz(1.87510407), 1.0, 1e-4);
  EXPECT_NEAR(r.states[0].frequencies_hz[1] / CantileverHz(4.69409113), 1.0, 1e-3);
  // Every mode kept lies below the default cut-off (0.4 x 500 Hz).
  EXPECT_LE(r.states[0].frequencies_hz.maxCoeff(), 200.0);
  // Strip theory: C_A from the rectangle table, m_a = C_A rho pi a^2.
  const double a = 0.0258 / 2;
  EXPECT_NEAR(r.states[1].added_mass_per_length,
              r.states[1].added_mass_coefficient * 1000 * kPi * a * a, 1e-12);
  EXPECT_GT(r.states[1].added_mass_coefficient, 1.51);  // a/b = 0.76: between 1.51
  EXPECT_LT(r.states[1].added_mass_coefficient, 1.70);  // and 1.70
  EXPECT_LT(r.states[1].frequencies_hz[0], r.states[0].frequencies_hz[0]);

  const UffFile f = ReadUff(dir.File("data/air.uff"));
  const auto functions = f.Functions();
  ASSERT_EQ(functions.size(), 10u);
  EXPECT_EQ(functions[0]->function_type, 1);
  EXPECT_EQ(functions[0]->response_node, 10);
  EXPECT_EQ(functions[0]->response_direction, 1);
  EXPECT_EQ(functions[9]->response_node, 1);
  EXPECT_EQ(functions[0]->reference_node, 9);
  EXPECT_NEAR(functions[0]->abscissa_increment, 1.0 / 500, 1e-15);
  EXPECT_EQ(functions[0]->y.size(), 4000);
}

TEST(Simulate, NeedsARecordsSection) {
  testing::ScratchDir dir;
  WriteText(dir.File("s.yaml"),
            kBeam + "measurements:\n  - {state: air, frequencies_hz: [7]}\n");
  EXPECT_THROW(RunSimulate(LoadStudy(dir.File("s.yaml"))), InputError);
  // A file name with a folder, a bad extension, water on a dry state.
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"file: air.uff", "file: sub/air.uff"},
           {"file: air.uff", "file: air.wav"},
           {"{state: air, damping",
            "{state: air, immersion: dry, water: {depth: 1, width: 0.02, thickness: "
            "0.03}, damping"}}) {
    std::string text = RealBeam(0);
    text.replace(text.find(from), from.size(), to);
    WriteText(dir.File("bad.yaml"), text);
    EXPECT_THROW(LoadStudy(dir.File("bad.yaml")), InputError) << to;
  }
}

TEST(PrepareMeasurements, IdentifiesMapsChannelsAndExpands) {
  testing::ScratchDir dir;
  const SimulateResult sim = Simulate(dir, 0.01);
  // Channel 1 reversed; expansion by SEREP on two model modes.
  WriteText(dir.File("a.yaml"),
            Nominal("    expansion: {method: serep, modes: 2}", Sensors("-n10:ux")));
  const Study study = LoadStudy(dir.File("a.yaml"));
  const std::vector<PreparedState> p = PrepareMeasurements(study);
  ASSERT_EQ(p.size(), 2u);
  for (int s = 0; s < 2; ++s) {
    ASSERT_TRUE(p[s].identified.has_value());
    EXPECT_EQ(p[s].identified_modes, (std::vector<int>{1, 2}));
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(p[s].at_sensors.frequencies_hz[k] / sim.states[s].frequencies_hz[k],
                  1.0, 1e-3);
    }
    EXPECT_EQ(p[s].at_sensors.sensor_dofs.size(), 10u);
    EXPECT_EQ(p[s].data.shapes.rows(), study.model.num_dofs());
    EXPECT_TRUE(p[s].data.sensor_dofs.empty());
    EXPECT_EQ(p[s].expansion_method, "serep");
  }
  // The expansion's quality shows the reversed sensor: the model's modes cannot
  // fit air's shapes with channel 1 flipped, and fit water's.
  EXPECT_LT(p[0].expansion_sensor_mac.maxCoeff(), 0.9);
  EXPECT_GT(p[1].expansion_sensor_mac.minCoeff(), 0.99);
  // The reversed channel: air's first row has the opposite sign to water's
  // (unreversed) relative to the second row.
  const auto& air = p[0].at_sensors.shapes;
  const auto& water = p[1].at_sensors.shapes;
  EXPECT_LT(air(0, 0) * air(1, 0) * water(0, 0) * water(1, 0), 0.0);
  // Against the full-DOF truth: the expanded water mode 1 vs the model's own
  // wet mode (every DOF), with the strip-theory mass as added mass.
  const Modes dry = SolveModes(study.model.stiffness(), study.model.mass());
  EXPECT_GT(Mac(p[1].data.shapes.col(0), dry.shapes.col(0)), 0.999);
}

TEST(PrepareMeasurements, SkipsChannelsAndReadsModesJson) {
  testing::ScratchDir dir;
  Simulate(dir, 0.0);
  std::string sensors = Sensors("skip");
  WriteText(dir.File("a.yaml"), Nominal("", sensors));
  const std::vector<PreparedState> p = PrepareMeasurements(LoadStudy(dir.File("a.yaml")));
  EXPECT_EQ(p[0].at_sensors.sensor_dofs.size(), 9u);
  EXPECT_EQ(p[0].at_sensors.shapes.rows(), 9);
  ASSERT_TRUE(p[1].identified.has_value());
  {
    OutputDir out(dir.File("ident"));
    std::vector<std::string> warnings;
    WriteIdentifyOutputs(*p[1].identified, false, &out, &warnings);
    out.Commit();
  }
  std::string text = Nominal("", Sensors("n10:ux"));
  const std::string from = "identify: {file: data/water.uff, max_frequency_hz: 100}";
  text.replace(text.find(from), from.size(), "modes_file: ident/modes.json");
  WriteText(dir.File("b.yaml"), text);
  const std::vector<PreparedState> q = PrepareMeasurements(LoadStudy(dir.File("b.yaml")));
  EXPECT_FALSE(q[1].identified.has_value());
  EXPECT_EQ(q[1].source, dir.File("ident/modes.json"));
  EXPECT_NEAR(q[1].data.frequencies_hz[1], p[1].data.frequencies_hz[1], 1e-9);
}

TEST(PrepareMeasurements, BadInputIsNamed) {
  testing::ScratchDir dir;
  Simulate(dir, 0.0);
  auto expect = [&](std::string text, const std::string& needle, bool at_load) {
    WriteText(dir.File("bad.yaml"), text);
    try {
      const Study s = LoadStudy(dir.File("bad.yaml"));
      ASSERT_FALSE(at_load) << needle;
      PrepareMeasurements(s);
      ADD_FAILURE() << "no error: " << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  const std::string good = Nominal("", Sensors("n10:ux"));
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  expect(with("modes: 2", "modes: 5"), "gives 2 stable mode", false);
  expect(with("sensors: [n10:ux, ", "sensors: ["), "10 channels", false);
  expect(with("data/air.uff", "data/none.uff"), "none.uff", false);
  expect(with("sensors: [n10:ux", "sensors: [n99:ux"), "n99:ux", true);
  expect(with("sensors: [n10:ux, n9:ux", "sensors: [n10:ux, n10:ux"), "twice", true);
  expect(with("    modes: 2\n", "    modes: 2\n    frequencies_hz: [7, 49]\n"),
         "not both", true);
  expect(with("    modes: 2\n", "    modes: 2\n    expansion: {method: guyan}\n"),
         "guyan", true);
}

TEST(Update, AddedMassFromRecordsMatchesStripTheory) {
  testing::ScratchDir dir;
  const SimulateResult sim = Simulate(dir, 0.01);
  // The truth is in the model's span (same mesh, strip theory on whole
  // elements); the error left is the expansion's: SEREP on 3 dry modes gives
  // -2.5 % here (2 modes -10 %, 4 modes -15 %: docs/experiment.md).
  WriteText(dir.File("a.yaml"),
            Nominal("    expansion: {method: serep, modes: 3}", Sensors("n10:ux")));
  const UpdateResult r = RunUpdate(LoadStudy(dir.File("a.yaml")));
  ASSERT_TRUE(r.solution.summary.usable());
  const double strip_kg = sim.states[1].added_mass_per_length * 1.52;
  EXPECT_NEAR(r.added_mass_summary.total_kg / strip_kg, 1.0, 0.04);
  EXPECT_EQ(r.added_mass_summary.wet_elements, 8);
  EXPECT_NEAR(r.added_mass_summary.wet_length_m, 1.52, 1e-12);
  // Sa is the mean of the eight factors.
  double mean = 0;
  for (int i = 10; i < 18; ++i) mean += r.solution.x[i] / 8;
  EXPECT_NEAR(r.added_mass_summary.sa, mean, 1e-12);
  // Eq. 2 from the measured frequencies.
  ASSERT_EQ(r.added_mass_summary.eq2_coefficients.size(), 2u);
  const double q = r.states[0].measured_hz[0] / r.states[1].measured_hz[0];
  EXPECT_NEAR(r.added_mass_summary.eq2_coefficients[0], q * q - 1, 1e-12);
  for (const StateComparison& c : r.states) {
    for (Eigen::Index k = 0; k < 2; ++k)
      EXPECT_NEAR(c.updated_hz[k] / c.measured_hz[k], 1.0, 0.01) << c.state;
  }
}

TEST(Compare, TwoStudiesSideBySide) {
  testing::ScratchDir dir;
  Simulate(dir, 0.0);
  const std::string a =
      Nominal("    expansion: {method: serep, modes: 2}", Sensors("n10:ux"));
  std::string e = a;
  const std::string from = "added_mass: per_element}";
  e.replace(e.find(from), from.size(), "added_mass: {layout: single, select: wet}}");
  WriteText(dir.File("a.yaml"), a);
  WriteText(dir.File("e.yaml"), e);
  const CompareResult r = RunCompare({dir.File("a.yaml"), dir.File("e.yaml")});
  ASSERT_EQ(r.updates.size(), 2u);
  EXPECT_EQ(r.element_factor[0].size(), 8u);
  ASSERT_EQ(r.element_factor[1].size(), 8u);  // one factor over eight elements
  EXPECT_EQ(r.element_factor[1][0], r.element_factor[1][7]);
  EXPECT_NEAR(r.updates[1].added_mass_summary.sa, r.element_factor[1][0], 1e-12);
  EXPECT_THROW(RunCompare({dir.File("a.yaml")}), InputError);
  EXPECT_NE(CompareReport(r).find("Sa"), std::string::npos);
}

}  // namespace
}  // namespace femup
