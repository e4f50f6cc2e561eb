"""The module's results against the command line's JSON on the bundled
examples: the same library, so the same numbers (to rounding in the JSON)."""

import numpy as np
import pytest

import femup
from conftest import EXAMPLES

RUN_EXAMPLES = [
    "paper_chain_masses_1-3_wet.yaml",
    "paper_chain_masses_1-3_wet_stacked.yaml",
    "paper_chain_masses_1-3_wet_unconstrained.yaml",
    "paper_chain_masses_1-2_wet.yaml",
    "paper_chain_bounded_comparison.yaml",
    "paper_chain_solver_comparison.yaml",
    "paper_table1_frequencies.yaml",
    "cantilever_model_a.yaml",
    "space_frame/jacket.yaml",
    "uff_modes/model.yaml",
]


def close(a, b, rel=1e-9, abs_=1e-12):
    np.testing.assert_allclose(np.asarray(a, float), np.asarray(b, float), rtol=rel, atol=abs_)


@pytest.mark.parametrize("example", RUN_EXAMPLES)
def test_run_matches_result_json(example, run_cli):
    path = EXAMPLES / example
    expected = run_cli("run", path, "result.json")
    result = femup.run_update(femup.load_study(str(path)))
    by_name = {p["name"]: p for p in expected["parameters"]}
    assert [f.name for f in result.factors] == [p["name"] for p in expected["parameters"]]
    for f in result.factors:
        p = by_name[f.name]
        assert f.kind == p["kind"] and f.fixed == p["fixed"]
        close(f.estimate, p["estimate"], abs_=1e-12)
        if "preset" in p:
            close(f.preset, p["preset"])
        if p.get("standard_error") is not None:
            close(f.standard_error, p["standard_error"], rel=1e-6, abs_=1e-15)
    assert result.solution.summary.status == expected["solver"]["status"]
    assert result.solver_name == expected["solver"]["name"]
    assert result.problem.A.shape == (expected["system"]["rows"], expected["system"]["unknowns"])
    assert result.form == expected["system"]["form"]
    assert len(result.states) == len(expected["states"])
    for state, js in zip(result.states, expected["states"]):
        assert state.state == js["state"]
        close(state.measured_hz, js["measured_hz"])
        close(state.model_hz, js["model_hz"])
        close(state.updated_hz, js["updated_hz"], rel=1e-9)


def test_noise_study_matches_noise_json(run_cli, tmp_path):
    # The paper's noise study with fewer draws (the seed fixed by the study).
    text = (EXAMPLES / "paper_chain_noise.yaml").read_text()
    assert "draws: 1000" in text
    study_file = tmp_path / "noise_short.yaml"
    study_file.write_text(text.replace("draws: 1000", "draws: 40"))
    expected = run_cli("noise", study_file, "noise.json")
    study = femup.load_study(str(study_file))
    assert study.noise_study.draws == 40
    one = femup.run_noise_study(study, threads=1)
    two = femup.run_noise_study(study, threads=2)
    np.testing.assert_array_equal(one.rm_mean, two.rm_mean)  # any thread count
    close(one.levels, expected["levels"])
    assert one.usable_draws == expected["usable_draws"]
    close(one.rm_average, expected["rm_average_percent"], rel=1e-12)
    assert len(expected["rm_percent"]) == len(one.added_mass_indices)
    for k, js in enumerate(expected["rm_percent"]):
        assert one.parameter_names[one.added_mass_indices[k]] == js["parameter"]
        close(one.rm_mean[:, k], js["mean"], rel=1e-12)
        close([row[k].p90 for row in one.rm], js["p90"], rel=1e-12)
    figure = expected["estimates_at_level"]
    close(one.figure_level, figure["level"])
    close(one.figure_mean, [p["mean"] for p in figure["parameters"]], rel=1e-12)


def test_modes_matches_modes_json(run_cli):
    path = EXAMPLES / "cantilever_model_a.yaml"
    expected = run_cli("modes", path, "modes.json")
    result = femup.run_modes(femup.load_study(str(path)))
    close(result.nominal.frequencies_hz, expected["frequencies_hz"])
    close(result.nominal.eigenvalues, expected["eigenvalues"])
    assert result.dof_labels == expected["dof_labels"]
    shapes = np.array(expected["shapes_mass_normalised"]).T
    close(result.nominal.shapes, shapes, rel=1e-9, abs_=1e-12)


