#include "femup/core/fe/builders.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "fe/assembly.h"
#include "femup/core/enum_names.h"
#include "femup/core/errors.h"
#include "femup/core/fe/beam_modifications.h"
#include "text_util.h"

namespace femup {

using internal::FromTriplets;
using internal::Scatter;
using internal::Triplets;

namespace {

std::string Str(double v) { return internal::ShortestDecimal(v); }

// 0 <= z0 < z1 <= tip, finite.
void CheckInterval(const std::string& where, double z0, double z1, double tip) {
  if (!std::isfinite(z0) || !std::isfinite(z1) || !(z0 >= 0) || !(z1 > z0) ||
      !(z1 <= tip)) {
    throw InputError(where, "z0 = " + Str(z0) + ", z1 = " + Str(z1) +
                                " m; expected 0 <= z0 < z1 <= " + Str(tip) +
                                " (the tip)");
  }
}

void CheckNonNegative(const std::string& where, const char* name, double v,
                      const char* unit) {
  if (!(v >= 0) || !std::isfinite(v)) {
    throw InputError(where, std::string(name) + " = " + Str(v) + "; expected a finite " +
                                unit + " >= 0");
  }
}

// The modifications of `spec` (heights up to `tip`), each named by its entry.
void CheckModifications(const CantileverSpec& spec, double tip) {
  for (std::size_t i = 0; i < spec.distributed_masses.size(); ++i) {
    const CantileverSpec::DistributedMass& d = spec.distributed_masses[i];
    const std::string where = "model.distributed_masses[" + std::to_string(i + 1) + "]";
    CheckInterval(where, d.z0, d.z1, tip);
    CheckNonNegative(where, "mass_per_length", d.mass_per_length,
                     "mass per length (kg/m)");
    CheckNonNegative(where, "fade", d.fade, "length (m)");
  }
  const auto& changes = spec.stiffness_changes;
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const std::string where = "model.stiffness_changes[" + std::to_string(i + 1) + "]";
    CheckInterval(where, changes[i].z0, changes[i].z1, tip);
    if (!(changes[i].factor > -1) || !std::isfinite(changes[i].factor)) {
      throw InputError(where, "factor = " + Str(changes[i].factor) +
                                  "; expected a finite number > -1 (E I times 1 + factor "
                                  "must stay positive)");
    }
  }
  // Overlapping changes add up; the sum is lowest at the start of some change.
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const double z = changes[i].z0;
    double sum = 0;
    for (const CantileverSpec::StiffnessChange& c : changes) {
      if (c.z0 <= z && z < c.z1) sum += c.factor;
    }
    if (!(1 + sum > 0)) {
      throw InputError("model.stiffness_changes",
                       "the factors of the changes that overlap at z = " + Str(z) +
                           " m add up to " + Str(sum) +
                           "; expected a sum > -1 (E I must stay positive)");
    }
  }
  for (std::size_t i = 0; i < spec.point_masses.size(); ++i) {
    const CantileverSpec::PointMass& p = spec.point_masses[i];
    const std::string where = "model.point_masses[" + std::to_string(i + 1) + "]";
    if (!(p.height >= 0 && p.height <= tip)) {
      throw InputError(where, "height = " + Str(p.height) +
                                  " m; expected 0 <= height <= " + Str(tip) +
                                  " (the tip)");
    }
    CheckNonNegative(where, "mass", p.mass, "mass (kg)");
    CheckNonNegative(where, "rotary_inertia", p.rotary_inertia,
                     "rotary inertia (kg m^2)");
  }
}

// A chain that idealises a building's storeys (a shear building) leaves out
// the flexural part of the building's deformation: columns continuous through
// the floors, joints that rotate where the floors are not rigid, columns that
// shorten. All of it resists a change of drift from one storey to the next,
// so a frame's higher modes, whose drifts reverse, are stiffer than its
// chain's (by 0.2-3 % on mode 2 and 1.2-8.5 % on mode 5 for floors 10-100
// times stiffer than the columns), while the first mode, to whose drifts the
// springs were fitted, is nearly unchanged. The variants add that
// resistance: between storeys s and s + 1 a spring on the difference of
// their drifts, of 0.1 of their mean storey stiffness in all (the coupled
// shear-flexural idealisation of a building, its flexural part at one
// standard deviation), shared along the height in two ways, falling from the
// base (column shortening weighs most there in a tall frame) and rising to
// the roof: two directions, so that the flexural part may vary linearly
// along the height.
std::vector<FormVariant> FlexuralFormVariants(const Structure& s, const ChainSpec& spec) {
  constexpr double kShare = 0.1;
  const int n = static_cast<int>(spec.masses.size());
  std::vector<FormVariant> variants;
  for (const bool from_base : {true, false}) {
    Triplets ct;
    for (int j = 1; j < n; ++j) {
      // drift_j - drift_{j-1} = x_j - 2 x_{j-1} + x_{j-2} (x_{-1} = 0, the ground).
      const double z = static_cast<double>(j) / n;  // the floor's height, of the roof's
      const double c = kShare * (from_base ? 1 - z : z) * 0.5 *
                       (spec.springs[j - 1] + spec.springs[j]);
      const int dofs[3] = {j, j - 1, j - 2};
      const double g[3] = {1.0, -2.0, 1.0};
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          if (dofs[a] >= 0 && dofs[b] >= 0)
            ct.emplace_back(dofs[a], dofs[b], c * g[a] * g[b]);
        }
      }
    }
    SparseMatrix kv = s.stiffness + FromTriplets(n, ct);
    kv.makeCompressed();
    variants.push_back({std::string("flexural deformation of the storeys, ") +
                            (from_base ? "falling from the base" : "rising to the roof") +
                            " (a spring on the change of drift between adjacent storeys, "
                            "up to 0.1 of their storey stiffness)",
                        std::move(kv),
                        s.mass,
                        {},
                        nullptr});
  }
  return variants;
}

}  // namespace

