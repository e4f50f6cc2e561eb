"""Models: builders, study-schema models, factors, K and M as scipy.sparse,
modes, MAC and mode pairing."""

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp

import femup


def test_chain_matrices_by_hand():
    s = femup.chain([1.0, 2.0, 3.0], [10.0, 20.0, 30.0], wet=[2])
    assert s.type == "chain" and s.num_dofs == 3 and s.dof_labels == ["x1", "x2", "x3"]
    k = np.array([[30.0, -20, 0], [-20, 50, -30], [0, -30, 30]])
    assert isinstance(s.stiffness, sp.csc_matrix)
    np.testing.assert_array_equal(s.stiffness.toarray(), k)
    np.testing.assert_array_equal(s.mass.toarray(), np.diag([1.0, 2.0, 3.0]))
    assert [e.wet for e in s.elements] == [False, True, False]
    assert [e.label for e in s.elements] == ["1", "2", "3"]
    assert s.find_element(2) == 1 and s.find_element(9) == -1
    e2 = s.elements[1]
    np.testing.assert_array_equal(e2.mass.toarray(), np.diag([0.0, 2.0, 0.0]))
    assert e2.stiffness.toarray()[0, 0] == 20.0


def test_a_chain_idealising_a_building_carries_its_flexural_variants():
    assert femup.chain([1.0, 2.0, 3.0], [10.0, 20.0, 30.0]).form_variant_names == []
    s = femup.chain([1.0, 2.0, 3.0], [10.0, 20.0, 30.0], shear_building=True)
    names = s.form_variant_names
    assert len(names) == 2 and all("flexural" in n for n in names)


def test_chain_errors_name_the_field():
    with pytest.raises(femup.InputError, match=r"model\.masses\[2\]"):
        femup.chain([1.0, -1.0], [1.0, 1.0])
    with pytest.raises(femup.InputError, match=r"model\.wet"):
        femup.chain([1.0], [1.0], wet=[3])


def test_sparse_matrices_are_views_of_the_model():
    structure = femup.chain([50] * 5, [2.9e7] * 5, wet=[1, 2, 3])
    model = femup.build_model(structure)
    a, b = model.stiffness, model.stiffness
    assert np.shares_memory(a.data, b.data)  # both view the model's storage
    assert not a.data.flags.writeable
    with pytest.raises(ValueError):
        a.data[0] = 1.0
    np.testing.assert_array_equal(model.mass.toarray(), structure.mass.toarray())
    modes = femup.solve_modes(a, model.mass)
    assert np.shares_memory(modes.shapes, modes.shapes)
    assert not modes.shapes.flags.owndata  # a view of the C++ Modes


def test_build_model_families():
    s = femup.chain([50] * 5, [2.9e7] * 5, wet=[1, 2, 3])
    m = femup.build_model(s)
    assert m.num_parameters == 13 and m.num_dofs == 5
    assert m.parameter_names[:2] == ["mass[1]", "mass[2]"]
    assert m.parameters_of_kind("added_mass") == [10, 11, 12]
    assert m.parameters[10].kind == "added_mass" and "wet" in m.parameters[10].tags
    m2 = femup.build_model(s, mass="none", stiffness={"layout": "groups",
                                                      "groups": [[1, 2], [3, 4, 5]]},
                           added_mass="single")
    assert m2.parameter_names == ["stiffness[1+2]", "stiffness[3-5]", "added_mass[wet]"]
    m3 = femup.build_model(s, mass="none", stiffness={"layout": "per_element", "select": "dry"},
                           added_mass="none")
    assert m3.parameter_names == ["stiffness[4]", "stiffness[5]"]
    with pytest.raises(femup.InputError, match=r"parameters\.stiffness"):
        femup.build_model(s, stiffness="every")
    with pytest.raises(femup.InputError, match=r"parameters\.mass\.select"):
        femup.build_model(s, mass={"layout": "single", "select": "damp"})


