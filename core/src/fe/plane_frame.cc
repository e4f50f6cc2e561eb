#include "femup/core/fe/plane_frame.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fe/assembly.h"
#include "femup/core/errors.h"
#include "femup/core/fe/form_variant.h"

namespace femup {
namespace {

using internal::FromTriplets;
using internal::Scatter;
using internal::Triplets;

Invalid CheckSection(const BeamSection& s, const std::string& field) {
  const double v[4] = {s.E, s.A, s.I, s.rho};
  for (double x : v) {
    if (!(x > 0) || !std::isfinite(x)) {
      return {field, "E, A, I and rho must be positive and finite"};
    }
  }
  return {};
}

// The frame's geometry, shared by both builders: free nodes (the joints, column
// line by column line bottom up, then each member's inner nodes, member by
// member), members storey by storey (columns left to right, then beams), and
// each member's elements in order along it.
struct FrameMember {
  int a, b;  // end nodes (-1 = base, clamped)
  double xa, ya, xb, yb;
  bool column;
  int storey;  // 1-based
  int index;   // column line or bay, 0-based
};
struct FramePiece {
  int a, b;
  double xa, ya, xb, yb;
  std::size_t member;
};
struct FrameLayout {
  std::vector<double> x, y;
  std::vector<FrameMember> members;
  std::vector<FramePiece> pieces;  // grouped by member, in member order
};

FrameLayout LayOut(const PlaneFrameSpec& spec) {
  FrameLayout f;
  const int lines = spec.bays + 1;
  const int e = spec.elements_per_member;
  auto joint = [&](int c, int s) { return s == 0 ? -1 : c * spec.storeys + (s - 1); };
  for (int c = 0; c < lines; ++c) {
    for (int s = 1; s <= spec.storeys; ++s) {
      f.x.push_back(c * spec.bay_width);
      f.y.push_back(s * spec.storey_height);
    }
  }
  for (int s = 1; s <= spec.storeys; ++s) {
    for (int c = 0; c < lines; ++c) {
      f.members.push_back({joint(c, s - 1), joint(c, s), c * spec.bay_width,
                           (s - 1) * spec.storey_height, c * spec.bay_width,
                           s * spec.storey_height, true, s, c});
    }
    for (int c = 0; c < spec.bays; ++c) {
      f.members.push_back({joint(c, s), joint(c + 1, s), c * spec.bay_width,
                           s * spec.storey_height, (c + 1) * spec.bay_width,
                           s * spec.storey_height, false, s, c});
    }
  }
  for (std::size_t m = 0; m < f.members.size(); ++m) {
    const FrameMember& mb = f.members[m];
    int prev = mb.a;
    double px = mb.xa, py = mb.ya;
    for (int k = 1; k <= e; ++k) {
      const double t = static_cast<double>(k) / e;
      const double qx = mb.xa + t * (mb.xb - mb.xa), qy = mb.ya + t * (mb.yb - mb.ya);
      int next = mb.b;
      if (k < e) {
        next = static_cast<int>(f.x.size());
        f.x.push_back(qx);
        f.y.push_back(qy);
      }
      f.pieces.push_back({prev, next, px, py, qx, qy, m});
      prev = next;
      px = qx;
      py = qy;
    }
  }
  return f;
}

}  // namespace

Invalid PlaneFrameSpec::Validate() const {
  std::string field;
  std::ostringstream msg;
  auto at = [&](const std::string& name) -> std::ostream& {
    field = name;
    return msg;
  };
  if (storeys < 1)
    at("storeys") << "must be >= 1, got " << storeys;
  else if (bays < 1)
    at("bays") << "must be >= 1, got " << bays;
  else if (!(storey_height > 0) || !std::isfinite(storey_height))
    at("storey_height") << "must be positive and finite";
  else if (!(bay_width > 0) || !std::isfinite(bay_width))
    at("bay_width") << "must be positive and finite";
  else if (elements_per_member < 1)
    at("elements_per_member") << "must be >= 1, got " << elements_per_member;
  else if (blocks_per_storey < 1 || blocks_per_storey > bays)
    at("blocks_per_storey") << "must be in 1.." << bays << ", got " << blocks_per_storey;
  else if (wet_storeys < 0 || wet_storeys > storeys)
    at("wet_storeys") << "must be in 0.." << storeys << ", got " << wet_storeys;
  for (const auto& [name, k] :
       {std::pair<const char*, double>{"horizontal", base.horizontal},
        {"vertical", base.vertical},
        {"rotation", base.rotation}}) {
    if (field.empty() && !(k >= 0 && std::isfinite(k)))
      at(std::string("base.") + name)
          << "a spring stiffness must be >= 0 and finite, got " << k;
  }
  for (const auto& [name, a] :
       {std::pair<const char*, double>{"column.shear_area", column_shear_area},
        {"beam.shear_area", beam_shear_area}}) {
    if (field.empty() && !(a >= 0 && std::isfinite(a)))
      at(name) << "must be >= 0 and finite (0: half the area), got " << a;
  }
  if (field.empty() && theory != BeamTheory::kEulerBernoulli &&
      theory != BeamTheory::kTimoshenko)
    at("theory") << "must be euler_bernoulli or timoshenko";
  if (!field.empty()) return {field, msg.str()};
  Invalid bad = CheckSection(column, "column");
  if (bad.ok()) bad = CheckSection(beam, "beam");
  return bad;
}

ParametrisedModel BuildPlaneFrame(const PlaneFrameSpec& spec) {
  ThrowIfInvalid(spec.Validate(), "model");
  if (!spec.base.rigid()) {
    throw InputError("model.base",
                     "base springs are a plane_frame Structure's (the study model); "
                     "the benchmark frame is clamped");
  }
  if (spec.theory != BeamTheory::kEulerBernoulli) {
    throw InputError(
        "model.theory",
        "Timoshenko members are a plane_frame Structure's (the study model); "
        "the benchmark frame is Euler-Bernoulli");
  }
  const int lines = spec.bays + 1;
  const FrameLayout layout = LayOut(spec);
  const std::vector<double>& x = layout.x;
  // Block of bay/column line c: consecutive lines share a block.
  auto block = [&](int c) {
    return std::min(spec.blocks_per_storey - 1, c * spec.blocks_per_storey / lines);
  };
  auto beam_block = [&](int bay) { return bay * spec.blocks_per_storey / spec.bays; };
  const int n = 3 * static_cast<int>(x.size());
  std::vector<std::string> labels;
  labels.reserve(n);
  for (std::size_t k = 0; k < x.size(); ++k) {
    for (const char* d : {":ux", ":uy", ":rz"}) {
      labels.push_back("n" + std::to_string(k + 1) + d);
    }
  }

  // Triplets per substructure.
  const int blocks = spec.blocks_per_storey;
  auto col_index = [&](int s, int b) { return (s - 1) * blocks + b; };
  std::vector<Triplets> k_col(spec.storeys * blocks), k_beam(spec.storeys * blocks),
      m_storey(spec.storeys), w_col(spec.wet_storeys * blocks);
  Triplets kt, mt;
  for (const FramePiece& el : layout.pieces) {
    const FrameMember& mb = layout.members[el.member];
    const int blk = mb.column ? block(mb.index) : beam_block(mb.index);
    const BeamSection& sec = mb.column ? spec.column : spec.beam;
    const std::array<int, 6> d = {el.a < 0 ? -1 : 3 * el.a,
                                  el.a < 0 ? -1 : 3 * el.a + 1,
                                  el.a < 0 ? -1 : 3 * el.a + 2,
                                  3 * el.b,
                                  3 * el.b + 1,
                                  3 * el.b + 2};
    const Matrix6 ke = Frame2dStiffness(sec, el.xa, el.ya, el.xb, el.yb);
    const Matrix6 me = Frame2dConsistentMass(sec, el.xa, el.ya, el.xb, el.yb);
    Triplets& kg =
        mb.column ? k_col[col_index(mb.storey, blk)] : k_beam[col_index(mb.storey, blk)];
    Scatter(ke, d, &kg);
    Scatter(ke, d, &kt);
    Scatter(me, d, &m_storey[mb.storey - 1]);
    Scatter(me, d, &mt);
    if (mb.column && mb.storey <= spec.wet_storeys) {
      Scatter(Frame2dTransverseMass(sec.rho * sec.A, el.xa, el.ya, el.xb, el.yb), d,
              &w_col[col_index(mb.storey, blk)]);
    }
  }

  ParametrisedModel model(FromTriplets(n, kt), FromTriplets(n, mt), std::move(labels));
  auto add = [&](const std::string& name, ParameterKind kind, const Triplets& t,
                 const std::string& tag) {
    Parameter p;
    p.name = name;
    p.kind = kind;
    p.basis = BasisMatrix::FromTriplets(n, t.cbegin(), t.cend());
    p.tags = {tag};
    model.AddParameter(std::move(p));
  };
  // Parameter order: mass, stiffness, added mass (as BuildModel orders them).
  for (int s = 1; s <= spec.storeys; ++s) {
    add("mass[s" + std::to_string(s) + "]", ParameterKind::kMass, m_storey[s - 1],
        s <= spec.wet_storeys ? "wet" : "dry");
  }
  for (int s = 1; s <= spec.storeys; ++s) {
    for (int b = 0; b < blocks; ++b) {
      const std::string where = "s" + std::to_string(s) + ":";
      add("stiffness[" + where + "col" + std::to_string(b + 1) + "]",
          ParameterKind::kStiffness, k_col[col_index(s, b)], "columns");
      add("stiffness[" + where + "beam" + std::to_string(b + 1) + "]",
          ParameterKind::kStiffness, k_beam[col_index(s, b)], "beams");
    }
  }
  for (int s = 1; s <= spec.wet_storeys; ++s) {
    for (int b = 0; b < blocks; ++b) {
      add("added_mass[s" + std::to_string(s) + ":col" + std::to_string(b + 1) + "]",
          ParameterKind::kAddedMass, w_col[col_index(s, b)], "wet");
    }
  }
  return model;
}

}  // namespace femup

