// A large 2D plane frame (storeys x bays of columns and beams, each member
// split into several Euler-Bernoulli beam-column elements, columns clamped at
// the base), built directly as a ParametrisedModel with correction factors on
// substructures: a test model of 10^5 DOF and 10^3 factors for the solver
// benchmarks (the element-by-element Structure does not scale to that size).
//
// Substructures: in every storey, the columns and the beams are cut into
// `blocks_per_storey` blocks of consecutive bays; each block of columns and each
// block of beams carries one stiffness factor ("stiffness[s<storey>:col<block>]",
// "stiffness[s<storey>:beam<block>]"), one mass factor per storey
// ("mass[s<storey>]", all its members), and one added-mass factor per column
// block in the lowest `wet_storeys` storeys ("added_mass[s<storey>:col<block>]",
// transverse consistent mass of the columns, the members that water loads).
// Storeys are numbered from 1 at the base, blocks from 1 at the left.
// DOFs: three per free node, "n<k>:ux", "n<k>:uy", "n<k>:rz"; joints first
// (column line by column line, bottom up, k from 1), then the nodes inside the
// members.
#pragma once

#include "femup/core/fe/fe.h"
#include "femup/core/fe/frame3d.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"
#include "femup/core/invalid.h"

namespace femup {

// Springs to the ground at every column base, per direction (N/m, N/m,
// N m/rad). Zero: that direction is rigid (its DOF is not in the model). A
// foundation that is not a rigid clamp (soil, piles, a base plate) is modelled
// so, and support_flexibility can then soften it.
struct PlaneFrameBase {
  double horizontal = 0;  // along x (ux)
  double vertical = 0;    // along y (uy)
  double rotation = 0;    // about z (rz)
  bool rigid() const { return horizontal == 0 && vertical == 0 && rotation == 0; }
};

struct PlaneFrameSpec {
  int storeys = 10;
  int bays = 5;
  double storey_height = 3.5;  // m
  double bay_width = 6.0;      // m
  int elements_per_member = 4;
  int blocks_per_storey = 1;  // column and beam blocks per storey (<= bays)
  int wet_storeys = 0;        // lowest storeys whose columns carry added mass
  BeamSection column{210e9, 0.02, 4e-4, 7850};
  BeamSection beam{210e9, 0.012, 2.5e-4, 7850};
  PlaneFrameBase base;  // BuildPlaneFrameStructure only; BuildPlaneFrame: rigid
  // BuildPlaneFrameStructure only: members without shear deformation
  // (Euler-Bernoulli, the default) or with it (Timoshenko, fe.h's BeamShear,
  // Poisson's ratio 0.3).
  BeamTheory theory = BeamTheory::kEulerBernoulli;
  // Shear areas kappa A (m^2) of the columns and the beams; 0: half the area, a
  // thin-walled section's (rolled I and H sections have 0.3-0.6 A, solid
  // rectangles 5/6 A). Used by a Timoshenko frame and, for an Euler-Bernoulli
  // one, by its form variant (Structure::form_variants).
  double column_shear_area = 0;
  double beam_shear_area = 0;
  // Ok when valid; otherwise the field and what is wrong.
  Invalid Validate() const;
};

// Throws InputError naming the field for an invalid spec.
ParametrisedModel BuildPlaneFrame(const PlaneFrameSpec& spec);

// The same frame as a Structure whose elements are its members (the study
// model type `plane_frame`: portal frames, multi-bay, multi-storey): each member,
// split into `elements_per_member` beam-column elements, keeps its own stiffness,
// mass and (columns of the lowest `wet_storeys` storeys) transverse added-mass
// basis, so correction factors and unmodelled effects act per member. Members
// are numbered storey by storey, columns left to right then beams left to right;
// labels "s<storey>:col<line>" and "s<storey>:beam<bay>" (1-based). Where a
// member has several elements, Structure::members lists it (its element's
// index and label) with its elements as parts (MemberPart: spans in fractions
// from its first joint, a column's foot or a beam's left end), what a
// stiffness loss over part of a member acts on. DOFs and
// node names as BuildPlaneFrame; Structure::nodes holds every free node's
// coordinates (x along the bays, y up). With base springs, each column base is
// a node "b<line>" (after the others) with a DOF per sprung direction, the
// spring in K, and listed in Structure::supports ("base rotation at b1", ...);
// the description says which. An Euler-Bernoulli frame carries, as
// Structure::form_variants, the same frame with shear deformation (the form
// error the diagnosis allows for). blocks_per_storey is not used. Throws
// InputError naming the field for an invalid spec.
Structure BuildPlaneFrameStructure(const PlaneFrameSpec& spec);

}  // namespace femup
