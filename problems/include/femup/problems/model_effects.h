// Unmodelled effects as changes of the model itself: each family is a
// parametrised change dK(theta), dM(theta) of a Structure's matrices, built from
// that structure's own element matrices, DOFs, node heights and supports, so one
// family serves every model type that has what it needs (issue 26; effects.h is
// the older form that edits a CantileverSpec and rebuilds the beam).
//
// A family on a structure comes as one or more instances, one per region it can
// act on (a stiffness loss in storey 3, an attached mass at node n7): the
// discrete choice is the instance, the continuous parameters are theta. Each
// parameter's range is also its prior, uniform in the parameter's coordinate
// (log coordinates for magnitudes spanning decades), unless a study states
// another (effect_priors.h: ranges and normal priors on the physical
// quantities, the regions kept).
//
// The families (kinds), with theta and the change they make:
//   material_scaling    ln(s): every element's stiffness times s (E error);
//                       dK = (s - 1) sum_e K_e. Region: all elements.
//   stiffness_loss      ln(loss fraction): one element's stiffness (a chain's
//                       spring: a storey; a beam element) times 1 - loss;
//                       dK = -loss K_e. One instance per element, and where
//                       the elements are groups of members (a space frame's
//                       levels; Structure::members), one per member as well,
//                       up to ModelEffectOptions::max_members of them, and one
//                       per finite element of a member that has several (a
//                       space frame's, a plane frame's: a loss over part of
//                       its length); a member that is its element's only one
//                       (a plane frame's) is that element's instance. Where
//                       the builder knows a member's end connections
//                       (Structure::connections: a plane frame's beams), one
//                       more per member, "connections of <member>": its
//                       connections semi-rigid, a rotational spring between
//                       each connected end and its joint, k = k_rr (1 - loss)
//                       / loss (k_rr the end element's own rotational
//                       stiffness there), condensed out statically:
//                       dK = -K_R (K_RR + D)^-1 K_R' on the end element, and
//                       its mass carried by the same condensation.
//   attached_mass       ln(m / m_ref): a point mass on one node's translational
//                       DOFs (sensors, cables, equipment); m_ref is the
//                       structure's total mass (m_ref below). One instance per
//                       node with translational DOFs; and, where the model has
//                       line elements, one per element segment (where it names
//                       its candidate nodes, its attached_mass_segments only:
//                       a space frame's top horizontals) with its position
//                       xi in [0.05, 0.95]
//                       fitted: a point mass between the nodes, read through
//                       the element's shape functions (femup/sensor.h).
//                       Where the model has rotational DOFs and node
//                       coordinates (a cantilever, a plane or space frame),
//                       the mass also carries a rotary inertia m r^2 about
//                       each of the model's rotation axes (equipment, a deck
//                       module), its radius of gyration r = l_ref exp(theta)
//                       fitted from a negligible 1e-3 l_ref to 0.1 l_ref
//                       (l_ref: the structure's extent, ReferenceLength); at
//                       a point between nodes the rotation is the element's
//                       (the slope of its transverse field, its twist).
//   added_mass          ln(ratio) [, level]: the elements' added-mass bases
//                       (water acting on the wet part) times ratio. Where the
//                       elements have heights (x0 < x1 along the structure:
//                       a cantilever), the wet part is below `level` (m), each
//                       element counted by the fraction of it below the level;
//                       otherwise (a chain), the elements flagged wet. Acts in
//                       wet states only when the study has wet states.
//   support_flexibility ln(c), or ln(c_t), ln(c_r) where the supports restrain
//                       translations and rotations both (a footing's sway and
//                       rocking stiffness are two numbers): each restrained
//                       direction given a compliance c times its reference.
//                       Where the supports are springs (Structure::supports;
//                       a chain's ground spring, a cantilever's elastic base,
//                       a frame on base springs), each spring in series with
//                       one c times more compliant: k -> k / (1 + c). Where
//                       they are rigid (Structure::rigid_supports: a clamped
//                       frame's feet), a spring k_bb(d, d) / c on each
//                       restrained direction d, condensed out (Guyan).
//
// Every change and its derivatives with respect to theta are exact (analytic):
// the families are linear in exp(theta_0), and the level's weights are
// piecewise linear.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/fe/structure.h"
#include "femup/core/sysid/measurement.h"
#include "femup/problems/effects.h"

