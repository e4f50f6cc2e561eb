// Models: the built-in structures (chain, cantilever, plane and space frames),
// Matrix Market import, correction-factor plans, ParametrisedModel with K and M
// as scipy.sparse views, modes, MAC and mode pairing.
#include <string>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/core/fe/builders.h"
#include "femup/core/fe/frame3d.h"
#include "femup/core/fe/model.h"
#include "femup/core/fe/plane_frame.h"
#include "femup/core/fe/space_frame.h"
#include "femup/core/fe/structure.h"
#include "femup/core/io/matrix_market.h"
#include "femup/core/linalg/modal.h"
#include "femup/core/sysid/measurement.h"

namespace femup_python {

namespace {

// A frame spec's `theory` property (plane and space frames alike): its name,
// and the setter that refuses an unknown one naming the study's field.
template <typename Spec>
std::string TheoryName(const Spec& s) {
  return femup::ToString(s.theory);
}
template <typename Spec>
void SetTheory(Spec& s, const std::string& text) {
  if (!femup::BeamTheoryFromString(text, &s.theory)) {
    throw femup::InputError("model.theory",
                            "expected euler_bernoulli or timoshenko, got '" + text + "'");
  }
}

using femup::ParameterFamily;

femup::ParameterKind KindFrom(const std::string& text, const std::string& field) {
  femup::ParameterKind kind;
  if (!femup::ParameterKindFromString(text, &kind)) {
    throw femup::InputError(field,
                            "expected mass, stiffness or added_mass, got '" + text + "'");
  }
  return kind;
}

// A family as the study's `parameters.<kind>` gives it: "none", "per_element",
// "single", or {"layout": ..., "select": all|wet|dry, "groups": [[1, 2], [3]]}.
ParameterFamily FamilyFrom(py::handle value, const std::string& field) {
  ParameterFamily family;
  std::string layout;
  py::object select = py::none(), groups = py::none();
  if (py::isinstance<py::str>(value)) {
    layout = value.cast<std::string>();
  } else if (py::isinstance<py::dict>(value)) {
    const py::dict d = py::reinterpret_borrow<py::dict>(value);
    for (const auto& kv : d) {
      const std::string key = py::str(kv.first);
      if (key != "layout" && key != "select" && key != "groups") {
        throw femup::InputError(field + "." + key,
                                "unknown key (expected one of: layout, select, groups)");
      }
    }
    if (!d.contains("layout")) throw femup::InputError(field, "missing key 'layout'");
    layout = py::str(d["layout"]);
    if (d.contains("select")) select = d["select"];
    if (d.contains("groups")) groups = d["groups"];
  } else {
    throw femup::InputError(field, "expected a layout name or a dict");
  }
  if (layout == "none") {
    family.scope = ParameterFamily::Scope::kNone;
  } else if (layout == "per_element") {
    family.scope = ParameterFamily::Scope::kPerElement;
  } else if (layout == "single") {
    family.scope = ParameterFamily::Scope::kSingle;
  } else if (layout == "groups") {
    family.scope = ParameterFamily::Scope::kGroups;
    if (groups.is_none()) throw femup::InputError(field + ".groups", "missing");
    try {
      family.groups = groups.cast<std::vector<std::vector<int>>>();
    } catch (const py::cast_error&) {
      throw femup::InputError(field + ".groups", "expected lists of element ids");
    }
  } else {
    throw femup::InputError(
        field, "expected none, per_element, single or groups, got '" + layout + "'");
  }
  if (!select.is_none()) {
    const std::string s = py::str(select);
    if (s == "all") {
      family.selection = ParameterFamily::Selection::kAll;
    } else if (s == "wet") {
      family.selection = ParameterFamily::Selection::kWet;
    } else if (s == "dry") {
      family.selection = ParameterFamily::Selection::kDry;
    } else {
      throw femup::InputError(field + ".select",
                              "expected all, wet or dry, got '" + s + "'");
    }
  }
  return family;
}

femup::EigenOptions EigenOptionsFrom(int num_modes, const std::string& method,
                                     double shift, double tolerance) {
  femup::EigenOptions options;
  options.num_modes = num_modes;
  if (method == "auto") {
    options.method = femup::EigenOptions::Method::kAuto;
  } else if (method == "dense") {
    options.method = femup::EigenOptions::Method::kDense;
  } else if (method == "sparse") {
    options.method = femup::EigenOptions::Method::kSparseShiftInvert;
  } else {
    throw femup::InputError("method",
                            "expected auto, dense or sparse, got '" + method + "'");
  }
  options.shift = shift;
  options.tolerance = tolerance;
  if (const femup::Invalid bad = options.Validate())
    throw femup::InputError("", bad.message);
  return options;
}

void BindStructure(py::module_& m) {
  py::class_<femup::ElementMatrices>(m, "Element",
                                     "One element (substructure) in global free DOFs.")
      .def_readonly("id", &femup::ElementMatrices::id, "1-based element number")
      .def_readonly("label", &femup::ElementMatrices::label,
                    "used in parameter names: '3' (chain), 'e3' (frame)")
      .def_readonly("wet", &femup::ElementMatrices::wet)
      .def_readonly("x0", &femup::ElementMatrices::x0, "start along the structure (m)")
      .def_readonly("x1", &femup::ElementMatrices::x1, "end along the structure (m)")
      .def_property_readonly(
          "stiffness",
          [](py::object self) {
            return CscView(self.cast<const femup::ElementMatrices&>().stiffness, self);
          },
          "K_e (num_dofs x num_dofs, scipy.sparse.csc_matrix view)")
      .def_property_readonly(
          "mass",
          [](py::object self) {
            return CscView(self.cast<const femup::ElementMatrices&>().mass, self);
          },
          "M_e")
      .def_property_readonly(
          "added_mass_basis",
          [](py::object self) {
            return CscView(self.cast<const femup::ElementMatrices&>().added_mass_basis,
                           self);
          },
          "Mw_e, the basis of water added mass")
      .def("__repr__", [](const femup::ElementMatrices& e) {
        return "<femup.Element " + std::to_string(e.id) + " '" + e.label + "'" +
               (e.wet ? " wet" : "") + ">";
      });

  py::class_<femup::ModelNode>(m, "ModelNode")
      .def_readonly("name", &femup::ModelNode::name)
      .def_readonly("xyz", &femup::ModelNode::xyz, "coordinates (m), the model's axes");

  py::class_<femup::SupportSpring>(m, "SupportSpring")
      .def_readonly("dof", &femup::SupportSpring::dof)
      .def_readonly("stiffness", &femup::SupportSpring::stiffness)
      .def_readonly("name", &femup::SupportSpring::name)
      .def_readonly("unit", &femup::SupportSpring::unit);

  py::class_<femup::Structure>(
      m, "Structure",
      "An assembled finite element model with its elements kept apart (what a "
      "builder or a study's `model:` makes).")
      .def_readonly("type", &femup::Structure::type)
      .def_readonly("description", &femup::Structure::description)
      .def_property_readonly(
          "stiffness",
          [](py::object self) {
            return CscView(self.cast<const femup::Structure&>().stiffness, self);
          },
          "baseline K (scipy.sparse.csc_matrix viewing the model's storage)")
      .def_property_readonly(
          "mass",
          [](py::object self) {
            return CscView(self.cast<const femup::Structure&>().mass, self);
          },
          "baseline M (scipy.sparse.csc_matrix view)")
      .def_readonly("dof_labels", &femup::Structure::dof_labels)
      .def_property_readonly(
          "form_variant_names",
          [](const femup::Structure& s) {
            std::vector<std::string> names;
            for (const femup::FormVariant& v : s.form_variants) names.push_back(v.name);
            return names;
          },
          "the richer formulations the diagnosis allows for (e.g. shear deformation)")
      .def_property_readonly(
          "num_dofs",
          [](const femup::Structure& s) { return static_cast<int>(s.dof_labels.size()); })
      .def_property_readonly("elements",
                             [](py::object self) {
                               return RefList(
                                   self.cast<const femup::Structure&>().elements, self);
                             })
      .def_property_readonly("nodes",
                             [](py::object self) {
                               return RefList(self.cast<const femup::Structure&>().nodes,
                                              self);
                             })
      .def_property_readonly("supports",
                             [](py::object self) {
                               return RefList(
                                   self.cast<const femup::Structure&>().supports, self);
                             })
      .def_readonly("length", &femup::Structure::length)
      .def_readonly("dof_positions", &femup::Structure::dof_positions)
      .def("find_element", &femup::Structure::FindElement, py::arg("id"),
           "index of the element with this id, or -1")
      .def("__repr__", [](const femup::Structure& s) {
        return "<femup.Structure " + s.type + ": " + std::to_string(s.dof_labels.size()) +
               " DOFs, " + std::to_string(s.elements.size()) + " elements>";
      });
}

void BindModel(py::module_& m) {
  py::class_<femup::Parameter>(m, "Parameter", "One correction factor.")
      .def_readonly("name", &femup::Parameter::name)
      .def_property_readonly(
          "kind", [](const femup::Parameter& p) { return femup::ToString(p.kind); })
      .def_readonly("elements", &femup::Parameter::elements)
      .def_readonly("tags", &femup::Parameter::tags)
      .def_property_readonly(
          "basis", [](const femup::Parameter& p) { return CscOwned(p.basis.ToSparse()); },
          "the basis matrix it scales (num_dofs x num_dofs, a copy)")
      .def("__repr__",
           [](const femup::Parameter& p) { return "<femup.Parameter " + p.name + ">"; });

  py::class_<femup::ParametrisedModel>(
      m, "ParametrisedModel",
      "Baseline K and M on the free DOFs plus named correction factors:\n"
      "K~ = K + sum d_b K_b, M~dry = M + sum d_a M_a, dMa = sum d_w Mw_w.")
      .def(py::init([](py::object k, py::object mass, std::vector<std::string> labels) {
             return femup::ParametrisedModel(ToSparse(k, "stiffness"),
                                             ToSparse(mass, "mass"), std::move(labels));
           }),
           py::arg("stiffness"), py::arg("mass"), py::arg("dof_labels"))
      .def_property_readonly(
          "stiffness",
          [](py::object self) {
            return CscView(self.cast<const femup::ParametrisedModel&>().stiffness(),
                           self);
          },
          "baseline K (scipy.sparse.csc_matrix viewing the model's storage)")
      .def_property_readonly(
          "mass",
          [](py::object self) {
            return CscView(self.cast<const femup::ParametrisedModel&>().mass(), self);
          },
          "baseline M (scipy.sparse.csc_matrix view)")
      .def_property_readonly("dof_labels", &femup::ParametrisedModel::dof_labels)
      .def_property_readonly("num_dofs", &femup::ParametrisedModel::num_dofs)
      .def_property_readonly("num_parameters", &femup::ParametrisedModel::num_parameters)
      .def_property_readonly(
          "parameters",
          [](py::object self) {
            return RefList(self.cast<const femup::ParametrisedModel&>().parameters(),
                           self);
          })
      .def_property_readonly("parameter_names", &femup::ParametrisedModel::ParameterNames)
      .def(
          "add_parameter",
          [](femup::ParametrisedModel& model, const std::string& name,
             const std::string& kind, py::object basis, std::vector<int> elements,
             std::vector<std::string> tags) {
            femup::Parameter p;
            p.name = name;
            p.kind = KindFrom(kind, "kind");
            p.basis = femup::BasisMatrix(ToSparse(basis, "basis"));
            p.elements = std::move(elements);
            p.tags = std::move(tags);
            return model.AddParameter(std::move(p));
          },
          py::arg("name"), py::arg("kind"), py::arg("basis"),
          py::arg("elements") = std::vector<int>(),
          py::arg("tags") = std::vector<std::string>(),
          "Adds a factor scaling `basis` (symmetric, num_dofs square); returns its "
          "index.")
      .def("find_parameter", &femup::ParametrisedModel::FindParameter, py::arg("name"))
      .def("find_dof", &femup::ParametrisedModel::FindDof, py::arg("label"))
      .def(
          "parameters_of_kind",
          [](const femup::ParametrisedModel& model, const std::string& kind) {
            return model.ParametersOfKind(KindFrom(kind, "kind"));
          },
          py::arg("kind"))
      .def(
          "updated_stiffness",
          [](const femup::ParametrisedModel& model, const Eigen::VectorXd& d) {
            return CscOwned(model.UpdatedStiffness(d));
          },
          py::arg("d"), "K + sum d_b K_b")
      .def(
          "updated_dry_mass",
          [](const femup::ParametrisedModel& model, const Eigen::VectorXd& d) {
            return CscOwned(model.UpdatedDryMass(d));
          },
          py::arg("d"))
      .def(
          "added_mass",
          [](const femup::ParametrisedModel& model, const Eigen::VectorXd& d) {
            return CscOwned(model.AddedMass(d));
          },
          py::arg("d"), "dMa (Eq. 32-33)")
      .def(
          "updated_wet_mass",
          [](const femup::ParametrisedModel& model, const Eigen::VectorXd& d) {
            return CscOwned(model.UpdatedWetMass(d));
          },
          py::arg("d"))
      .def("__repr__", [](const femup::ParametrisedModel& model) {
        return "<femup.ParametrisedModel " + std::to_string(model.num_dofs()) +
               " DOFs, " + std::to_string(model.num_parameters()) + " factors>";
      });

  m.def(
      "build_model",
      [](const femup::Structure& structure, py::object mass, py::object stiffness,
         py::object added_mass) {
        femup::ParameterPlan plan;
        plan.mass = FamilyFrom(mass, "parameters.mass");
        plan.stiffness = FamilyFrom(stiffness, "parameters.stiffness");
        plan.added_mass = FamilyFrom(added_mass, "parameters.added_mass");
        return femup::BuildModel(structure, plan);
      },
      py::arg("structure"), py::arg("mass") = "per_element",
      py::arg("stiffness") = "per_element", py::arg("added_mass") = "per_element",
      "Correction factors on a structure's elements, each family as a study's "
      "`parameters.<kind>`: 'none', 'per_element', 'single' or {'layout': 'groups', "
      "'groups': [[1, 2], [3]], 'select': 'all'|'wet'|'dry'}.");
}

void BindBuilders(py::module_& m) {
  py::class_<femup::ChainSpec>(m, "ChainSpec")
      .def(py::init<>())
      .def_readwrite("masses", &femup::ChainSpec::masses, "kg")
      .def_readwrite("springs", &femup::ChainSpec::springs,
                     "N/m, spring 1 = ground to mass 1")
      .def_readwrite("wet", &femup::ChainSpec::wet, "per mass: in water")
      .def_readwrite("shear_building", &femup::ChainSpec::shear_building,
                     "the chain idealises a building's storeys: its flexural "
                     "deformation is carried as form variants");
  m.def("build_chain", &femup::BuildSpringMassChain, py::arg("spec"),
        "The paper's spring-mass chain fixed at mass 1's end.");

  py::class_<femup::BeamSection>(m, "BeamSection")
      .def(py::init([](double e, double a, double i, double rho) {
             return femup::BeamSection{e, a, i, rho};
           }),
           py::arg("E") = 0.0, py::arg("A") = 0.0, py::arg("I") = 0.0,
           py::arg("rho") = 0.0)
      .def_readwrite("E", &femup::BeamSection::E, "Pa")
      .def_readwrite("A", &femup::BeamSection::A, "m^2")
      .def_readwrite("I", &femup::BeamSection::I, "m^4")
      .def_readwrite("rho", &femup::BeamSection::rho, "kg/m^3");

  py::class_<femup::LumpedMass>(m, "LumpedMass")
      .def(py::init([](int node, double mass, double rotary_inertia) {
             return femup::LumpedMass{node, mass, rotary_inertia};
           }),
           py::arg("node") = 0, py::arg("mass") = 0.0, py::arg("rotary_inertia") = 0.0)
      .def_readwrite("node", &femup::LumpedMass::node)
      .def_readwrite("mass", &femup::LumpedMass::mass)
      .def_readwrite("rotary_inertia", &femup::LumpedMass::rotary_inertia);

  using Spec = femup::CantileverSpec;
  py::class_<Spec::DistributedMass>(m, "DistributedMass")
      .def(py::init([](double z0, double z1, double mpl, double fade) {
             return Spec::DistributedMass{z0, z1, mpl, fade};
           }),
           py::arg("z0"), py::arg("z1"), py::arg("mass_per_length"),
           py::arg("fade") = 0.0)
      .def_readwrite("z0", &Spec::DistributedMass::z0)
      .def_readwrite("z1", &Spec::DistributedMass::z1)
      .def_readwrite("mass_per_length", &Spec::DistributedMass::mass_per_length)
      .def_readwrite("fade", &Spec::DistributedMass::fade);
  py::class_<Spec::StiffnessChange>(m, "StiffnessChange")
      .def(py::init([](double z0, double z1, double factor) {
             return Spec::StiffnessChange{z0, z1, factor};
           }),
           py::arg("z0"), py::arg("z1"), py::arg("factor"))
      .def_readwrite("z0", &Spec::StiffnessChange::z0)
      .def_readwrite("z1", &Spec::StiffnessChange::z1)
      .def_readwrite("factor", &Spec::StiffnessChange::factor);
  py::class_<Spec::PointMass>(m, "PointMass")
      .def(py::init([](double height, double mass, double rotary_inertia) {
             return Spec::PointMass{height, mass, rotary_inertia};
           }),
           py::arg("height"), py::arg("mass"), py::arg("rotary_inertia") = 0.0)
      .def_readwrite("height", &Spec::PointMass::height)
      .def_readwrite("mass", &Spec::PointMass::mass)
      .def_readwrite("rotary_inertia", &Spec::PointMass::rotary_inertia);

  py::class_<Spec>(
      m, "CantileverSpec",
      "A vertical 2D frame cantilever (fields as the study's model: "
      "type: cantilever). Lists are copied on assignment: assign whole lists.")
      .def(py::init<>())
      .def_readwrite("node_heights", &Spec::node_heights, "m, first = 0 (base)")
      .def_readwrite("section", &Spec::section)
      .def_readwrite("water_depth", &Spec::water_depth)
      .def_property(
          "added_mass_basis",
          [](const Spec& s) { return femup::ToString(s.added_mass_basis); },
          [](Spec& s, const std::string& text) {
            if (!femup::AddedMassBasisFromString(text, &s.added_mass_basis)) {
              throw femup::InputError(
                  "model.added_mass_basis",
                  "expected element_mass or transverse, got '" + text + "'");
            }
          })
      .def_readwrite("support_transverse", &Spec::support_transverse)
      .def_readwrite("support_axial", &Spec::support_axial)
      .def_readwrite("support_rotation", &Spec::support_rotation)
      .def_readwrite("lumped_masses", &Spec::lumped_masses)
      .def_readwrite("axial_force", &Spec::axial_force)
      .def_readwrite("distributed_masses", &Spec::distributed_masses)
      .def_readwrite("stiffness_changes", &Spec::stiffness_changes)
      .def_readwrite("point_masses", &Spec::point_masses)
      .def_readwrite("shear_area", &Spec::shear_area,
                     "kappa A (m^2) of the model's Timoshenko form variant; 0: A / 2");
  m.def("uniform_heights", &femup::UniformHeights, py::arg("length"),
        py::arg("num_elements"));
  m.def("build_cantilever", &femup::BuildCantilever, py::arg("spec"));

  py::class_<femup::PlaneFrameSpec>(m, "PlaneFrameSpec")
      .def(py::init<>())
      .def_readwrite("storeys", &femup::PlaneFrameSpec::storeys)
      .def_readwrite("bays", &femup::PlaneFrameSpec::bays)
      .def_readwrite("storey_height", &femup::PlaneFrameSpec::storey_height)
      .def_readwrite("bay_width", &femup::PlaneFrameSpec::bay_width)
      .def_readwrite("elements_per_member", &femup::PlaneFrameSpec::elements_per_member)
      .def_readwrite("blocks_per_storey", &femup::PlaneFrameSpec::blocks_per_storey)
      .def_readwrite("wet_storeys", &femup::PlaneFrameSpec::wet_storeys)
      .def_readwrite("column", &femup::PlaneFrameSpec::column)
      .def_readwrite("beam", &femup::PlaneFrameSpec::beam)
      .def_property("theory", &TheoryName<femup::PlaneFrameSpec>,
                    &SetTheory<femup::PlaneFrameSpec>)
      .def_readwrite("column_shear_area", &femup::PlaneFrameSpec::column_shear_area,
                     "kappa A (m^2); 0: A / 2")
      .def_readwrite("beam_shear_area", &femup::PlaneFrameSpec::beam_shear_area,
                     "kappa A (m^2); 0: A / 2");
  m.def("build_plane_frame", &femup::BuildPlaneFrame, py::arg("spec"),
        "The large plane frame with factors on substructures (a ParametrisedModel).");
  m.def("build_plane_frame_structure", &femup::BuildPlaneFrameStructure, py::arg("spec"),
        "The plane frame as a Structure whose elements are its members.");

  py::class_<femup::FrameSection3d>(m, "FrameSection3d")
      .def(py::init<>())
      .def_readwrite("E", &femup::FrameSection3d::E)
      .def_readwrite("G", &femup::FrameSection3d::G)
      .def_readwrite("nu", &femup::FrameSection3d::nu)
      .def_readwrite("A", &femup::FrameSection3d::A)
      .def_readwrite("Iy", &femup::FrameSection3d::Iy)
      .def_readwrite("Iz", &femup::FrameSection3d::Iz)
      .def_readwrite("J", &femup::FrameSection3d::J)
      .def_readwrite("rho", &femup::FrameSection3d::rho)
      .def_readwrite("Ip", &femup::FrameSection3d::Ip)
      .def_readwrite("shear_area_y", &femup::FrameSection3d::shear_area_y)
      .def_readwrite("shear_area_z", &femup::FrameSection3d::shear_area_z);
  m.def("circular_tube", &femup::CircularTube, py::arg("diameter"), py::arg("wall"),
        py::arg("E"), py::arg("nu"), py::arg("rho"));

  py::class_<femup::SpaceFrameSpec>(m, "SpaceFrameSpec")
      .def(py::init<>())
      .def_readwrite("levels", &femup::SpaceFrameSpec::levels)
      .def_readwrite("bays_x", &femup::SpaceFrameSpec::bays_x)
      .def_readwrite("bays_y", &femup::SpaceFrameSpec::bays_y)
      .def_readwrite("level_height", &femup::SpaceFrameSpec::level_height)
      .def_readwrite("bay_width_x", &femup::SpaceFrameSpec::bay_width_x)
      .def_readwrite("bay_width_y", &femup::SpaceFrameSpec::bay_width_y)
      .def_readwrite("elements_per_member", &femup::SpaceFrameSpec::elements_per_member)
      .def_readwrite("blocks_per_level", &femup::SpaceFrameSpec::blocks_per_level)
      .def_property(
          "bracing",
          [](const femup::SpaceFrameSpec& s) { return femup::ToString(s.bracing); },
          [](femup::SpaceFrameSpec& s, const std::string& text) {
            if (!femup::FaceBracingFromString(text, &s.bracing)) {
              throw femup::InputError("model.bracing",
                                      "expected none, diagonal or x, got '" + text + "'");
            }
          })
      .def_readwrite("water_depth", &femup::SpaceFrameSpec::water_depth)
      .def_property("theory", &TheoryName<femup::SpaceFrameSpec>,
                    &SetTheory<femup::SpaceFrameSpec>)
      .def_readwrite("legs", &femup::SpaceFrameSpec::legs)
      .def_readwrite("braces", &femup::SpaceFrameSpec::braces)
      .def_readwrite("horizontals", &femup::SpaceFrameSpec::horizontals)
      .def("validate", &ValidateText<femup::SpaceFrameSpec>,
           "'' when valid, else '<field>: what is wrong'");
  m.def("build_space_frame", &femup::BuildSpaceFrame, py::arg("spec"),
        py::call_guard<py::gil_scoped_release>(),
        "The jacket-like 3D frame (10^4-10^6 DOF) with factors by level and block.");

  py::class_<femup::MatrixMarketElement>(m, "MatrixMarketElement")
      .def(py::init<>())
      .def_readwrite("id", &femup::MatrixMarketElement::id)
      .def_readwrite("label", &femup::MatrixMarketElement::label)
      .def_readwrite("stiffness_file", &femup::MatrixMarketElement::stiffness_file)
      .def_readwrite("mass_file", &femup::MatrixMarketElement::mass_file)
      .def_readwrite("added_mass_file", &femup::MatrixMarketElement::added_mass_file)
      .def_readwrite("dofs", &femup::MatrixMarketElement::dofs, "0-based global DOFs")
      .def_readwrite("wet", &femup::MatrixMarketElement::wet);
  py::class_<femup::MatrixMarketModelSpec>(m, "MatrixMarketModelSpec")
      .def(py::init<>())
      .def_readwrite("stiffness_file", &femup::MatrixMarketModelSpec::stiffness_file)
      .def_readwrite("mass_file", &femup::MatrixMarketModelSpec::mass_file)
      .def_readwrite("elements", &femup::MatrixMarketModelSpec::elements)
      .def_readwrite("dof_labels", &femup::MatrixMarketModelSpec::dof_labels);
  m.def("import_matrix_market", &femup::ImportMatrixMarketStructure, py::arg("spec"),
        py::arg("base_dir") = ".", "A Structure from Matrix Market files.");
  m.def(
      "read_matrix_market",
      [](const std::string& path) { return CscOwned(femup::ReadMatrixMarket(path)); },
      py::arg("path"), "A Matrix Market file as a scipy.sparse.csc_matrix.");
  m.def(
      "write_matrix_market",
      [](const std::string& path, py::object matrix, bool symmetric) {
        femup::WriteMatrixMarket(path, ToSparse(matrix, "matrix"), symmetric);
      },
      py::arg("path"), py::arg("matrix"), py::arg("symmetric") = false);
}

void BindModes(py::module_& m) {
  py::class_<femup::Modes>(m, "Modes", "Eigenpairs of (K, M), M-normalised shapes.")
      .def(py::init<>())
      .def_readwrite("eigenvalues", &femup::Modes::eigenvalues,
                     "lambda = omega^2 (rad^2/s^2), ascending")
      .def_readwrite("shapes", &femup::Modes::shapes, "num_dofs x num_modes")
      .def_property_readonly("frequencies_hz", &femup::Modes::FrequenciesHz)
      .def("__len__", &femup::Modes::size);

  m.def(
      "solve_modes",
      [](py::object k, py::object mass, int num_modes, const std::string& method,
         double shift, double tolerance) {
        const femup::SparseMatrix kk = ToSparse(k, "stiffness");
        const femup::SparseMatrix mm = ToSparse(mass, "mass");
        const femup::EigenOptions options =
            EigenOptionsFrom(num_modes, method, shift, tolerance);
        py::gil_scoped_release release;
        return femup::SolveModes(kk, mm, options);
      },
      py::arg("stiffness"), py::arg("mass"), py::arg("num_modes") = -1,
      py::arg("method") = "auto", py::arg("shift") = 0.0, py::arg("tolerance") = 1e-10,
      "Lowest modes of K phi = lambda M phi (dense up to 1500 DOFs, else sparse "
      "shift-invert: num_modes needed), M-normalised, largest entry positive.");
  m.def("mac", &femup::Mac, py::arg("a"), py::arg("b"),
        "(a'b)^2 / ((a'a)(b'b)), in [0, 1]");
  m.def("mac_matrix", &femup::MacMatrix, py::arg("a"), py::arg("b"),
        "MAC of every column of a against every column of b");

  py::class_<femup::ModePair>(m, "ModePair")
      .def_readonly("reference", &femup::ModePair::reference)
      .def_readonly("candidate", &femup::ModePair::candidate, "-1: unpaired")
      .def_readonly("mac", &femup::ModePair::mac)
      .def("__repr__", [](const femup::ModePair& p) {
        return "<femup.ModePair " + std::to_string(p.reference) + " -> " +
               std::to_string(p.candidate) + ", MAC " + std::to_string(p.mac) + ">";
      });
  m.def("pair_modes_by_mac", &femup::PairModesByMac, py::arg("reference"),
        py::arg("candidate"), py::arg("min_mac") = 0.0,
        "Each reference mode with a distinct candidate, largest MAC first.");
  m.def("pair_modes_by_mac_and_misfit", &femup::PairModesByMacAndMisfit, py::arg("mac"),
        py::arg("shape_misfit"), py::arg("frequency_misfit"), py::arg("min_mac") = 0.0,
        py::arg("tie") = 9.0,
        "As pair_modes_by_mac on a MAC matrix, but candidates whose shape misfits are "
        "within `tie` of the best one's are paired by least shape + frequency misfit.");
  m.def("pair_modes_in_order", &femup::PairModesInOrder, py::arg("reference"),
        py::arg("candidate"),
        "Order-keeping pairing maximising the number of pairs, then the sum of MACs.");
}

}  // namespace

void InitModels(py::module_& m) {
  BindStructure(m);
  BindModel(m);
  BindBuilders(m);
  BindModes(m);
}

}  // namespace femup_python