def test_updated_matrices_and_parametrised_model_from_arrays():
    k = sp.csc_matrix(np.array([[2.0, -1.0], [-1.0, 1.0]]))
    m = np.eye(2)
    model = femup.ParametrisedModel(k, m, ["a", "b"])
    i = model.add_parameter("stiffness[s]", "stiffness", k, elements=[1], tags=["t"])
    j = model.add_parameter("added_mass[w]", "added_mass", np.diag([1.0, 0.0]))
    assert (i, j) == (0, 1) and model.find_parameter("added_mass[w]") == 1
    assert model.find_dof("b") == 1
    d = np.array([0.5, 0.2])
    np.testing.assert_allclose(model.updated_stiffness(d).toarray(), 1.5 * k.toarray())
    np.testing.assert_allclose(model.updated_dry_mass(d).toarray(), np.eye(2))
    np.testing.assert_allclose(model.added_mass(d).toarray(), np.diag([0.2, 0.0]))
    np.testing.assert_allclose(model.updated_wet_mass(d).toarray(), np.diag([1.2, 1.0]))
    np.testing.assert_allclose(model.parameters[1].basis.toarray(), np.diag([1.0, 0.0]))
    with pytest.raises(femup.InputError, match="kind"):
        model.add_parameter("x", "damping", k)
    with pytest.raises(femup.InputError, match="stiffness"):
        femup.ParametrisedModel("not a matrix", m, ["a", "b"])
    with pytest.raises(femup.InputError, match="mass"):
        femup.ParametrisedModel(k, np.array([[np.nan, 0], [0, 1.0]]), ["a", "b"])


def test_cantilever_against_euler_bernoulli():
    # Clamped-free beam: f_1 = (1.8751^2 / 2 pi) sqrt(E I / (rho A L^4)).
    spec = femup.CantileverSpec()
    spec.node_heights = femup.uniform_heights(1.9, 40)
    spec.section = femup.BeamSection(E=206e9, A=8.8e-4, I=8.53e-8, rho=7850)
    s = femup.build_cantilever(spec)
    assert s.type == "cantilever" and len(s.elements) == 40 and len(s.nodes) == 41
    modes = femup.solve_modes(s.stiffness, s.mass, num_modes=4, method="sparse")
    e, a, i, rho, length = 206e9, 8.8e-4, 8.53e-8, 7850, 1.9
    f1 = 1.875104 ** 2 / (2 * np.pi) * np.sqrt(e * i / (rho * a * length ** 4))
    assert modes.frequencies_hz[0] == pytest.approx(f1, rel=1e-4)
    # Its form variant, the same beam of Timoshenko elements (kappa A = A / 2
    # unless stated), which the diagnosis allows for as the model's form error.
    assert s.form_variant_names == [
        "shear deformation and rotary inertia (Timoshenko elements; shear area 0.00044 m^2)"]
    spec.shear_area = 7.3e-4
    assert "shear area 0.00073 m^2" in femup.build_cantilever(spec).form_variant_names[0]
    spec.shear_area = 9e-4
    with pytest.raises(femup.InputError, match="shear_area"):
        femup.build_cantilever(spec)
    spec.shear_area = 0.0
    spec.lumped_masses = [femup.LumpedMass(node=40, mass=0.5)]
    spec.point_masses = [femup.PointMass(height=1.0, mass=0.1)]
    spec.distributed_masses = [femup.DistributedMass(0.0, 1.0, 1.5)]
    spec.stiffness_changes = [femup.StiffnessChange(0.4, 0.5, -0.3)]
    spec.added_mass_basis = "transverse"
    heavier = femup.build_cantilever(spec)
    f_heavier = femup.solve_modes(heavier.stiffness, heavier.mass, 2, "sparse").frequencies_hz
    assert f_heavier[0] < modes.frequencies_hz[0]
    with pytest.raises(femup.InputError, match="added_mass_basis"):
        spec.added_mass_basis = "physical"


