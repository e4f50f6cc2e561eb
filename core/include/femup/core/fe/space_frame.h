// A large jacket-like 3D space frame, built directly as a ParametrisedModel with
// correction factors on substructures: the 3D sibling of plane_frame.h, a test
// model of 10^5 to 10^6 DOF for the solver benchmarks, assembled from element
// triplets in O(nnz) (no dense matrix, no per-element Structure).
//
// Geometry (m; global Z up, the base at Z = 0): a plan grid of
// (bays_x + 1) x (bays_y + 1) legs, spaced bay_width_x along X and bay_width_y
// along Y, running vertically through `levels` levels spaced level_height and
// clamped at the base; at every level 1..levels horizontal members join
// neighbouring legs along X and along Y. The four outer faces carry braces in
// every storey panel (`bracing`): one diagonal per panel (alternating direction
// from panel to panel and storey to storey) or an X of two diagonals joined at
// the panel centre by a joint. Every member is split into
// `elements_per_member` 3D frame elements (frame3d.h, all of `theory`); an X
// counts as four members (corner to centre).
// Member axes: local y is the component of global Z normal to the member, for
// the vertical legs global X.
//
// Levels: level k (1 at the bottom) holds the legs and braces of the storey
// between heights (k - 1) h and k h and the horizontals at height k h.
// Blocks: every level is cut along X into `blocks_per_level` blocks of
// neighbouring grid lines (members on grid line X = i, i = 0..bays_x, are in
// block 1 + floor(i B / (bays_x + 1)); members spanning bay i = 0..bays_x - 1
// along X in block 1 + floor(i B / bays_x)).
// Water: an element is wet when its midpoint lies below Z = water_depth.
//
// Correction factors, in this order (k = level, b = block, both from 1):
//   "mass[l<k>]"                  consistent mass of all elements of level k
//                                 (tag "wet" if any of them is wet, else "dry");
//   "stiffness[l<k>:legs<b>]",    stiffness of the legs, braces and horizontals
//   "stiffness[l<k>:braces<b>]",  of level k in block b (tags "legs", "braces",
//   "stiffness[l<k>:horizontals<b>]"  "horizontals"), for k, then b;
//   "added_mass[l<k>:legs<b>]" ... the same groups restricted to wet elements:
//                                 their transverse consistent mass (frame3d.h,
//                                 Frame3dTransverseMass) with mass per length
//                                 rho A of the member, tag "wet".
// A factor exists only when its group has elements (no bracing: no "braces";
// only wet groups have added mass), so every basis is nonzero. Each factor's
// `elements` lists its element indices in SpaceFrameGeometry(spec).elements.
//
// DOFs: six per free node, "n<k>:ux", "n<k>:uy", "n<k>:uz", "n<k>:rx",
// "n<k>:ry", "n<k>:rz" (m, rad, global axes). Nodes: the joints level by level
// (k = 1..levels, then Y line j, then X line i), then the X-brace centres, then
// the nodes inside the members, member by member.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "femup/core/fe/frame3d.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"
#include "femup/core/invalid.h"

