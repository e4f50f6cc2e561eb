// Reading a study file (study.h): the YAML parsed, the sections read in order
// (ReadStudy: model, parameters, truth, records, measurements, system, solver,
// diagnosis, noise study, output) through the readers of study_reader.h.
#include "femup/studies/study.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include "femup/core/errors.h"
#include "study_reader.h"

namespace femup {
namespace {

namespace fs = std::filesystem;

using study_reader::BoundValue;
using study_reader::CheckMassPositiveDefinite;
using study_reader::Field;
using study_reader::ForEachParameterKey;
using study_reader::ReadCantilever;
using study_reader::ReadChain;
using study_reader::ReadDiagnosis;
using study_reader::ReadFamily;
using study_reader::ReadMatrixMarketModel;
using study_reader::ReadMeasurement;
using study_reader::ReadPlaneFrame;
using study_reader::ReadRecords;
using study_reader::ReadSolver;
using study_reader::ReadSpaceFrame;

// "study.yaml:3:7" for a yaml-cpp error (the file alone without a position).
std::string WhereIn(const std::string& path, const YAML::Exception& e) {
  std::ostringstream w;
  w << path;
  if (!e.mark.is_null()) w << ":" << e.mark.line + 1 << ":" << e.mark.column + 1;
  return w.str();
}

// The study whose parsed YAML is `root`; with `model_only`, its model and
// factors alone (ParseStudyModel).
Study ReadStudy(const YAML::Node& root, const std::string& path, bool model_only) {
  const Field top(root, path, "");
  if (model_only) {
    top.ExpectKeys({"name", "description", "model", "parameters", "truth"});
  } else {
    top.ExpectKeys({"name", "description", "model", "parameters", "truth", "measurements",
                    "system", "solver", "noise_study", "output", "records", "diagnosis"});
  }
  Study study;
  study.path = path;
  study.name = top.Has("name") ? top["name"].Str() : fs::path(path).stem().string();
  if (top.Has("description")) study.description = top["description"].Str();

  const Field mf = top["model"];
  const std::string type = mf["type"].Str();
  if (type == "chain") {
    study.structure = ReadChain(mf);
  } else if (type == "cantilever") {
    CantileverSpec spec;
    study.structure = ReadCantilever(mf, &spec);
    study.cantilever = spec;
  } else if (type == "matrix_market") {
    study.structure = ReadMatrixMarketModel(mf);
  } else if (type == "space_frame") {
    study.model = ReadSpaceFrame(mf, &study.structure);
  } else if (type == "plane_frame") {
    study.structure = ReadPlaneFrame(mf);
  } else {
    mf["type"].Fail("unknown model type '" + type +
                    "' (expected chain, cantilever, plane_frame, matrix_market or "
                    "space_frame)");
  }
  const bool generated = type == "space_frame";  // the generator sets the factors

  ParameterPlan plan = PaperParameterPlan();
  if (generated && top.Has("parameters")) {
    for (const char* family : {"mass", "stiffness", "added_mass"}) {
      if (top["parameters"].Has(family)) {
        top["parameters"][family].Fail(
            "a space_frame model has its factors by level and block (see "
            "blocks_per_level); parameters may fix, bound or relate them only");
      }
    }
  }
  if (!(top.Has("parameters") && top["parameters"].Has("added_mass")) &&
      std::none_of(study.structure.elements.begin(), study.structure.elements.end(),
                   [](const ElementMatrices& e) { return e.wet; })) {
    // Nothing is wet and the study asks for no added mass: the default is none
    // (asked for explicitly, it is still an error below).
    plan.added_mass.scope = ParameterFamily::Scope::kNone;
  }
  if (top.Has("parameters")) {
    const Field pf = top["parameters"];
    pf.ExpectKeys({"mass", "stiffness", "added_mass", "fix", "bounds", "equalities"});
    if (pf.Has("mass")) plan.mass = ReadFamily(pf["mass"]);
    if (pf.Has("stiffness")) plan.stiffness = ReadFamily(pf["stiffness"]);
    if (pf.Has("added_mass")) plan.added_mass = ReadFamily(pf["added_mass"]);
  }
  if (!generated) {
    try {
      study.model = BuildModel(study.structure, plan);
    } catch (const InputError& e) {
      (top.Has("parameters") ? top["parameters"] : mf).Fail(e.what());
    }
  }
  CheckMassPositiveDefinite(mf, study.model);

  auto parameter_index = [&](const Field& key_field, const std::string& name) {
    const int i = study.model.FindParameter(name);
    if (i < 0) {
      std::string names;
      for (const auto& n : study.model.ParameterNames())
        names += (names.empty() ? "" : ", ") + n;
      key_field.Fail("no parameter is called '" + name + "' (parameters: " + names + ")");
    }
    return i;
  };
  if (top.Has("parameters") && top["parameters"].Has("fix")) {
    const Field ff = top["parameters"]["fix"];
    if (!ff.IsMap()) ff.Fail("expected a mapping of parameter names to known values");
    for (const auto& kv : ff.node()) {
      const std::string name = ff.Key(kv.first);
      const Field value(kv.second, ff.file(), ff.path() + "." + name);
      parameter_index(value, name);
      study.fixed[name] = value.Num();
    }
  }
  if (top.Has("parameters") && top["parameters"].Has("bounds")) {
    const int n = study.model.num_parameters();
    study.lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
    study.upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    ForEachParameterKey(top["parameters"]["bounds"], study.model,
                        [&](const Field& v, int i) {
                          const std::vector<Field> pair = v.Items();
                          if (pair.size() != 2)
                            v.Fail("expected [lower, upper] (use -inf / inf for none)");
                          const double lo = BoundValue(pair[0]), hi = BoundValue(pair[1]);
                          if (std::isnan(lo) || std::isnan(hi))
                            v.Fail("a bound is empty; use -inf / inf for none");
                          if (lo > hi) v.Fail("lower bound exceeds upper bound");
                          study.lower[i] = lo;
                          study.upper[i] = hi;
                        });
    for (const auto& [name, value] : study.fixed) {
      const int i = study.model.FindParameter(name);
      if (value < study.lower[i] || value > study.upper[i])
        top["parameters"]["fix"][name].Fail(
            "the fixed value is outside the parameter's bounds");
    }
  }
  if (top.Has("parameters") && top["parameters"].Has("equalities")) {
    const std::vector<Field> rows = top["parameters"]["equalities"].Items();
    const int n = study.model.num_parameters();
    study.equality_matrix = Eigen::MatrixXd::Zero(rows.size(), n);
    study.equality_rhs = Eigen::VectorXd::Zero(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      rows[r].ExpectKeys({"coefficients", "value"});
      const Field cf = rows[r]["coefficients"];
      if (!cf.IsMap()) cf.Fail("expected a mapping of parameter names to coefficients");
      for (const auto& kv : cf.node()) {
        const std::string name = cf.Key(kv.first);
        const Field value(kv.second, cf.file(), cf.path() + "." + name);
        study.equality_matrix(r, parameter_index(value, name)) = value.Num();
      }
      study.equality_rhs[r] = rows[r].Has("value") ? rows[r]["value"].Num() : 0.0;
    }
  }
  if (top.Has("truth")) {
    const Field tf = top["truth"];
    if (!tf.IsMap()) tf.Fail("expected a mapping of parameter names to factor values");
    Eigen::VectorXd truth = Eigen::VectorXd::Zero(study.model.num_parameters());
    ForEachParameterKey(tf, study.model,
                        [&](const Field& value, int i) { truth[i] = value.Num(); });
    study.truth = truth;
  }
  if (model_only) return study;
  if (top.Has("records")) study.records = ReadRecords(top["records"], study.model);
  if (study.records && !top.Has("measurements")) return study;

  for (const Field& f : top["measurements"].Items()) {
    study.measurements.push_back(
        ReadMeasurement(f, study.model, study.truth.has_value(), study.structure));
  }
  if (study.measurements.empty()) top["measurements"].Fail("expected at least one state");
  {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < study.measurements.size(); ++i) {
      if (!seen.insert(study.measurements[i].state).second) {
        top["measurements"].Items()[i]["state"].Fail(
            "state '" + study.measurements[i].state + "' is listed twice");
      }
    }
  }