def test_cantilever_diagnosis_matches_diagnosis_json(run_cli, tmp_path):
    # The cantilever's own pipeline (diagnosis.engine: cantilever); by default a
    # cantilever, as every model, runs on the one engine.
    example = EXAMPLES / "diagnosis" / "added_mass.yaml"
    assert isinstance(femup.diagnose(femup.load_study(str(example))),
                      femup.StructureDiagnosisResult)
    text = example.read_text()
    assert text.rstrip().endswith("shape: 0.01}")  # the diagnosis section last
    path = tmp_path / "added_mass_own.yaml"
    path.write_text(text + "  engine: cantilever\n")
    expected = run_cli("diagnose", path, "diagnosis.json")
    result = femup.diagnose(femup.load_study(str(path)))
    assert isinstance(result, femup.DiagnosisResult)
    assert result.verdict == expected["verdict"]["text"]
    assert result.candidates[0].label == expected["verdict"]["kind"]
    close(result.verdict_probability, expected["verdict"]["probability"], rel=1e-9)
    assert result.separated == expected["verdict"]["separated"]
    assert result.indistinguishable == expected["verdict"]["indistinguishable"]
    assert [c.label for c in result.candidates] == [e["kind"] for e in expected["effects"]]
    for k, (c, e) in enumerate(zip(result.candidates, expected["effects"])):
        close(c.probability, e["probability"], rel=1e-9, abs_=1e-300)
        close(c.chi2, e["chi2"], rel=1e-9)
        gap_before, gap_after = result.gap(-1), result.gap(k)
        for key in ("rms_frequency_error", "mean_mac"):
            close(gap_before[key], e["gap_before"][key], rel=1e-12)
            close(gap_after[key], e["gap_after"][key], rel=1e-12)
    kinds = dict(result.kind_probabilities)
    for kind, p in expected["kind_probabilities"].items():
        close(kinds[kind], p, rel=1e-9, abs_=1e-300)


def test_structure_diagnosis_matches_diagnosis_json(run_cli):
    path = EXAMPLES / "diagnosis" / "shear_building.yaml"
    expected = run_cli("diagnose", path, "diagnosis.json")
    result = femup.diagnose(femup.load_study(str(path)))
    assert isinstance(result, femup.StructureDiagnosisResult)
    assert result.model_type == expected["model_type"]
    classes = result.classes
    assert [(c.kind, c.region) for c in classes] == [
        (e["kind"], e["region"]) for e in expected["classes"]]
    assert result.ranking.bagging_copies == expected["bagging_copies"] == 400
    for c, e in zip(classes, expected["classes"]):
        close(c.probability, e["probability"], rel=1e-9, abs_=1e-300)
        close(c.laplace_probability, e["laplace_probability"], rel=1e-9, abs_=1e-300)
        close(c.chi2, e["chi2"], rel=1e-9)
        close(c.evidence.log_evidence, e["log_evidence"], rel=1e-9)
        assert c.equivalent == e["equivalent"]
        assert c.fitted == e["fitted"]
        close(c.explained, e["explained"], rel=1e-9, abs_=1e-12)
        assert 0 <= c.explained <= 1
        for m, em in zip(c.magnitudes, e["magnitudes"]):
            assert m.name == em["name"] and m.unit == em["unit"]
            close(m.value, em["value"], rel=1e-9)
    close(result.ranking.temperature, expected["temperature"])
    # Without pairs, each family's presence is its own probability.
    assert [f for f, _ in result.ranking.family_presence] == [
        e["family"] for e in expected["family_presence"]]
    for (f, p), e in zip(result.ranking.family_presence, expected["family_presence"]):
        close(p, e["probability"], rel=1e-9)
    assert dict(result.ranking.family_presence) == pytest.approx(
        dict(result.ranking.kind_probabilities), rel=1e-12)
    close(result.ranking.gap_probability, expected["verdict"]["gap_probability"], rel=1e-9)
    assert result.ranking.gap_below_confidence is False
    assert expected["verdict"]["gap_below_confidence"] is False
    assert expected["gap_confidence"] == 0
    # The verdict explains the gap (a damaged storey): named, as the CLI did.
    assert result.ranking.gap_unexplained is False
    assert expected["verdict"]["gap_unexplained"] is False
    assert expected["gap_explained"] == pytest.approx(1 / 3, rel=1e-15)
    assert classes[0].explained >= 1 / 3
    # A gap beyond the noise: none's misfit above what the noise gives.
    assert result.ranking.gap_within_noise is False
    assert expected["verdict"]["gap_within_noise"] is False
    close(result.ranking.nominal_misfit, expected["verdict"]["nominal_misfit"], rel=1e-9)
    close(result.ranking.noise_misfit, expected["verdict"]["noise_misfit"], rel=1e-15)
    assert result.ranking.nominal_misfit > result.ranking.noise_misfit
    # How far the gap shrinks: the nominal model's and the verdict's predictions
    # of each measured mode, as diagnosis.json's gap states them.
    none = next(c for c in classes if c.kind == "none")
    assert expected["gap"]["class"] == "stiffness_loss at element 3"
    assert len(none.modes) == len(classes[0].modes) == len(expected["gap"]["modes"]) == 4
    for a, b, e in zip(none.modes, classes[0].modes, expected["gap"]["modes"]):
        assert (a.mode + 1, b.mode + 1) == (e["mode"], e["mode"])
        close(a.measured_hz, e["measured_hz"], rel=1e-12)
        close(a.model_hz, e["nominal_hz"], rel=1e-9)
        close(b.model_hz, e["updated_hz"], rel=1e-9)
        close(b.mac, e["updated_mac"], rel=1e-9)
    # The verdict fitted again without the highest mode predicts it.
    held = result.ranking.held_out
    assert held is not None and held.ok
    assert (held.kind, held.region) == ("stiffness_loss", "element 3")
    assert [(m.state, m.mode) for m in held.refit] == [(0, 3)]
    (e,) = expected["held_out"]["modes"]
    close(held.refit[0].model_hz, e["refit_hz"], rel=1e-9)
    close(held.nominal[0].model_hz, e["nominal_hz"], rel=1e-9)


