#include "femup/core/fe/space_frame.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "fe/assembly.h"
#include "femup/core/enum_names.h"
#include "femup/core/errors.h"

namespace femup {
namespace {

using internal::FromTriplets;
using internal::Scatter;
using internal::Triplets;

constexpr int kMemberKinds = 3;  // legs, braces, horizontals
const char* const kMemberNames[kMemberKinds] = {"legs", "braces", "horizontals"};

Invalid CheckSection(const FrameSection3d& s, BeamTheory theory,
                     const std::string& field) {
  return s.Validate(theory).Under(field);
}

const FrameSection3d& SectionOf(const SpaceFrameSpec& spec, SpaceFrameMember m) {
  switch (m) {
    case SpaceFrameMember::kLeg:
      return spec.legs;
    case SpaceFrameMember::kBrace:
      return spec.braces;
    case SpaceFrameMember::kHorizontal:
      break;
  }
  return spec.horizontals;
}

// Stiffness / added-mass group of an element: level, then block, then member.
int GroupOf(const SpaceFrameElement& e, int blocks) {
  return ((e.level - 1) * blocks + (e.block - 1)) * kMemberKinds +
         static_cast<int>(e.member);
}

// The DOFs of the base joints on springs (SpaceFrameBase): joint j of the
// base (j = the level-1 joint above it, X line fastest) has dof[j][d] for
// direction d = ux, uy, uz, rx, ry, rz, or -1 where that direction is rigid.
// They are numbered from `first`, the first DOF after the free nodes'.
struct BaseDofs {
  std::vector<std::array<int, 6>> dof;
  std::array<double, 6> stiffness{};
  int count = 0;
  double wx = 1, wy = 1;
  int nx = 1;
  // The base joint at `at` (a point of the base plane).
  int JointAt(const Eigen::Vector3d& at) const {
    return static_cast<int>(std::lround(at.y() / wy)) * nx +
           static_cast<int>(std::lround(at.x() / wx));
  }
};

BaseDofs BaseDofsOf(const SpaceFrameSpec& spec, int first) {
  BaseDofs b;
  b.nx = spec.bays_x + 1;
  b.wx = spec.bay_width_x;
  b.wy = spec.bay_width_y;
  const SpaceFrameBase& k = spec.base;
  b.stiffness = {k.horizontal, k.horizontal, k.vertical, k.rocking, k.rocking, k.torsion};
  b.dof.assign(static_cast<std::size_t>(b.nx * (spec.bays_y + 1)),
               {-1, -1, -1, -1, -1, -1});
  if (k.rigid()) return b;
  for (auto& joint : b.dof) {
    for (int d = 0; d < 6; ++d)
      if (b.stiffness[d] > 0) joint[d] = first + b.count++;
  }
  return b;
}

// The element's 12 DOFs; a base end's are its base joint's sprung DOFs (-1
// where rigid).
std::array<int, 12> DofsOf(const SpaceFrameElement& e, const BaseDofs& base) {
  std::array<int, 12> d;
  const std::array<int, 6>* b1 = e.node1 < 0 ? &base.dof[base.JointAt(e.end1)] : nullptr;
  const std::array<int, 6>* b2 = e.node2 < 0 ? &base.dof[base.JointAt(e.end2)] : nullptr;
  for (int i = 0; i < 6; ++i) {
    d[i] = b1 ? (*b1)[i] : 6 * e.node1 + i;
    d[6 + i] = b2 ? (*b2)[i] : 6 * e.node2 + i;
  }
  return d;
}

// The springs' stiffness on the base joints' DOFs, added to the total K.
SparseMatrix WithBaseSprings(SparseMatrix k, const BaseDofs& base) {
  if (base.count == 0) return k;
  Triplets t;
  for (const auto& joint : base.dof) {
    for (int d = 0; d < 6; ++d)
      if (joint[d] >= 0) t.emplace_back(joint[d], joint[d], base.stiffness[d]);
  }
  return k + FromTriplets(static_cast<int>(k.rows()), t);
}

// The base joints' DOF labels, "b<k>:ux" ..., in DOF order.
void AppendBaseLabels(const BaseDofs& base, std::vector<std::string>* labels) {
  const char* const dirs[6] = {":ux", ":uy", ":uz", ":rx", ":ry", ":rz"};
  for (std::size_t j = 0; j < base.dof.size(); ++j) {
    for (int d = 0; d < 6; ++d)
      if (base.dof[j][d] >= 0) labels->push_back("b" + std::to_string(j + 1) + dirs[d]);
  }
}

// "on base springs (horizontal 1e+08 N/m, rocking 1e+10 N m/rad)".
std::string BaseDescription(const SpaceFrameBase& b) {
  std::ostringstream o;
  o << "on base springs (";
  bool first = true;
  for (const auto& [name, k, unit] :
       {std::tuple<const char*, double, const char*>{"horizontal", b.horizontal, "N/m"},
        {"vertical", b.vertical, "N/m"},
        {"rocking", b.rocking, "N m/rad"},
        {"torsion", b.torsion, "N m/rad"}}) {
    if (k == 0) continue;
    o << (first ? "" : ", ") << name << " " << k << " " << unit;
    first = false;
  }
  o << ")";
  return o.str();
}

// Elements sorted by group (stable): group g is order[offset[g] .. offset[g+1]).
struct Grouping {
  std::vector<int> order;
  std::vector<int> offset;
};

template <typename GroupFn>
Grouping GroupElements(const std::vector<SpaceFrameElement>& elements, int groups,
                       GroupFn group_of) {
  Grouping g;
  g.offset.assign(groups + 1, 0);
  for (const SpaceFrameElement& e : elements) {
    const int k = group_of(e);
    if (k >= 0) ++g.offset[k + 1];
  }
  for (int k = 0; k < groups; ++k) g.offset[k + 1] += g.offset[k];
  g.order.resize(g.offset[groups]);
  std::vector<int> next(g.offset.begin(), g.offset.end() - 1);
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const int k = group_of(elements[i]);
    if (k >= 0) g.order[next[k]++] = static_cast<int>(i);
  }
  return g;
}

// Assembles every group's basis into `bases` (one per group, held on its DOFs;
// empty groups give empty bases) from the element matrices `matrix(element)`; returns
// their sum when `total` is set (else a 0 x 0 matrix). One triplet list: each group's
// triplets are a segment of it, so the sum costs no second copy.
template <typename MatrixFn>
SparseMatrix AssembleGroups(int n, const std::vector<SpaceFrameElement>& elements,
                            const BaseDofs& base, const Grouping& g, MatrixFn matrix,
                            bool total, std::vector<BasisMatrix>* bases) {
  const int groups = static_cast<int>(g.offset.size()) - 1;
  // With a total, all triplets at once; without, the biggest group's.
  std::size_t reserve = 0, group_reserve = 0;
  for (int k = 0; k < groups; ++k) {
    std::size_t here = 0;
    for (int j = g.offset[k]; j < g.offset[k + 1]; ++j) {
      const SpaceFrameElement& e = elements[g.order[j]];
      const std::size_t free = 6 * ((e.node1 >= 0) + (e.node2 >= 0));
      here += free * free;
    }
    reserve += here;
    group_reserve = std::max(group_reserve, here);
  }
  Triplets t;
  t.reserve(total ? reserve : group_reserve);
  bases->clear();
  bases->resize(static_cast<std::size_t>(groups));
  for (int k = 0; k < groups; ++k) {
    if (g.offset[k + 1] == g.offset[k]) continue;
    const std::size_t start = t.size();
    for (int j = g.offset[k]; j < g.offset[k + 1]; ++j) {
      const SpaceFrameElement& e = elements[g.order[j]];
      Scatter(matrix(e), DofsOf(e, base), &t);
    }
    (*bases)[k] = BasisMatrix::FromTriplets(n, t.begin() + start, t.end());
    if (!total) t.clear();
  }
  if (!total) return SparseMatrix();
  return FromTriplets(n, t);
}

}  // namespace

