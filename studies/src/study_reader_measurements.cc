// The measured states of a study file (given, simulated, identified from a
// record file or read from a modes file, with the sensors and the UFF node
// map) and the records section (test records of the "real" structure for
// femup simulate).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>

#include "femup/core/errors.h"
#include "femup/core/fe/sensor.h"
#include "study_reader.h"

namespace femup::study_reader {
namespace {

namespace fs = std::filesystem;

std::vector<int> ReadSensors(const Field& f, const ParametrisedModel& model) {
  std::vector<int> dofs;
  for (const Field& item : f.Items()) {
    const std::string label = item.Str();
    const int dof = model.FindDof(label);
    if (dof < 0) {
      std::string some;
      for (int i = 0; i < std::min(model.num_dofs(), 6); ++i) {
        some += (i ? ", " : "") + model.dof_labels()[i];
      }
      item.Fail("no model DOF is labelled '" + label + "' (labels look like: " + some +
                (model.num_dofs() > 6 ? ", ..." : "") + ")");
    }
    dofs.push_back(dof);
  }
  return dofs;
}

// A measurement's sensors: DOF labels, or points on the structure (sensor.h):
// {node: n12, direction: y}, {at: [x, y, z], direction: [dx, dy, dz]},
// {x: 1.23} along a cantilever. Plain labels give sensor_dofs as before; any
// point makes every sensor a row of interpolation weights.
void ReadMeasuredSensors(const Field& f, const ParametrisedModel& model,
                         const Structure& structure, ModalData* data) {
  const std::vector<Field> items = f.Items();
  const bool any_point = std::any_of(items.begin(), items.end(),
                                     [](const Field& item) { return item.IsMap(); });
  if (!any_point) {
    data->sensor_dofs = ReadSensors(f, model);
    return;
  }
  std::vector<SensorRow> rows;
  for (const Field& item : items) {
    SensorSpec spec;
    if (!item.IsMap()) {
      spec.dof = item.Str();
    } else {
      item.ExpectKeys({"node", "at", "x", "direction", "dof"});
      if (item.Has("dof")) spec.dof = item["dof"].Str();
      if (item.Has("node")) spec.node = item["node"].Str();
      if (item.Has("at")) {
        const std::vector<double> at = item["at"].Numbers();
        if (at.size() != 3 && at.size() != 2)
          item["at"].Fail("expected [x, y, z] (or [x, y] on a plane model), m");
        spec.has_at = true;
        spec.at = Eigen::Vector3d(at[0], at[1], at.size() == 3 ? at[2] : 0.0);
        if (!spec.at.allFinite()) item["at"].Fail("has a NaN or infinite coordinate");
      }
      if (item.Has("x")) {
        spec.has_x = true;
        spec.x = item["x"].Num();
      }
      if (item.Has("direction")) {
        const Field d = item["direction"];
        if (d.IsSequence()) {
          const std::vector<double> v = d.Numbers();
          if (v.size() != 3 && v.size() != 2)
            d.Fail("expected x, y, z (or -x, ...) or [dx, dy, dz]");
          spec.direction = Eigen::Vector3d(v[0], v[1], v.size() == 3 ? v[2] : 0.0);
          if (!spec.direction.allFinite() || !(spec.direction.norm() > 0))
            d.Fail("expected a finite direction, not all zero");
          spec.direction.normalize();
        } else if (const Invalid bad = ParseSensorDirection(d.Str(), &spec.direction)) {
          d.Fail(bad.message);
        }
      }
    }
    SensorRow row;
    if (const Invalid bad = LocateSensor(structure, spec, &row)) {
      if (item.IsMap() && !bad.field.empty() && item.Has(bad.field))
        item[bad.field].Fail(bad.message);
      item.Fail(bad.message);
    }
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (rows[k].weights == row.weights) {
        item.Fail("reads the same as sensor " + std::to_string(k + 1) + " (" +
                  rows[k].name + ")");
      }
    }
    rows.push_back(row);
    data->sensor_specs.push_back(spec);
  }
  data->sensor_weights = SensorMatrix(rows, model.num_dofs());
  for (const SensorRow& r : rows) data->sensor_names.push_back(r.name);
}

// A path in the study file, taken relative to the study file's folder.
std::string RelativeToStudy(const Field& f) {
  const fs::path p(f.Str());
  if (p.is_absolute()) return p.string();
  const fs::path base = fs::path(f.file()).parent_path();
  return (base / p).lexically_normal().string();
}

ExpansionOptions ReadExpansion(const Field& f) {
  ExpansionOptions o;
  if (f.IsScalar()) {
    o.method = f.Str();
  } else {
    f.ExpectKeys({"method", "modes"});
    if (f.Has("method")) o.method = f["method"].Str();
    if (f.Has("modes")) o.num_modes = f["modes"].Int();
  }
  if (const Invalid bad = o.Validate()) {
    const std::string key = bad.field == "num_modes" ? "modes" : "method";
    (f.IsMap() && f.Has(key) ? f[key] : f).Fail(bad.message);
  }
  return o;
}

IdentifyOptions ReadIdentify(const Field& f) {
  f.ExpectKeys({"file", "format", "max_frequency_hz", "stable_orders", "orders",
                "first_sample", "min_emac", "max_damping_ratio", "tolerances"});
  IdentifyOptions o;
  o.file = RelativeToStudy(f["file"]);
  if (f.Has("format")) o.format = f["format"].Str();
  if (f.Has("max_frequency_hz")) o.max_frequency_hz = f["max_frequency_hz"].NonNegative();
  if (f.Has("stable_orders")) o.min_consecutive = f["stable_orders"].Int();
  if (f.Has("orders")) {
    const Field of = f["orders"];
    of.ExpectKeys({"min", "max", "step"});
    if (of.Has("min")) o.stabilisation.min_order = of["min"].Int();
    if (of.Has("max")) o.stabilisation.max_order = of["max"].Int();
    if (of.Has("step")) o.stabilisation.order_step = of["step"].Int();
  }
  if (f.Has("first_sample")) o.stabilisation.era.first_sample = f["first_sample"].Int();
  if (f.Has("tolerances")) {
    const Field tf = f["tolerances"];
    tf.ExpectKeys({"frequency", "damping", "mac"});
    if (tf.Has("frequency"))
      o.stabilisation.frequency_tolerance = tf["frequency"].Positive();
    if (tf.Has("damping")) o.stabilisation.damping_tolerance = tf["damping"].Positive();
    if (tf.Has("mac")) o.stabilisation.mac_tolerance = tf["mac"].Positive();
  }
  if (f.Has("min_emac")) o.stabilisation.era.min_emac = f["min_emac"].NonNegative();
  if (f.Has("max_damping_ratio"))
    o.stabilisation.era.max_damping_ratio = f["max_damping_ratio"].Positive();
  if (const Invalid bad = o.Validate()) f.Fail(bad.ToString());
  return o;
}

// Sensors of record channels: a DOF label per channel, "-label" for a sensor
// pointing against the DOF, "skip" for a channel not used.
void ReadChannelSensors(const Field& f, const ParametrisedModel& model,
                        MeasurementSpec* m) {
  std::set<int> seen;
  for (const Field& item : f.Items()) {
    std::string label = item.Str();
    if (label == "skip") {
      m->channel_dofs.push_back(-1);
      m->channel_signs.push_back(0.0);
      continue;
    }
    double sign = 1.0;
    if (!label.empty() && (label[0] == '-' || label[0] == '+')) {
      sign = label[0] == '-' ? -1.0 : 1.0;
      label = label.substr(1);
    }
    const int dof = model.FindDof(label);
    if (dof < 0) {
      item.Fail("no model DOF is labelled '" + label +
                "' (give a DOF label per channel, '-label' for a reversed sensor, "
                "or skip)");
    }
    if (!seen.insert(dof).second) item.Fail("DOF '" + label + "' is listed twice");
    m->channel_dofs.push_back(dof);
    m->channel_signs.push_back(sign);
  }
  if (seen.empty()) f.Fail("no channel is mapped to a model DOF");
}

}  // namespace

