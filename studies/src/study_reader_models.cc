// The model section of a study file: a spring-mass chain, a cantilever, a
// model of Matrix Market element matrices, a 2D plane frame or a jacket-like
// space frame, within the sizes a study may build; and the check that the
// model's mass matrix is positive definite.
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/io/matrix_market.h"
#include "study_reader.h"

namespace femup::study_reader {
namespace {

namespace fs = std::filesystem;

// The largest built-in models a study may describe. A cantilever keeps each
// element's matrices at the size of the whole model, so its memory grows with
// the square of the element count (measured: 0.45 GB at 3000 elements, 1.5 GB at
// 5000). Builds for fuzzing (scripts/fuzz.sh defines the usual macro
// FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION) accept small models only, so that
// the study fuzzer spends its time in the reader rather than in building
// legitimate large models under the sanitizers (a 1000-element cantilever takes
// 7 s there).
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr int kMaxCantileverElements = 100;
constexpr long long kFuzzingMaxSpaceFrameDofs = 600;  // otherwise Validate's 5e7
#else
constexpr int kMaxCantileverElements = 5000;
#endif
// Space frames up to this size get a Structure of per-group matrices (about
// groups x 3 n x n sparse matrices) for femup diagnose; larger ones only
// what femup run needs.
constexpr int kMaxDiagnosedSpaceFrameDofs = 60000;

}  // namespace

Structure ReadChain(const Field& m) {
  m.ExpectKeys({"type", "masses", "springs", "wet", "shear_building"});
  ChainSpec spec;
  if (m.Has("shear_building")) spec.shear_building = m["shear_building"].Bool();
  spec.masses = m["masses"].Numbers();
  spec.springs = m["springs"].Numbers();
  if (spec.springs.size() != spec.masses.size()) {
    m["springs"].Fail("has " + std::to_string(spec.springs.size()) +
                      " values; expected " + std::to_string(spec.masses.size()) +
                      " (one spring below each mass)");
  }
  for (std::size_t i = 0; i < spec.masses.size(); ++i) {
    if (!(spec.masses[i] > 0))
      m["masses"].Items()[i].Fail("expected a positive mass (kg)");
    if (!(spec.springs[i] > 0))
      m["springs"].Items()[i].Fail("expected a positive stiffness (N/m)");
  }
  spec.wet.assign(spec.masses.size(), false);
  if (m.Has("wet")) {
    for (const Field& item : m["wet"].Items()) {
      const int id = item.Int();
      if (id < 1 || id > static_cast<int>(spec.masses.size())) {
        item.Fail("mass " + std::to_string(id) + " does not exist (masses are 1.." +
                  std::to_string(spec.masses.size()) + ")");
      }
      spec.wet[id - 1] = true;
    }
  }
  return BuildSpringMassChain(spec);
}

Structure ReadCantilever(const Field& m, CantileverSpec* out) {
  m.ExpectKeys({"type", "length", "elements", "node_heights", "section", "water_depth",
                "added_mass_basis", "support", "lumped_masses", "distributed_masses",
                "stiffness_changes", "point_masses", "axial_force"});
  CantileverSpec spec;
  if (m.Has("node_heights")) {
    if (m.Has("length") || m.Has("elements")) {
      m.Fail("give either node_heights or length and elements, not both");
    }
    spec.node_heights = m["node_heights"].Numbers();
    if (spec.node_heights.size() > kMaxCantileverElements + 1u) {
      m["node_heights"].Fail("has " + std::to_string(spec.node_heights.size()) +
                             " nodes; expected at most " +
                             std::to_string(kMaxCantileverElements + 1) + " (" +
                             std::to_string(kMaxCantileverElements) + " elements)");
    }
  } else {
    const int elements = m["elements"].Int();
    if (elements < 1) m["elements"].Fail("expected at least one element");
    if (elements > kMaxCantileverElements) {
      m["elements"].Fail("expected at most " + std::to_string(kMaxCantileverElements) +
                         " elements, found " + std::to_string(elements) +
                         " (the memory of a cantilever grows with the square of its "
                         "element count)");
    }
    spec.node_heights = UniformHeights(m["length"].Positive(), elements);
  }
  const Field s = m["section"];
  s.ExpectKeys({"E", "A", "I", "rho", "shear_area"});
  spec.section = {s["E"].Positive(), s["A"].Positive(), s["I"].Positive(),
                  s["rho"].Positive()};
  if (s.Has("shear_area")) {
    spec.shear_area = s["shear_area"].Positive();
    if (spec.shear_area > spec.section.A)
      s["shear_area"].Fail("kappa A cannot exceed the area A (" +
                           std::to_string(spec.section.A) + " m^2)");
  }
  if (m.Has("water_depth")) spec.water_depth = m["water_depth"].NonNegative();
  // N, tension positive (a riser's tension), compression negative (a pile's load).
  if (m.Has("axial_force")) spec.axial_force = m["axial_force"].Num();
  if (m.Has("added_mass_basis")) {
    const Field f = m["added_mass_basis"];
    if (!AddedMassBasisFromString(f.Str(), &spec.added_mass_basis)) {
      f.Fail("unknown basis '" + f.Str() + "' (expected element_mass or transverse)");
    }
  }
  if (m.Has("support")) {
    const Field f = m["support"];
    f.ExpectKeys({"transverse", "axial", "rotation"});
    if (f.Has("transverse")) spec.support_transverse = f["transverse"].NonNegative();
    if (f.Has("axial")) spec.support_axial = f["axial"].NonNegative();
    if (f.Has("rotation")) spec.support_rotation = f["rotation"].NonNegative();
  }
  if (m.Has("lumped_masses")) {
    for (const Field& f : m["lumped_masses"].Items()) {
      f.ExpectKeys({"node", "mass", "rotary_inertia"});
      LumpedMass lm;
      lm.node = f["node"].Int();
      if (lm.node < 0 || lm.node >= static_cast<int>(spec.node_heights.size())) {
        f["node"].Fail("node " + std::to_string(lm.node) + " is not in 0.." +
                       std::to_string(spec.node_heights.size() - 1) + " (0 is the base)");
      }
      lm.mass = f["mass"].NonNegative();
      if (f.Has("rotary_inertia")) lm.rotary_inertia = f["rotary_inertia"].NonNegative();
      spec.lumped_masses.push_back(lm);
    }
  }
  if (m.Has("distributed_masses")) {
    for (const Field& f : m["distributed_masses"].Items()) {
      f.ExpectKeys({"from", "to", "mass_per_length", "fade"});
      CantileverSpec::DistributedMass d;
      d.z0 = f["from"].NonNegative();
      d.z1 = f["to"].NonNegative();
      if (!(d.z1 > d.z0)) f["to"].Fail("expected a height above from (m)");
      d.mass_per_length = f["mass_per_length"].NonNegative();
      if (f.Has("fade")) d.fade = f["fade"].NonNegative();
      spec.distributed_masses.push_back(d);
    }
  }
  if (m.Has("stiffness_changes")) {
    for (const Field& f : m["stiffness_changes"].Items()) {
      f.ExpectKeys({"from", "to", "factor"});
      CantileverSpec::StiffnessChange c;
      c.z0 = f["from"].NonNegative();
      c.z1 = f["to"].NonNegative();
      if (!(c.z1 > c.z0)) f["to"].Fail("expected a height above from (m)");
      c.factor = f["factor"].Num();
      if (!(c.factor > -1)) {
        f["factor"].Fail("expected a number > -1 (E I becomes E I (1 + factor)), found " +
                         f["factor"].Str());
      }
      spec.stiffness_changes.push_back(c);
    }
  }
  if (m.Has("point_masses")) {
    for (const Field& f : m["point_masses"].Items()) {
      f.ExpectKeys({"height", "mass", "rotary_inertia"});
      CantileverSpec::PointMass p;
      p.height = f["height"].NonNegative();
      p.mass = f["mass"].NonNegative();
      if (f.Has("rotary_inertia")) p.rotary_inertia = f["rotary_inertia"].NonNegative();
      spec.point_masses.push_back(p);
    }
  }
  *out = spec;
  try {
    return BuildCantilever(spec);
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
}

Structure ReadMatrixMarketModel(const Field& m) {
  m.ExpectKeys({"type", "stiffness", "mass", "dof_labels", "elements"});
  MatrixMarketModelSpec spec;
  if (m.Has("stiffness")) spec.stiffness_file = m["stiffness"].Str();
  if (m.Has("mass")) spec.mass_file = m["mass"].Str();
  if (m.Has("dof_labels")) {
    for (const Field& f : m["dof_labels"].Items()) spec.dof_labels.push_back(f.Str());
  }
  for (const Field& f : m["elements"].Items()) {
    f.ExpectKeys({"id", "label", "stiffness", "mass", "added_mass", "dofs", "wet"});
    MatrixMarketElement e;
    e.id = f["id"].Int();
    if (f.Has("label")) e.label = f["label"].Str();
    if (f.Has("stiffness")) e.stiffness_file = f["stiffness"].Str();
    if (f.Has("mass")) e.mass_file = f["mass"].Str();
    if (f.Has("added_mass")) e.added_mass_file = f["added_mass"].Str();
    if (f.Has("dofs")) {
      for (const Field& d : f["dofs"].Items()) {
        const int dof = d.Int();
        if (dof < 1) d.Fail("DOF numbers start at 1");
        e.dofs.push_back(dof - 1);
      }
    }
    if (f.Has("wet")) e.wet = f["wet"].Bool();
    spec.elements.push_back(e);
  }
  const std::string base = fs::path(m.file()).parent_path().string();
  try {
    return ImportMatrixMarketStructure(spec, base.empty() ? "." : base);
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
}

namespace {

FrameSection3d ReadTube(const Field& f, const FrameSection3d& defaults) {
  f.ExpectKeys({"diameter", "wall", "E", "nu", "rho"});
  const double diameter = f["diameter"].Positive();
  const double wall = f["wall"].Positive();
  if (wall > diameter / 2) f["wall"].Fail("must not exceed half the diameter");
  const double E = f.Has("E") ? f["E"].Positive() : defaults.E;
  const double nu = f.Has("nu")      ? f["nu"].NonNegative()
                    : defaults.G > 0 ? defaults.E / (2 * defaults.G) - 1
                                     : 0.3;
  const double rho = f.Has("rho") ? f["rho"].Positive() : defaults.rho;
  if (!(nu < 0.5)) f["nu"].Fail("Poisson's ratio must be below 0.5");
  return CircularTube(diameter, wall, E, nu, rho);
}

}  // namespace

// A 2D plane frame (portal, multi-bay, multi-storey) as a Structure of members.
Structure ReadPlaneFrame(const Field& m) {
  m.ExpectKeys({"type", "storeys", "bays", "storey_height", "bay_width",
                "elements_per_member", "wet_storeys", "column", "beam", "base",
                "theory"});
  PlaneFrameSpec spec;
  spec.storeys = m["storeys"].Int();
  spec.bays = m["bays"].Int();
  spec.storey_height = m["storey_height"].Positive();
  spec.bay_width = m["bay_width"].Positive();
  if (m.Has("elements_per_member"))
    spec.elements_per_member = m["elements_per_member"].Int();
  if (m.Has("wet_storeys")) spec.wet_storeys = m["wet_storeys"].Int();
  for (const char* which : {"column", "beam"}) {
    const Field s = m[which];
    s.ExpectKeys({"E", "A", "I", "rho", "shear_area"});
    const BeamSection section{s["E"].Positive(), s["A"].Positive(), s["I"].Positive(),
                              s["rho"].Positive()};
    const bool column = std::string(which) == "column";
    (column ? spec.column : spec.beam) = section;
    if (s.Has("shear_area")) {
      const double a = s["shear_area"].Positive();
      if (a > section.A)
        s["shear_area"].Fail("kappa A cannot exceed the area A (" +
                             std::to_string(section.A) + " m^2)");
      (column ? spec.column_shear_area : spec.beam_shear_area) = a;
    }
  }
  if (m.Has("theory") && !BeamTheoryFromString(m["theory"].Str(), &spec.theory))
    m["theory"].Fail("expected euler_bernoulli or timoshenko");
  if (m.Has("base")) {
    // Springs at every column base; a direction not given stays rigid.
    const Field b = m["base"];
    b.ExpectKeys({"horizontal", "vertical", "rotation"});
    if (b.Has("horizontal")) spec.base.horizontal = b["horizontal"].Positive();
    if (b.Has("vertical")) spec.base.vertical = b["vertical"].Positive();
    if (b.Has("rotation")) spec.base.rotation = b["rotation"].Positive();
    if (spec.base.rigid()) b.Fail("give at least one of horizontal, vertical, rotation");
  }
  spec.blocks_per_storey = 1;
  if (const Invalid bad = spec.Validate()) m[bad.field].Fail(bad.message);
  return BuildPlaneFrameStructure(spec);
}

// A jacket-like space frame (space_frame.h): the model and its factors come
// from the generator; `structure` gets the description, labels and, for
// plots, each DOF's height.
ParametrisedModel ReadSpaceFrame(const Field& m, Structure* structure) {
  m.ExpectKeys({"type", "levels", "bays_x", "bays_y", "level_height", "bay_width_x",
                "bay_width_y", "elements_per_member", "blocks_per_level", "bracing",
                "water_depth", "theory", "legs", "braces", "horizontals", "base"});
  SpaceFrameSpec spec;
  if (m.Has("levels")) spec.levels = m["levels"].Int();
  if (m.Has("bays_x")) spec.bays_x = m["bays_x"].Int();
  if (m.Has("bays_y")) spec.bays_y = m["bays_y"].Int();
  if (m.Has("level_height")) spec.level_height = m["level_height"].Positive();
  if (m.Has("bay_width_x")) spec.bay_width_x = m["bay_width_x"].Positive();
  if (m.Has("bay_width_y")) spec.bay_width_y = m["bay_width_y"].Positive();
  if (m.Has("elements_per_member"))
    spec.elements_per_member = m["elements_per_member"].Int();
  if (m.Has("blocks_per_level")) spec.blocks_per_level = m["blocks_per_level"].Int();
  if (m.Has("bracing") && !FaceBracingFromString(m["bracing"].Str(), &spec.bracing))
    m["bracing"].Fail("expected none, diagonal or x");
  if (m.Has("water_depth")) spec.water_depth = m["water_depth"].NonNegative();
  if (m.Has("theory") && !BeamTheoryFromString(m["theory"].Str(), &spec.theory))
    m["theory"].Fail("expected euler_bernoulli or timoshenko");
  if (m.Has("legs")) spec.legs = ReadTube(m["legs"], spec.legs);
  if (m.Has("braces")) spec.braces = ReadTube(m["braces"], spec.braces);
  if (m.Has("horizontals"))
    spec.horizontals = ReadTube(m["horizontals"], spec.horizontals);
  if (m.Has("base")) {
    // Springs under every leg; a direction not given stays rigid.
    const Field b = m["base"];
    b.ExpectKeys({"horizontal", "vertical", "rocking", "torsion"});
    if (b.Has("horizontal")) spec.base.horizontal = b["horizontal"].Positive();
    if (b.Has("vertical")) spec.base.vertical = b["vertical"].Positive();
    if (b.Has("rocking")) spec.base.rocking = b["rocking"].Positive();
    if (b.Has("torsion")) spec.base.torsion = b["torsion"].Positive();
    if (spec.base.rigid())
      b.Fail("give at least one of horizontal, vertical, rocking, torsion");
  }
  if (const Invalid bad = spec.Validate()) {
    // Located at the study's key: field "bays_x" -> model.bays_x: must be >= 1;
    // field "legs.Iy" -> model.legs: Iy: ...
    const std::string key = bad.field.substr(0, bad.field.find('.'));
    if (!m.Has(key)) m.Fail(bad.ToString());
    const std::string rest =
        key.size() < bad.field.size() ? bad.field.substr(key.size() + 1) : "";
    m[key].Fail(Invalid{rest, bad.message}.ToString());
  }
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  {
    // SpaceFrameSpec::Validate's estimate of the DOFs, at once (the exact count,
    // SpaceFrameModelSize, takes seconds for a large frame under the sanitizers).
    const double nx = spec.bays_x + 1.0, ny = spec.bays_y + 1.0;
    const double faces = 2.0 * (spec.bays_x + spec.bays_y);
    const double members = nx * ny + (nx - 1) * ny + nx * (ny - 1) + 4 * faces;
    const double dofs =
        6.0 * spec.levels * (nx * ny + faces + (spec.elements_per_member - 1) * members);
    if (dofs > kFuzzingMaxSpaceFrameDofs) {
      m.Fail("has about " + std::to_string(static_cast<long long>(dofs)) +
             " DOFs; a build for fuzzing takes at most " +
             std::to_string(kFuzzingMaxSpaceFrameDofs));
    }
  }
#endif
  ParametrisedModel model;
  try {
    model = BuildSpaceFrame(spec);
    if (model.num_dofs() <= kMaxDiagnosedSpaceFrameDofs) {
      // Every group's matrices, the nodes and heights: femup diagnose acts on them.
      *structure = BuildSpaceFrameStructure(spec);
      return model;
    }
  } catch (const InputError& e) {
    m.Fail(e.what());
  }
  // Too large to hold each group's matrices (femup diagnose refuses it):
  // description, labels and heights for femup run.
  std::ostringstream d;
  d << "space frame, " << spec.bays_x << " x " << spec.bays_y << " bays, " << spec.levels
    << " levels of " << spec.level_height << " m, " << ToString(spec.bracing)
    << " bracing, water " << spec.water_depth << " m";
  structure->type = "space_frame";
  structure->description = d.str();
  structure->dof_labels = model.dof_labels();
  const SpaceFrameGeometryData geometry = SpaceFrameGeometry(spec);
  structure->dof_positions.reserve(model.num_dofs());
  for (const Eigen::Vector3d& node : geometry.nodes) {
    for (int k = 0; k < 6; ++k) structure->dof_positions.push_back(node.z());
  }
  structure->dof_positions.resize(model.dof_labels().size(), 0.0);  // base springs
  for (std::size_t k = 0; k < geometry.nodes.size(); ++k)
    structure->nodes.push_back({"n" + std::to_string(k + 1), geometry.nodes[k]});
  structure->length = spec.levels * spec.level_height;
  // Shape plots: the sway (ux) of the corner leg at X = Y = 0, bottom to top.
  std::vector<std::pair<double, int>> leg;
  for (std::size_t k = 0; k < geometry.nodes.size(); ++k) {
    const Eigen::Vector3d& node = geometry.nodes[k];
    if (std::abs(node.x()) < 1e-9 && std::abs(node.y()) < 1e-9)
      leg.emplace_back(node.z(), static_cast<int>(6 * k));
  }
  std::sort(leg.begin(), leg.end());
  for (const auto& [z, dof] : leg) structure->plot_dofs.push_back(dof);
  return model;
}

void CheckMassPositiveDefinite(const Field& model_field, const ParametrisedModel& model) {
  Eigen::SimplicialLLT<SparseMatrix> llt(model.mass());
  if (llt.info() != Eigen::Success) {
    model_field.Fail(
        "the mass matrix is not positive definite (every DOF needs mass or "
        "rotary inertia, and no mass may be negative)");
  }
}

}  // namespace femup::study_reader
