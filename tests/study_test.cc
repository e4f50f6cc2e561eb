// Study files: every bad input ends in an InputError naming the file and the
// field; good files build the model and measurements they describe.
#include "femup/studies/study.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "femup/core/errors.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

std::string Write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(::testing::TempDir()) / "femup_study_test";
  fs::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

const char* kChain = R"(
model:
  type: chain
  masses: [50, 50, 50]
  springs: [2.9e7, 2.9e7, 2.9e7]
  wet: [1]
truth: {"added_mass[1]": 0.2}
measurements:
  - {state: air, simulate_modes: 2}
  - {state: water, simulate_modes: 2}
)";

// Expects LoadStudy to throw an InputError whose message contains every needle.
void ExpectError(const std::string& name, const std::string& text,
                 std::vector<std::string> needles) {
  const std::string path = Write(name, text);
  try {
    LoadStudy(path);
    ADD_FAILURE() << name << ": no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    for (const auto& n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << n << " in " << msg;
  }
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

TEST(Study, LoadsAChainStudy) {
  const Study s = LoadStudy(Write("ok.yaml", kChain));
  EXPECT_EQ(s.model.num_dofs(), 3);
  EXPECT_EQ(s.model.num_parameters(), 7);  // 3 mass, 3 stiffness, 1 added mass
  ASSERT_TRUE(s.truth.has_value());
  EXPECT_DOUBLE_EQ((*s.truth)[s.model.FindParameter("added_mass[1]")], 0.2);
  const auto states = MeasuredStates(s);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[1].immersion, Immersion::kWet);  // "water" defaults to wet
  EXPECT_EQ(s.name, "ok");
}

TEST(Study, JsonIsAccepted) {
  const Study s = LoadStudy(Write("ok.json", R"({
    "model": {"type": "chain", "masses": [1, 1], "springs": [10, 10]},
    "parameters": {"added_mass": "none"},
    "measurements": [{"state": "air", "frequencies_hz": [0.3, 0.8],
                      "shapes": [[1, 1.6], [1, -0.6]]}]})"));
  EXPECT_EQ(s.model.num_parameters(), 4);
  EXPECT_EQ(s.measurements[0].data.shapes.rows(), 2);
}

TEST(Study, MissingFile) {
  try {
    LoadStudy("/nonexistent/study.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/study.yaml: study file not found"),
              std::string::npos);
  }
}

TEST(Study, SyntaxErrorNamesLine) {
  ExpectError("syntax.yaml", "model: [1, 2\n", {"not valid YAML"});
}

TEST(Study, UnknownKeysAreRejected) {
  ExpectError("unknown_top.yaml", std::string(kChain) + "solvr: {name: lstsq}\n",
              {"solvr", "unknown key", "solver"});
  ExpectError("unknown_model.yaml",
              Replace(kChain, "wet: [1]", "wet: [1]\n  colour: red"),
              {"model.colour", "unknown key"});
}

TEST(Study, WrongSizes) {
  ExpectError("springs.yaml",
              Replace(kChain, "springs: [2.9e7, 2.9e7, 2.9e7]", "springs: [1, 2]"),
              {"model.springs", "expected 3"});
  ExpectError("shape_rows.yaml",
              Replace(kChain, "- {state: air, simulate_modes: 2}",
                      "- {state: air, frequencies_hz: [30], shapes: [[1, 2]]}"),
              {"shapes", "expected 3"});
  ExpectError("shape_count.yaml",
              Replace(kChain, "- {state: air, simulate_modes: 2}",
                      "- {state: air, frequencies_hz: [30, 40], shapes: [[1, 2, 3]]}"),
              {"1 shapes for 2 frequencies"});
}

TEST(Study, SensorsMustMatchShapes) {
  ExpectError("sensors.yaml",
              Replace(kChain, "- {state: air, simulate_modes: 2}",
                      "- {state: air, frequencies_hz: [30], sensors: [x1, x2], "
                      "shapes: [[1, 2, 3]]}"),
              {"expected 2 (one per sensor)"});
  ExpectError("sensor_label.yaml",
              Replace(kChain, "- {state: air, simulate_modes: 2}",
                      "- {state: air, frequencies_hz: [30], sensors: [x1, x9], "
                      "shapes: [[1, 2]]}"),
              {"sensors[2]", "'x9'", "x1, x2, x3"});
}