RecordsSpec ReadRecords(const Field& f, const ParametrisedModel& model) {
  f.ExpectKeys({"sample_rate_hz", "duration_s", "sensors", "impulse", "noise", "seed",
                "states", "cutoff_hz"});
  RecordsSpec r;
  r.sample_rate_hz = f["sample_rate_hz"].Positive();
  r.duration_s = f["duration_s"].Positive();
  if (r.sample_rate_hz * r.duration_s < 16)
    f["duration_s"].Fail("gives fewer than 16 samples at this sample rate");
  if (r.sample_rate_hz * r.duration_s > 1e7)
    f["duration_s"].Fail("gives more than 10^7 samples per channel");
  r.sensor_dofs = ReadSensors(f["sensors"], model);
  {
    const Field i = f["impulse"];
    i.ExpectKeys({"dof", "amplitude"});
    const int dof = model.FindDof(i["dof"].Str());
    if (dof < 0) i["dof"].Fail("no model DOF is labelled '" + i["dof"].Str() + "'");
    r.impulse_dof = dof;
    if (i.Has("amplitude")) {
      r.impulse = i["amplitude"].Num();
      if (r.impulse == 0) i["amplitude"].Fail("expected a non-zero impulse (N s)");
    }
  }
  if (f.Has("noise")) r.noise = f["noise"].NonNegative();
  if (f.Has("cutoff_hz")) {
    r.cutoff_hz = f["cutoff_hz"].Positive();
    if (r.cutoff_hz > r.sample_rate_hz / 2)
      f["cutoff_hz"].Fail("is above the Nyquist frequency (half the sample rate)");
  }
  if (f.Has("seed")) r.seed = f["seed"].Seed();
  std::set<std::string> names, files;
  for (const Field& sf : f["states"].Items()) {
    sf.ExpectKeys({"state", "immersion", "damping", "water", "file"});
    RecordStateSpec st;
    st.state = sf["state"].Str();
    if (!names.insert(st.state).second)
      sf["state"].Fail("state '" + st.state + "' is listed twice");
    st.immersion = st.state == "water" ? Immersion::kWet : Immersion::kDry;
    if (sf.Has("immersion")) {
      const std::string v = sf["immersion"].Str();
      if (v != "wet" && v != "dry")
        sf["immersion"].Fail("expected wet or dry, found '" + v + "'");
      st.immersion = v == "wet" ? Immersion::kWet : Immersion::kDry;
    }
    if (sf.Has("damping")) {
      const Field d = sf["damping"];
      st.damping_ratios = d.IsScalar() ? std::vector<double>{d.Num()} : d.Numbers();
      if (st.damping_ratios.empty()) d.Fail("expected at least one damping ratio");
      for (double z : st.damping_ratios) {
        if (!(z >= 0 && z < 1)) d.Fail("damping ratios must be in [0, 1)");
      }
    }
    if (sf.Has("water")) {
      const Field w = sf["water"];
      w.ExpectKeys(
          {"depth", "fluid_density", "width", "thickness", "coefficient", "fade"});
      StripTheoryWater water;
      water.depth = w["depth"].Positive();
      if (w.Has("fluid_density")) water.fluid_density = w["fluid_density"].Positive();
      water.width = w["width"].Positive();
      if (w.Has("thickness")) water.thickness = w["thickness"].Positive();
      if (w.Has("coefficient")) water.coefficient = w["coefficient"].Positive();
      if (water.coefficient == 0 && water.thickness == 0)
        w.Fail("give the section's thickness (along the motion) or the coefficient C_A");
      if (w.Has("fade")) water.fade = w["fade"].NonNegative();
      if (st.immersion != Immersion::kWet) w.Fail("water needs immersion: wet");
      st.water = water;
    }
    st.file = sf["file"].Str();
    const std::string ext = fs::path(st.file).extension().string();
    if (ext != ".uff" && ext != ".unv" && ext != ".csv")
      sf["file"].Fail("expected a .uff, .unv or .csv file name, got '" + st.file + "'");
    if (fs::path(st.file).has_parent_path() || st.file.empty())
      sf["file"].Fail("expected a plain file name (it is written in the output folder)");
    if (!files.insert(st.file).second)
      sf["file"].Fail("file '" + st.file + "' is listed twice");
    r.states.push_back(st);
  }
  if (r.states.empty()) f["states"].Fail("expected at least one state");
  return r;
}

