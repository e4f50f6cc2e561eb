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

// Probability of each region for the given kinds.
std::map<std::string, double> RegionProbability(const EffectRanking& r,
                                                const std::vector<std::string>& kinds) {
  std::map<std::string, double> p;
  for (const RankedClass& c : r.classes) {
    if (std::find(kinds.begin(), kinds.end(), c.kind) != kinds.end())
      p[c.region] += c.probability;
  }
  return p;
}

// Each segment of `e`, broken from the next by a NaN point.
void AddSegments(const DiagnosisMap::Element& e, PlotSeries* series) {
  for (std::size_t i = 0; i + 1 < e.x.size(); i += 2) {
    series->x.insert(series->x.end(), {e.x[i], e.x[i + 1], NAN});
    series->y.insert(series->y.end(), {e.y[i], e.y[i + 1], NAN});
  }
}

struct Band {
  double low, high;
  const char* color;
  double width;
  const char* label;
};

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
  return map;
}

Figure DiagnosisMapFigure(const DiagnosisMap& map, const EffectRanking& ranking,
                          const std::string& title) {
  static const Band kBands[] = {{0.5, 2.0, "#c0392b", 5, "P >= 0.5"},
                                {0.1, 0.5, "#e67e22", 4, "P 0.1-0.5"},
                                {0.01, 0.1, "#f1c40f", 3, "P 0.01-0.1"}};
  Plot p;
  p.equal_axes = map.to_scale;
  p.key_outside = true;
  p.x_label = map.to_scale ? "x (m)" : "";
  p.y_label = map.to_scale ? "height (m)" : "element (storey) number";
  // The structure in grey, one polyline per element, broken between them.
  PlotSeries frame;
  frame.style = PlotSeries::Style::kLines;
  frame.color = "#b0b0b0";
  frame.width = 1.5;
  for (const auto& e : map.elements) AddSegments(e, &frame);
  frame.title = "model";
  p.series.push_back(frame);

  const auto loss = RegionProbability(ranking, {"stiffness_loss"});
  for (const Band& b : kBands) {
    PlotSeries s;
    s.style = PlotSeries::Style::kLines;
    s.color = b.color;
    s.width = b.width;
    for (const auto& e : map.elements) {
      const auto it = loss.find(e.region);
      if (it == loss.end() || it->second < b.low || it->second >= b.high) continue;
      AddSegments(e, &s);
    }
    if (s.x.empty()) continue;
    s.title = std::string("stiffness loss, ") + b.label;
    p.series.push_back(s);
  }
  const auto mass = RegionProbability(ranking, {"attached_mass"});
  std::map<std::string, std::pair<double, double>> at;  // node region -> (x, y)
  for (const auto& n : map.nodes) at[n.region] = {n.x, n.y};
  static const char* kMassColors[] = {"#1f4e9c", "#4a90d9", "#9cc3ee"};
  for (int k = 0; k < 3; ++k) {
    PlotSeries s;
    s.style = PlotSeries::Style::kPoints;
    s.color = kMassColors[k];
    s.width = 3.0 - 0.6 * k;
    for (const auto& n : map.nodes) {
      const auto it = mass.find(n.region);
      if (it == mass.end() || it->second < kBands[k].low || it->second >= kBands[k].high)
        continue;
      s.x.push_back(n.x);
      s.y.push_back(n.y);
    }
    // Masses between nodes ("n1-n7", position xi fitted): at their fitted point.
    for (const RankedClass& c : ranking.classes) {
      const std::size_t dash = c.region.find('-');
      if (c.kind != "attached_mass" || dash == std::string::npos || c.theta.size() != 2 ||
          c.probability < kBands[k].low || c.probability >= kBands[k].high)
        continue;
      const auto a = at.find("node " + c.region.substr(0, dash));
      const auto b = at.find("node " + c.region.substr(dash + 1));
      if (a == at.end() || b == at.end()) continue;  // an end on a rigid support
      const double xi = c.theta[1];
      s.x.push_back((1 - xi) * a->second.first + xi * b->second.first);
      s.y.push_back((1 - xi) * a->second.second + xi * b->second.second);
    }
    if (s.x.empty()) continue;
    s.title = std::string("attached mass, ") + kBands[k].label;
    p.series.push_back(s);
  }
  const auto support = RegionProbability(ranking, {"support_flexibility"});
  const double p_support = support.count("supports") ? support.at("supports") : 0.0;
  if (p_support >= 0.01 && !map.supports.empty()) {
    PlotSeries s;
    s.style = PlotSeries::Style::kPoints;
    s.color = p_support >= 0.5 ? "#6c3483" : p_support >= 0.1 ? "#a569bd" : "#d2b4de";
    s.width = 3.0;
    for (const auto& n : map.supports) {
      s.x.push_back(n.x);
      s.y.push_back(n.y);
    }
    std::ostringstream t;
    t.precision(2);
    t << "softer supports, P " << p_support;
    s.title = t.str();
    p.series.push_back(s);
  }
  // The explanations that have no place: in the title, with their probability.
  std::ostringstream global;
  global.precision(2);
  for (const auto& [kind, prob] : ranking.kind_probabilities) {
    if (kind == "stiffness_loss" || kind == "attached_mass" ||
        kind == "support_flexibility" || prob < 0.01)
      continue;
    global << (global.tellp() > 0 ? ", " : "") << kind << " P " << prob;
  }
  p.title = title + (global.tellp() > 0 ? " (everywhere: " + global.str() + ")" : "");
  Figure f;
  f.panels.push_back(p);
  f.width_px = 900;
  f.height_px = 650;
  return f;
}

}  // namespace femup