namespace femup {

enum class FaceBracing {
  kNone,      // no braces (a moment frame)
  kDiagonal,  // one diagonal per face panel
  kX,         // two diagonals per face panel, joined at the centre
};
// "none", "diagonal", "x".
const char* ToString(FaceBracing bracing);
// Returns false when `text` names no bracing.
bool FaceBracingFromString(const std::string& text, FaceBracing* bracing);

// Springs to the ground under every leg (N/m, N/m, N m/rad, N m/rad): a pile
// group's or a mudmat's flexibility. Zero: that direction is rigid (its DOF is
// not in the model). With any spring, each leg's base joint "b<k>" (k = 1, 2,
// ... in the order of the level-1 joints above them) has the sprung DOFs,
// labelled "b<k>:ux" ...; they come after every "n<k>" DOF, whose labels stay
// as on a clamped frame. support_flexibility softens these springs.
struct SpaceFrameBase {
  double horizontal = 0;  // along X and along Y (ux, uy)
  double vertical = 0;    // along Z (uz)
  double rocking = 0;     // about X and about Y (rx, ry)
  double torsion = 0;     // about Z (rz)
  bool rigid() const {
    return horizontal == 0 && vertical == 0 && rocking == 0 && torsion == 0;
  }
};

struct SpaceFrameSpec {
  int levels = 10;
  int bays_x = 2;
  int bays_y = 2;
  double level_height = 10.0;  // m
  double bay_width_x = 15.0;   // m
  double bay_width_y = 15.0;   // m
  int elements_per_member = 4;
  int blocks_per_level = 1;  // stiffness / added-mass blocks per level (<= bays_x)
  FaceBracing bracing = FaceBracing::kX;
  double water_depth = 0;  // m above the base; elements with midpoint below are wet
  BeamTheory theory = BeamTheory::kEulerBernoulli;
  // Steel tubes (outer diameter, wall in m).
  FrameSection3d legs = CircularTube(1.2, 0.03, 210e9, 0.3, 7850);
  FrameSection3d braces = CircularTube(0.6, 0.015, 210e9, 0.3, 7850);
  FrameSection3d horizontals = CircularTube(0.6, 0.015, 210e9, 0.3, 7850);
  SpaceFrameBase base;  // clamped by default
  // Ok when valid; otherwise the field and what is wrong (sections: field
  // "legs.Iy").
  Invalid Validate() const;
};

enum class SpaceFrameMember { kLeg, kBrace, kHorizontal };

struct SpaceFrameElement {
  int node1 = -1, node2 = -1;  // free-node index k - 1 of "n<k>"; -1: clamped base
  Eigen::Vector3d end1, end2;  // coordinates (m)
  Eigen::Vector3d reference;   // sets local y (frame3d.h)
  SpaceFrameMember member = SpaceFrameMember::kLeg;
  int level = 1;      // from 1
  int member_id = 0;  // the member it is part of (from 0, in the builder's order)
  int block = 1;      // from 1
  bool wet = false;
};

struct SpaceFrameGeometryData {
  std::vector<Eigen::Vector3d> nodes;  // free node k - 1 = "n<k>" (m)
  std::vector<SpaceFrameElement> elements;
};

// The nodes and elements of the frame, in the builder's order. O(elements).
// Throws InputError naming the field for an invalid spec.
SpaceFrameGeometryData SpaceFrameGeometry(const SpaceFrameSpec& spec);

struct SpaceFrameSize {
  long long num_nodes = 0;  // free nodes
  long long num_dofs = 0;   // 6 per free node, and the base springs' DOFs
  long long num_elements = 0;
  long long num_wet_elements = 0;
  int num_mass_factors = 0;
  int num_stiffness_factors = 0;
  int num_added_mass_factors = 0;
  int num_parameters = 0;  // the three above together
  // Upper bound on the stored entries of K (and of M) in full symmetric
  // storage: 36 (free nodes + 2 elements between free nodes). Entries that
  // are exactly zero (axis-aligned members) are not stored, so the real count
  // can be lower.
  long long nnz_bound = 0;
};

// The size BuildSpaceFrame(spec) would have, without assembling anything:
// O(elements) time and memory. Throws as SpaceFrameGeometry.
SpaceFrameSize SpaceFrameModelSize(const SpaceFrameSpec& spec);

// Throws InputError naming the field ("model.bays_x", "model.legs.Iy") for an
// invalid spec.
ParametrisedModel BuildSpaceFrame(const SpaceFrameSpec& spec);

// The same frame as a Structure (type "space_frame") for the diagnosis
// (model_effects.h): one element per stiffness group of BuildSpaceFrame, in
// its order and labelled as its factors ("l2:legs1" for
// "stiffness[l2:legs1]"), each with the group's stiffness (equal to the
// factor's basis), the consistent mass of the same elements (a level's groups
// sum to the basis of "mass[l<k>]"), and, when some of them are wet, the
// added-mass basis of "added_mass[...]" (else an empty n x n matrix); x0, x1
// are the bounds of the group's level (m). stiffness and mass are the model's
// K and M. Nodes: every free node "n<k>" with its coordinates; no supports
// (the base is clamped). attached_mass_nodes: the joints of the top level;
// attached_mass_segments: the segments of its horizontals, where at most 24.
// members: every member of the frame in the builder's order, labelled by its
// kind and end joints ("brace n8-n24"; an end at the base is its base joint
// "b<k>", clamped or on springs), with its stiffness; a group's members sum to
// its stiffness.
// Every group is held as n x n sparse matrices (n = 6 x free nodes), so the
// memory grows with groups x n: meant for models up to about 10^5 DOF.
// Throws as BuildSpaceFrame.
Structure BuildSpaceFrameStructure(const SpaceFrameSpec& spec);

}  // namespace femup
