#include "femup/core/fe/sensor.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "femup/core/errors.h"

namespace femup {
namespace {

const char* kAxes[3] = {"x", "y", "z"};

std::string Num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// "ux", "-uy", or "(0.6, 0.8, 0)" for a direction; "r..." for rotations.
std::string DirectionName(const Eigen::Vector3d& d) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(std::abs(d[k]) - 1.0) < 1e-12) {
      return std::string(d[k] < 0 ? "-u" : "u") + kAxes[k];
    }
  }
  return "(" + Num(d.x()) + ", " + Num(d.y()) + ", " + Num(d.z()) + ")";
}

// Adds w * (d . (node's translations or rotations)) to `out`; DOFs the node
// does not have are held at zero.
void AddNode(const std::map<std::string, int>& dofs, const std::string& node,
             const Eigen::Vector3d& d, double w, bool rotation,
             std::map<int, double>* out) {
  if (w == 0) return;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) continue;
    const auto it = dofs.find(node + (rotation ? ":r" : ":u") + kAxes[k]);
    if (it != dofs.end()) (*out)[it->second] += w * d[k];
  }
}

std::map<std::string, int> DofIndex(const Structure& s) {
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i)
    index.emplace(s.dof_labels[i], static_cast<int>(i));
  return index;
}

std::vector<std::pair<int, double>> Sorted(const std::map<int, double>& m) {
  std::vector<std::pair<int, double>> v;
  for (const auto& [dof, w] : m) {
    if (w != 0) v.emplace_back(dof, w);
  }
  return v;
}

// The weights at xi, or with `slope` their derivatives with respect to xi.
std::vector<std::pair<int, double>> Weights(const Structure& s,
                                            const std::map<std::string, int>& dofs,
                                            const LineSegment& seg, double xi,
                                            const Eigen::Vector3d& d, bool rotation,
                                            bool slope = false) {
  const Eigen::Vector3d axis = seg.b - seg.a;
  const double length = axis.norm();
  const Eigen::Vector3d e = axis / length;
  const Eigen::Matrix3d along = e * e.transpose();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - along;
  const double x2 = xi * xi, x3 = x2 * xi;
  std::map<int, double> w;
  const std::string a = seg.node_a >= 0 ? s.nodes[seg.node_a].name : "";
  const std::string b = seg.node_b >= 0 ? s.nodes[seg.node_b].name : "";
  // Each end's translations and rotations take a vector of weights.
  auto add = [&](const std::string& node, const Eigen::Vector3d& wu,
                 const Eigen::Vector3d& wr) {
    if (node.empty()) return;  // a rigid support
    const double nu = wu.norm(), nr = wr.norm();
    if (nu > 0) AddNode(dofs, node, wu / nu, nu, false, &w);
    if (nr > 0) AddNode(dofs, node, wr / nr, nr, true, &w);
  };
  if (!rotation && slope) {  // d/dxi of the functions below
    const Eigen::Vector3d pd = across * d, ed = along * d, exd = e.cross(d);
    const double n1 = -6 * xi + 6 * x2, n2 = 1 - 4 * xi + 3 * x2;
    const double n3 = 6 * xi - 6 * x2, n4 = -2 * xi + 3 * x2;
    add(a, -ed + n1 * pd, length * n2 * exd);
    add(b, ed + n3 * pd, length * n4 * exd);
  } else if (!rotation) {
    const Eigen::Vector3d pd = across * d, ed = along * d, exd = e.cross(d);
    const double n1 = 1 - 3 * x2 + 2 * x3, n2 = xi - 2 * x2 + x3;
    const double n3 = 3 * x2 - 2 * x3, n4 = -x2 + x3;
    add(a, (1 - xi) * ed + n1 * pd, length * n2 * exd);
    add(b, xi * ed + n3 * pd, length * n4 * exd);
  } else if (slope) {  // d/dxi of the rotation's functions below
    const Eigen::Vector3d pd = across * d, ed = along * d, dxe = d.cross(e);
    const double n1 = -6 + 12 * xi, n2 = -4 + 6 * xi;
    const double n3 = 6 - 12 * xi, n4 = -2 + 6 * xi;
    add(a, n1 / length * dxe, -ed + n2 * pd);
    add(b, n3 / length * dxe, ed + n4 * pd);
  } else {
    const Eigen::Vector3d pd = across * d, ed = along * d, dxe = d.cross(e);
    const double n1 = -6 * xi + 6 * x2, n2 = 1 - 4 * xi + 3 * x2;
    const double n3 = 6 * xi - 6 * x2, n4 = -2 * xi + 3 * x2;
    add(a, n1 / length * dxe, (1 - xi) * ed + n2 * pd);
    add(b, n3 / length * dxe, xi * ed + n4 * pd);
  }
  return Sorted(w);
}