def test_plane_and_space_frames():
    spec = femup.PlaneFrameSpec()
    spec.storeys, spec.bays, spec.elements_per_member = 2, 1, 2
    spec.wet_storeys = 1
    structure = femup.build_plane_frame_structure(spec)
    assert structure.type == "plane_frame"
    assert len(structure.elements) == 2 * 2 + 2 * 1  # columns and beams per storey
    assert len(structure.form_variant_names) == 2  # shear deformation, a finer mesh
    assert "shear deformation" in structure.form_variant_names[0]
    assert structure.form_variant_names[1] == \
        "a finer mesh (8 elements per member instead of 2)"
    model = femup.build_plane_frame(spec)
    assert model.num_dofs == structure.num_dofs
    spec.theory, spec.column_shear_area = "timoshenko", 0.008
    sheared = femup.build_plane_frame_structure(spec)
    assert sheared.form_variant_names == ["a finer mesh (8 elements per member instead of 2)"]
    assert femup.solve_modes(sheared.stiffness, sheared.mass, 1).frequencies_hz[0] < \
        femup.solve_modes(structure.stiffness, structure.mass, 1).frequencies_hz[0]
    with pytest.raises(femup.InputError, match="theory"):
        spec.theory = "rayleigh"
    spec.theory = "euler_bernoulli"
    assert any(n.startswith("added_mass[s1") for n in model.parameter_names)

    frame = femup.SpaceFrameSpec()
    frame.levels, frame.bays_x, frame.bays_y, frame.elements_per_member = 2, 1, 1, 1
    frame.bracing = "diagonal"
    frame.water_depth = 5.0
    assert frame.validate() == ""
    tube = femup.circular_tube(0.6, 0.015, 210e9, 0.3, 7850)
    assert tube.A == pytest.approx(np.pi / 4 * (0.6 ** 2 - 0.57 ** 2))
    frame.braces = tube
    jacket = femup.build_space_frame(frame)
    assert jacket.num_dofs % 6 == 0 and "mass[l1]" in jacket.parameter_names
    modes = femup.solve_modes(jacket.stiffness, jacket.mass)
    assert np.all(modes.eigenvalues > 0)
    with pytest.raises(femup.InputError, match="bracing"):
        frame.bracing = "k"
    with pytest.raises(femup.InputError, match="theory"):
        frame.theory = "rayleigh"


def test_model_from_dict_every_type(tmp_path):
    structure, model = femup.model_from_dict(
        {"type": "cantilever", "length": 1.9, "elements": 10,
         "section": {"E": 206e9, "A": 8.8e-4, "I": 8.53e-8, "rho": 7850},
         "water_depth": 1.5})
    assert structure.num_dofs == 30 and model.num_parameters == 10 + 10 + 8
    structure, model = femup.model_from_dict(
        {"type": "plane_frame", "storeys": 1, "bays": 1, "storey_height": 3.0,
         "bay_width": 5.0, "elements_per_member": 2,
         "column": {"E": 210e9, "A": 0.02, "I": 4e-4, "rho": 7850},
         "beam": {"E": 210e9, "A": 0.012, "I": 2.5e-4, "rho": 7850}},
        parameters={"mass": "none", "stiffness": "per_element", "added_mass": "none"})
    assert model.num_parameters == 3
    structure, model = femup.model_from_dict(
        {"type": "space_frame", "levels": 2, "bays_x": 1, "bays_y": 1,
         "elements_per_member": 1})
    assert structure.num_dofs == model.num_dofs > 0
    # Matrix Market: a two-spring chain written out and read back.
    k1 = sp.csc_matrix(np.array([[1.0, 0], [0, 0]]))
    k2 = sp.csc_matrix(np.array([[1.0, -1], [-1, 1]]))
    m1 = sp.csc_matrix(np.diag([2.0, 0]))
    m2 = sp.csc_matrix(np.diag([0.0, 3.0]))
    for name, mat in [("k1", k1), ("k2", k2), ("m1", m1), ("m2", m2)]:
        femup.write_matrix_market(str(tmp_path / f"{name}.mtx"), mat, symmetric=True)
    np.testing.assert_array_equal(femup.read_matrix_market(str(tmp_path / "k2.mtx")).toarray(),
                                  k2.toarray())
    model_dict = {"type": "matrix_market", "dof_labels": ["u1", "u2"],
                  "elements": [{"id": 1, "stiffness": "k1.mtx", "mass": "m1.mtx", "wet": True},
                               {"id": 2, "stiffness": "k2.mtx", "mass": "m2.mtx"}]}
    structure, model = femup.model_from_dict(model_dict, base_dir=tmp_path)
    np.testing.assert_allclose(structure.stiffness.toarray(), (k1 + k2).toarray())
    assert model.parameter_names == ["mass[e1]", "mass[e2]", "stiffness[e1]",
                                     "stiffness[e2]", "added_mass[e1]"]
    spec = femup.MatrixMarketModelSpec()
    el1, el2 = femup.MatrixMarketElement(), femup.MatrixMarketElement()
    el1.id, el1.stiffness_file, el1.mass_file = 1, "k1.mtx", "m1.mtx"
    el2.id, el2.stiffness_file, el2.mass_file = 2, "k2.mtx", "m2.mtx"
    spec.elements = [el1, el2]
    direct = femup.import_matrix_market(spec, str(tmp_path))
    np.testing.assert_allclose(direct.mass.toarray(), np.diag([2.0, 3.0]))
    with pytest.raises(femup.InputError, match=r"model\.section\.E"):
        femup.model_from_dict({"type": "cantilever", "length": 1, "elements": 2,
                               "section": {"E": "steel", "A": 1, "I": 1, "rho": 1}})