// Sensors as points (sensor.h): read into interpolation weights; every bad
// placement is refused naming the sensor's field and what is wrong.
TEST(Study, SensorsBetweenNodes) {
  const std::string frame = R"(
model: {type: plane_frame, storeys: 1, bays: 1, storey_height: 3, bay_width: 6,
        elements_per_member: 2, column: {E: 210e9, A: 7.8e-3, I: 8.4e-5, rho: 7850},
        beam: {E: 210e9, A: 5.4e-3, I: 1.9e-4, rho: 7850}}
measurements:
  - state: test
    frequencies_hz: [2.0]
    sensors: [n1:ux, {at: [0, 2.25], direction: x}, {node: n3, direction: [1, 0]},
              {at: [1.5, 3], direction: -y}]
    shapes: [[1, 0.8, 0.9, 0.1]]
)";
  const Study s = LoadStudy(Write("points.yaml", frame));
  const ModalData& d = s.measurements[0].data;
  ASSERT_TRUE(d.HasInterpolatedSensors());
  EXPECT_TRUE(d.sensor_dofs.empty());
  EXPECT_EQ(d.sensor_weights.rows(), 4);
  EXPECT_EQ(d.sensor_weights.cols(), s.model.num_dofs());
  EXPECT_EQ(d.sensor_names, (std::vector<std::string>{"n1:ux", "at(0, 2.25, 0):ux",
                                                      "n3:ux", "at(1.5, 3, 0):-uy"}));
  // The middle of the beam's first element (L = 3 m), read along -y: Hermite
  // weights -1/2 on both ends' uy, -/+ L/8 on their rz; nothing else.
  const Eigen::RowVectorXd w = Eigen::MatrixXd(d.sensor_weights).row(3);
  const auto at = [&](const std::string& label) { return w[s.model.FindDof(label)]; };
  EXPECT_EQ((w.array() != 0).count(), 4);
  EXPECT_DOUBLE_EQ(at("n1:uy"),
                   -0.5);  // joint n1 at (0, 3), the beam's node n5 at (3, 3)
  EXPECT_DOUBLE_EQ(at("n5:uy"), -0.5);
  EXPECT_DOUBLE_EQ(at("n1:rz"), -3.0 / 8);
  EXPECT_DOUBLE_EQ(at("n5:rz"), 3.0 / 8);
  ExpectError("off.yaml", Replace(frame, "[1.5, 3]", "[1.5, 2]"),
              {"sensors[4].at", "not on the structure", "m away"});
  ExpectError("plane.yaml", Replace(frame, "direction: -y", "direction: z"),
              {"sensors[4].direction", "no DOFs along z"});
  ExpectError("word.yaml", Replace(frame, "direction: -y", "direction: up"),
              {"sensors[4].direction", "expected x, y, z"});
  ExpectError("node.yaml", Replace(frame, "node: n3", "node: n33"),
              {"sensors[3].node", "'n33'"});
  ExpectError("both.yaml",
              Replace(frame, "{node: n3, direction: [1, 0]}",
                      "{node: n3, at: [0, 1], direction: x}"),
              {"sensors[3]", "exactly one of"});
  ExpectError("along.yaml", Replace(frame, "{node: n3, direction: [1, 0]}", "{x: 1.0}"),
              {"sensors[3].x", "cantilever"});
  ExpectError("twice.yaml",
              Replace(frame, "{node: n3, direction: [1, 0]}", "{node: n1, direction: x}"),
              {"sensors[3]", "reads the same as sensor 1"});
  ExpectError("key.yaml",
              Replace(frame, "{node: n3, direction: [1, 0]}", "{node: n3, dir: x}"),
              {"sensors[3]", "dir"});
  ExpectError("rows.yaml", Replace(frame, "[[1, 0.8, 0.9, 0.1]]", "[[1, 0.8, 0.9]]"),
              {"expected 4 (one per sensor)"});
}

TEST(Study, NaNAndBadNumbers) {
  ExpectError("nan.yaml",
              Replace(kChain, "masses: [50, 50, 50]", "masses: [50, .nan, 50]"),
              {"model.masses[2]", "expected a number"});
  ExpectError("nan2.yaml",
              Replace(kChain, "masses: [50, 50, 50]", "masses: [50, nan, 50]"),
              {"model.masses[2]", "finite"});
  ExpectError("word.yaml",
              Replace(kChain, "masses: [50, 50, 50]", "masses: [50, heavy, 50]"),
              {"'heavy'"});
  ExpectError("negative.yaml",
              Replace(kChain, "masses: [50, 50, 50]", "masses: [50, -5, 50]"),
              {"model.masses[2]", "positive"});
  ExpectError("freq.yaml",
              Replace(kChain, "- {state: air, simulate_modes: 2}",
                      "- {state: air, frequencies_hz: [-3], shapes: [[1, 2, 3]]}"),
              {"frequencies", "positive"});
}