constexpr EnumName<FaceBracing> kFaceBracingNames[] = {
    {FaceBracing::kNone, "none"},
    {FaceBracing::kDiagonal, "diagonal"},
    {FaceBracing::kX, "x"},
};

const char* ToString(FaceBracing bracing) {
  return NameIn(kFaceBracingNames, bracing, "unknown");
}

bool FaceBracingFromString(const std::string& text, FaceBracing* bracing) {
  return ValueIn(kFaceBracingNames, text, bracing);
}

Invalid SpaceFrameSpec::Validate() const {
  std::string field;
  std::ostringstream msg;
  auto at = [&](const char* name) -> std::ostream& {
    field = name;
    return msg;
  };
  auto positive = [](double x) { return x > 0 && std::isfinite(x); };
  if (levels < 1)
    at("levels") << "must be >= 1, got " << levels;
  else if (bays_x < 1)
    at("bays_x") << "must be >= 1, got " << bays_x;
  else if (bays_y < 1)
    at("bays_y") << "must be >= 1, got " << bays_y;
  else if (!positive(level_height))
    at("level_height") << "must be positive and finite";
  else if (!positive(bay_width_x))
    at("bay_width_x") << "must be positive and finite";
  else if (!positive(bay_width_y))
    at("bay_width_y") << "must be positive and finite";
  else if (elements_per_member < 1)
    at("elements_per_member") << "must be >= 1, got " << elements_per_member;
  else if (blocks_per_level < 1 || blocks_per_level > bays_x)
    at("blocks_per_level") << "must be in 1.." << bays_x << ", got " << blocks_per_level;
  else if (bracing != FaceBracing::kNone && bracing != FaceBracing::kDiagonal &&
           bracing != FaceBracing::kX)
    at("bracing") << "must be none, diagonal or x";
  else if (!(water_depth >= 0) || !std::isfinite(water_depth))
    at("water_depth") << "must be >= 0 and finite";
  else if (theory != BeamTheory::kEulerBernoulli && theory != BeamTheory::kTimoshenko)
    at("theory") << "must be euler_bernoulli or timoshenko";
  for (const auto& [name, k] :
       {std::pair<const char*, double>{"base.horizontal", base.horizontal},
        {"base.vertical", base.vertical},
        {"base.rocking", base.rocking},
        {"base.torsion", base.torsion}}) {
    if (field.empty() && !(k >= 0 && std::isfinite(k)))
      at(name) << "must be >= 0 and finite (0: rigid), got " << k;
  }
  if (!field.empty()) return {field, msg.str()};
  // Sizes whose sparse matrices would overflow their int indices (about 18
  // stored entries per DOF).
  const double nx = bays_x + 1.0, ny = bays_y + 1.0, faces = 2.0 * (bays_x + bays_y);
  const double members = nx * ny + (nx - 1) * ny + nx * (ny - 1) + 4 * faces;
  const double dofs =
      6.0 * levels * (nx * ny + faces + (elements_per_member - 1) * members);
  if (dofs > 5e7) {
    msg << levels << " levels of " << bays_x << " x " << bays_y << " bays with "
        << elements_per_member << " elements per member exceed the limit of 5e7 DOFs";
    return {"levels", msg.str()};
  }
  Invalid bad = CheckSection(legs, theory, "legs");
  if (bad.ok()) bad = CheckSection(braces, theory, "braces");
  if (bad.ok()) bad = CheckSection(horizontals, theory, "horizontals");
  return bad;
}

