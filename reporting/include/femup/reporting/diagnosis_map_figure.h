// The diagnosis map drawn: the structure's geometry (femup/studies/diagnosis_map.h)
// coloured by where the ranked explanations lie.
#pragma once

#include <string>

#include "femup/reporting/plot.h"
#include "femup/studies/diagnosis_map.h"
#include "femup/studies/effect_ranking.h"

namespace femup {

// The map's figure: the structure in grey, then each element, node and the
// supports coloured by the probability of the explanation there (bands
// >= 0.5, 0.1-0.5, 0.01-0.1), the global explanations in the title. A pair of
// effects (kind "a+b") counts for each of its two: its local part is drawn where
// it lies, its global part named in the title, each with the probability of
// every class that holds it.
Figure DiagnosisMapFigure(const DiagnosisMap& map, const EffectRanking& ranking,
                          const std::string& title);

}  // namespace femup