namespace femup {
namespace {

// The finer mesh a frame carries as a form variant: 4 times its elements per
// member, or 2 times where that is more than this many DOFs; none where both
// are (the variant's modes are solved at every diagnosis).
constexpr int kFinerMeshMaxDofs = 4000;

Structure BuildFrame(const PlaneFrameSpec& spec, bool variants);

// How many times finer the mesh of the form variants of a frame of n DOFs and
// `elements` finite elements is (4, or 2 where 4 would be more than
// kFinerMeshMaxDofs DOFs); 0: none.
int FinerMeshFactor(std::size_t n, std::size_t elements) {
  for (const std::size_t factor : {4, 2}) {
    // Each element adds factor - 1 inner nodes of 3 DOFs.
    if (n + elements * (factor - 1) * 3 <= kFinerMeshMaxDofs)
      return static_cast<int>(factor);
  }
  return 0;
}

// An Euler-Bernoulli frame's form variants: the same members with shear
// deformation (kv, mv: its global K and M on the frame's own mesh, the base
// springs included; used where factor is 0), and the frame on a mesh `factor`
// times finer (FinerMeshFactor). Where the finer mesh is
// not too large, the shear variant is on it too: on two elements per member a
// Timoshenko member changes the higher modes far less than it does once the
// mesh resolves them (a portal's fifth mode: 2 % against 8 %). A Timoshenko
// frame carries the finer mesh alone.
void AddFormVariants(const PlaneFrameSpec& spec, int factor,
                     const BeamShear& column_shear, const BeamShear& beam_shear,
                     const Triplets& kv, const Triplets& mv, Structure* s) {
  PlaneFrameSpec finer = spec;
  finer.elements_per_member *= factor;
  std::ostringstream mesh;
  mesh << "a finer mesh (" << finer.elements_per_member
       << " elements per member instead of " << spec.elements_per_member << ")";
  std::string shear_name;  // the shear variant's, on the mesh it is built on
  if (spec.theory != BeamTheory::kTimoshenko) {
    std::ostringstream what;
    what << "shear deformation (Timoshenko members; shear areas " << column_shear.area
         << " m^2 in the columns, " << beam_shear.area << " m^2 in the beams)";
    if (factor == 0) {
      const int n = static_cast<int>(s->dof_labels.size());
      s->form_variants.push_back(
          {what.str(), FromTriplets(n, kv), FromTriplets(n, mv), {}, {}});
    } else {
      PlaneFrameSpec sheared = finer;
      sheared.theory = BeamTheory::kTimoshenko;
      sheared.column_shear_area = column_shear.area;
      sheared.beam_shear_area = beam_shear.area;
      shear_name = what.str();
      what << " on " << mesh.str();
      s->form_variants.push_back(
          FinerMeshVariant(*s, BuildFrame(sheared, false), what.str()));
    }
  }
  if (factor > 0) {
    // The finer frame as a model too, with the shear variant (on its DOFs,
    // which are the sheared frame's) as its own form variant.
    Structure fine = BuildFrame(finer, false);
    FormVariant v = FinerMeshVariant(*s, fine, mesh.str());
    if (spec.theory != BeamTheory::kTimoshenko) {
      const FormVariant& sheared = s->form_variants.back();
      fine.form_variants.push_back({shear_name, sheared.stiffness, sheared.mass, {}, {}});
    }
    v.model = std::make_shared<const Structure>(RefinedModel(*s, std::move(fine)));
    s->form_variants.push_back(std::move(v));
  }
}

}  // namespace

Structure BuildPlaneFrameStructure(const PlaneFrameSpec& spec) {
  return BuildFrame(spec, true);
}

namespace {

Structure BuildFrame(const PlaneFrameSpec& spec, bool variants) {
  ThrowIfInvalid(spec.Validate(), "model");
  const FrameLayout layout = LayOut(spec);
  const std::vector<double>& x = layout.x;
  const std::vector<double>& y = layout.y;
  const auto& members = layout.members;
  const int per_member = spec.elements_per_member;
  Structure s;
  s.type = "plane_frame";
  for (std::size_t k = 0; k < x.size(); ++k) {
    const std::string name = "n" + std::to_string(k + 1);
    for (const char* d : {":ux", ":uy", ":rz"}) {
      s.dof_labels.push_back(name + d);
      s.dof_positions.push_back(y[k]);
    }
    s.nodes.push_back({name, Eigen::Vector3d(x[k], y[k], 0.0)});
  }
  // Column bases on springs: a node per column line, a DOF per sprung
  // direction (-1: rigid), numbered after the frame's own.
  const std::array<double, 3> base_k = {spec.base.horizontal, spec.base.vertical,
                                        spec.base.rotation};
  const std::array<const char*, 3> base_dir = {":ux", ":uy", ":rz"};
  const std::array<const char*, 3> base_name = {"base horizontal", "base vertical",
                                                "base rotation"};
  std::vector<std::array<int, 3>> base_dofs(spec.bays + 1, {-1, -1, -1});
  std::vector<int> base_node(spec.bays + 1, -1);  // index into s.nodes; -1: rigid
  Triplets kt, mt;
  if (!spec.base.rigid()) {
    for (int c = 0; c <= spec.bays; ++c) {
      const std::string name = "b" + std::to_string(c + 1);
      for (int d = 0; d < 3; ++d) {
        if (base_k[d] == 0) continue;
        base_dofs[c][d] = static_cast<int>(s.dof_labels.size());
        s.dof_labels.push_back(name + base_dir[d]);
        s.dof_positions.push_back(0.0);
        kt.emplace_back(base_dofs[c][d], base_dofs[c][d], base_k[d]);
        s.supports.push_back({base_dofs[c][d], base_k[d],
                              base_name[d] + std::string(" at ") + name,
                              d == 2 ? "N m/rad" : "N/m"});
      }
      base_node[c] = static_cast<int>(s.nodes.size());
      s.nodes.push_back({name, Eigen::Vector3d(c * spec.bay_width, 0.0, 0.0)});
    }
  }
  // Clamped column bases: each a rigid support whose restrained directions
  // couple to the frame through its column's first element.
  if (spec.base.rigid()) {
    for (int c = 0; c <= spec.bays; ++c) {
      RigidSupport support;
      support.name = "b" + std::to_string(c + 1);
      support.xyz = Eigen::Vector3d(c * spec.bay_width, 0.0, 0.0);
      support.directions = {"ux", "uy", "rz"};
      s.rigid_supports.push_back(std::move(support));
    }
  }
  const int n = static_cast<int>(s.dof_labels.size());
  // An Euler-Bernoulli frame's form variant: the same members with shear
  // deformation (its global K and M, the base springs included).
  const bool timoshenko = spec.theory == BeamTheory::kTimoshenko;
  const int finer =
      variants ? FinerMeshFactor(static_cast<std::size_t>(n), layout.pieces.size()) : 0;
  // The shear variant on the frame's own mesh: only where there is no finer one.
  const bool own_mesh_shear = variants && !timoshenko && finer == 0;
  Triplets kv = own_mesh_shear ? kt : Triplets{}, mv;
  auto shear = [&](bool column) {
    const BeamSection& sec = column ? spec.column : spec.beam;
    const double stated = column ? spec.column_shear_area : spec.beam_shear_area;
    return BeamShear{stated > 0 ? stated : 0.5 * sec.A, 0.3};
  };
  for (std::size_t m = 0; m < members.size(); ++m) {
    const FrameMember& mb = members[m];
    const BeamSection& sec = mb.column ? spec.column : spec.beam;
    const BeamShear sheared = shear(mb.column);
    const BeamShear model_shear = timoshenko ? sheared : BeamShear{};
    Triplets ke, me, we;
    // A beam's connections to the joints at its ends: its end elements.
    MemberConnections joints;
    joints.element = static_cast<int>(m);
    // Its finite elements, where it has several: what damage over part of its
    // length (a crack at one end, a dent) acts on (MemberPart).
    std::vector<MemberPart> parts;
    for (std::size_t k = m * per_member; k < (m + 1) * per_member; ++k) {
      const FramePiece& p = layout.pieces[k];
      // A base end: the sprung DOFs of its column line's base node, if any.
      const int line = static_cast<int>(std::lround(p.xa / spec.bay_width));
      const std::array<int, 6> d = {p.a < 0 ? base_dofs[line][0] : 3 * p.a,
                                    p.a < 0 ? base_dofs[line][1] : 3 * p.a + 1,
                                    p.a < 0 ? base_dofs[line][2] : 3 * p.a + 2,
                                    3 * p.b,
                                    3 * p.b + 1,
                                    3 * p.b + 2};
      s.segments.push_back({p.a < 0 ? base_node[line] : p.a, p.b,
                            Eigen::Vector3d(p.xa, p.ya, 0.0),
                            Eigen::Vector3d(p.xb, p.yb, 0.0), static_cast<int>(m)});
      const Matrix6 k6 = timoshenko
                             ? Frame2dStiffness(sec, model_shear, p.xa, p.ya, p.xb, p.yb)
                             : Frame2dStiffness(sec, p.xa, p.ya, p.xb, p.yb);
      const Matrix6 m6 =
          timoshenko ? Frame2dConsistentMass(sec, model_shear, p.xa, p.ya, p.xb, p.yb)
                     : Frame2dConsistentMass(sec, p.xa, p.ya, p.xb, p.yb);
      Scatter(k6, d, &ke);
      Scatter(m6, d, &me);
      const bool first = k == m * per_member, last = k + 1 == (m + 1) * per_member;
      if (per_member > 1) {
        Triplets kp;
        Scatter(k6, d, &kp);
        MemberPart part;
        const double i = static_cast<double>(k - m * per_member);
        part.from = i / per_member;
        part.to = (i + 1) / per_member;
        part.stiffness = BasisMatrix::FromTriplets(n, kp.cbegin(), kp.cend());
        part.x0 = std::min(p.ya, p.yb);
        part.x1 = std::max(p.ya, p.yb);
        parts.push_back(std::move(part));
      }
      if (!mb.column && (first || last)) {
        ConnectionEnd end{std::vector<int>(d.begin(), d.end()), k6, m6, {}};
        if (first) end.rotations.push_back(2);
        if (last) end.rotations.push_back(5);
        joints.ends.push_back(std::move(end));
      }
      if (p.a < 0 && !s.rigid_supports.empty()) {
        internal::AddToRigidSupport<6>(k6, m6, d, {0, 1, 2, -1, -1, -1},
                                       &s.rigid_supports[line]);
      }
      if (!timoshenko) {
        if (own_mesh_shear) {
          Scatter(Frame2dStiffness(sec, sheared, p.xa, p.ya, p.xb, p.yb), d, &kv);
          Scatter(Frame2dConsistentMass(sec, sheared, p.xa, p.ya, p.xb, p.yb), d, &mv);
        }
      }
      if (mb.column && mb.storey <= spec.wet_storeys) {
        Scatter(Frame2dTransverseMass(sec.rho * sec.A, p.xa, p.ya, p.xb, p.yb), d, &we);
      }
    }
    ElementMatrices el;
    el.id = static_cast<int>(m) + 1;
    el.label = "s" + std::to_string(mb.storey) + (mb.column ? ":col" : ":beam") +
               std::to_string(mb.index + 1);
    el.stiffness = FromTriplets(n, ke);
    el.mass = FromTriplets(n, me);
    el.added_mass_basis = FromTriplets(n, we);
    el.wet = mb.column && mb.storey <= spec.wet_storeys;
    // Heights of its ends (a beam: x0 == x1): where it applies along the height.
    el.x0 = std::min(mb.ya, mb.yb);
    el.x1 = std::max(mb.ya, mb.yb);
    if (!joints.ends.empty()) {
      joints.label = el.label;
      s.connections.push_back(std::move(joints));
    }
    if (!parts.empty()) {
      // The member is its element; its parts are what it adds (the member's
      // own instance would be its element's: effects skip it).
      ElementMember member;
      member.label = el.label;
      member.element = static_cast<int>(m);
      member.stiffness = BasisMatrix::FromTriplets(n, ke.cbegin(), ke.cend());
      member.x0 = el.x0;
      member.x1 = el.x1;
      member.parts = std::move(parts);
      s.members.push_back(std::move(member));
    }
    kt.insert(kt.end(), ke.begin(), ke.end());
    mt.insert(mt.end(), me.begin(), me.end());
    s.elements.push_back(std::move(el));
  }
  s.stiffness = FromTriplets(n, kt);
  s.mass = FromTriplets(n, mt);
  s.length = spec.storeys * spec.storey_height;
  std::ostringstream desc;
  desc << "2D plane frame, " << spec.storeys << " storeys x " << spec.bays << " bays ("
       << spec.storey_height << " m x " << spec.bay_width << " m), " << members.size()
       << " members of " << per_member << " "
       << (timoshenko ? "Timoshenko" : "Euler-Bernoulli") << " elements, columns ";
  if (spec.base.rigid()) {
    desc << "clamped";
  } else {
    desc << "on base springs (";
    bool first = true;
    for (int d = 0; d < 3; ++d) {
      if (base_k[d] == 0) continue;
      desc << (first ? "" : ", ") << std::string(base_name[d]).substr(5) << " "
           << base_k[d] << " " << (d == 2 ? "N m/rad" : "N/m");
      first = false;
    }
    desc << "; rigid otherwise)";
  }
  s.description = desc.str();
  if (variants) AddFormVariants(spec, finer, shear(true), shear(false), kv, mv, &s);
  return s;
}

}  // namespace
}  // namespace femup