TEST(Study, NonPositiveDefiniteMassFromMatrixMarket) {
  const std::string dir = std::string(FEMUP_TEST_DATA_DIR) + "/mm/model/";
  const std::string bad_m = Write("bad_m.mtx",
                                  "%%MatrixMarket matrix coordinate real symmetric\n"
                                  "3 3 3\n1 1 1\n2 2 -1\n3 3 1\n");
  const std::string text = "model:\n  type: matrix_market\n  stiffness: " + dir +
                           "k.mtx\n  mass: " + bad_m +
                           "\n  elements:\n    - {id: 1, stiffness: " + dir +
                           "e3_k.mtx, mass: " + dir + "e3_m.mtx}\n" +
                           "parameters: {added_mass: none}\n"
                           "measurements:\n  - {state: air, frequencies_hz: [1]}\n";
  ExpectError("not_pd.yaml", text, {"model", "not positive definite"});
}

TEST(Study, NamesMustMatchParameters) {
  ExpectError("fix.yaml", std::string(kChain) + "parameters: {fix: {\"mass[9]\": 0}}\n",
              {"parameters.fix.mass[9]", "no parameter is called 'mass[9]'", "mass[1]"});
  ExpectError("truth.yaml", Replace(kChain, "added_mass[1]", "added_mass[2]"),
              {"truth.added_mass[2]", "no parameter"});
}

TEST(Study, SimulationNeedsTruthAndSolverMustExist) {
  ExpectError("no_truth.yaml", Replace(kChain, "truth: {\"added_mass[1]\": 0.2}", ""),
              {"simulate_modes", "truth"});
  ExpectError("solver.yaml", std::string(kChain) + "solver: {name: magic}\n",
              {"unknown solver 'magic'", "lstsq"});
  ExpectError("form.yaml", std::string(kChain) + "system: {form: folded}\n",
              {"system.form", "stacked or summed"});
}

TEST(Study, CantileverOptions) {
  const Study s = LoadStudy(Write("beam.yaml", R"(
model:
  type: cantilever
  node_heights: [0, 0.5, 1.0, 1.2, 1.9]
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
  water_depth: 1.1
  added_mass_basis: transverse
  support: {rotation: 1e5}
  lumped_masses: [{node: 4, mass: 0.2, rotary_inertia: 1e-5}]
parameters:
  mass: none
  stiffness: {layout: groups, groups: [[1, 2], [3, 4]]}
  added_mass: single
measurements:
  - {state: water, frequencies_hz: [6.5]}
)"));
  // Base rotation is free (held by the spring): 4 nodes x 3 + 1 DOF.
  EXPECT_EQ(s.model.num_dofs(), 13);
  EXPECT_EQ(s.model.ParameterNames(),
            (std::vector<std::string>{"stiffness[e1+e2]", "stiffness[e3+e4]",
                                      "added_mass[wet]"}));
  // The shear form variant: A / 2 unless the section states its shear area.
  ASSERT_EQ(s.structure.form_variants.size(), 1u);
  EXPECT_NE(s.structure.form_variants[0].name.find("shear area 0.00044 m^2"),
            std::string::npos)
      << s.structure.form_variants[0].name;
  const Study stated = LoadStudy(Write("beam_shear.yaml", R"(
model:
  type: cantilever
  length: 1.9
  elements: 4
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850, shear_area: 7.3e-4}
measurements:
  - {state: air, frequencies_hz: [6.5]}
)"));
  EXPECT_NE(stated.structure.form_variants.at(0).name.find("shear area 0.00073 m^2"),
            std::string::npos);
  ExpectError("beam_shear_bad.yaml", R"(
model:
  type: cantilever
  length: 1.9
  elements: 4
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850, shear_area: 9e-4}
measurements: [{state: air, frequencies_hz: [6.5]}]
)",
              {"model.section.shear_area", "cannot exceed the area A"});
  ExpectError("beam_bad.yaml", R"(
model:
  type: cantilever
  node_heights: [0, 0.5, 0.4]
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
measurements: [{state: air, frequencies_hz: [6.5]}]
)",
              {"node_heights", "increase"});
}

