#include "femup/studies/diagnosis_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace femup {
namespace {

std::string NodeOf(const std::string& label) {
  const auto colon = label.find(':');
  return colon == std::string::npos ? label : label.substr(0, colon);
}

}  // namespace

DiagnosisMap MapGeometry(const Structure& s) {
  DiagnosisMap map;
  std::map<std::string, Eigen::Vector3d> where;
  for (const ModelNode& n : s.nodes) where[n.name] = n.xyz;
  const bool three_d =
      std::any_of(s.nodes.begin(), s.nodes.end(),
                  [](const ModelNode& n) { return std::abs(n.xyz.z()) > 1e-12; });
  map.to_scale = !where.empty();
  auto plane = [&](const Eigen::Vector3d& p) {
    return std::pair<double, double>(p.x(), three_d ? p.z() : p.y());
  };
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const ElementMatrices& el = s.elements[e];
    DiagnosisMap::Element m;
    m.region = "element " + el.label;
    if (map.to_scale) {
      // Node pairs its stiffness couples: the segments to draw.
      std::set<std::pair<std::string, std::string>> pairs;
      std::set<std::string> touched;
      for (int k = 0; k < el.stiffness.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(el.stiffness, k); it; ++it) {
          if (it.value() == 0) continue;
          const std::string a = NodeOf(s.dof_labels[it.row()]);
          const std::string b = NodeOf(s.dof_labels[it.col()]);
          if (!where.count(a) || !where.count(b)) continue;
          touched.insert(a);
          if (a < b) pairs.insert({a, b});
        }
      }
      for (const auto& [a, b] : pairs) {
        const auto [xa, ya] = plane(where[a]);
        const auto [xb, yb] = plane(where[b]);
        m.x.insert(m.x.end(), {xa, xb});
        m.y.insert(m.y.end(), {ya, yb});
      }
      // A vertical member standing on a rigid support: its foot has no DOF,
      // so no pair reaches it; draw it down to the height the member starts.
      if (!touched.empty() && el.x1 > el.x0) {
        const double x = plane(where[*touched.begin()]).first;
        double low = INFINITY;
        bool vertical = true;
        for (const auto& n : touched) {
          const auto [nx, ny] = plane(where[n]);
          vertical = vertical && std::abs(nx - x) < 1e-9;
          low = std::min(low, ny);
        }
        if (vertical && low > el.x0 + 1e-9) {
          m.x.insert(m.x.end(), {x, x});
          m.y.insert(m.y.end(), {el.x0, low});
        }
      }
    } else {
      m.x = {0.0, 0.0};
      m.y = {static_cast<double>(e), static_cast<double>(e + 1)};
    }
    if (!m.x.empty()) map.elements.push_back(std::move(m));
  }
  // A member's end connections (stiffness_loss "connections of s1:beam1"): a
  // stub from each connected joint a quarter of the way along its end element.
  for (const MemberConnections& c : s.connections) {
    if (!map.to_scale) break;
    DiagnosisMap::Element m;
    m.region = "connections of " + c.label;
    for (const ConnectionEnd& end : c.ends) {
      std::set<std::string> nodes;
      for (int d : end.dofs) nodes.insert(NodeOf(s.dof_labels[d]));
      for (int r : end.rotations) {
        const std::string joint = NodeOf(s.dof_labels[end.dofs[r]]);
        for (const std::string& other : nodes) {
          if (other == joint || !where.count(joint) || !where.count(other)) continue;
          const auto [xa, ya] = plane(where[joint]);
          const auto [xb, yb] = plane(where[other]);
          m.x.insert(m.x.end(), {xa, xa + 0.25 * (xb - xa)});
          m.y.insert(m.y.end(), {ya, ya + 0.25 * (yb - ya)});
        }
      }
    }
    if (!m.x.empty()) map.elements.push_back(std::move(m));
  }
  // Every node of the model, where the ranking may place an attached mass
  // (the figure marks only those it names).
  std::vector<std::string> seen;
  for (std::size_t i = 0; i < s.dof_labels.size(); ++i) {
    const std::string node = NodeOf(s.dof_labels[i]);
    if (std::find(seen.begin(), seen.end(), node) != seen.end()) continue;
    seen.push_back(node);
    DiagnosisMap::Node n;
    n.region = "node " + node;
    if (map.to_scale) {
      if (!where.count(node)) continue;
      std::tie(n.x, n.y) = plane(where[node]);
    } else {
      n.y = static_cast<double>(seen.size());  // a chain's k-th mass at height k
    }
    map.nodes.push_back(n);
  }
  for (const SupportSpring& sp : s.supports) {
    const std::string node = NodeOf(s.dof_labels[sp.dof]);
    DiagnosisMap::Node n;
    n.region = "supports";
    if (map.to_scale) {
      if (!where.count(node)) continue;
      std::tie(n.x, n.y) = plane(where[node]);
    }  // else: a chain's ground spring, at the foot (0, 0)
    map.supports.push_back(n);
  }
  // Rigid supports that support flexibility may release, at their joints.
  for (const RigidSupport& sp : s.rigid_supports) {
    if (!map.to_scale) break;
    DiagnosisMap::Node n;
    n.region = "supports";
    std::tie(n.x, n.y) = plane(sp.xyz);
    map.supports.push_back(n);
  }
  return map;
}

}  // namespace femup
