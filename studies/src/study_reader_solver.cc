// The parameters and the solver of a study file: a family's layout of factors
// (none, per element, single, groups), the bounds of a factor, and the solver
// section (linear or sensitivity method, regularisation, prior, options).
#include <cmath>
#include <limits>

#include "femup/core/errors.h"
#include "study_reader.h"

namespace femup::study_reader {
namespace {

std::vector<int> ElementIds(const Field& f) {
  std::vector<int> ids;
  for (const Field& item : f.Items()) {
    const int id = item.Int();
    if (id < 1) item.Fail("element ids start at 1");
    ids.push_back(id);
  }
  return ids;
}

}  // namespace

ParameterFamily ReadFamily(const Field& f) {
  ParameterFamily family;
  using Scope = ParameterFamily::Scope;
  using Selection = ParameterFamily::Selection;
  auto scope_of = [&](const Field& s) {
    const std::string v = s.Str();
    if (v == "none") return Scope::kNone;
    if (v == "per_element") return Scope::kPerElement;
    if (v == "single") return Scope::kSingle;
    if (v == "groups") return Scope::kGroups;
    s.Fail("unknown layout '" + v + "' (expected none, per_element, single or groups)");
  };
  if (f.IsScalar()) {
    family.scope = scope_of(f);
    if (family.scope == Scope::kGroups)
      f.Fail("groups need a list: {groups: [[1, 2], [3]]}");
    return family;
  }
  f.ExpectKeys({"layout", "select", "groups"});
  family.scope = f.Has("layout")
                     ? scope_of(f["layout"])
                     : (f.Has("groups") ? Scope::kGroups : Scope::kPerElement);
  if (f.Has("select")) {
    const std::string v = f["select"].Str();
    if (v == "all") {
      family.selection = Selection::kAll;
    } else if (v == "wet") {
      family.selection = Selection::kWet;
    } else if (v == "dry") {
      family.selection = Selection::kDry;
    } else {
      f["select"].Fail("unknown selection '" + v + "' (expected all, wet or dry)");
    }
  }
  if (family.scope == Scope::kGroups) {
    for (const Field& g : f["groups"].Items()) family.groups.push_back(ElementIds(g));
  } else if (f.Has("groups")) {
    f["groups"].Fail("groups are only used with layout: groups");
  }
  return family;
}

double BoundValue(const Field& f) {
  if (f.IsScalar()) {
    const std::string s = f.node().Scalar();
    if (s == "-inf" || s == "-.inf") return -std::numeric_limits<double>::infinity();
    if (s == "inf" || s == ".inf" || s == "+inf")
      return std::numeric_limits<double>::infinity();
    if (s == "null" || s == "~" || s.empty()) return std::nan("");
  }
  return f.Num();
}

namespace {

RegularisationOptions ReadRegularisation(const Field& f) {
  f.ExpectKeys({"parameter_choice", "lambda", "noise_norm", "discrepancy_factor",
                "operator", "grid_points", "lambda_min", "lambda_max"});
  RegularisationOptions o;
  if (f.Has("parameter_choice")) o.parameter_choice = f["parameter_choice"].Str();
  if (f.Has("lambda")) o.lambda = f["lambda"].NonNegative();
  if (f.Has("noise_norm")) o.noise_norm = f["noise_norm"].Positive();
  if (f.Has("discrepancy_factor"))
    o.discrepancy_factor = f["discrepancy_factor"].Positive();
  if (f.Has("operator")) o.op = f["operator"].Str();
  if (f.Has("grid_points")) o.grid_points = f["grid_points"].Int();
  if (f.Has("lambda_min")) o.lambda_min = f["lambda_min"].NonNegative();
  if (f.Has("lambda_max")) o.lambda_max = f["lambda_max"].NonNegative();
  if (const Invalid bad = o.Validate())
    (f.Has(bad.field) ? f[bad.field] : f).Fail(bad.message);
  return o;
}

}  // namespace

SolverSpec ReadSolver(const Field& sf, const ParametrisedModel& model) {
  sf.ExpectKeys({"label", "method", "name", "rank_tolerance", "scale_columns",
                 "truncation", "regularisation", "prior_mean", "max_iterations",
                 "kkt_tolerance", "confidence_level", "trust_region", "hessian",
                 "sensitivity"});
  SolverSpec spec;
  if (sf.Has("method")) spec.method = sf["method"].Str();
  if (spec.method != "linear" && spec.method != "sensitivity")
    sf["method"].Fail(
        "unknown method '" + spec.method +
        "' (expected linear: the paper's Z d = F, or sensitivity: iterative "
        "eigen-sensitivity updating)");
  spec.name =
      sf.Has("name") ? sf["name"].Str() : (spec.method == "linear" ? "lstsq" : "ceres");
  spec.label = sf.Has("label") ? sf["label"].Str() : spec.method + " (" + spec.name + ")";
  LinearSolverOptions& lo = spec.linear;
  NonlinearSolverOptions& no = spec.nonlinear;
  if (sf.Has("rank_tolerance"))
    lo.relative_rank_tolerance = sf["rank_tolerance"].Positive();
  if (sf.Has("scale_columns")) lo.scale_columns = sf["scale_columns"].Bool();
  if (sf.Has("truncation")) lo.truncation = sf["truncation"].Int();
  if (sf.Has("regularisation"))
    lo.regularisation = ReadRegularisation(sf["regularisation"]);
  if (sf.Has("max_iterations"))
    lo.max_iterations = no.max_iterations = sf["max_iterations"].Int();
  if (sf.Has("kkt_tolerance"))
    lo.kkt_tolerance = no.kkt_tolerance = sf["kkt_tolerance"].Positive();
  if (sf.Has("confidence_level")) lo.confidence_level = sf["confidence_level"].Positive();
  if (sf.Has("trust_region")) no.trust_region = sf["trust_region"].Str();
  if (sf.Has("hessian")) no.hessian = sf["hessian"].Str();
  if (sf.Has("prior_mean")) {
    spec.prior_mean = Eigen::VectorXd::Zero(model.num_parameters());
    ForEachParameterKey(sf["prior_mean"], model,
                        [&](const Field& v, int i) { spec.prior_mean[i] = v.Num(); });
  }
  if (sf.Has("sensitivity")) {
    const Field tf = sf["sensitivity"];
    tf.ExpectKeys({"frequency_sigma", "shape_sigma", "shape_noise", "shape_scaling",
                   "use_shapes", "extra_modes", "min_mac", "prior_sigma", "threads"});
    EigenSensitivityOptions& so = spec.sensitivity;
    if (tf.Has("frequency_sigma")) so.frequency_sigma = tf["frequency_sigma"].Positive();
    if (tf.Has("shape_sigma")) so.shape_sigma = tf["shape_sigma"].Positive();
    if (tf.Has("shape_noise")) so.shape_noise = tf["shape_noise"].Str();
    if (tf.Has("shape_scaling")) so.shape_scaling = tf["shape_scaling"].Str();
    if (tf.Has("use_shapes")) so.use_shapes = tf["use_shapes"].Bool();
    if (tf.Has("extra_modes")) so.extra_modes = tf["extra_modes"].Int();
    if (tf.Has("min_mac")) so.min_mac = tf["min_mac"].NonNegative();
    if (tf.Has("threads")) so.threads = tf["threads"].Int();
    if (tf.Has("prior_sigma")) {
      so.prior_sigma = Eigen::VectorXd::Zero(model.num_parameters());
      ForEachParameterKey(tf["prior_sigma"], model, [&](const Field& v, int i) {
        so.prior_sigma[i] = v.NonNegative();
      });
      if (spec.prior_mean.size() > 0) so.prior_mean = spec.prior_mean;
    }
    if (const Invalid bad = so.Validate()) tf.Fail(bad.ToString());
  }
  try {
    if (spec.method == "linear") {
      CreateLinearSolver(spec.name, lo);
    } else {
      CreateNonlinearSolver(spec.name, no);
    }
  } catch (const InputError& e) {
    sf.Fail(e.what());
  }
  return spec;
}

}  // namespace femup::study_reader