Structure BuildSpringMassChain(const ChainSpec& spec) {
  const int n = static_cast<int>(spec.masses.size());
  if (n == 0) throw InputError("model.masses", "the chain needs at least one mass");
  if (static_cast<int>(spec.springs.size()) != n) {
    std::ostringstream msg;
    msg << "has " << spec.springs.size() << " values, expected " << n
        << " (one spring below each mass)";
    throw InputError("model.springs", msg.str());
  }
  if (!spec.wet.empty() && static_cast<int>(spec.wet.size()) != n) {
    std::ostringstream msg;
    msg << "has " << spec.wet.size() << " values, expected " << n << " (one per mass)";
    throw InputError("model.wet", msg.str());
  }
  for (int i = 0; i < n; ++i) {
    if (!(spec.masses[i] > 0) || !std::isfinite(spec.masses[i])) {
      throw InputError("model.masses[" + std::to_string(i + 1) + "]",
                       "must be a positive finite mass (kg)");
    }
    if (!(spec.springs[i] > 0) || !std::isfinite(spec.springs[i])) {
      throw InputError("model.springs[" + std::to_string(i + 1) + "]",
                       "must be a positive finite stiffness (N/m)");
    }
  }
  Structure s;
  s.type = "chain";
  s.description =
      "spring-mass chain of " + std::to_string(n) + " masses, fixed at x1's end";
  s.supports.push_back({0, spec.springs[0], "ground spring", "N/m"});
  Triplets kt, mt;
  for (int e = 0; e < n; ++e) {
    ElementMatrices el;
    el.id = e + 1;
    el.label = std::to_string(e + 1);
    el.wet = spec.wet.empty() ? false : spec.wet[e];
    el.x0 = e;
    el.x1 = e + 1;
    Triplets ke, me;
    const double k = spec.springs[e];
    ke.emplace_back(e, e, k);
    if (e > 0) {
      ke.emplace_back(e - 1, e - 1, k);
      ke.emplace_back(e - 1, e, -k);
      ke.emplace_back(e, e - 1, -k);
    }
    me.emplace_back(e, e, spec.masses[e]);
    el.stiffness = FromTriplets(n, ke);
    el.mass = FromTriplets(n, me);
    el.added_mass_basis = el.mass;
    kt.insert(kt.end(), ke.begin(), ke.end());
    mt.insert(mt.end(), me.begin(), me.end());
    s.dof_labels.push_back("x" + std::to_string(e + 1));
    s.dof_positions.push_back(e + 1);
    s.elements.push_back(std::move(el));
  }
  s.stiffness = FromTriplets(n, kt);
  s.mass = FromTriplets(n, mt);
  s.length = n;
  if (spec.shear_building && n >= 2) s.form_variants = FlexuralFormVariants(s, spec);
  return s;
}

constexpr EnumName<AddedMassBasis> kAddedMassBasisNames[] = {
    {AddedMassBasis::kElementMass, "element_mass"},
    {AddedMassBasis::kTransverse, "transverse"},
};

const char* ToString(AddedMassBasis basis) {
  return NameIn(kAddedMassBasisNames, basis, "unknown");
}

bool AddedMassBasisFromString(const std::string& text, AddedMassBasis* basis) {
  return ValueIn(kAddedMassBasisNames, text, basis);
}

std::vector<double> UniformHeights(double length, int num_elements) {
  if (!(length > 0) || num_elements < 1) {
    throw InputError("model.mesh", "length must be positive and elements >= 1");
  }
  std::vector<double> h(num_elements + 1);
  for (int i = 0; i <= num_elements; ++i) h[i] = length * i / num_elements;
  return h;
}

