// Structure: an assembled finite element model with its elements kept apart, so
// that correction factors can be attached to elements or groups of elements.
// Builders (chain, 2D frame, Matrix Market import) produce a Structure; a
// ParameterPlan turns it into a ParametrisedModel.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "femup/core/fe/model.h"

namespace femup {

// One element (or substructure) in global free DOFs.
struct ElementMatrices {
  int id = 0;                     // 1-based element number
  std::string label;              // used in parameter names: "3" (chain), "e3" (frame)
  SparseMatrix stiffness;         // K_e, num_dofs x num_dofs
  SparseMatrix mass;              // M_e (structural mass of the element)
  SparseMatrix added_mass_basis;  // Mw_e: the basis for water added mass
  bool wet = false;               // below the water line
  double x0 = 0, x1 = 0;          // position along the structure (m), where it applies
};

// One finite element of a member that has several: what damage over part of
// a member's length (a dent, a crack at one end) acts on.
struct MemberPart {
  double from = 0, to = 1;  // its span along the member, fractions from the first joint
  BasisMatrix stiffness;    // its finite element's stiffness, on its DOFs
  double x0 = 0, x1 = 0;    // its extent along the structure (m), as the elements'
};

// A member inside an element, where the model's elements are groups of members
// (a space frame's level groups): what a local change, such as one damaged
// brace, acts on when it does not act on its whole group.
struct ElementMember {
  std::string label;              // "brace n8-n24", "leg b1-n1": its kind and end joints
  int element = -1;               // the Structure::elements entry (group) it belongs to
  BasisMatrix stiffness;          // its part of that element's stiffness, on its DOFs
  double x0 = 0, x1 = 0;          // its extent along the structure (m), as the elements'
  std::vector<MemberPart> parts;  // its finite elements, where it has more than one
};

// A node of a model with geometry.
struct ModelNode {
  std::string name;  // the prefix of its DOF labels: "n3" of "n3:ux"
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // m, the model's axes
};

// A straight line element of the mesh (a beam or bar), along which a point's
// displacement is interpolated by the beam's shape functions (sensor.h): its
// end nodes (indices into Structure::nodes; -1 for a rigid support, which has
// no node and no DOFs) and their coordinates.
struct LineSegment {
  int node_a = -1, node_b = -1;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  // m
  int element = -1;  // the Structure::elements entry it belongs to (a member, a group)
};

// A support modelled as a spring to the ground on one free DOF (a chain's
// ground spring, a cantilever's elastic base): what support flexibility softens.
struct SupportSpring {
  int dof = -1;          // index into dof_labels
  double stiffness = 0;  // N/m or N m/rad, > 0
  std::string name;      // "ground spring", "base rotation"
  std::string unit;      // of the stiffness: "N/m" or "N m/rad"
};

// A rigid support of a model with geometry (a clamped column base, a jacket's
// foot): its restrained directions have no DOF in the model, but the elements
// that meet there couple them to the model's DOFs. What support flexibility
// acts on where the model has no spring there (model_effects.h): a spring on
// each restrained direction, condensed out (Guyan) onto the model's DOFs.
struct RigidSupport {
  std::string name;                               // "b1": the support joint
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // m
  std::vector<std::string> directions;            // the restrained ones: "ux", "uy", "rz"
  std::vector<int> rows;  // the model's DOFs the restrained directions couple to
  // The elements' stiffness and mass between those DOFs and the restrained
  // directions (rows x directions), and among the restrained directions.
  Eigen::MatrixXd k_fb, m_fb, k_bb, m_bb;
  // Per restrained direction, the stiffness a support spring's compliance ratio
  // is relative to (a cantilever's 3 EI / L^3 and EI / L); empty: k_bb's
  // diagonal, the end stiffness of the elements that meet there.
  Eigen::VectorXd reference;
  // The range of that compliance ratio support flexibility fits, where the
  // builder states one (a cantilever's [1e-6, 10], as its own pipeline's);
  // 0: the family's default [1e-3, 100].
  double min_compliance = 0, max_compliance = 0;
};

// One end of a member where it is connected to a joint, where the model's
// builder knows the connection (a plane frame's beam-to-column connections):
// the member's finite element at that end, on its own DOFs, and which of them
// is the rotation the connection transmits (both ends' where the member is one
// element). What a semi-rigid connection softens (model_effects.h,
// stiffness_loss at a member's connections).
struct ConnectionEnd {
  std::vector<int> dofs;       // the end element's DOFs (indices into dof_labels)
  Eigen::MatrixXd k, m;        // its stiffness and mass on `dofs`
  std::vector<int> rotations;  // indices in `dofs` of the connected ends' rotations
};

// A member's end connections (both ends of a beam between two joints).
struct MemberConnections {
  std::string label;  // the member's element label: "s1:beam1"
  int element = -1;   // its Structure::elements entry
  std::vector<ConnectionEnd> ends;
};

// The same model in a richer formulation that its builder can make and the
// model leaves out (a frame of Euler-Bernoulli members with shear deformation,
// the frame on a finer mesh): the difference is a model-form error the
// diagnosis allows for (effect_ranking.h). On the model's DOFs, or on its own
// (a finer mesh; form_variant.h puts it on the model's).
struct Structure;
struct FormVariant {
  std::string name;  // what it adds, for reports
  SparseMatrix stiffness;
  SparseMatrix mass;
  // Empty: the matrices are on the model's DOFs. Otherwise the variant has
  // DOFs of its own and dofs[i] is the one at the model's DOF i.
  std::vector<int> dofs;
  // The variant as a whole model the diagnosis can run on instead, where its
  // builder made one (a finer mesh: RefinedModel, form_variant.h): its
  // stiffness and mass are the ones above, its DOFs those `dofs` index, its
  // nodes at the model's places named as the model's; null otherwise.
  std::shared_ptr<const Structure> model;
};

struct Structure {
  // What built it: "chain", "cantilever", "space_frame", "matrix_market", ...;
  // says which unmodelled effects apply (model_effects.h).
  std::string type;
  std::string description;
  SparseMatrix stiffness;  // baseline K (includes supports, springs)
  SparseMatrix mass;       // baseline M (includes lumped masses)
  std::vector<std::string> dof_labels;
  std::vector<ElementMatrices> elements;
  double length = 0;  // overall length where it applies (m), 0 otherwise
  // Positions along the structure of each DOF (for plots), may be empty.
  std::vector<double> dof_positions;
  // The DOFs that shape plots draw, in drawing order (e.g. one leg of a space
  // frame, bottom to top); empty: every transverse (":ux") DOF.
  std::vector<int> plot_dofs;
  // Every node of models with geometry (a cantilever: node k at (0, height, 0),
  // supported ones too; a space frame's free nodes); empty for a chain or a
  // Matrix Market model. Used to place test sensors by their coordinates.
  std::vector<ModelNode> nodes;
  // The mesh's line elements, where the model has them (a cantilever, a plane
  // or space frame); empty for a chain or a Matrix Market model. Sensors and
  // attached masses between nodes are placed on them.
  std::vector<LineSegment> segments;
  // The members inside the elements, where an element is a group of them (a
  // space frame); empty where each element is one member or finite element.
  std::vector<ElementMember> members;
  // Supports that are springs in the model (rigid supports have no DOF here).
  std::vector<SupportSpring> supports;
  // Supports that are rigid in the model, where its builder knows the
  // elements that meet there (a plane or space frame's clamped bases).
  std::vector<RigidSupport> rigid_supports;
  // The nodes (ModelNode::name) where the diagnosis looks for an attached
  // mass; empty: every node with translational DOFs. Large models name a few
  // (a space frame: the joints of its top level), not thousands of fits.
  std::vector<std::string> attached_mass_nodes;
  // Where attached_mass_nodes names them, the segments (indices into segments)
  // where a mass between nodes is looked for too (a space frame: its top
  // level's horizontals); otherwise unused.
  std::vector<int> attached_mass_segments;
  // Where given, the lines (each a chain of segments, end to end, indices into
  // segments) where a mass between nodes is looked for instead, one candidate
  // per line: a refined mesh's segments grouped as the coarser model's
  // elements (RefinedModel), so the candidates stay the model's.
  std::vector<std::vector<int>> attached_mass_lines;
  // The members whose end connections the diagnosis may find semi-rigid (a
  // plane frame's beams); empty: none known.
  std::vector<MemberConnections> connections;
  // Richer formulations of this model (see FormVariant); empty: none known.
  std::vector<FormVariant> form_variants;
  // Index of the element with the given id, or -1.
  int FindElement(int id) const;
};

// How one family of factors (mass, stiffness or added mass) is laid out.
struct ParameterFamily {
  enum class Scope {
    kNone,        // no factors of this kind
    kPerElement,  // one factor per selected element
    kSingle,      // one factor for all selected elements together
    kGroups,      // one factor per listed group of element ids
  };
  enum class Selection { kAll, kWet, kDry };
  Scope scope = Scope::kNone;
  Selection selection = Selection::kAll;
  std::vector<std::vector<int>> groups;  // used when scope == kGroups
};

struct ParameterPlan {
  ParameterFamily mass;
  ParameterFamily stiffness;
  ParameterFamily added_mass;  // only wet elements can carry added mass
};

// The paper's plan: mass and stiffness per element, added mass per wet element.
ParameterPlan PaperParameterPlan();

// Builds the parametrised model. Parameter order: mass, stiffness, added mass,
// each in element order. Names: "<kind>[<label>]", groups "<kind>[<l1>+<l2>+...]"
// and single factors "<kind>[all]" / "<kind>[wet]" / "<kind>[dry]".
// Throws InputError for unknown element ids or an empty selection.
ParametrisedModel BuildModel(const Structure& structure, const ParameterPlan& plan);

}  // namespace femup
