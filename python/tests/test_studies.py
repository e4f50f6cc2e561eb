"""Study files from a path or a dict: the same schema, the same checks, the
same messages naming the field; the study's parts and one identification."""

import numpy as np
import pytest

import femup
from conftest import EXAMPLES, paper_study_dict


def test_dict_and_file_give_the_same_study():
    from_file = femup.load_study(str(EXAMPLES / "paper_chain_masses_1-3_wet.yaml"))
    from_dict = femup.study_from_dict(paper_study_dict())
    assert from_dict.name == "paper_chain_dict" and from_dict.path == "<dict>"
    assert from_dict.model.parameter_names == from_file.model.parameter_names
    np.testing.assert_array_equal(from_dict.truth, from_file.truth)
    assert from_dict.fixed == from_file.fixed == {"mass[4]": 0.0058}
    assert from_dict.system_form == "summed" and from_dict.num_fem_modes == -1
    a = femup.run_update(from_file).solution.x
    b = femup.run_update(from_dict).solution.x
    np.testing.assert_array_equal(a, b)
    assert [m.state for m in from_dict.measurements] == ["air", "water"]
    assert from_dict.measurements[1].immersion == "wet"
    assert from_dict.measurements[0].simulate_modes == 2


@pytest.mark.parametrize("change, field", [
    (lambda d: d["model"].update(masses=[50, 50, -1, 50, 50]), r"model\.masses\[3\]"),
    (lambda d: d["model"].update(colour="red"), r"model\.colour: unknown key"),
    (lambda d: d.update(solver={"name": "magic"}), r"solver\.name"),
    (lambda d: d["parameters"].update(fix={"mass[9]": 0.1}), r"parameters\.fix\.mass\[9\]"),
    (lambda d: d.update(measurements=[]), r"measurements: expected at least one state"),
    (lambda d: d["measurements"][1].update(immersion="damp"),
     r"measurements\[2\]\.immersion"),
    (lambda d: d.update(truth={"mass[1]": "heavy"}), r"truth\.mass\[1\]"),
    (lambda d: d["system"].update(form="folded"), r"system\.form"),
])
def test_bad_dict_names_the_field(change, field):
    d = paper_study_dict()
    change(d)
    with pytest.raises(femup.InputError, match=field) as error:
        femup.study_from_dict(d)
    assert error.value.where.startswith("<dict>:")
    assert isinstance(error.value, ValueError)


def test_dict_values_that_cannot_be_written():
    with pytest.raises(femup.InputError, match="study: expected a dict"):
        femup.study_from_dict([1, 2])
    d = paper_study_dict()
    d["model"]["masses"] = [object()] * 5
    with pytest.raises(femup.InputError, match=r"model\.masses\[1\]"):
        femup.study_from_dict(d)


def test_numpy_arrays_and_infinite_bounds(tmp_path):
    d = paper_study_dict()
    d["model"]["masses"] = np.full(5, 50.0)
    d["parameters"]["bounds"] = {"added_mass": [0.0, float("inf")],
                                 "stiffness[2]": [-float("inf"), 0.5]}
    study = femup.study_from_dict(d, base_dir=tmp_path, name="bounded.json")
    assert study.path == str(tmp_path / "bounded.json") and study.name == "paper_chain_dict"
    assert np.isinf(study.upper[study.model.find_parameter("added_mass[1]")])
    assert study.lower[study.model.find_parameter("added_mass[1]")] == 0.0
    assert np.isinf(study.lower[study.model.find_parameter("stiffness[2]")])



def test_parse_study_text_and_missing_file():
    text = (EXAMPLES / "paper_chain_masses_1-3_wet.yaml").read_text()
    study = femup.parse_study(text, "elsewhere/paper.yaml")
    assert study.name == "paper_chain_masses_1-3_wet"
    with pytest.raises(femup.InputError, match="study file not found"):
        femup.load_study("no/such/study.yaml")
    with pytest.raises(femup.InputError, match=r"elsewhere/bad\.yaml:"):
        femup.parse_study("model: [unclosed\n", "elsewhere/bad.yaml")


def test_solver_override_and_solve_factors():
    study = femup.study_from_dict(paper_study_dict())
    states = femup.measured_states(study)
    prepared = femup.prepare_measurements(study)
    assert [p.data.state for p in prepared] == ["air", "water"]
    np.testing.assert_array_equal(prepared[0].data.frequencies_hz, states[0].frequencies_hz)
    fem = femup.fem_modes_for(study)
    assert len(fem) == 5
    spec = femup.SolverSpec()
    spec.name = "bvls"
    solve = femup.solve_factors(study, spec, fem, states)
    assert solve.solution.summary.status == "solved"
    np.testing.assert_allclose(solve.solution.x, study.truth, atol=1e-9)
    # As the command line's --method sensitivity --solver ipopt.
    study.solver.method = "sensitivity"
    study.solver.name = "ipopt"
    result = femup.run_update(study)
    assert result.method == "sensitivity" and result.solver_name == "ipopt"
    np.testing.assert_allclose(result.solution.x, study.truth, atol=1e-6)


def test_noise_and_diagnosis_settings_are_changed_in_place():
    study = femup.load_study(str(EXAMPLES / "paper_chain_noise.yaml"))
    study.noise_study.draws = 5
    study.noise_study.levels = [0.01]
    assert study.noise_study.draws == 5
    result = femup.run_noise_study(study)
    assert result.levels == [0.01] and result.usable_draws == [5]
    assert result.rm_mean.shape == (1, len(result.added_mass_indices))
    assert "Rm" in result.report()
    assert study.diagnosis is None
    study.diagnosis = femup.DiagnosisSpec()
    study.diagnosis.max_effects = 1
    assert study.diagnosis.max_effects == 1
    assert study.diagnosis.pair_places == 10
    study.diagnosis.pair_places = -1
    assert study.diagnosis.pair_places == -1
    # The defaults of the switches a study may turn (docs/diagnosis.md).
    assert study.diagnosis.form_step and not study.diagnosis.refine_mesh
    assert study.diagnosis.engine == ""  # the model type's own default
    study.diagnosis.form_step = False
    assert not study.diagnosis.form_step
    assert not study.diagnosis.form_fit
    assert study.diagnosis.form_error_on_shapes
    study.diagnosis.form_error_on_shapes = False
    assert not study.diagnosis.form_error_on_shapes
    assert study.diagnosis.stiffness_uncertainty == 0
    study.diagnosis.stiffness_uncertainty = 0.02
    study.diagnosis.mass_uncertainty = 0.01
    assert study.diagnosis.stiffness_uncertainty == 0.02
    assert study.diagnosis.mass_uncertainty == 0.01
    assert study.diagnosis.gap_confidence == 0
    study.diagnosis.gap_confidence = 0.9
    assert study.diagnosis.gap_confidence == 0.9
    study.diagnosis.frequency_temperature = "marginal"
    assert study.diagnosis.frequency_temperature == "marginal"
    study.diagnosis.form_fit = True
    assert study.diagnosis.form_fit
    assert study.diagnosis.rotary_inertia
    study.diagnosis.rotary_inertia = False
    assert not study.diagnosis.rotary_inertia