namespace {

// A UFF modes_file (.uff, .unv): which model DOF each node component is.
//   uff_dofs: {"101:+Y": n3:ux, "102:-Y": n5:ux, "7": skip, "*": skip}
//     "<node>:<direction>" (X, Y, Z, RX, RY, RZ with an optional sign, or the
//     UFF codes 1..6) to a DOF label ("-label": the DOF points against the
//     direction), "<node>": skip for a node not used, "*": skip to leave out
//     every node nothing else maps (otherwise such a node is an error);
//   geometry_file: the nodes named by neither are matched to model nodes by
//     their coordinates (datasets 15 / 2411 of this file), within
//     geometry_tolerance (m; default 1 % of the model's largest extent), along
//     uff_directions (default: every direction of the data the model node has).
bool IsUffFile(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".uff" || ext == ".unv";
}

const char* const kUffKeys[] = {"uff_dofs", "geometry_file", "geometry_tolerance",
                                "uff_directions"};

UffDofMap ReadUffMap(const Field& f, const ParametrisedModel& model,
                     const std::vector<ModelNode>& nodes) {
  if (f.Has("sensors")) {
    f["sensors"].Fail(
        "a UFF modes_file names its nodes: map them with uff_dofs ({\"101:+Y\": "
        "n3:ux}) or place them by their coordinates with geometry_file, not with "
        "sensors");
  }
  if (!f.Has("uff_dofs") && !f.Has("geometry_file")) {
    f["modes_file"].Fail(
        "a UFF modes_file needs uff_dofs ({\"101:+Y\": n3:ux, \"7\": skip}) or "
        "geometry_file (nodes matched to the model's by coordinates) to say which "
        "model DOF each node component is");
  }
  UffDofMap map;
  if (f.Has("uff_dofs")) {
    const Field uf = f["uff_dofs"];
    if (!uf.IsMap() || uf.node().size() == 0) {
      uf.Fail(
          "expected a mapping of \"node:direction\" to model DOF labels, e.g. "
          "{\"101:+Y\": n3:ux, \"102:-Y\": n5:ux, \"7\": skip}");
    }
    std::set<std::pair<int, int>> components;
    std::set<int> dofs;
    for (const auto& kv : uf.node()) {
      const std::string key = uf.Key(kv.first);
      const Field value(kv.second, uf.file(), uf.path() + "." + key);
      const Field key_field(kv.first, uf.file(), uf.path() + "." + key);
      if (key == "*") {
        if (value.Str() != "skip")
          value.Fail(
              "\"*\" takes skip: the nodes no other entry (or geometry_file) "
              "maps are left out");
        map.skip_unmapped = true;
        continue;
      }
      const std::size_t colon = key.find(':');
      const std::string node_text = key.substr(0, colon);
      int node = 0;
      std::size_t used = 0;
      try {
        node = std::stoi(node_text, &used);
      } catch (...) {
        used = 0;
      }
      int direction = 0;
      if (used == 0 || used != node_text.size() ||
          (colon != std::string::npos &&
           !ParseUffDirection(key.substr(colon + 1), &direction))) {
        key_field.Fail(
            "expected \"<node>:<direction>\" (a UFF node number; X, Y, Z, RX, RY or RZ "
            "with an optional sign, or 1..6) or \"<node>\" with skip, found '" +
            key + "'");
      }
      const std::string source = value.Where() + ": " + value.path();
      const std::string label = value.Str();
      if (label == "skip") {
        if (colon != std::string::npos) {
          value.Fail("skip leaves out a whole node: write \"" + node_text +
                     "\": skip (components of a mapped node that are not listed are "
                     "not used anyway)");
        }
        map.skipped.push_back({node, source});
        continue;
      }
      if (colon == std::string::npos) {
        key_field.Fail("a node without a direction takes skip; map a component as \"" +
                       node_text + ":+X\": <DOF label>");
      }
      if (!components.insert({node, std::abs(direction)}).second) {
        key_field.Fail("node " + node_text + " direction " +
                       UffDirectionName(std::abs(direction)) + " is listed twice");
      }
      std::string dof_label = label;
      if (!dof_label.empty() && (dof_label[0] == '-' || dof_label[0] == '+')) {
        if (dof_label[0] == '-') direction = -direction;
        dof_label.erase(0, 1);
      }
      const int dof = model.FindDof(dof_label);
      if (dof < 0) {
        std::string some;
        for (int i = 0; i < std::min(model.num_dofs(), 6); ++i)
          some += (i ? ", " : "") + model.dof_labels()[i];
        value.Fail("no model DOF is labelled '" + dof_label + "' (labels look like: " +
                   some + (model.num_dofs() > 6 ? ", ..." : "") +
                   "; '-label' for a DOF pointing against the direction, or skip)");
      }
      if (!dofs.insert(dof).second) value.Fail("DOF '" + dof_label + "' is listed twice");
      UffSensor sensor;
      sensor.node = node;
      sensor.direction = direction;
      sensor.dof = dof;
      sensor.source = source;
      map.sensors.push_back(sensor);
    }
    std::set<int> mapped;
    for (const UffSensor& s : map.sensors) mapped.insert(s.node);
    for (const UffSkippedNode& k : map.skipped) {
      if (mapped.count(k.node)) {
        throw InputError(k.source, "node " + std::to_string(k.node) +
                                       " is skipped and also mapped; expected one or the "
                                       "other");
      }
    }
  }
  if (f.Has("geometry_file")) {
    if (nodes.empty()) {
      f["geometry_file"].Fail(
          "this model has no node coordinates (a chain or a Matrix Market model); map "
          "the UFF nodes with uff_dofs");
    }
    map.by_geometry = true;
    map.geometry_file = RelativeToStudy(f["geometry_file"]);
    map.model_nodes = nodes;
    if (f.Has("geometry_tolerance")) {
      map.tolerance = f["geometry_tolerance"].Positive();
    } else {
      Eigen::Vector3d lo = nodes[0].xyz, hi = nodes[0].xyz;
      for (const ModelNode& n : nodes) {
        lo = lo.cwiseMin(n.xyz);
        hi = hi.cwiseMax(n.xyz);
      }
      map.tolerance = 0.01 * (hi - lo).maxCoeff();
      if (!(map.tolerance > 0)) map.tolerance = 1e-3;
    }
    if (f.Has("uff_directions")) {
      std::set<int> seen;
      for (const Field& item : f["uff_directions"].Items()) {
        int d = 0;
        if (!ParseUffDirection(item.Str(), &d))
          item.Fail(
              "expected a direction: X, Y, Z, RX, RY or RZ (optionally signed) or "
              "1..6, found '" +
              item.Str() + "'");
        if (!seen.insert(std::abs(d)).second) item.Fail("direction is listed twice");
        map.directions.push_back(d);
      }
      if (map.directions.empty()) f["uff_directions"].Fail("expected at least one");
    }
  } else {
    for (const char* key : {"geometry_tolerance", "uff_directions"}) {
      if (f.Has(key))
        f[key].Fail(
            "applies to nodes placed by their coordinates: it needs geometry_file");
    }
  }
  return map;
}

}  // namespace