// Fuzzing (issue 25): a key that is null, a list or a mapping escaped LoadStudy
// as yaml-cpp's TypedBadConversion ("internal error", without the file's name).
// The inputs of fuzz/regressions/study/ and the same at every depth.
TEST(Study, KeysThatAreNotNamesAreInputErrors) {
  ExpectError("list_key.yaml", "[a]: 1\n",
              {"list_key.yaml:1:1", "expected each key to be a name, found a list"});
  ExpectError("complex_key.yaml", "name: x\n? [a]\n: 1\n",
              {"complex_key.yaml:2:3", "found a list"});
  ExpectError("map_key.yaml", "{a: 1}: 2\n", {"found a mapping"});
  ExpectError("null_key.yaml", "~: 1\nmodel: {type: chain}\n",
              {"null_key.yaml:1:1", "found an empty (null) key"});
  ExpectError("empty_key.yaml", "? \n: 1\n", {"empty_key.yaml:2:1", "found a mapping"});
  ExpectError("truth_key.yaml", Replace(kChain, "{\"added_mass[1]\": 0.2}", "{[a]: 0.2}"),
              {"truth_key.yaml:", "truth: expected each key to be a name, found a list"});
  ExpectError("model_key.yaml", Replace(kChain, "  wet: [1]\n", "  wet: [1]\n  [x]: 1\n"),
              {"model: expected each key to be a name"});
  const std::string parameters = "parameters:\n  fix: {? [m]: 0.1}\n";
  ExpectError("fix_key.yaml", kChain + parameters, {"parameters.fix: expected each key"});
  ExpectError("bounds_key.yaml",
              kChain + std::string("parameters:\n  bounds: {{a: 1}: [0, 1]}\n"),
              {"parameters.bounds: expected each key to be a name, found a mapping"});
  ExpectError(
      "equality_key.yaml",
      kChain + std::string("parameters:\n  equalities:\n    - coefficients: {[a]: 1}\n"),
      {"parameters.equalities[1].coefficients: expected each key"});
}

// Fuzzing (issue 25): counts that allocate before any check. A cantilever of
// 10^9 elements allocated 8 GB of node heights (std::bad_alloc, "internal
// error"); "modes: 1000000000" a list of 10^9 mode numbers.
// fuzz/regressions/study/.
TEST(Study, CountsThatWouldExhaustMemoryAreInputErrors) {
  const std::string beam = R"(
model:
  type: cantilever
  length: 1.9
  elements: 1000000000
  section: {E: 206e9, A: 8.8e-4, I: 8.53e-8, rho: 7850}
measurements:
  - {state: air, frequencies_hz: [6.5]}
)";
  ExpectError(
      "elements.yaml", beam,
      {"elements.yaml:5:13: model.elements: expected at most 5000 elements, found "
       "1000000000"});
  std::string heights = "[0";
  for (int i = 1; i <= 5001; ++i) heights += ", " + std::to_string(i);
  ExpectError(
      "heights.yaml",
      Replace(Replace(beam, "  length: 1.9\n", ""), "elements: 1000000000",
              "node_heights: " + heights + "]"),
      {"model.node_heights: has 5002 nodes; expected at most 5001 (5000 elements)"});
  ExpectError("modes.yaml",
              Replace(kChain, "{state: water, simulate_modes: 2}",
                      "{state: water, modes_file: m.json, sensors: [x1, x2, "
                      "x3], modes: 1000000000}"),
              {"measurements[2].modes: expected at most 3 modes (the model has 3 DOFs), "
               "found 1000000000"});
}

// Fuzzing (issue 25, session 20's campaign): a seed of 2.2e29 was converted to
// unsigned long long out of range (undefined behaviour, UBSan's report). A seed
// is a whole number from 0 to 2^53. fuzz/regressions/study/.
TEST(Study, SeedsOutOfRangeAreInputErrors) {
  const std::string noise = "noise_study:\n  levels: [0.01]\n  seed: ";
  ExpectError("huge_seed.yaml", kChain + noise + "2.2e29\n",
              {"noise_study.seed: expected a whole number from 0 to 2^53", "2.2e29"});
  ExpectError("fraction_seed.yaml", kChain + noise + "1.5\n",
              {"noise_study.seed: expected a whole number"});
  ExpectError("negative_seed.yaml", kChain + noise + "-3\n",
              {"noise_study.seed: expected a whole number"});
  EXPECT_EQ(ParseStudy(kChain + noise + "9007199254740992\n", "s.yaml").noise_study->seed,
            9007199254740992ull);
}