namespace femup {

// A change of the model's matrices (same DOFs as the structure). Either may be
// empty (0 x 0): no change of that matrix.
struct ModelChange {
  SparseMatrix stiffness;
  SparseMatrix mass;
};

// Where in the structure an instance acts.
struct EffectRegion {
  std::string name;           // "all elements", "element 3", "node n7", "support"
  std::vector<int> elements;  // indices into Structure::elements
  std::vector<int> dofs;  // indices into the structure's DOFs (attached mass, support)
  int member = -1;        // index into Structure::members where it is one member
  int part = -1;          // and into its parts where it is one of them
};

class ModelEffect {
 public:
  virtual ~ModelEffect() = default;
  // "material_scaling", "stiffness_loss", ...
  virtual std::string kind() const = 0;
  virtual const EffectRegion& region() const = 0;
  // Parameters and their prior ranges.
  virtual std::vector<EffectParameter> Parameters() const = 0;
  // Starting points for a multi-start fit (each of size Parameters().size()).
  virtual std::vector<Eigen::VectorXd> Starts() const = 0;
  // The change at theta in a state of the given immersion.
  virtual ModelChange Change(const Eigen::VectorXd& theta, Immersion immersion) const = 0;
  // Its derivative with respect to theta[i].
  virtual ModelChange Derivative(const Eigen::VectorXd& theta, int i,
                                 Immersion immersion) const = 0;
  virtual EffectLocation Location(const Eigen::VectorXd& theta) const = 0;
  virtual std::vector<EffectMagnitude> Magnitudes(const Eigen::VectorXd& theta) const = 0;
};

struct ModelEffectOptions {
  // Added mass acts in wet states only (the study has wet states); otherwise in
  // every state.
  bool wet_only_added_mass = false;
  // Stiffness loss tries each member of a group on its own, and each of a
  // member's finite elements (MemberPartName), when the structure has at most
  // this many members (each is one more fit; the 10^4-DOF jacket has 530); -1:
  // all of them, however many.
  int max_members = 200;
  // Attached masses carry a fitted rotary inertia where the structure has
  // rotational DOFs and node coordinates; false: translational masses only.
  bool rotary_inertia = true;
};

// The region name of stiffness loss on part of a member (one of its finite
// elements): "member brace n8-n24 (0.50-1.00)", the span in fractions of its
// length from the first joint named.
std::string MemberPartName(const ElementMember& member, const MemberPart& part);

// The kinds model_effects knows, in a fixed order.
std::vector<std::string> ModelEffectKinds();

// The kinds that apply to `structure`, and for the others why not (the same
// order as ModelEffectKinds, one entry per kind; empty reason = applies).
struct FamilyApplicability {
  std::string kind;
  std::string why_not;  // empty when it applies
  // Tried where a study names no candidates (axial_load is not: a load is
  // known to whoever applies it, and a study names it when it may be there).
  bool by_default = true;
};
std::vector<FamilyApplicability> ApplicableModelEffects(const Structure& structure);

// The instances of `kind` on `structure`. Throws InputError("effect", ...) for
// an unknown kind (listing the known ones) and for a kind that does not apply to
// the structure (saying why). The instances keep a pointer to `structure`,
// which must outlive them.
std::vector<std::unique_ptr<ModelEffect>> CreateModelEffects(
    const std::string& kind, const Structure& structure,
    const ModelEffectOptions& options = {});

// The structure's matrices changed by `effects` at their parameters `thetas`
// (one vector each) for a state of the given immersion.
void ApplyModelEffects(const Structure& structure,
                       const std::vector<const ModelEffect*>& effects,
                       const std::vector<Eigen::VectorXd>& thetas, Immersion immersion,
                       SparseMatrix* stiffness, SparseMatrix* mass);

// The reference mass of the attached-mass family: the structure's mass moving
// with a unit rigid translation along its most massive translational direction
// (every ":ux" DOF, every ":uy" DOF, ..., or every DOF of a chain), kg.
double ReferenceMass(const Structure& structure);

// The reference length of an attached mass's radius of gyration: the
// structure's largest extent along x, y or z (its nodes and line elements), m;
// 0 where it has no node coordinates (a chain, a Matrix Market model without
// them).
double ReferenceLength(const Structure& structure);

}  // namespace femup