MeasurementSpec ReadMeasurement(const Field& f, const ParametrisedModel& model,
                                bool have_truth, const Structure& structure) {
  const std::vector<ModelNode>& nodes = structure.nodes;
  f.ExpectKeys({"state", "immersion", "simulate_modes", "frequencies_hz", "shapes",
                "sensors", "identify", "modes_file", "modes", "expansion", "uff_dofs",
                "geometry_file", "geometry_tolerance", "uff_directions"});
  MeasurementSpec m;
  m.field = f.path();
  m.state = f["state"].Str();
  m.immersion = m.state == "water" ? Immersion::kWet : Immersion::kDry;
  if (f.Has("immersion")) {
    const std::string v = f["immersion"].Str();
    if (v == "wet") {
      m.immersion = Immersion::kWet;
    } else if (v == "dry") {
      m.immersion = Immersion::kDry;
    } else {
      f["immersion"].Fail("expected wet or dry, found '" + v + "'");
    }
  }
  if (f.Has("expansion")) m.expansion = ReadExpansion(f["expansion"]);
  if (f.Has("identify") || f.Has("modes_file")) {
    for (const char* other : {"simulate_modes", "frequencies_hz", "shapes"}) {
      if (f.Has(other)) {
        f[other].Fail(std::string("give modes either from a file (identify / modes_file) "
                                  "or as ") +
                      other + ", not both");
      }
    }
    if (f.Has("identify") && f.Has("modes_file"))
      f.Fail("give either identify (a record file) or modes_file, not both");
    if (f.Has("identify")) {
      m.identify = ReadIdentify(f["identify"]);
    } else {
      m.modes_file = RelativeToStudy(f["modes_file"]);
    }
    if (!m.modes_file.empty() && IsUffFile(m.modes_file)) {
      m.uff_map = ReadUffMap(f, model, nodes);
    } else {
      for (const char* key : kUffKeys) {
        if (f.Has(key))
          f[key].Fail(
              "maps the nodes of a UFF modes_file (.uff, .unv); this "
              "measurement has none");
      }
      ReadChannelSensors(f["sensors"], model, &m);
    }
    if (f.Has("modes")) {
      const Field mf = f["modes"];
      if (mf.IsScalar()) {
        const int n = mf.Int();
        if (n < 1) mf.Fail("expected the number of lowest modes to use (>= 1)");
        if (n > model.num_dofs()) {
          mf.Fail("expected at most " + std::to_string(model.num_dofs()) +
                  " modes (the model has " + std::to_string(model.num_dofs()) +
                  " DOFs), found " + std::to_string(n));
        }
        for (int i = 1; i <= n; ++i) m.use_modes.push_back(i);
      } else {
        std::set<int> seen;
        for (const Field& item : mf.Items()) {
          const int k = item.Int();
          if (k < 1) item.Fail("identified modes are numbered from 1 (lowest frequency)");
          if (!seen.insert(k).second)
            item.Fail("mode " + std::to_string(k) + " is listed twice");
          m.use_modes.push_back(k);
        }
      }
    }
    m.data.state = m.state;
    m.data.immersion = m.immersion;
    return m;
  }
  if (f.Has("modes")) {
    f["modes"].Fail("modes selects identified modes; it needs identify or modes_file");
  }
  for (const char* key : kUffKeys) {
    if (f.Has(key))
      f[key].Fail(
          "maps the nodes of a UFF modes_file (.uff, .unv); this measurement "
          "has none");
  }
  if (m.expansion && f.Has("simulate_modes")) {
    f["expansion"].Fail("simulated modes are known at every DOF; nothing to expand");
  }
  if (f.Has("simulate_modes")) {
    if (f.Has("frequencies_hz") || f.Has("shapes")) {
      f.Fail("give either simulate_modes or measured frequencies_hz/shapes, not both");
    }
    if (!have_truth) {
      f["simulate_modes"].Fail(
          "simulated measurements need a 'truth' section with the "
          "factors of the real structure");
    }
    m.simulate_modes = f["simulate_modes"].Int();
    if (m.simulate_modes < 1 || m.simulate_modes > model.num_dofs()) {
      f["simulate_modes"].Fail("expected 1.." + std::to_string(model.num_dofs()) +
                               " modes");
    }
    return m;
  }
  m.data.state = m.state;
  m.data.immersion = m.immersion;
  const std::vector<double> freq = f["frequencies_hz"].Numbers();
  m.data.frequencies_hz = Eigen::Map<const Eigen::VectorXd>(freq.data(), freq.size());
  if (f.Has("sensors")) ReadMeasuredSensors(f["sensors"], model, structure, &m.data);
  if (f.Has("shapes")) {
    const auto modes = f["shapes"].Items();
    const int rows =
        m.data.HasInterpolatedSensors() ? static_cast<int>(m.data.sensor_weights.rows())
        : m.data.sensor_dofs.empty()    ? model.num_dofs()
                                        : static_cast<int>(m.data.sensor_dofs.size());
    if (modes.size() != freq.size()) {
      f["shapes"].Fail("has " + std::to_string(modes.size()) + " shapes for " +
                       std::to_string(freq.size()) + " frequencies (one shape per mode)");
    }
    m.data.shapes.resize(rows, static_cast<Eigen::Index>(modes.size()));
    for (std::size_t j = 0; j < modes.size(); ++j) {
      const std::vector<double> v = modes[j].Numbers();
      if (static_cast<int>(v.size()) != rows) {
        modes[j].Fail("has " + std::to_string(v.size()) + " entries; expected " +
                      std::to_string(rows) +
                      (m.data.sensor_dofs.empty() && !m.data.HasInterpolatedSensors()
                           ? " (one per model DOF, or list the sensors)"
                           : " (one per sensor)"));
      }
      for (int i = 0; i < rows; ++i) m.data.shapes(i, j) = v[i];
    }
  } else if (f.Has("sensors")) {
    f["sensors"].Fail("sensors are listed but no shapes are given");
  }
  try {
    m.data.Validate(model.num_dofs(), f.path());
  } catch (const InputError& e) {
    f.Fail(e.what());
  }
  if (m.expansion && (!m.data.HasShapes() ||
                      (m.data.sensor_dofs.empty() && !m.data.HasInterpolatedSensors()))) {
    f["expansion"].Fail(
        "expansion needs shapes measured at listed sensors (these shapes are " +
        std::string(m.data.HasShapes() ? "complete already)" : "missing)"));
  }
  return m;
}

}  // namespace femup::study_reader