// The text of a study, without a file: errors name the path given.
TEST(Study, ParseStudyReadsTextAndNamesThePath) {
  const Study s = ParseStudy(kChain, "in_memory/chain.yaml");
  EXPECT_EQ(s.model.num_dofs(), 3);
  EXPECT_EQ(s.path, "in_memory/chain.yaml");
  try {
    ParseStudy("model: [unclosed\n", "in_memory/bad.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("in_memory/bad.yaml:"), std::string::npos)
        << e.what();
  }
}

// model.shear_building: the chain idealises a building, and its structure
// carries the flexural form variants; a value that is not a boolean is refused
// naming the key.
TEST(Study, AChainStatedAsAShearBuildingCarriesItsFormVariant) {
  const Study plain =
      ParseStudyModel("model: {type: chain, masses: [1, 2, 3], springs: [10, 20, 30]}\n",
                      "in_memory/a.json");
  EXPECT_TRUE(plain.structure.form_variants.empty());
  const Study building = ParseStudyModel(
      "model: {type: chain, masses: [1, 2, 3], springs: [10, 20, 30], shear_building: "
      "true}\n",
      "in_memory/b.json");
  EXPECT_EQ(building.structure.form_variants.size(), 2u);
  try {
    ParseStudyModel(
        "model: {type: chain, masses: [1, 2], springs: [10, 20], shear_building: 3}\n",
        "in_memory/c.json");
    ADD_FAILURE() << "no error for shear_building: 3";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model.shear_building"), std::string::npos)
        << e.what();
  }
}

// A model and its factors alone (the Python module's model_from_dict): no
// measurements needed, the same checks and messages as a whole study, and the
// keys of the other sections refused.
TEST(Study, ParseStudyModelReadsModelAndFactorsOnly) {
  const Study s = ParseStudyModel(
      "model: {type: chain, masses: [1, 2, 3], springs: [10, 20, 30], wet: [2]}\n"
      "parameters: {mass: none, fix: {\"stiffness[2]\": 0.1}}\n"
      "truth: {\"added_mass[2]\": 0.3}\n",
      "in_memory/model.json");
  EXPECT_EQ(s.model.num_dofs(), 3);
  EXPECT_EQ(s.model.ParameterNames(),
            (std::vector<std::string>{"stiffness[1]", "stiffness[2]", "stiffness[3]",
                                      "added_mass[2]"}));
  EXPECT_EQ(s.fixed.at("stiffness[2]"), 0.1);
  ASSERT_TRUE(s.truth.has_value());
  EXPECT_EQ((*s.truth)[3], 0.3);
  EXPECT_TRUE(s.measurements.empty());
  EXPECT_EQ(s.name, "model");
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"model: {type: chain, masses: [1, -2], springs: [1, 1]}\n",
            "model.masses[2]"},
           {"model: {type: chain, masses: [1], springs: [1]}\nmeasurements: []\n",
            "measurements: unknown key"},
           {"parameters: {mass: none}\n", "missing required key 'model'"}}) {
    try {
      ParseStudyModel(text, "in_memory/model.json");
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("in_memory/model.json"), std::string::npos);
    }
  }
}

// diagnosis.priors and diagnosis.weights (docs/diagnosis.md, "Stated priors"):
// parsed in the quantities' own units, checked against the model while the
// study is read, every refusal naming the file and the field.
const char* kShear = R"(
model:
  type: chain
  masses: [1e5, 1e5, 1e5, 1e5]
  springs: [2e8, 2e8, 2e8, 2e8]
measurements:
  - {state: air, frequencies_hz: [1.9, 5.5, 8.4]}
diagnosis:
  candidates: [attached_mass, stiffness_loss, material_scaling, support_flexibility]
)";

std::string WithPriors(const std::string& lines) { return kShear + lines; }