// The direction components the model has no DOFs for anywhere.
Invalid CheckDirection(const Structure& s, const Eigen::Vector3d& d) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) continue;
    const std::string tail = std::string(":u") + kAxes[k];
    const bool any =
        std::any_of(s.dof_labels.begin(), s.dof_labels.end(), [&](const std::string& l) {
          return l.size() >= tail.size() &&
                 l.compare(l.size() - tail.size(), tail.size(), tail) == 0;
        });
    if (!any) {
      return {"direction", std::string("the model has no DOFs along ") + kAxes[k] +
                               " (no '" + tail.substr(1) + "' DOF; a plane model?)"};
    }
  }
  return {};
}

}  // namespace

int SensorRow::SingleDof() const {
  return weights.size() == 1 && weights[0].second == 1.0 ? weights[0].first : -1;
}

Invalid ParseSensorDirection(const std::string& text, Eigen::Vector3d* direction) {
  const std::string t = text;
  double sign = 1;
  std::string axis = t;
  if (!axis.empty() && (axis[0] == '-' || axis[0] == '+')) {
    sign = axis[0] == '-' ? -1 : 1;
    axis = axis.substr(1);
  }
  for (int k = 0; k < 3; ++k) {
    if (axis == kAxes[k]) {
      *direction = Eigen::Vector3d::Zero();
      (*direction)[k] = sign;
      return {};
    }
  }
  return {"direction",
          "expected x, y, z (or -x, -y, -z) or three numbers, got '" + t + "'"};
}

std::vector<std::pair<int, double>> SegmentWeights(const Structure& structure,
                                                   const LineSegment& segment, double xi,
                                                   const Eigen::Vector3d& direction,
                                                   bool rotation, bool slope) {
  return Weights(structure, DofIndex(structure), segment, xi, direction, rotation, slope);
}

DofLabelIndex IndexDofLabels(const Structure& structure,
                             const std::vector<std::string>& nodes) {
  if (nodes.empty()) return DofIndex(structure);
  const std::set<std::string> wanted(nodes.begin(), nodes.end());
  DofLabelIndex index;
  for (std::size_t i = 0; i < structure.dof_labels.size(); ++i) {
    const std::string& label = structure.dof_labels[i];
    const std::size_t colon = label.rfind(':');
    if (colon != std::string::npos && wanted.count(label.substr(0, colon)))
      index.emplace(label, static_cast<int>(i));
  }
  return index;
}

std::vector<std::pair<int, double>> SegmentWeights(const Structure& structure,
                                                   const DofLabelIndex& dofs,
                                                   const LineSegment& segment, double xi,
                                                   const Eigen::Vector3d& direction,
                                                   bool rotation, bool slope) {
  return Weights(structure, dofs, segment, xi, direction, rotation, slope);
}