def test_solve_modes_dense_and_sparse_against_scipy():
    structure = femup.chain([50, 40, 30, 20, 10, 5], [3e7, 2e7, 2e7, 1e7, 1e7, 5e6])
    k, m = structure.stiffness, structure.mass
    reference = scipy.linalg.eigh(k.toarray(), m.toarray(), eigvals_only=True)
    dense = femup.solve_modes(k, m)
    np.testing.assert_allclose(dense.eigenvalues, reference, rtol=1e-10)
    sparse = femup.solve_modes(k, m, num_modes=3, method="sparse")
    np.testing.assert_allclose(sparse.eigenvalues, reference[:3], rtol=1e-9)
    phi = dense.shapes
    np.testing.assert_allclose(phi.T @ m.toarray() @ phi, np.eye(6), atol=1e-10)
    assert len(dense) == 6
    with pytest.raises(femup.InputError, match="method"):
        femup.solve_modes(k, m, method="lanczos")


def test_mac_and_pairing():
    a = np.array([1.0, 2.0, 3.0])
    assert femup.mac(a, -2 * a) == pytest.approx(1.0)
    assert femup.mac(np.array([1.0, 0]), np.array([0, 1.0])) == 0.0
    ref = np.eye(3)
    cand = ref[:, [2, 0, 1]] + 0.01
    macs = femup.mac_matrix(ref, cand)
    expected = np.array([[(ref[:, i] @ cand[:, j]) ** 2 /
                          ((ref[:, i] @ ref[:, i]) * (cand[:, j] @ cand[:, j]))
                          for j in range(3)] for i in range(3)])
    np.testing.assert_allclose(macs, expected)
    pairs = femup.pair_modes_by_mac(ref, cand)
    assert [(p.reference, p.candidate) for p in pairs] == [(0, 1), (1, 2), (2, 0)]
    assert femup.pair_modes_by_mac(ref, cand, min_mac=1.1)[0].candidate == -1
    # Two candidates the sensors see alike (MACs differing by noise, shape
    # misfits within the tie): the frequency pairs the measured mode.
    mac = np.array([[0.9981, 0.9980]])
    shape = np.array([[2.0, 3.0]])
    frequency = np.array([[4900.0, 67.0]])
    assert femup.pair_modes_by_mac_and_misfit(mac, shape, frequency)[0].candidate == 1
    assert femup.pair_modes_by_mac_and_misfit(mac, shape, frequency, tie=0)[0].candidate == 0
    assert femup.pair_modes_by_mac_and_misfit(mac, shape + [[0, 20]], frequency)[0].candidate == 0
    with pytest.raises(femup.InputError, match="tie"):
        femup.pair_modes_by_mac_and_misfit(mac, shape, frequency, tie=-1)
    with pytest.raises(femup.InputError, match="misfit"):
        femup.pair_modes_by_mac_and_misfit(mac, shape[:, :1], frequency)
    ordered = femup.pair_modes_in_order(ref, cand)
    cands = [p.candidate for p in ordered if p.candidate >= 0]
    assert cands == sorted(cands)


def test_predict_modes_states():
    structure = femup.chain([50] * 5, [2.9e7] * 5, wet=[1, 2, 3])
    model = femup.build_model(structure)
    d = np.zeros(model.num_parameters)
    dry = femup.predict_modes(model, d, "dry", 3, "air")
    fem = femup.solve_modes(model.stiffness, model.mass)
    np.testing.assert_allclose(dry.frequencies_hz, fem.frequencies_hz[:3], rtol=1e-12)
    d[model.find_parameter("added_mass[1]")] = 0.5
    wet = femup.predict_modes(model, d, "wet", 3, "water")
    assert wet.immersion == "wet" and np.all(wet.frequencies_hz < dry.frequencies_hz)
    with pytest.raises(femup.InputError, match="immersion"):
        femup.predict_modes(model, d, "damp", 3)


def test_numerical_failures_are_their_own_exception():
    # A numerical method failing on valid input (an eigensolver that does not
    # converge) is a RuntimeError, not the ValueError of bad input.
    assert issubclass(femup.NumericalError, RuntimeError)
    assert not issubclass(femup.NumericalError, ValueError)
    assert not issubclass(femup.InputError, RuntimeError)
    assert femup.NumericalError is not femup.InputError
