// Two effects at once, as one effect: the change of a model where both act
// (the second family's change added to the first's), with the parameters of
// the first followed by those of the second. The ranking (effect_ranking.h,
// EffectRankingOptions::max_effects) fits such pairs, e.g. water on the wet
// states together with a material error in every state, as the cantilever's
// own pipeline does with its own effects; or two places of one family, apart
// (two damaged storeys, two masses).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "femup/problems/model_effects.h"

namespace femup {

// Whether two regions share an element or a DOF.
bool RegionsOverlap(const EffectRegion& a, const EffectRegion& b);

// The pair of `first` and `second` (neither null; of different kinds, or of
// one kind at regions that do not overlap). Its
// kind is "<first kind>+<second kind>"; its region is named "<first region> +
// <second region>" and holds both regions' elements and DOFs; its location is
// the first's. Its starts are `starts` (each of the pair's size: say where the
// singles' fits ended), then each of the first's starts beside the second's
// first start and the first's first start beside each of the second's others.
// Throws InputError("pair", ...) for a null effect, two effects of one kind
// whose regions overlap, or a start of the wrong size.
std::unique_ptr<ModelEffect> PairOfModelEffects(std::shared_ptr<const ModelEffect> first,
                                                std::shared_ptr<const ModelEffect> second,
                                                std::vector<Eigen::VectorXd> starts = {});

}  // namespace femup
