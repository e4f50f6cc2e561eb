// The blind benchmark (evaluation/include/femup/evaluation/blind_benchmark.h):
// the engine its cases are diagnosed by (written into each study file, checked
// up front), and a case diagnosed by the one engine scored from its kinds.
#include "femup/evaluation/blind_benchmark.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace femup {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("femup_blind_benchmark_" + name);
  fs::remove_all(d);
  return d;
}

TEST(BenchmarkOptions, ValidatesTheEngine) {
  BenchmarkOptions o;
  EXPECT_EQ(o.engine, "model_effects");  // diagnose's default
  EXPECT_EQ(o.Validate().ToString(), "");
  o.engine = "cantilever";
  EXPECT_EQ(o.Validate().ToString(), "");
  o.engine = "modal";
  EXPECT_EQ(o.Validate().field, "engine");
  EXPECT_NE(o.Validate().message.find("'modal'"), std::string::npos)
      << o.Validate().ToString();
  // What only the own pipeline reads is refused on the one engine, not ignored.
  o.engine = "model_effects";
  o.evidence = "sampled";
  EXPECT_EQ(o.Validate().field, "evidence") << o.Validate().ToString();
  EXPECT_NE(o.Validate().message.find("engine cantilever"), std::string::npos);
  o.evidence = "laplace";
  o.form_error = 0.02;
  EXPECT_EQ(o.Validate().field, "form_error") << o.Validate().ToString();
  o.engine = "cantilever";
  o.evidence = "sampled";
  EXPECT_EQ(o.Validate().ToString(), "");
}

TEST(GenerateBenchmark, WritesTheEngineIntoEveryStudyFile) {
  BenchmarkOptions o;
  o.cases = 2;
  o.suite = "mixed";
  const fs::path one = TempDir("one");
  GenerateBenchmark(o, one.string());
  o.engine = "cantilever";
  const fs::path own = TempDir("own");
  GenerateBenchmark(o, own.string());
  o.suite = "single";
  o.engine = "model_effects";
  const fs::path single = TempDir("single");
  GenerateBenchmark(o, single.string());
  for (const std::string name : {"mixed_001", "mixed_002"}) {
    ASSERT_TRUE(fs::exists(one / "cases" / (name + ".yaml"))) << name;
    const std::string a = Read(one / "cases" / (name + ".yaml"));
    const std::string b = Read(own / "cases" / (name + ".yaml"));
    // The mixed suite's truths include pairs: the one engine tries them.
    EXPECT_NE(a.find("max_effects: 2"), std::string::npos) << a;
    EXPECT_EQ(a.find("engine:"), std::string::npos) << a;
    EXPECT_NE(b.find("engine: cantilever"), std::string::npos) << b;
    EXPECT_EQ(b.find("max_effects"), std::string::npos) << b;
    // The same case otherwise: the data do not depend on the engine.
    EXPECT_EQ(a.substr(0, a.find("diagnosis:")), b.substr(0, b.find("diagnosis:")));
    EXPECT_EQ(Read(one / "truth" / (name + ".json")),
              Read(own / "truth" / (name + ".json")));
  }
  for (const std::string name : {"single_001", "single_002"}) {
    const std::string a = Read(single / "cases" / (name + ".yaml"));
    EXPECT_EQ(a.find("max_effects"), std::string::npos) << a;  // one effect, one state
    EXPECT_EQ(a.find("engine:"), std::string::npos) << a;
  }
  for (const fs::path& d : {one, own, single}) fs::remove_all(d);
}

TEST(RunBenchmark, ScoresTheOneEnginesKinds) {
  BenchmarkOptions o;
  o.suite = "single";
  o.cases = 1;
  o.threads = 1;
  const fs::path dir = TempDir("run");
  const BenchmarkResult r = RunBenchmark(o, dir.string());
  ASSERT_EQ(r.cases.size(), 1u);
  const BenchmarkCase& c = r.cases[0];
  ASSERT_FALSE(c.failed) << c.error;
  // One record per kind (none and the five families a cantilever is
  // diagnosed with by default), the verdict's first, probabilities summing
  // to 1.
  ASSERT_GE(c.classes.size(), 2u);
  EXPECT_EQ(c.classes.front().label, c.top);
  EXPECT_DOUBLE_EQ(c.classes.front().probability, c.probability);
  std::set<std::string> labels;
  double sum = 0;
  for (const BenchmarkClassOutcome& k : c.classes) {
    EXPECT_TRUE(labels.insert(k.label).second) << "twice: " << k.label;
    EXPECT_EQ(k.label.find(" at "), std::string::npos) << k.label;  // a kind, no place
    EXPECT_GE(k.chi2, 0);
    EXPECT_TRUE(std::isfinite(k.score)) << k.label;
    sum += k.probability;
    if (k.label == "none") {
      EXPECT_EQ(k.parameters, 0);
    }
  }
  EXPECT_TRUE(labels.count("none"));
  EXPECT_NEAR(sum, 1, 1e-9);
  EXPECT_EQ(c.top_kinds.empty(), c.top == "none");
  // The nominal model's gap, from the none class's predictions.
  EXPECT_GT(c.gap_before, 0);
  EXPECT_GE(c.gap_after, 0);
  EXPECT_GT(c.degrees_of_freedom, 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace femup