Invalid LocateSensor(const Structure& s, const SensorSpec& spec, SensorRow* row) {
  const int given = (spec.dof.empty() ? 0 : 1) + (spec.node.empty() ? 0 : 1) +
                    (spec.has_at ? 1 : 0) + (spec.has_x ? 1 : 0);
  if (given != 1) {
    return {"",
            "give exactly one of a DOF label, node (with direction), at: [x, y, z] "
            "(with direction) or x (along a cantilever)"};
  }
  const std::map<std::string, int> dofs = DofIndex(s);
  *row = SensorRow();
  if (!spec.dof.empty()) {
    std::string label = spec.dof;
    double sign = 1;
    if (label[0] == '-' || label[0] == '+') {
      sign = label[0] == '-' ? -1 : 1;
      label = label.substr(1);
    }
    const auto it = dofs.find(label);
    if (it == dofs.end()) {
      std::string some;
      for (std::size_t i = 0; i < std::min<std::size_t>(s.dof_labels.size(), 6); ++i)
        some += (i ? ", " : "") + s.dof_labels[i];
      return {"dof", "no model DOF is labelled '" + label + "' (labels look like: " +
                         some + (s.dof_labels.size() > 6 ? ", ..." : "") + ")"};
    }
    row->name = spec.dof;
    row->weights = {{it->second, sign}};
    return {};
  }
  Eigen::Vector3d d = spec.direction;
  if (spec.has_x && d.isZero()) d = Eigen::Vector3d::UnitX();
  if (d.isZero()) return {"direction", "missing: the direction the sensor measures in"};
  if (const Invalid bad = CheckDirection(s, d)) return bad;
  if (s.nodes.empty()) {
    return {spec.node.empty() ? (spec.has_at ? "at" : "x") : "node",
            "this model (" + (s.type.empty() ? std::string("no type") : s.type) +
                ") has no node coordinates; give its sensors as DOF labels"};
  }
  if (!spec.node.empty()) {
    const auto it = std::find_if(s.nodes.begin(), s.nodes.end(),
                                 [&](const ModelNode& n) { return n.name == spec.node; });
    if (it == s.nodes.end()) {
      return {"node", "no node is called '" + spec.node + "' (nodes are " +
                          s.nodes.front().name + " .. " + s.nodes.back().name + ")"};
    }
    std::map<int, double> w;
    AddNode(dofs, spec.node, d, 1.0, false, &w);
    row->name = spec.node + ":" + DirectionName(d);
    row->weights = Sorted(w);
    return {};
  }
  Eigen::Vector3d p = spec.at;
  std::string field = "at";
  if (spec.has_x) {
    field = "x";
    if (s.type != "cantilever" || s.segments.empty()) {
      return {"x",
              "a position along the structure applies to a cantilever; this model is "
              "a " +
                  s.type + " (give at: [x, y, z] and a direction)"};
    }
    const Eigen::Vector3d base = s.segments.front().a;
    const Eigen::Vector3d top = s.segments.back().b;
    const double length = (top - base).norm();
    if (!(spec.x >= 0) || !(spec.x <= length * (1 + 1e-9))) {
      return {"x", "is " + Num(spec.x) + " m; expected 0.." + Num(length) +
                       " m (the cantilever's length)"};
    }
    p = base + spec.x * (top - base) / length;
  }
  if (s.segments.empty()) {  // nodes only: the point must be one of them
    double best = std::numeric_limits<double>::infinity();
    std::size_t nearest = 0;
    double extent = 1;
    for (std::size_t k = 0; k < s.nodes.size(); ++k) {
      extent = std::max(extent, s.nodes[k].xyz.cwiseAbs().maxCoeff());
      const double dist = (s.nodes[k].xyz - p).norm();
      if (dist < best) best = dist, nearest = k;
    }
    if (best > 1e-6 * extent) {
      return {field, "no node is at this point (the nearest, " + s.nodes[nearest].name +
                         ", is " + Num(best) +
                         " m away; this model has no elements to interpolate along)"};
    }
    std::map<int, double> w;
    AddNode(dofs, s.nodes[nearest].name, d, 1.0, false, &w);
    row->name = s.nodes[nearest].name + ":" + DirectionName(d);
    row->weights = Sorted(w);
    return {};
  }
  double best = std::numeric_limits<double>::infinity();
  std::size_t nearest = 0;
  double best_xi = 0;
  for (std::size_t k = 0; k < s.segments.size(); ++k) {
    const LineSegment& g = s.segments[k];
    const Eigen::Vector3d ab = g.b - g.a;
    const double xi = std::clamp((p - g.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double dist = (g.a + xi * ab - p).norm();
    if (dist < best) best = dist, nearest = k, best_xi = xi;
  }
  const LineSegment& g = s.segments[nearest];
  if (best > 1e-3 * (g.b - g.a).norm()) {
    auto end = [&](int node, const Eigen::Vector3d& at) {
      return node >= 0 ? s.nodes[node].name
                       : "support (" + Num(at.x()) + ", " + Num(at.y()) + ", " +
                             Num(at.z()) + ")";
    };
    return {field, "(" + Num(p.x()) + ", " + Num(p.y()) + ", " + Num(p.z()) +
                       ") is not on the structure: the nearest element, " +
                       end(g.node_a, g.a) + " - " + end(g.node_b, g.b) + ", is " +
                       Num(best) + " m away"};
  }
  row->weights = Weights(s, dofs, g, best_xi, d, false);
  row->name = spec.has_x ? "x=" + Num(spec.x) + ":" + DirectionName(d)
                         : "at(" + Num(p.x()) + ", " + Num(p.y()) + ", " + Num(p.z()) +
                               "):" + DirectionName(d);
  if (row->weights.empty()) {
    return {field, "the sensor reads nothing here (the point is on a rigid support)"};
  }
  return {};
}

Eigen::MatrixXd ReadSensors(const std::vector<SensorRow>& sensors,
                            const Eigen::MatrixXd& shapes) {
  Eigen::MatrixXd out =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(sensors.size()), shapes.cols());
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    for (const auto& [dof, w] : sensors[i].weights)
      out.row(static_cast<Eigen::Index>(i)) += w * shapes.row(dof);
  }
  return out;
}

SparseMatrix SensorMatrix(const std::vector<SensorRow>& sensors, int num_dofs) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    for (const auto& [dof, w] : sensors[i].weights)
      t.emplace_back(static_cast<int>(i), dof, w);
  }
  SparseMatrix m(static_cast<Eigen::Index>(sensors.size()), num_dofs);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

}  // namespace femup