SpaceFrameGeometryData SpaceFrameGeometry(const SpaceFrameSpec& spec) {
  ThrowIfInvalid(spec.Validate(), "model");
  const int bx = spec.bays_x, by = spec.bays_y, nx = bx + 1, ny = by + 1;
  const int levels = spec.levels, blocks = spec.blocks_per_level;
  const int per_level = nx * ny;
  const double h = spec.level_height, wx = spec.bay_width_x, wy = spec.bay_width_y;
  const Eigen::Vector3d ref_z(0, 0, 1), ref_x(1, 0, 0);

  SpaceFrameGeometryData g;
  // Joint (i, j, k): X line i, Y line j, level k (0 = base, clamped).
  auto joint = [&](int i, int j, int k) {
    return k == 0 ? -1 : (k - 1) * per_level + j * nx + i;
  };
  auto position = [&](int i, int j, int k) {
    return Eigen::Vector3d(i * wx, j * wy, k * h);
  };
  for (int k = 1; k <= levels; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) g.nodes.push_back(position(i, j, k));
    }
  }
  auto line_block = [&](int i) { return std::min(blocks - 1, i * blocks / nx) + 1; };
  auto bay_block = [&](int i) { return i * blocks / bx + 1; };

  // Face panels of one storey: bottom corners a, b and top corners c (above a),
  // d (above b), as (i, j) grid positions.
  struct Panel {
    int ai, aj, bi, bj;
    int index;  // bay index along the face, for the diagonal's direction
    int block;
  };
  std::vector<Panel> panels;
  if (spec.bracing != FaceBracing::kNone) {
    for (int j : {0, by}) {
      for (int i = 0; i < bx; ++i) panels.push_back({i, j, i + 1, j, i, bay_block(i)});
    }
    for (int i : {0, bx}) {
      for (int j = 0; j < by; ++j) panels.push_back({i, j, i, j + 1, j, line_block(i)});
    }
  }
  // X-brace centres, storey by storey.
  const int first_centre = static_cast<int>(g.nodes.size());
  if (spec.bracing == FaceBracing::kX) {
    for (int k = 1; k <= levels; ++k) {
      for (const Panel& p : panels) {
        g.nodes.push_back(0.25 *
                          (position(p.ai, p.aj, k - 1) + position(p.bi, p.bj, k - 1) +
                           position(p.ai, p.aj, k) + position(p.bi, p.bj, k)));
      }
    }
  }

  struct Member {
    int a, b;
    Eigen::Vector3d pa, pb, ref;
    SpaceFrameMember kind;
    int level, block;
  };
  std::vector<Member> members;
  auto add = [&](int i0, int j0, int k0, int i1, int j1, int k1,
                 const Eigen::Vector3d& ref, SpaceFrameMember kind, int level,
                 int block) {
    members.push_back({joint(i0, j0, k0), joint(i1, j1, k1), position(i0, j0, k0),
                       position(i1, j1, k1), ref, kind, level, block});
  };
  for (int k = 1; k <= levels; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        add(i, j, k - 1, i, j, k, ref_x, SpaceFrameMember::kLeg, k, line_block(i));
      }
    }
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < bx; ++i) {
        add(i, j, k, i + 1, j, k, ref_z, SpaceFrameMember::kHorizontal, k, bay_block(i));
      }
    }
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < by; ++j) {
        add(i, j, k, i, j + 1, k, ref_z, SpaceFrameMember::kHorizontal, k, line_block(i));
      }
    }
    for (std::size_t q = 0; q < panels.size(); ++q) {
      const Panel& p = panels[q];
      const auto brace = SpaceFrameMember::kBrace;
      if (spec.bracing == FaceBracing::kDiagonal) {
        if ((p.index + k) % 2 == 0) {
          add(p.ai, p.aj, k - 1, p.bi, p.bj, k, ref_z, brace, k, p.block);
        } else {
          add(p.bi, p.bj, k - 1, p.ai, p.aj, k, ref_z, brace, k, p.block);
        }
      } else {
        const int c = first_centre + (k - 1) * static_cast<int>(panels.size()) +
                      static_cast<int>(q);
        const Eigen::Vector3d pc = g.nodes[c];
        const int corners[4][3] = {
            {p.ai, p.aj, k - 1}, {p.bi, p.bj, k}, {p.bi, p.bj, k - 1}, {p.ai, p.aj, k}};
        // Bottom corners towards the centre, the centre towards the top ones.
        for (int r = 0; r < 4; ++r) {
          const int ci = corners[r][0], cj = corners[r][1], ck = corners[r][2];
          if (ck == k - 1) {
            members.push_back({joint(ci, cj, ck), c, position(ci, cj, ck), pc, ref_z,
                               brace, k, p.block});
          } else {
            members.push_back({c, joint(ci, cj, ck), pc, position(ci, cj, ck), ref_z,
                               brace, k, p.block});
          }
        }
      }
    }
  }

  const int e = spec.elements_per_member;
  g.elements.reserve(members.size() * e);
  g.nodes.reserve(g.nodes.size() + members.size() * (e - 1));
  for (std::size_t id = 0; id < members.size(); ++id) {
    const Member& mb = members[id];
    int prev = mb.a;
    Eigen::Vector3d p = mb.pa;
    for (int s = 1; s <= e; ++s) {
      const double t = static_cast<double>(s) / e;
      const Eigen::Vector3d q =
          s == e ? mb.pb : Eigen::Vector3d(mb.pa + t * (mb.pb - mb.pa));
      int next = mb.b;
      if (s < e) {
        next = static_cast<int>(g.nodes.size());
        g.nodes.push_back(q);
      }
      SpaceFrameElement el;
      el.node1 = prev;
      el.node2 = next;
      el.end1 = p;
      el.end2 = q;
      el.reference = mb.ref;
      el.member = mb.kind;
      el.level = mb.level;
      el.block = mb.block;
      el.member_id = static_cast<int>(id);
      el.wet = 0.5 * (p.z() + q.z()) < spec.water_depth;
      g.elements.push_back(el);
      prev = next;
      p = q;
    }
  }
  return g;
}