Structure BuildCantilever(const CantileverSpec& spec) {
  const auto& z = spec.node_heights;
  const int num_nodes = static_cast<int>(z.size());
  if (num_nodes < 2) {
    throw InputError("model.node_heights", "needs at least two nodes (base and tip)");
  }
  if (z[0] != 0.0)
    throw InputError("model.node_heights", "the first height must be 0 (base)");
  for (int i = 1; i < num_nodes; ++i) {
    if (!(z[i] > z[i - 1]) || !std::isfinite(z[i])) {
      std::ostringstream msg;
      msg << "heights must increase strictly; entry " << i + 1 << " is " << z[i]
          << " after " << z[i - 1];
      throw InputError("model.node_heights", msg.str());
    }
  }
  if (!(spec.water_depth >= 0) || !std::isfinite(spec.water_depth)) {
    throw InputError("model.water_depth", "must be a finite depth >= 0 (m)");
  }
  const double supports[3] = {spec.support_transverse, spec.support_axial,
                              spec.support_rotation};
  for (double v : supports) {
    if (!(v >= 0) || !std::isfinite(v)) {
      throw InputError("model.support", "spring stiffnesses must be finite and >= 0");
    }
  }
  CheckModifications(spec, z.back());
  if (!std::isfinite(spec.axial_force)) {
    throw InputError("model.axial_force", "must be finite (N, tension positive)");
  }
  if (!(spec.shear_area >= 0) || !std::isfinite(spec.shear_area) ||
      spec.shear_area > spec.section.A) {
    std::ostringstream msg;
    msg << "must be a shear area kappa A in (0, A = " << spec.section.A
        << "] m^2 (0: A / 2), found " << spec.shear_area;
    throw InputError("model.section.shear_area", msg.str());
  }

  // Global DOF numbering: base DOFs only where a support spring frees them.
  static const char* kDofNames[3] = {"ux", "uy", "rz"};
  std::vector<std::array<int, 3>> dof(num_nodes);
  Structure s;
  s.type = "cantilever";
  int next = 0;
  for (int node = 0; node < num_nodes; ++node) {
    for (int k = 0; k < 3; ++k) {
      const bool free = node > 0 || supports[k] > 0;
      dof[node][k] = free ? next++ : -1;
      if (free) {
        s.dof_labels.push_back("n" + std::to_string(node) + ":" + kDofNames[k]);
        s.dof_positions.push_back(z[node]);
      }
    }
    s.nodes.push_back({"n" + std::to_string(node), Eigen::Vector3d(0.0, z[node], 0.0)});
  }
  const int n = next;
  Triplets kt, mt;
  // The shear variant's change of K and M, element by element (Timoshenko
  // minus Euler-Bernoulli), where the elements' matrices are built.
  Triplets shear_k, shear_m;
  const BeamShear shear{spec.shear_area > 0 ? spec.shear_area : 0.5 * spec.section.A,
                        0.3};
  const double mass_per_length = spec.section.rho * spec.section.A;
  // A clamped base (no support spring): a rigid support whose bending
  // directions (ux, rz) couple to the beam through its first element, so
  // support flexibility can release them (model_effects.h), a spring's
  // compliance relative to the whole beam's, 3 EI / L^3 and EI / L, in
  // [1e-6, 10] (the cantilever's own translation_ and
  // rotation_compliance_ratio and their range, effects.h).
  // The axial direction stays rigid: the bending modes do not move it.
  const bool clamped = supports[0] == 0 && supports[1] == 0 && supports[2] == 0;
  if (clamped && spec.element_matrices) {
    RigidSupport base;
    base.name = "n0";
    base.directions = {"ux", "rz"};
    const double ei = spec.section.E * spec.section.I, l = z.back();
    base.reference = Eigen::Vector2d(3 * ei / (l * l * l), ei / l);
    base.min_compliance = 1e-6;
    base.max_compliance = 10;
    s.rigid_supports.push_back(std::move(base));
  }
  for (int e = 0; e + 1 < num_nodes; ++e) {
    const std::array<int, 6> d = {dof[e][0],     dof[e][1],     dof[e][2],
                                  dof[e + 1][0], dof[e + 1][1], dof[e + 1][2]};
    const Matrix6 ke = Frame2dStiffness(spec.section, 0, z[e], 0, z[e + 1]);
    const Matrix6 me = Frame2dConsistentMass(spec.section, 0, z[e], 0, z[e + 1]);
    if (e == 0 && !s.rigid_supports.empty()) {
      internal::AddToRigidSupport<6>(ke, me, d, {0, -1, 1, -1, -1, -1},
                                     &s.rigid_supports.front());
    }
    s.segments.push_back({e, e + 1, Eigen::Vector3d(0.0, z[e], 0.0),
                          Eigen::Vector3d(0.0, z[e + 1], 0.0), e});
    ElementMatrices el;
    el.id = e + 1;
    el.label = "e" + std::to_string(e + 1);
    el.x0 = z[e];
    el.x1 = z[e + 1];
    el.wet = 0.5 * (z[e] + z[e + 1]) < spec.water_depth;
    if (!spec.element_matrices) {
      Scatter(ke, d, &kt);
      Scatter(me, d, &mt);
      s.elements.push_back(std::move(el));
      continue;
    }
    Triplets tk, tm, tw;
    Scatter(ke, d, &tk);
    Scatter(me, d, &tm);
    Scatter(Matrix6(Frame2dStiffness(spec.section, shear, 0, z[e], 0, z[e + 1]) - ke), d,
            &shear_k);
    Scatter(Matrix6(Frame2dConsistentMass(spec.section, shear, 0, z[e], 0, z[e + 1]) +
                    Frame2dRotaryInertiaMass(spec.section, 0, z[e], 0, z[e + 1]) - me),
            d, &shear_m);
    el.stiffness = FromTriplets(n, tk);
    el.mass = FromTriplets(n, tm);
    if (spec.added_mass_basis == AddedMassBasis::kElementMass) {
      el.added_mass_basis = el.mass;
    } else {
      Scatter(Frame2dTransverseMass(mass_per_length, 0, z[e], 0, z[e + 1]), d, &tw);
      el.added_mass_basis = FromTriplets(n, tw);
    }
    kt.insert(kt.end(), tk.begin(), tk.end());
    mt.insert(mt.end(), tm.begin(), tm.end());
    s.elements.push_back(std::move(el));
  }
  static const char* kSupportNames[3] = {"base transverse", "base axial",
                                         "base rotation"};
  for (int k = 0; k < 3; ++k) {
    if (supports[k] > 0) {
      kt.emplace_back(dof[0][k], dof[0][k], supports[k]);
      s.supports.push_back(
          {dof[0][k], supports[k], kSupportNames[k], k < 2 ? "N/m" : "N m/rad"});
    }
  }
  for (std::size_t i = 0; i < spec.lumped_masses.size(); ++i) {
    const LumpedMass& lm = spec.lumped_masses[i];
    const std::string where = "model.lumped_masses[" + std::to_string(i + 1) + "]";
    if (lm.node < 0 || lm.node >= num_nodes) {
      throw InputError(where, "node " + std::to_string(lm.node) + " is not in 0.." +
                                  std::to_string(num_nodes - 1));
    }
    if (!(lm.mass >= 0) || !(lm.rotary_inertia >= 0) || !std::isfinite(lm.mass) ||
        !std::isfinite(lm.rotary_inertia)) {
      throw InputError(where, "mass and rotary_inertia must be finite and >= 0");
    }
    for (int k = 0; k < 3; ++k) {
      const double v = k < 2 ? lm.mass : lm.rotary_inertia;
      if (dof[lm.node][k] >= 0 && v > 0)
        mt.emplace_back(dof[lm.node][k], dof[lm.node][k], v);
    }
  }
  s.stiffness = FromTriplets(n, kt);
  s.mass = FromTriplets(n, mt);
  s.length = z.back();
  // Local modifications: on the global matrices only, after assembly.
  for (const CantileverSpec::DistributedMass& d : spec.distributed_masses) {
    s.mass += TransverseMassOverInterval(s, d.z0, d.z1, d.mass_per_length, d.fade);
  }
  const double ei = spec.section.E * spec.section.I;
  for (const CantileverSpec::StiffnessChange& c : spec.stiffness_changes) {
    s.stiffness += BendingStiffnessOverInterval(s, c.z0, c.z1, c.factor * ei);
  }
  for (const CantileverSpec::PointMass& p : spec.point_masses) {
    s.mass += PointMassAt(s, p.height, p.mass, p.rotary_inertia);
  }
  if (spec.axial_force != 0) s.stiffness += AxialForceStiffness(s, spec.axial_force);
  s.stiffness.makeCompressed();
  s.mass.makeCompressed();
  if (spec.element_matrices) {
    std::ostringstream what;
    what << "shear deformation and rotary inertia (Timoshenko elements; shear area "
         << shear.area << " m^2)";
    SparseMatrix kv = s.stiffness + FromTriplets(n, shear_k);
    SparseMatrix mv = s.mass + FromTriplets(n, shear_m);
    kv.makeCompressed();
    mv.makeCompressed();
    s.form_variants.push_back({what.str(), std::move(kv), std::move(mv), {}, {}});
  }
  std::ostringstream desc;
  desc << "2D frame cantilever, " << num_nodes - 1 << " elements over " << z.back()
       << " m, water depth " << spec.water_depth << " m, added-mass basis "
       << ToString(spec.added_mass_basis);
  s.description = desc.str();
  return s;
}

}  // namespace femup
