#include <algorithm>
#include <string>
#include <utility>

#include "effect_ranking_steps.h"
#include "observational_equivalence.h"

namespace femup::effect_ranking_steps {

void PutInOrder(std::vector<RankedClass> classes,
                const std::map<std::string, double>& by_kind,
                const EffectRankingOptions& options, EffectRanking* out) {
  // The most probable family first ("none" is a family of one class), and
  // within it the most probable class: the verdict answers which effect before
  // where, so a family whose probability is shared among many places is not
  // outranked by a single class that has less. Within a family the fitted
  // classes come before the screened ones, whose place and size are one
  // linearised step's: screened classes more probable than every fitted one
  // of their family are said in one note per family, the most probable named.
  std::map<std::string, double> best_fitted;
  for (const RankedClass& c : classes)
    if (c.fitted) best_fitted[c.kind] = std::max(best_fitted[c.kind], c.probability);
  std::map<std::string, std::pair<int, const RankedClass*>> above;  // kind -> count, most
  for (const RankedClass& c : classes) {
    if (c.fitted || !(c.probability > best_fitted[c.kind])) continue;
    auto& [count, most] = above[c.kind];
    ++count;
    if (most == nullptr || c.probability > most->probability) most = &c;
  }
  for (const auto& [kind, a] : above) {
    out->notes.push_back(
        std::to_string(a.first) + " screened, unfitted places of " + kind +
        " are more probable than every fitted one (the most: " + ClassLabel(*a.second) +
        ", " + std::to_string(a.second->probability) +
        "); raise diagnosis.members_fitted to fit them");
  }
  // No gap is named unless one is probable at the stated confidence: "none"
  // then comes first whatever the families' shares.
  const auto none_it = by_kind.find("none");
  out->gap_probability = none_it == by_kind.end() ? 1.0 : 1.0 - none_it->second;
  out->gap_below_confidence =
      none_it != by_kind.end() && out->gap_probability < options.gap_confidence;
  const bool none_first = out->gap_below_confidence;
  std::stable_sort(classes.begin(), classes.end(),
                   [&by_kind, none_first](const RankedClass& a, const RankedClass& b) {
                     if (none_first && (a.kind == "none") != (b.kind == "none"))
                       return a.kind == "none";
                     const double ka = by_kind.at(a.kind), kb = by_kind.at(b.kind);
                     if (ka != kb) return ka > kb;
                     if (a.kind != b.kind) return a.kind < b.kind;
                     if (a.fitted != b.fitted) return a.fitted;
                     return a.probability > b.probability;
                   });
  // No effect is named the gap's cause unless it explains enough of it.
  if (classes.front().kind != "none" &&
      classes.front().explained < options.gap_explained) {
    out->gap_unexplained = true;
    std::stable_sort(classes.begin(), classes.end(),
                     [](const RankedClass& a, const RankedClass& b) {
                       return a.kind == "none" && b.kind != "none";
                     });
  }
  out->classes = std::move(classes);
  if (out->frequency_temperature ==
          EffectRankingOptions::FrequencyTemperature::kMarginal &&
      !out->classes.empty())
    out->temperature = out->classes[0].frequency_temperature;
  out->kind_probabilities.assign(by_kind.begin(), by_kind.end());
  std::stable_sort(out->kind_probabilities.begin(), out->kind_probabilities.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
}

}  // namespace femup::effect_ranking_steps