TEST(Study, StatedPriorsAreRead) {
  const Study s = LoadStudy(Write("priors.yaml", WithPriors(R"(  priors:
    attached_mass: {mass_kg: [0.002, 0.010], regions: [x3, x4]}
    material_scaling: {factor: {normal: [1.0, 0.05]}}
    stiffness_loss: {loss: [0.05, 0.6], regions: [3, 4]}
    support_flexibility: {compliance_ratio: [0.01, 10]}
  weights: {none: 1, stiffness_loss: 2}
)")));
  ASSERT_TRUE(s.diagnosis.has_value());
  const StatedPriors& p = s.diagnosis->priors;
  ASSERT_EQ(p.families.size(), 4u);
  const FamilyPrior* mass = p.Find("attached_mass");
  ASSERT_NE(mass, nullptr);
  ASSERT_EQ(mass->quantities.size(), 1u);
  EXPECT_EQ(mass->quantities[0].quantity, "mass_kg");
  EXPECT_FALSE(mass->quantities[0].normal);
  EXPECT_DOUBLE_EQ(mass->quantities[0].lower, 0.002);
  EXPECT_DOUBLE_EQ(mass->quantities[0].upper, 0.010);
  EXPECT_EQ(mass->regions, (std::vector<std::string>{"x3", "x4"}));
  const FamilyPrior* e = p.Find("material_scaling");
  ASSERT_NE(e, nullptr);
  EXPECT_TRUE(e->quantities[0].normal);
  EXPECT_DOUBLE_EQ(e->quantities[0].mean, 1.0);
  EXPECT_DOUBLE_EQ(e->quantities[0].sigma, 0.05);
  EXPECT_EQ(p.Find("stiffness_loss")->regions, (std::vector<std::string>{"3", "4"}));
  EXPECT_DOUBLE_EQ(p.Weight("stiffness_loss"), 2);
  EXPECT_DOUBLE_EQ(p.Weight("none"), 1);
  EXPECT_DOUBLE_EQ(p.Weight("attached_mass"), 1);
  // Without the keys: nothing stated.
  EXPECT_TRUE(LoadStudy(Write("no_priors.yaml", kShear)).diagnosis->priors.empty());
}

TEST(Study, BadStatedPriorsNameTheField) {
  ExpectError("p_lower.yaml",
              WithPriors("  priors: {attached_mass: {mass_kg: [0.01, 0.002]}}\n"),
              {"diagnosis.priors.attached_mass.mass_kg: lower 0.01 > upper 0.002"});
  ExpectError("p_equal.yaml",
              WithPriors("  priors: {attached_mass: {mass_kg: [2, 2]}}\n"),
              {"diagnosis.priors.attached_mass.mass_kg: lower = upper"});
  ExpectError(
      "p_family.yaml", WithPriors("  priors: {corrosion: {rate: [1, 2]}}\n"),
      {"diagnosis.priors.corrosion: unknown family 'corrosion'", "attached_mass"});
  ExpectError("p_key.yaml", WithPriors("  priors: {attached_mass: {mass: [1, 2]}}\n"),
              {"diagnosis.priors.attached_mass.mass: unknown key", "mass_kg, regions"});
  ExpectError("p_std.yaml",
              WithPriors("  priors: {material_scaling: {factor: {normal: [1.0, 0]}}}\n"),
              {"diagnosis.priors.material_scaling.factor.normal[2]",
               "positive standard deviation"});
  ExpectError(
      "p_negstd.yaml",
      WithPriors("  priors: {material_scaling: {factor: {normal: [1.0, -0.1]}}}\n"),
      {"diagnosis.priors.material_scaling.factor.normal[2]"});
  ExpectError("p_normal_key.yaml",
              WithPriors("  priors: {material_scaling: {factor: {gauss: [1.0, 0.1]}}}\n"),
              {"diagnosis.priors.material_scaling.factor.gauss: unknown key"});
  ExpectError("p_shape.yaml", WithPriors("  priors: {attached_mass: {mass_kg: [1]}}\n"),
              {"diagnosis.priors.attached_mass.mass_kg", "expected [lower, upper]"});
  ExpectError("p_scalar.yaml", WithPriors("  priors: {attached_mass: {mass_kg: 5}}\n"),
              {"diagnosis.priors.attached_mass.mass_kg", "expected [lower, upper]"});
  ExpectError("p_domain.yaml",
              WithPriors("  priors: {stiffness_loss: {loss: [0.5, 1.2]}}\n"),
              {"diagnosis.priors.stiffness_loss.loss", "(0, 0.99]"});
  ExpectError("p_mass.yaml",
              WithPriors("  priors: {attached_mass: {mass_kg: [-1, 5]}}\n"),
              {"diagnosis.priors.attached_mass.mass_kg", "(0, inf)"});
  ExpectError("p_mean.yaml",
              WithPriors("  priors: {material_scaling: {factor: {normal: [-1, 0.1]}}}\n"),
              {"diagnosis.priors.material_scaling.factor", "the mean -1"});
  ExpectError(
      "p_region.yaml",
      WithPriors("  priors: {attached_mass: {mass_kg: [1, 5], regions: [x2, n7]}}\n"),
      {"diagnosis.priors.attached_mass.regions[2]", "'n7' names no element"});
  ExpectError("p_region_kind.yaml",
              WithPriors("  priors: {stiffness_loss: {regions: [x2]}}\n"),
              {"diagnosis.priors.stiffness_loss.regions[1]", "names a node"});
  ExpectError("p_region_one.yaml",
              WithPriors("  priors: {material_scaling: {regions: [1]}}\n"),
              {"diagnosis.priors.material_scaling.regions", "one place"});
  ExpectError("p_empty.yaml", WithPriors("  priors: {attached_mass: {}}\n"),
              {"diagnosis.priors.attached_mass", "expected a mapping"});
  // A family the study does not try, or one that does not apply to the model.
  const std::string few = Replace(
      kShear, "[attached_mass, stiffness_loss, material_scaling, support_flexibility]",
      "[attached_mass]");
  ExpectError("p_candidate.yaml",
              few + "  priors: {stiffness_loss: {loss: [0.05, 0.6]}}\n",
              {"diagnosis.priors.stiffness_loss", "not among diagnosis.candidates"});
  const std::string all =
      Replace(kShear,
              "  candidates: [attached_mass, stiffness_loss, material_scaling, "
              "support_flexibility]\n",
              "");
  ExpectError("p_apply.yaml", all + "  priors: {added_mass: {ratio: [0.1, 1]}}\n",
              {"diagnosis.priors.added_mass", "does not apply", "wet"});
  ExpectError("w_apply.yaml", all + "  weights: {added_mass: 2}\n",
              {"diagnosis.weights.added_mass", "does not apply"});
  ExpectError("w_value.yaml", WithPriors("  weights: {stiffness_loss: 0}\n"),
              {"diagnosis.weights.stiffness_loss", "positive"});
  ExpectError("w_family.yaml", WithPriors("  weights: {rust: 2}\n"),
              {"diagnosis.weights.rust: unknown family"});
}

// diagnosis.bagging_copies: the bootstrap copies of the structures' bagged
// posterior (effect_ranking.h), 400 unless stated, 0 for Laplace alone.
TEST(Study, BaggingCopiesAreReadAndChecked) {
  EXPECT_EQ(LoadStudy(Write("bag_default.yaml", kShear)).diagnosis->bagging_copies, 400);
  EXPECT_EQ(
      LoadStudy(Write("bag_off.yaml", kShear + std::string("  bagging_copies: 0\n")))
          .diagnosis->bagging_copies,
      0);
  ExpectError("bag_negative.yaml", kShear + std::string("  bagging_copies: -3\n"),
              {"diagnosis.bagging_copies", "0 (Laplace probabilities alone) to 100000"});
  ExpectError("bag_text.yaml", kShear + std::string("  bagging_copies: many\n"),
              {"diagnosis.bagging_copies"});
}

// diagnosis.max_members: how many members stiffness loss tries one by one
// (effect_ranking.h), 200 unless stated, -1 for all of them; and
// diagnosis.members_fitted: how many of them are fitted after the screen, 12
// unless stated, -1 for all.
TEST(Study, MaxMembersIsReadAndChecked) {
  EXPECT_EQ(LoadStudy(Write("mm_default.yaml", kShear)).diagnosis->max_members, 200);
  EXPECT_EQ(LoadStudy(Write("mm_all.yaml", kShear + std::string("  max_members: -1\n")))
                .diagnosis->max_members,
            -1);
  ExpectError("mm_negative.yaml", kShear + std::string("  max_members: -2\n"),
              {"diagnosis.max_members", "expected >= 0, or -1 for every member"});
  ExpectError("mm_text.yaml", kShear + std::string("  max_members: some\n"),
              {"diagnosis.max_members"});
  EXPECT_EQ(LoadStudy(Write("mf_default.yaml", kShear)).diagnosis->members_fitted, 12);
  EXPECT_EQ(
      LoadStudy(Write("mf_all.yaml", kShear + std::string("  members_fitted: -1\n")))
          .diagnosis->members_fitted,
      -1);
  ExpectError("mf_negative.yaml", kShear + std::string("  members_fitted: -3\n"),
              {"diagnosis.members_fitted", "expected >= 0, or -1 to fit every member"});
}

// diagnosis.gap_confidence: the probability a gap must reach to be named
// (effect_ranking.h), 0 unless stated, in [0, 1).
TEST(Study, GapConfidenceIsReadAndChecked) {
  EXPECT_EQ(LoadStudy(Write("gc_default.yaml", kShear)).diagnosis->gap_confidence, 0.0);
  EXPECT_EQ(
      LoadStudy(Write("gc_stated.yaml", kShear + std::string("  gap_confidence: 0.9\n")))
          .diagnosis->gap_confidence,
      0.9);
  ExpectError("gc_one.yaml", kShear + std::string("  gap_confidence: 1\n"),
              {"diagnosis.gap_confidence", "up to, not including, 1"});
  ExpectError("gc_negative.yaml", kShear + std::string("  gap_confidence: -0.1\n"),
              {"diagnosis.gap_confidence"});
  ExpectError("gc_text.yaml", kShear + std::string("  gap_confidence: sure\n"),
              {"diagnosis.gap_confidence"});
}

// diagnosis.gap_explained: the share of the nominal misfit beyond the noise an
// effect must remove to be named (effect_ranking.h), a third unless stated, in
// [0, 1), refused on the cantilever's own pipeline.
TEST(Study, GapExplainedIsReadAndChecked) {
  EXPECT_EQ(LoadStudy(Write("ge_default.yaml", kShear)).diagnosis->gap_explained,
            1.0 / 3);
  EXPECT_EQ(
      LoadStudy(Write("ge_stated.yaml", kShear + std::string("  gap_explained: 0\n")))
          .diagnosis->gap_explained,
      0.0);
  ExpectError("ge_one.yaml", kShear + std::string("  gap_explained: 1\n"),
              {"diagnosis.gap_explained", "up to, not including, 1"});
  ExpectError("ge_negative.yaml", kShear + std::string("  gap_explained: -0.2\n"),
              {"diagnosis.gap_explained"});
  ExpectError("ge_text.yaml", kShear + std::string("  gap_explained: most\n"),
              {"diagnosis.gap_explained"});
}

// The cantilever's effects are placed by a fitted height: regions are refused
// (x_m states where), and the sampled evidence takes uniform priors only.
TEST(Study, CantileverPriorsUseHeights) {
  const std::string beam = R"(
model:
  type: cantilever
  length: 2.0
  elements: 10
  section: {E: 210e9, A: 9e-4, I: 1.6875e-8, rho: 7850}
measurements:
  - {state: air, frequencies_hz: [2.9, 18.3, 51.2]}
diagnosis:
)";
  const Study s = LoadStudy(
      Write("beam_priors.yaml",
            beam + "  priors: {attached_mass: {mass_kg: [1, 2], x_m: [1.4, 1.9]},\n"
                   "           added_mass: {level_m: [0, 1.5], kg_per_m: {normal: [2.8, "
                   "0.5]}}}\n"));
  EXPECT_EQ(s.diagnosis->priors.Find("attached_mass")->quantities.size(), 2u);
  ExpectError("beam_regions.yaml", beam + "  priors: {attached_mass: {regions: [n7]}}\n",
              {"diagnosis.priors.attached_mass.regions", "x_m"});
  ExpectError("beam_height.yaml", beam + "  priors: {attached_mass: {x_m: [1.0, 2.5]}}\n",
              {"diagnosis.priors.attached_mass.x_m", "[0, 2]"});
  ExpectError("beam_sampled.yaml",
              beam + "  evidence: sampled\n" +
                  "  priors: {material_scaling: {factor: {normal: [1, 0.05]}}}\n",
              {"diagnosis.priors.material_scaling.factor", "evidence: laplace"});
  ExpectError("beam_axial.yaml", beam + "  priors: {axial_load: {force_n: [0, 5000]}}\n",
              {"diagnosis.priors.axial_load", "default candidates"});
  ExpectError("beam_quantity.yaml",
              beam + "  priors: {support_flexibility: {compliance_ratio: [0.01, 1]}}\n",
              {"diagnosis.priors.support_flexibility.compliance_ratio",
               "rotation_compliance_ratio"});
}

}  // namespace
}  // namespace femup