def test_frame_diagnosis_states_the_form_error_it_allowed_for(run_cli):
    path = EXAMPLES / "diagnosis" / "portal_frame.yaml"
    expected = run_cli("diagnose", path, "diagnosis.json")
    result = femup.diagnose(femup.load_study(str(path)))
    allowed = result.ranking.form_errors
    assert [e.name for e in allowed] == [e["variant"] for e in expected["form_errors"]]
    assert "shear deformation" in allowed[0].name
    for e, x in zip(allowed, expected["form_errors"]):
        close(e.max_frequency_change, x["max_frequency_change"], rel=1e-9)
        close(e.noise_units, x["noise_units"], rel=1e-9)
    assert (result.classes[0].kind, result.classes[0].region) == (
        expected["verdict"]["kind"], expected["verdict"]["region"])


def test_a_stated_model_uncertainty_is_allowed_for_as_form_error():
    building = femup.load_study(str(EXAMPLES / "diagnosis" / "shear_building.yaml"))
    building.diagnosis.stiffness_uncertainty = 0.02
    result = femup.run_structure_diagnosis(building)
    names = [e.name for e in result.ranking.form_errors]
    assert names == ["the stated uncertainty of the model's overall stiffness (2 %)"]
    # K (1 + s) moves each frequency by s / 2 of the model's, stated relative to
    # the measured ones, which the damaged storey has lowered by up to 11 %.
    assert 0.01 <= result.ranking.form_errors[0].max_frequency_change <= 0.0112
    # A damaged storey changes the modes unevenly and is still named.
    assert (result.classes[0].kind, result.classes[0].region) == ("stiffness_loss", "element 3")
    building.diagnosis.mass_uncertainty = 0.7
    with pytest.raises(femup.InputError, match="mass_uncertainty"):
        femup.run_structure_diagnosis(building)


def test_a_marginal_frequency_temperature_is_chosen_from_python():
    building = femup.load_study(str(EXAMPLES / "diagnosis" / "shear_building.yaml"))
    assert building.diagnosis.frequency_temperature == "auto"
    building.diagnosis.frequency_temperature = "marginal"
    result = femup.run_structure_diagnosis(building)
    assert result.ranking.frequency_temperature == "marginal"
    top = result.classes[0]
    assert (top.kind, top.region) == ("stiffness_loss", "element 3")
    # The damaged storey explains the frequencies: its temperature stays near 1,
    # while none, which misfits them, is judged at a far higher one.
    none = next(c for c in result.classes if c.kind == "none")
    assert top.frequency_temperature < 2 < none.frequency_temperature
    assert result.ranking.temperature == top.frequency_temperature
    with pytest.raises(femup.InputError, match="frequency_temperature"):
        building.diagnosis.frequency_temperature = "hot"


def test_the_two_diagnosis_pipelines_directly_and_their_refusals():
    cantilever = femup.load_study(str(EXAMPLES / "diagnosis" / "added_mass.yaml"))
    building = femup.load_study(str(EXAMPLES / "diagnosis" / "shear_building.yaml"))
    direct = femup.run_diagnosis(cantilever)
    # diagnosis.engine: cantilever dispatches to the cantilever's own pipeline.
    cantilever.diagnosis.engine = "cantilever"
    assert direct.verdict == femup.diagnose(cantilever).verdict
    structure = femup.run_structure_diagnosis(building)
    assert (structure.classes[0].kind, structure.classes[0].region) == (
        "stiffness_loss", "element 3")
    # Unstated (the default) or model_effects: the cantilever on the one engine.
    cantilever.diagnosis.candidates = ["added_mass", "material_scaling"]
    for engine in ("", "model_effects"):
        cantilever.diagnosis.engine = engine
        assert isinstance(femup.diagnose(cantilever), femup.StructureDiagnosisResult)
    # The cantilever's pipeline refuses a chain, naming the model; the other
    # refuses a study without measurements.
    with pytest.raises(femup.InputError, match="model"):
        femup.run_diagnosis(building)
    with pytest.raises(femup.InputError, match="measurements"):
        femup.run_structure_diagnosis(femup.parse_study_model(femup.study_text(
            {"model": {"type": "chain", "masses": [1, 1], "springs": [1, 1]}}), "<dict>"))
