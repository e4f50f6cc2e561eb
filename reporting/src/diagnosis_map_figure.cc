#include "femup/reporting/diagnosis_map_figure.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace femup {
namespace {

struct Part {
  std::string kind, region;
};

// The effects a class holds: itself, or both of a pair (kind "a+b", region
// "A + B"; model_effect_pair.h).
std::vector<Part> Parts(const std::string& kind, const std::string& region) {
  const std::size_t plus = kind.find('+');
  const std::size_t joint = region.find(" + ");
  if (plus == std::string::npos) return {{kind, region}};
  if (joint == std::string::npos)
    return {{kind.substr(0, plus), region}, {kind.substr(plus + 1), region}};
  return {{kind.substr(0, plus), region.substr(0, joint)},
          {kind.substr(plus + 1), region.substr(joint + 3)}};
}

bool IsLocal(const std::string& kind) {
  return kind == "stiffness_loss" || kind == "attached_mass" ||
         kind == "support_flexibility";
}

// Probability of an effect of one of `kinds` at each region: the classes
// there, alone or in a pair.
std::map<std::string, double> RegionProbability(const EffectRanking& r,
                                                const std::vector<std::string>& kinds) {
  std::map<std::string, double> p;
  for (const RankedClass& c : r.classes) {
    for (const Part& part : Parts(c.kind, c.region)) {
      if (std::find(kinds.begin(), kinds.end(), part.kind) != kinds.end())
        p[part.region] += c.probability;
    }
  }
  return p;
}

// The fitted position along its element of the `which`-th mass between nodes
// in `c` (its parameters "xi", in the order of the class's parts), or NaN.
double MassPosition(const RankedClass& c, int which) {
  for (std::size_t i = 0; i < c.names.size(); ++i) {
    if (c.names[i] != "xi") continue;
    if (which-- > 0) continue;
    return static_cast<Eigen::Index>(i) < c.theta.size()
               ? c.theta[static_cast<Eigen::Index>(i)]
               : NAN;
  }
  return NAN;
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
    // Masses between nodes ("n1-n7", alone or in a pair): at their fitted
    // position xi along the element.
    for (const RankedClass& c : ranking.classes) {
      if (c.probability < kBands[k].low || c.probability >= kBands[k].high) continue;
      int between = 0;  // masses between nodes so far in this class
      for (const Part& part : Parts(c.kind, c.region)) {
        const std::size_t dash = part.region.find('-');
        if (part.kind != "attached_mass" || dash == std::string::npos) continue;
        const double xi = MassPosition(c, between++);
        if (std::isnan(xi)) continue;
        const auto a = at.find("node " + part.region.substr(0, dash));
        const auto b = at.find("node " + part.region.substr(dash + 1));
        if (a == at.end() || b == at.end()) continue;  // an end on a rigid support
        s.x.push_back((1 - xi) * a->second.first + xi * b->second.first);
        s.y.push_back((1 - xi) * a->second.second + xi * b->second.second);
      }
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
  // The explanations that have no place: in the title, each with the
  // probability of the families that hold it (alone or in a pair; a pair's
  // local part is drawn above).
  std::ostringstream global;
  global.precision(2);
  for (const auto& [kind, prob] : FamilyPresence(ranking)) {
    if (IsLocal(kind) || prob < 0.01) continue;
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
