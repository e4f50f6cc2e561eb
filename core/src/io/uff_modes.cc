// Measured modes from UFF dataset 55 at a model's DOFs.
#include "femup/core/io/uff_modes.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "femup/core/errors.h"

namespace femup {
namespace {

const char* const kDirectionNames[6] = {"X", "Y", "Z", "RX", "RY", "RZ"};

std::string At(const std::string& name, long long line) {
  return name + ": line " + std::to_string(line);
}

std::string Number(double value, int digits = 6) {
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}

std::string Xyz(const std::array<double, 3>& p) {
  return "(" + Number(p[0]) + ", " + Number(p[1]) + ", " + Number(p[2]) + ")";
}

std::string Xyz(const Eigen::Vector3d& p) {
  return Xyz(std::array<double, 3>{p.x(), p.y(), p.z()});
}

std::string DirectionsHeld(int per_node) {
  std::string out;
  for (int d = 1; d <= std::min(per_node, 6); ++d)
    out += (d > 1 ? " " : "") + UffDirectionName(d);
  return out;
}

// "dataset 55 (mode 2 of the file, 45.7 Hz)".
std::string ModeName(const UffModeShape& s, double frequency_hz) {
  return "dataset 55 (mode " + std::to_string(s.mode_number) + ", " +
         Number(frequency_hz, 5) + " Hz)";
}

bool IsMode(const UffModeShape& s) {
  return s.analysis_type == UffAnalysisType::kNormalMode ||
         s.analysis_type == UffAnalysisType::kComplexFirstOrder ||
         s.analysis_type == UffAnalysisType::kComplexSecondOrder;
}

struct ModeEntry {
  const UffModeShape* shape = nullptr;
  double frequency_hz = 0;
  double damping_ratio = 0;
};

// Row of each node label in `s`; a node given twice is an error.
std::unordered_map<int, Eigen::Index> NodeRows(const UffModeShape& s,
                                               const std::string& name) {
  std::unordered_map<int, Eigen::Index> rows;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const auto [it, fresh] = rows.emplace(s.nodes[i], static_cast<Eigen::Index>(i));
    if (!fresh) {
      const long long line = i < s.node_lines.size() ? s.node_lines[i] : s.line;
      const auto first = static_cast<std::size_t>(it->second);
      throw InputError(
          At(name, line),
          "dataset 55 record 9: node " + std::to_string(s.nodes[i]) +
              " is given twice in one mode (also at line " +
              std::to_string(first < s.node_lines.size() ? s.node_lines[first] : s.line) +
              ")");
    }
  }
  return rows;
}

long long NodeLine(const UffModeShape& s, Eigen::Index row) {
  const auto i = static_cast<std::size_t>(row);
  return i < s.node_lines.size() ? s.node_lines[i] : s.line;
}

}  // namespace

bool ParseUffDirection(std::string_view text, int* direction) {
  std::string t;
  for (char c : text) {
    if (c != ' ') t += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  int sign = 1;
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) {
    sign = t[0] == '-' ? -1 : 1;
    t.erase(0, 1);
  }
  for (int d = 1; d <= 6; ++d) {
    if (t == kDirectionNames[d - 1] || t == std::to_string(d)) {
      *direction = sign * d;
      return true;
    }
  }
  return false;
}

std::string UffDirectionName(int direction) {
  const int d = std::abs(direction);
  if (d < 1 || d > 6) return std::to_string(direction);
  return std::string(direction < 0 ? "-" : "+") + kDirectionNames[d - 1];
}