SpaceFrameSize SpaceFrameModelSize(const SpaceFrameSpec& spec) {
  const SpaceFrameGeometryData g = SpaceFrameGeometry(spec);
  const int blocks = spec.blocks_per_level;
  const int groups = spec.levels * blocks * kMemberKinds;
  std::vector<char> stiff(groups, 0), wet(groups, 0);
  SpaceFrameSize size;
  size.num_nodes = static_cast<long long>(g.nodes.size());
  size.num_dofs = 6 * size.num_nodes + BaseDofsOf(spec, 0).count;
  size.num_elements = static_cast<long long>(g.elements.size());
  long long inner = 0;
  for (const SpaceFrameElement& e : g.elements) {
    stiff[GroupOf(e, blocks)] = 1;
    if (e.wet) {
      wet[GroupOf(e, blocks)] = 1;
      ++size.num_wet_elements;
    }
    if (e.node1 >= 0 && e.node2 >= 0) ++inner;
  }
  size.num_mass_factors = spec.levels;
  size.num_stiffness_factors =
      static_cast<int>(std::count(stiff.begin(), stiff.end(), 1));
  size.num_added_mass_factors = static_cast<int>(std::count(wet.begin(), wet.end(), 1));
  size.num_parameters =
      size.num_mass_factors + size.num_stiffness_factors + size.num_added_mass_factors;
  size.nnz_bound = 36 * (size.num_nodes + 2 * inner);
  return size;
}

