// Test helper: an Eigen vector from a list of numbers, e.g. a parameter vector
// written in place (VectorOf({std::log(0.4), 1.2})): the effect families' own
// (problems/src/vector_of.h).
#pragma once

#include "../problems/src/vector_of.h"

namespace femup {
namespace fixtures {

using internal::VectorOf;

}  // namespace fixtures
}  // namespace femup