  if (top.Has("system")) {
    const Field sf = top["system"];
    sf.ExpectKeys({"form", "fem_modes"});
    if (sf.Has("form") && !SystemFormFromString(sf["form"].Str(), &study.system.form)) {
      sf["form"].Fail("unknown form '" + sf["form"].Str() +
                      "' (expected stacked or summed)");
    }
    if (sf.Has("fem_modes")) {
      const Field f = sf["fem_modes"];
      if (f.IsScalar() && f.node().Scalar() == "all") {
        study.system.num_fem_modes = -1;
      } else {
        study.system.num_fem_modes = f.Int();
        if (study.system.num_fem_modes < 1 ||
            study.system.num_fem_modes > study.model.num_dofs()) {
          f.Fail("expected 'all' or 1.." + std::to_string(study.model.num_dofs()));
        }
      }
    }
  }
  if (top.Has("solver")) study.solver = ReadSolver(top["solver"], study.model);
  if (top.Has("diagnosis")) study.diagnosis = ReadDiagnosis(top["diagnosis"], study);
  if (top.Has("noise_study")) {
    const Field nf = top["noise_study"];
    nf.ExpectKeys({"levels", "draws", "seed", "distribution", "figure_level",
                   "shape_level_ratio", "shape_noise", "compare"});
    NoiseStudySpec spec;
    spec.levels = nf["levels"].Numbers();
    for (std::size_t i = 0; i < spec.levels.size(); ++i) {
      if (!(spec.levels[i] >= 0 && spec.levels[i] < 1)) {
        nf["levels"].Items()[i].Fail(
            "a corruption level is relative: expected 0 <= level < 1");
      }
    }
    if (spec.levels.empty()) nf["levels"].Fail("expected at least one level");
    if (nf.Has("draws")) {
      spec.draws = nf["draws"].Int();
      if (spec.draws < 1) nf["draws"].Fail("expected at least one draw");
    }
    if (nf.Has("seed")) spec.seed = nf["seed"].Seed();
    if (nf.Has("distribution") &&
        !NoiseDistributionFromString(nf["distribution"].Str(), &spec.distribution)) {
      nf["distribution"].Fail("expected gaussian or uniform");
    }
    if (nf.Has("figure_level")) spec.figure_level = nf["figure_level"].NonNegative();
    if (nf.Has("shape_level_ratio"))
      spec.shape_level_ratio = nf["shape_level_ratio"].NonNegative();
    if (nf.Has("shape_noise")) {
      spec.shape_noise = nf["shape_noise"].Str();
      if (spec.shape_noise != "entry" && spec.shape_noise != "peak") {
        nf["shape_noise"].Fail("expected entry or peak, got '" + spec.shape_noise + "'");
      }
    }
    if (nf.Has("compare")) {
      for (const Field& item : nf["compare"].Items())
        spec.compare.push_back(ReadSolver(item, study.model));
    }
    if (!study.truth)
      nf.Fail("a noise study needs a 'truth' section (the preset factors)");
    study.noise_study = spec;
  }
  if (top.Has("output")) {
    const Field of = top["output"];
    of.ExpectKeys({"plots"});
    if (of.Has("plots")) study.plots = of["plots"].Bool();
  }
  return study;
}

}  // namespace

namespace {

Study ParseStudyText(std::string_view text, const std::string& path, bool model_only) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw InputError(WhereIn(path, e), "not valid YAML/JSON: " + e.msg);
  }
  try {
    return ReadStudy(root, path, model_only);
  } catch (const YAML::Exception& e) {
    // Every read goes through Field, which checks a node's type first; should
    // yaml-cpp still object, it is the file's content, never an internal error.
    throw InputError(WhereIn(path, e), "unexpected YAML content: " + e.msg);
  }
}

}  // namespace

Study ParseStudy(std::string_view text, const std::string& path) {
  return ParseStudyText(text, path, false);
}

Study ParseStudyModel(std::string_view text, const std::string& path) {
  return ParseStudyText(text, path, true);
}

Study LoadStudy(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, "study file not found");
  if (!fs::is_regular_file(path)) throw InputError(path, "is not a file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) throw InputError(path, "cannot read the study file");
  return ParseStudy(text.str(), path);
}

}  // namespace femup