const char* FrameDofName(int direction) {
  static const char* const kNames[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const int d = std::abs(direction);
  return d >= 1 && d <= 6 ? kNames[d - 1] : "";
}

RealShape BestRealShape(const Eigen::VectorXcd& psi) {
  RealShape out;
  const std::complex<double> ptp = psi.transpose() * psi;  // no conjugate
  const double php = psi.squaredNorm();
  if (!(php > 0)) {
    out.shape = Eigen::VectorXd::Zero(psi.size());
    out.mpc = 0;
    return out;
  }
  out.mpc = std::norm(ptp) / (php * php);
  const double theta = std::abs(ptp) > 0 ? -0.5 * std::arg(ptp) : 0.0;
  const Eigen::VectorXcd rotated = psi * std::polar(1.0, theta);
  out.shape = rotated.real();
  out.imaginary_fraction = rotated.imag().squaredNorm() / php;
  Eigen::Index largest = 0;
  out.shape.cwiseAbs().maxCoeff(&largest);
  if (out.shape[largest] < 0) out.shape = -out.shape;
  return out;
}

void ComplexEigenvalueModes(std::complex<double> lambda, double* frequency_hz,
                            double* damping_ratio, const std::string& where) {
  const double w = std::abs(lambda);
  if (!(w > 0) || !std::isfinite(w)) {
    throw InputError(where, "the eigenvalue (record 8 fields 1-2) is " +
                                Number(lambda.real()) + " + " + Number(lambda.imag()) +
                                "i; expected a nonzero complex eigenvalue (rad/s)");
  }
  *frequency_hz = w / (2 * M_PI);
  *damping_ratio = -lambda.real() / w;
}

std::vector<UffNode> UffNodeCoordinates(const UffFile& file, const std::string& name) {
  std::vector<UffNode> out;
  std::unordered_map<int, std::size_t> seen;
  for (const UffNodes* set : file.Nodes()) {
    for (const UffNode& node : set->nodes) {
      const auto [it, fresh] = seen.emplace(node.label, out.size());
      if (fresh) {
        out.push_back(node);
        continue;
      }
      const UffNode& first = out[it->second];
      double gap = 0;
      for (std::size_t c = 0; c < 3; ++c)
        gap = std::max(gap, std::abs(first.xyz[c] - node.xyz[c]));
      const double scale = std::max({std::abs(first.xyz[0]), std::abs(first.xyz[1]),
                                     std::abs(first.xyz[2]), 1e-300});
      if (gap > 1e-6 * scale) {
        throw InputError(At(name, node.line), "dataset " + std::to_string(set->dataset) +
                                                  ": node " + std::to_string(node.label) +
                                                  " at " + Xyz(node.xyz) +
                                                  " is also at " + Xyz(first.xyz) +
                                                  " (line " + std::to_string(first.line) +
                                                  "); expected one place per node label");
      }
    }
  }
  if (out.empty()) {
    throw InputError(name,
                     "no node coordinates in the file: expected dataset 15 or 2411 "
                     "(nodes with their coordinates)");
  }
  return out;
}

UffModes ExtractUffModes(const UffFile& file, const std::string& name,
                         const UffDofMap& map, const std::vector<std::string>& dof_labels,
                         const std::vector<int>& use) {
  // The modes of the file, with frequency and damping.
  std::vector<ModeEntry> modes;
  for (const UffModeShape* s : file.ModeShapes()) {
    if (!IsMode(*s)) {
      throw InputError(At(name, s->line),
                       "dataset 55 holds a frequency response shape (analysis type 5, " +
                           Number(s->frequency_hz) +
                           " Hz), not a mode; expected normal modes (analysis type 2) or "
                           "complex modes (3, 7)");
    }
    ModeEntry e;
    e.shape = s;
    if (s->analysis_type == UffAnalysisType::kNormalMode) {
      if (!(s->frequency_hz > 0)) {
        throw InputError(
            At(name, s->line),
            "dataset 55 record 8 field 1 (frequency): " + Number(s->frequency_hz) +
                " Hz; expected a positive natural frequency");
      }
      e.frequency_hz = s->frequency_hz;
      e.damping_ratio = s->viscous_damping_ratio;
    } else {
      ComplexEigenvalueModes(s->eigenvalue, &e.frequency_hz, &e.damping_ratio,
                             At(name, s->line) + ": dataset 55 (complex mode " +
                                 std::to_string(s->mode_number) + ")");
    }
    modes.push_back(e);
  }
  if (modes.empty()) {
    std::map<int, int> held;
    for (const UffDatasetHeader& h : file.headers) ++held[h.number];
    std::string list;
    for (const auto& [number, count] : held) {
      list += (list.empty() ? "" : ", ") + std::to_string(count) + " x dataset " +
              std::to_string(number);
    }
    throw InputError(name, "no mode shape (dataset 55) in the file; it holds " +
                               (list.empty() ? std::string("no dataset") : list) +
                               (held.count(58) ? " (records of dataset 58 go through "
                                                 "identify:, not modes_file)"
                                               : ""));
  }
  std::stable_sort(modes.begin(), modes.end(),
                   [](const ModeEntry& a, const ModeEntry& b) {
                     return a.frequency_hz < b.frequency_hz;
                   });

  UffModes out;
  for (const ModeEntry& e : modes) out.all_frequencies_hz.push_back(e.frequency_hz);
  out.used = use;
  if (out.used.empty()) {
    for (std::size_t k = 0; k < modes.size(); ++k)
      out.used.push_back(static_cast<int>(k) + 1);
  }
  for (int k : out.used) {
    if (k < 1 || k > static_cast<int>(modes.size())) {
      std::string hz;
      for (const ModeEntry& e : modes)
        hz += (hz.empty() ? "" : ", ") + Number(e.frequency_hz, 5);
      throw InputError(
          name, "mode " + std::to_string(k) + " is asked for (modes), but the file has " +
                    std::to_string(modes.size()) +
                    " mode(s) in dataset 55, numbered by ascending frequency: " + hz +
                    " Hz");
    }
  }

  // One node set for every used mode: that of the first.
  const ModeEntry& first = modes[static_cast<std::size_t>(out.used[0] - 1)];
  const UffModeShape& ref = *first.shape;
  const auto ref_rows = NodeRows(ref, name);
  const int per_node = static_cast<int>(ref.values.cols());
  for (std::size_t u = 1; u < out.used.size(); ++u) {
    const ModeEntry& e = modes[static_cast<std::size_t>(out.used[u] - 1)];
    const UffModeShape& s = *e.shape;
    const std::string what = ModeName(s, e.frequency_hz);
    const std::string against =
        "the modes must share one node set: " + ModeName(ref, first.frequency_hz) +
        " at line " + std::to_string(ref.line) + " has nodes " + LabelRanges(ref.nodes);
    const auto rows = NodeRows(s, name);
    if (s.values.cols() != per_node) {
      throw InputError(
          At(name, s.line),
          what + " record 6: " + std::to_string(s.values.cols()) + " values per node; " +
              ModeName(ref, first.frequency_hz) + " at line " + std::to_string(ref.line) +
              " has " + std::to_string(per_node) + "; expected the same for every mode");
    }
    for (int node : ref.nodes) {
      if (!rows.count(node)) {
        throw InputError(At(name, s.line), what + ": node " + std::to_string(node) +
                                               " is missing; " + against);
      }
    }
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      if (!ref_rows.count(s.nodes[i])) {
        throw InputError(At(name, NodeLine(s, static_cast<Eigen::Index>(i))),
                         what + " record 9: node " + std::to_string(s.nodes[i]) +
                             " is not in the other modes; " + against);
      }
    }
  }

  // Sensors: explicit entries, skipped nodes, then the rest by coordinates.
  const std::string in_modes = "dataset 55 of " + name + " (line " +
                               std::to_string(ref.line) + ": nodes " +
                               LabelRanges(ref.nodes) + ", " + std::to_string(per_node) +
                               " values per node: " + DirectionsHeld(per_node) + ")";
  std::map<int, std::vector<const UffSensor*>> explicit_by_node;
  for (const UffSensor& s : map.sensors) {
    if (!ref_rows.count(s.node)) {
      throw InputError(s.source,
                       "node " + std::to_string(s.node) + " is not in " + in_modes);
    }
    if (std::abs(s.direction) > per_node) {
      throw InputError(s.source, "direction " + UffDirectionName(s.direction) +
                                     " is missing: " + in_modes);
    }
    explicit_by_node[s.node].push_back(&s);
  }
  std::set<int> skipped;
  for (const UffSkippedNode& k : map.skipped) {
    if (!ref_rows.count(k.node)) {
      throw InputError(k.source,
                       "node " + std::to_string(k.node) + " is not in " + in_modes);
    }
    if (explicit_by_node.count(k.node)) {
      throw InputError(k.source, "node " + std::to_string(k.node) +
                                     " is skipped and also mapped (" +
                                     explicit_by_node[k.node][0]->source +
                                     "); expected one or the other");
    }
    skipped.insert(k.node);
  }
  std::unordered_map<std::string, int> dof_of;
  for (std::size_t i = 0; i < dof_labels.size(); ++i)
    dof_of.emplace(dof_labels[i], static_cast<int>(i));
  std::unordered_map<int, const UffNode*> coordinates;
  for (const UffNode& n : map.geometry) coordinates.emplace(n.label, &n);
  for (int d : map.directions) {
    if (std::abs(d) > per_node) {
      throw InputError(map.geometry_file.empty() ? name : map.geometry_file,
                       "direction " + UffDirectionName(d) +
                           " (uff_directions) is missing: " + in_modes);
    }
  }

  for (std::size_t i = 0; i < ref.nodes.size(); ++i) {
    const int node = ref.nodes[i];
    if (skipped.count(node)) continue;
    const auto found = explicit_by_node.find(node);
    if (found != explicit_by_node.end()) {
      std::vector<const UffSensor*> list = found->second;
      std::stable_sort(list.begin(), list.end(),
                       [](const UffSensor* a, const UffSensor* b) {
                         return std::abs(a->direction) < std::abs(b->direction);
                       });
      for (const UffSensor* s : list) out.sensors.push_back(*s);
      continue;
    }
    const std::string where =
        At(name, ref.node_lines.size() > i ? ref.node_lines[i] : ref.line);
    if (!map.by_geometry) {
      if (map.skip_unmapped) continue;
      throw InputError(where,
                       "dataset 55 record 9: node " + std::to_string(node) +
                           " is not mapped to the model: give its DOFs in uff_dofs (\"" +
                           std::to_string(node) + ":+X\": <DOF label>), skip it (\"" +
                           std::to_string(node) +
                           "\": skip), or place the nodes by their coordinates "
                           "(geometry_file)");
    }
    const auto c = coordinates.find(node);
    if (c == coordinates.end()) {
      if (map.skip_unmapped) continue;
      throw InputError(
          where, "dataset 55 record 9: node " + std::to_string(node) +
                     " has no coordinates in " + map.geometry_file +
                     " (datasets 15 / 2411 hold nodes " +
                     [&] {
                       std::vector<int> l;
                       for (const UffNode& n : map.geometry) l.push_back(n.label);
                       return LabelRanges(l);
                     }() +
                     "); map it in uff_dofs or skip it (\"" + std::to_string(node) +
                     "\": skip)");
    }
    const UffNode& at = *c->second;
    const Eigen::Vector3d p(at.xyz[0], at.xyz[1], at.xyz[2]);
    double best = std::numeric_limits<double>::infinity(), second = best;
    std::size_t nearest = 0, runner_up = 0;
    for (std::size_t m = 0; m < map.model_nodes.size(); ++m) {
      const double d = (map.model_nodes[m].xyz - p).norm();
      if (d < best) {
        second = best;
        runner_up = nearest;
        best = d;
        nearest = m;
      } else if (d < second) {
        second = d;
        runner_up = m;
      }
    }
    const std::string node_at = "node " + std::to_string(node) + " at " + Xyz(at.xyz) +
                                " (" + map.geometry_file + " line " +
                                std::to_string(at.line) + ")";
    if (map.model_nodes.empty() || !(best <= map.tolerance)) {
      if (map.skip_unmapped) continue;
      throw InputError(
          where,
          node_at + " is " + Number(best, 4) + " m from the nearest model node" +
              (map.model_nodes.empty() ? std::string()
                                       : " " + map.model_nodes[nearest].name + " at " +
                                             Xyz(map.model_nodes[nearest].xyz)) +
              "; expected one within the tolerance " + Number(map.tolerance, 4) +
              " m (geometry_tolerance): map it in uff_dofs or skip it (\"" +
              std::to_string(node) + "\": skip)");
    }
    if (second <= map.tolerance) {
      throw InputError(where, node_at + " is within the tolerance " +
                                  Number(map.tolerance, 4) + " m of two model nodes, " +
                                  map.model_nodes[nearest].name + " and " +
                                  map.model_nodes[runner_up].name +
                                  "; lower geometry_tolerance or map it in uff_dofs");
    }
    const ModelNode& model_node = map.model_nodes[nearest];
    std::vector<int> directions = map.directions;
    const bool listed = !directions.empty();
    if (!listed) {
      for (int d = 1; d <= std::min(per_node, 6); ++d) directions.push_back(d);
    }
    std::size_t added = 0;
    for (int d : directions) {
      const std::string label = model_node.name + ":" + FrameDofName(d);
      const auto dof = dof_of.find(label);
      if (dof == dof_of.end()) {
        if (!listed) continue;
        throw InputError(where, node_at + " lies at model node " + model_node.name +
                                    ", which has no DOF " + label + " for direction " +
                                    UffDirectionName(d) +
                                    " (uff_directions); map the node in uff_dofs or "
                                    "skip it (\"" +
                                    std::to_string(node) + "\": skip)");
      }
      UffSensor s;
      s.node = node;
      s.direction = d;
      s.dof = dof->second;
      s.source = model_node.name + ", " + Number(best, 3) + " m away";
      out.sensors.push_back(s);
      ++added;
    }
    if (added == 0) {
      if (map.skip_unmapped) continue;
      throw InputError(where, node_at + " lies at model node " + model_node.name +
                                  ", which has no free DOF along " +
                                  DirectionsHeld(per_node) + " (a support); skip it (\"" +
                                  std::to_string(node) + "\": skip)");
    }
  }
  if (out.sensors.empty()) {
    throw InputError(name, "no node of " + in_modes + " is mapped to a model DOF");
  }
  std::unordered_map<int, const UffSensor*> by_dof;
  for (UffSensor& s : out.sensors) {
    if (s.dof < 0 || s.dof >= static_cast<int>(dof_labels.size())) {
      throw InputError(s.source,
                       "model DOF index " + std::to_string(s.dof) + " is out of range");
    }
    s.label = dof_labels[static_cast<std::size_t>(s.dof)];
    const auto [it, fresh] = by_dof.emplace(s.dof, &s);
    if (!fresh) {
      const UffSensor& o = *it->second;
      throw InputError(name, "model DOF " + dof_labels[static_cast<std::size_t>(s.dof)] +
                                 " is measured twice: by node " + std::to_string(o.node) +
                                 " " + UffDirectionName(o.direction) + " (" + o.source +
                                 ") and by node " + std::to_string(s.node) + " " +
                                 UffDirectionName(s.direction) + " (" + s.source +
                                 "); expected one component per DOF");
    }
  }

  // Shapes.
  const auto rows = static_cast<Eigen::Index>(out.sensors.size());
  out.shapes.resize(rows, static_cast<Eigen::Index>(out.used.size()));
  for (std::size_t u = 0; u < out.used.size(); ++u) {
    const ModeEntry& e = modes[static_cast<std::size_t>(out.used[u] - 1)];
    const UffModeShape& s = *e.shape;
    const auto node_rows = NodeRows(s, name);
    Eigen::VectorXcd psi(rows);
    for (Eigen::Index r = 0; r < rows; ++r) {
      const UffSensor& sensor = out.sensors[static_cast<std::size_t>(r)];
      const double sign = sensor.direction < 0 ? -1.0 : 1.0;
      psi[r] = sign * s.values(node_rows.at(sensor.node), std::abs(sensor.direction) - 1);
    }
    UffMode m;
    m.line = s.line;
    m.mode_number = s.mode_number;
    m.analysis_type = s.analysis_type;
    m.frequency_hz = e.frequency_hz;
    m.damping_ratio = e.damping_ratio;
    if (psi.squaredNorm() == 0) {
      throw InputError(At(name, s.line), ModeName(s, e.frequency_hz) +
                                             ": the shape is zero at every mapped DOF; "
                                             "expected a mode shape");
    }
    if (psi.imag().cwiseAbs().maxCoeff() > 0) {
      const RealShape real = BestRealShape(psi);
      out.shapes.col(static_cast<Eigen::Index>(u)) = real.shape;
      m.mpc = real.mpc;
      m.imaginary_fraction = real.imaginary_fraction;
    } else {
      out.shapes.col(static_cast<Eigen::Index>(u)) = psi.real();
    }
    out.modes.push_back(m);
  }
  return out;
}

}  // namespace femup