ParametrisedModel BuildSpaceFrame(const SpaceFrameSpec& spec) {
  SpaceFrameGeometryData g = SpaceFrameGeometry(spec);
  const std::vector<SpaceFrameElement>& elements = g.elements;
  const BaseDofs base = BaseDofsOf(spec, 6 * static_cast<int>(g.nodes.size()));
  const int n = 6 * static_cast<int>(g.nodes.size()) + base.count;
  const int blocks = spec.blocks_per_level;
  const int groups = spec.levels * blocks * kMemberKinds;
  const BeamTheory theory = spec.theory;
  std::vector<std::string> labels;
  labels.reserve(n);
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const std::string node = "n" + std::to_string(k + 1);
    for (const char* d : {":ux", ":uy", ":uz", ":rx", ":ry", ":rz"}) {
      labels.push_back(node + d);
    }
  }
  AppendBaseLabels(base, &labels);
  g.nodes = {};  // only the elements are needed from here

  const Grouping by_group = GroupElements(
      elements, groups, [&](const SpaceFrameElement& e) { return GroupOf(e, blocks); });
  const Grouping by_level = GroupElements(
      elements, spec.levels, [](const SpaceFrameElement& e) { return e.level - 1; });
  const Grouping wet_by_group = GroupElements(
      elements, groups,
      [&](const SpaceFrameElement& e) { return e.wet ? GroupOf(e, blocks) : -1; });

  std::vector<BasisMatrix> k_groups, m_levels, w_groups;
  SparseMatrix k = AssembleGroups(
      n, elements, base, by_group,
      [&](const SpaceFrameElement& e) {
        return Frame3dStiffness(SectionOf(spec, e.member), e.end1, e.end2, e.reference,
                                theory);
      },
      true, &k_groups);
  SparseMatrix m = AssembleGroups(
      n, elements, base, by_level,
      [&](const SpaceFrameElement& e) {
        return Frame3dConsistentMass(SectionOf(spec, e.member), e.end1, e.end2,
                                     e.reference, theory);
      },
      true, &m_levels);
  AssembleGroups(
      n, elements, base, wet_by_group,
      [&](const SpaceFrameElement& e) {
        const FrameSection3d& s = SectionOf(spec, e.member);
        return Frame3dTransverseMass(s.rho * s.A, e.end1, e.end2, e.reference);
      },
      false, &w_groups);

  ParametrisedModel model(WithBaseSprings(std::move(k), base), std::move(m),
                          std::move(labels));
  auto add = [&](std::string name, ParameterKind kind, BasisMatrix* basis,
                 const Grouping& grouping, int group, std::vector<std::string> tags) {
    Parameter p;
    p.name = std::move(name);
    p.kind = kind;
    p.basis.swap(*basis);
    p.elements.assign(grouping.order.begin() + grouping.offset[group],
                      grouping.order.begin() + grouping.offset[group + 1]);
    p.tags = std::move(tags);
    model.AddParameter(std::move(p));
  };
  // Parameter order: mass, stiffness, added mass (as BuildPlaneFrame orders them).
  for (int level = 1; level <= spec.levels; ++level) {
    bool wet = false;
    for (int j = by_level.offset[level - 1]; j < by_level.offset[level]; ++j) {
      wet = wet || elements[by_level.order[j]].wet;
    }
    add("mass[l" + std::to_string(level) + "]", ParameterKind::kMass,
        &m_levels[level - 1], by_level, level - 1, {wet ? "wet" : "dry"});
  }
  auto name_of = [&](int group) {
    const int kind = group % kMemberKinds, block = (group / kMemberKinds) % blocks;
    const int level = group / (kMemberKinds * blocks);
    return "[l" + std::to_string(level + 1) + ":" + kMemberNames[kind] +
           std::to_string(block + 1) + "]";
  };
  for (int q = 0; q < groups; ++q) {
    if (by_group.offset[q + 1] == by_group.offset[q]) continue;
    add("stiffness" + name_of(q), ParameterKind::kStiffness, &k_groups[q], by_group, q,
        {kMemberNames[q % kMemberKinds]});
  }
  for (int q = 0; q < groups; ++q) {
    if (wet_by_group.offset[q + 1] == wet_by_group.offset[q]) continue;
    add("added_mass" + name_of(q), ParameterKind::kAddedMass, &w_groups[q], wet_by_group,
        q, {"wet", kMemberNames[q % kMemberKinds]});
  }
  return model;
}

