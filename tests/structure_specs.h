// Test fixtures shared by the unit tests: plane and space frame specs by their
// counts (and, optionally, their dimensions), and uniform chains (shear
// buildings). Every other field keeps the spec's default; a test sets what else
// it needs on the returned spec.
#pragma once

#include <tuple>

#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"

namespace femup {
namespace fixtures {

// `storeys` x `bays` of `storey_height` x `bay_width` (m), each member in
// `elements_per_member` elements.
inline PlaneFrameSpec PlaneFrame(int storeys, int bays, int elements_per_member,
                                 double storey_height, double bay_width) {
  PlaneFrameSpec spec;
  std::tie(spec.storeys, spec.bays, spec.elements_per_member) =
      std::make_tuple(storeys, bays, elements_per_member);
  std::tie(spec.storey_height, spec.bay_width) =
      std::make_tuple(storey_height, bay_width);
  return spec;
}

// The same with the spec's default storey height and bay width.
inline PlaneFrameSpec PlaneFrame(int storeys, int bays, int elements_per_member) {
  const PlaneFrameSpec defaults;
  return PlaneFrame(storeys, bays, elements_per_member, defaults.storey_height,
                    defaults.bay_width);
}

// `levels` x `bays_x` x `bays_y` of `level_height` x `bay_width_x` x
// `bay_width_y` (m), each member in `elements_per_member` elements.
inline SpaceFrameSpec SpaceFrame(int levels, int bays_x, int bays_y,
                                 int elements_per_member, double level_height,
                                 double bay_width_x, double bay_width_y) {
  SpaceFrameSpec spec;
  std::tie(spec.levels, spec.bays_x, spec.bays_y, spec.elements_per_member) =
      std::make_tuple(levels, bays_x, bays_y, elements_per_member);
  std::tie(spec.level_height, spec.bay_width_x, spec.bay_width_y) =
      std::make_tuple(level_height, bay_width_x, bay_width_y);
  return spec;
}

// The same with the spec's default level height and bay widths.
inline SpaceFrameSpec SpaceFrame(int levels, int bays_x, int bays_y,
                                 int elements_per_member) {
  const SpaceFrameSpec defaults;
  return SpaceFrame(levels, bays_x, bays_y, elements_per_member, defaults.level_height,
                    defaults.bay_width_x, defaults.bay_width_y);
}

// A chain of `storeys` equal masses (kg) on equal springs (N/m), storey 1 at
// the ground.
inline ChainSpec UniformChain(int storeys, double mass, double spring) {
  ChainSpec spec;
  spec.masses.assign(storeys, mass);
  spec.springs.assign(storeys, spring);
  return spec;
}

}  // namespace fixtures
}  // namespace femup