Structure BuildSpaceFrameStructure(const SpaceFrameSpec& spec) {
  const SpaceFrameGeometryData g = SpaceFrameGeometry(spec);
  const std::vector<SpaceFrameElement>& elements = g.elements;
  const int free_dofs = 6 * static_cast<int>(g.nodes.size());
  const BaseDofs base = BaseDofsOf(spec, free_dofs);
  const int n = free_dofs + base.count;
  const int blocks = spec.blocks_per_level;
  const int groups = spec.levels * blocks * kMemberKinds;
  const BeamTheory theory = spec.theory;

  // The stiffness factors' grouping for stiffness and mass alike; the added-mass
  // factors' grouping (wet elements only) for the added-mass bases.
  const Grouping by_group = GroupElements(
      elements, groups, [&](const SpaceFrameElement& e) { return GroupOf(e, blocks); });
  const Grouping wet_by_group = GroupElements(
      elements, groups,
      [&](const SpaceFrameElement& e) { return e.wet ? GroupOf(e, blocks) : -1; });
  std::vector<BasisMatrix> k_groups, m_groups, w_groups;
  Structure s;
  s.stiffness = AssembleGroups(
      n, elements, base, by_group,
      [&](const SpaceFrameElement& e) {
        return Frame3dStiffness(SectionOf(spec, e.member), e.end1, e.end2, e.reference,
                                theory);
      },
      true, &k_groups);
  s.stiffness = WithBaseSprings(std::move(s.stiffness), base);
  s.mass = AssembleGroups(
      n, elements, base, by_group,
      [&](const SpaceFrameElement& e) {
        return Frame3dConsistentMass(SectionOf(spec, e.member), e.end1, e.end2,
                                     e.reference, theory);
      },
      true, &m_groups);
  AssembleGroups(
      n, elements, base, wet_by_group,
      [&](const SpaceFrameElement& e) {
        const FrameSection3d& sec = SectionOf(spec, e.member);
        return Frame3dTransverseMass(sec.rho * sec.A, e.end1, e.end2, e.reference);
      },
      false, &w_groups);
  // An Euler-Bernoulli frame's form variant: its members with shear
  // deformation through their sections' shear areas (where every section has
  // them).
  const bool shear_areas = spec.legs.Validate(BeamTheory::kTimoshenko).ok() &&
                           spec.braces.Validate(BeamTheory::kTimoshenko).ok() &&
                           spec.horizontals.Validate(BeamTheory::kTimoshenko).ok();
  if (theory == BeamTheory::kEulerBernoulli && shear_areas) {
    std::vector<BasisMatrix> unused;
    FormVariant v;
    v.name = "shear deformation (Timoshenko members, the sections' shear areas)";
    v.stiffness = AssembleGroups(
        n, elements, base, by_group,
        [&](const SpaceFrameElement& e) {
          return Frame3dStiffness(SectionOf(spec, e.member), e.end1, e.end2, e.reference,
                                  BeamTheory::kTimoshenko);
        },
        true, &unused);
    v.stiffness = WithBaseSprings(std::move(v.stiffness), base);
    v.mass = AssembleGroups(
        n, elements, base, by_group,
        [&](const SpaceFrameElement& e) {
          return Frame3dConsistentMass(SectionOf(spec, e.member), e.end1, e.end2,
                                       e.reference, BeamTheory::kTimoshenko);
        },
        true, &unused);
    s.form_variants.push_back(std::move(v));
  }

  std::ostringstream d;
  d << "space frame, " << spec.bays_x << " x " << spec.bays_y << " bays, " << spec.levels
    << " levels of " << spec.level_height << " m, " << ToString(spec.bracing)
    << " bracing, water " << spec.water_depth << " m";
  if (!spec.base.rigid()) d << ", " << BaseDescription(spec.base);
  s.type = "space_frame";
  s.description = d.str();
  s.length = spec.levels * spec.level_height;
  s.dof_labels.reserve(n);
  s.dof_positions.reserve(n);
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const std::string node = "n" + std::to_string(k + 1);
    for (const char* c : {":ux", ":uy", ":uz", ":rx", ":ry", ":rz"}) {
      s.dof_labels.push_back(node + c);
      s.dof_positions.push_back(g.nodes[k].z());
    }
    s.nodes.push_back({node, g.nodes[k]});
  }
  // The base joints on springs: their DOFs, nodes (for sensors and segments)
  // and the supports that support_flexibility softens.
  const int first_base_node = static_cast<int>(s.nodes.size());
  if (base.count > 0) {
    AppendBaseLabels(base, &s.dof_labels);
    s.dof_positions.resize(s.dof_labels.size(), 0.0);
    const char* const names[6] = {"horizontal X",    "horizontal Y",    "vertical",
                                  "rocking about X", "rocking about Y", "torsion"};
    for (std::size_t j = 0; j < base.dof.size(); ++j) {
      const std::string node = "b" + std::to_string(j + 1);
      const int i = static_cast<int>(j) % base.nx, jy = static_cast<int>(j) / base.nx;
      s.nodes.push_back({node, Eigen::Vector3d(i * base.wx, jy * base.wy, 0.0)});
      for (int q = 0; q < 6; ++q) {
        if (base.dof[j][q] < 0) continue;
        s.supports.push_back({base.dof[j][q], base.stiffness[q],
                              std::string("base ") + names[q] + " at " + node,
                              q < 3 ? "N/m" : "N m/rad"});
      }
    }
  }
  // A clamped base: each joint a rigid support, coupled to the frame through
  // the members that meet it.
  if (spec.base.rigid()) {
    const int joints = static_cast<int>(base.dof.size());
    for (int j = 0; j < joints; ++j) {
      RigidSupport support;
      support.name = "b" + std::to_string(j + 1);
      support.xyz =
          Eigen::Vector3d((j % base.nx) * base.wx, (j / base.nx) * base.wy, 0.0);
      support.directions = {"ux", "uy", "uz", "rx", "ry", "rz"};
      s.rigid_supports.push_back(std::move(support));
    }
    for (const SpaceFrameElement& e : elements) {
      if (e.node1 >= 0 && e.node2 >= 0) continue;
      const Matrix12 k = Frame3dStiffness(SectionOf(spec, e.member), e.end1, e.end2,
                                          e.reference, theory);
      const Matrix12 m = Frame3dConsistentMass(SectionOf(spec, e.member), e.end1, e.end2,
                                               e.reference, theory);
      for (const bool first : {true, false}) {
        if ((first ? e.node1 : e.node2) >= 0) continue;
        std::array<int, 12> restrained;
        restrained.fill(-1);
        for (int i = 0; i < 6; ++i) restrained[(first ? 0 : 6) + i] = i;
        internal::AddToRigidSupport<12>(
            k, m, DofsOf(e, base), restrained,
            &s.rigid_supports[base.JointAt(first ? e.end1 : e.end2)]);
      }
    }
  }
  s.segments.reserve(g.elements.size());
  // A base end is its base joint's node when the base is on springs.
  auto node_of = [&](int node, const Eigen::Vector3d& end) {
    return node >= 0 || base.count == 0 ? node : first_base_node + base.JointAt(end);
  };
  for (const SpaceFrameElement& el : g.elements)
    s.segments.push_back(
        {node_of(el.node1, el.end1), node_of(el.node2, el.end2), el.end1, el.end2});
  // Shape plots: the sway (ux) of the corner leg at X = Y = 0, bottom to top.
  std::vector<std::pair<double, int>> leg;
  for (std::size_t k = 0; k < g.nodes.size(); ++k) {
    const Eigen::Vector3d& p = g.nodes[k];
    if (std::abs(p.x()) < 1e-9 && std::abs(p.y()) < 1e-9)
      leg.emplace_back(p.z(), static_cast<int>(6 * k));
  }
  std::sort(leg.begin(), leg.end());
  for (const auto& [z, dof] : leg) s.plot_dofs.push_back(dof);
  // Attached-mass candidates: the joints of the top level (the first nodes of
  // the top level's block in the node order), where decks and equipment sit.
  const int per_level = (spec.bays_x + 1) * (spec.bays_y + 1);
  for (int k = (spec.levels - 1) * per_level; k < spec.levels * per_level; ++k)
    s.attached_mass_nodes.push_back("n" + std::to_string(k + 1));
  // And between them, on the top level's horizontals (a deck's beams), where
  // they have at most kMaxDeckSegments element segments: each is a fit of two
  // unknowns, and the 10^4-DOF jacket's 48 would double its diagnosis time.
  constexpr std::size_t kMaxDeckSegments = 24;
  for (std::size_t k = 0; k < g.elements.size(); ++k) {
    const SpaceFrameElement& e = g.elements[k];
    if (e.level == spec.levels && e.member == SpaceFrameMember::kHorizontal)
      s.attached_mass_segments.push_back(static_cast<int>(k));
  }
  if (s.attached_mass_segments.size() > kMaxDeckSegments)
    s.attached_mass_segments.clear();

  const double h = spec.level_height;
  std::vector<int> element_of_group(static_cast<std::size_t>(groups), -1);
  for (int q = 0; q < groups; ++q) {
    if (by_group.offset[q + 1] == by_group.offset[q]) continue;
    element_of_group[static_cast<std::size_t>(q)] = static_cast<int>(s.elements.size());
    const int kind = q % kMemberKinds, block = (q / kMemberKinds) % blocks;
    const int level = q / (kMemberKinds * blocks) + 1;
    ElementMatrices e;
    e.id = static_cast<int>(s.elements.size()) + 1;
    e.label = "l" + std::to_string(level) + ":" + kMemberNames[kind] +
              std::to_string(block + 1);
    e.stiffness = k_groups[q].ToSparse();
    e.mass = m_groups[q].ToSparse();
    e.wet = wet_by_group.offset[q + 1] > wet_by_group.offset[q];
    e.added_mass_basis = e.wet ? w_groups[q].ToSparse() : SparseMatrix(n, n);
    e.x0 = (level - 1) * h;
    e.x1 = level * h;
    k_groups[q] = BasisMatrix();
    m_groups[q] = BasisMatrix();
    w_groups[q] = BasisMatrix();
    s.elements.push_back(std::move(e));
  }
  for (std::size_t k = 0; k < s.segments.size(); ++k) {
    s.segments[k].element =
        element_of_group[static_cast<std::size_t>(GroupOf(g.elements[k], blocks))];
  }
  // The members inside the groups, each with its own stiffness (its elements
  // are consecutive in the builder's order), named by its kind and end joints.
  const char* const singular[kMemberKinds] = {"leg", "brace", "horizontal"};
  auto end_name = [&](int node, const Eigen::Vector3d& end) {
    if (node >= 0) return s.nodes[static_cast<std::size_t>(node)].name;
    return "b" + std::to_string(base.JointAt(end) + 1);  // clamped or on springs
  };
  Triplets t;
  for (std::size_t first = 0; first < g.elements.size();) {
    std::size_t last = first;
    while (last + 1 < g.elements.size() &&
           g.elements[last + 1].member_id == g.elements[first].member_id)
      ++last;
    const SpaceFrameElement& a = g.elements[first];
    const SpaceFrameElement& b = g.elements[last];
    t.clear();
    ElementMember m;
    const int count = static_cast<int>(last - first + 1);
    for (std::size_t k = first; k <= last; ++k) {
      const SpaceFrameElement& e = g.elements[k];
      const std::size_t before = t.size();
      Scatter(Frame3dStiffness(SectionOf(spec, e.member), e.end1, e.end2, e.reference,
                               theory),
              DofsOf(e, base), &t);
      if (count == 1) continue;
      // Its finite elements, each a part of the member.
      const double length = (b.end2 - a.end1).norm();
      MemberPart part;
      part.from = (e.end1 - a.end1).norm() / length;
      part.to = (e.end2 - a.end1).norm() / length;
      part.stiffness =
          BasisMatrix::FromTriplets(n, t.begin() + static_cast<long>(before), t.end());
      part.x0 = std::min(e.end1.z(), e.end2.z());
      part.x1 = std::max(e.end1.z(), e.end2.z());
      m.parts.push_back(std::move(part));
    }
    m.label = std::string(singular[static_cast<int>(a.member)]) + " " +
              end_name(a.node1, a.end1) + "-" + end_name(b.node2, b.end2);
    m.element = element_of_group[static_cast<std::size_t>(GroupOf(a, blocks))];
    m.stiffness = BasisMatrix::FromTriplets(n, t.begin(), t.end());
    m.x0 = std::min(a.end1.z(), b.end2.z());
    m.x1 = std::max(a.end1.z(), b.end2.z());
    s.members.push_back(std::move(m));
    first = last + 1;
  }
  return s;
}

}  // namespace femup
