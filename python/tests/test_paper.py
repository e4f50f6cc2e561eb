"""The paper's numerical study (Liu et al. 2014, section 4) reproduced from
Python: the values tests/paper_chain_test.cc asserts, which come from the paper
and method.md, not from femup's own output."""

import numpy as np
import pytest

import femup
from conftest import EXAMPLES, PAPER_TRUTH, paper_study_dict

# FEM frequencies of the nominal chain (the paper, Hz, two decimals).
FEM_HZ = [34.50, 100.70, 158.75, 203.93, 232.60]
# True frequencies in air and in water (method.md, three decimals).
AIR_HZ = [34.808, 102.008, 159.698, 205.578, 234.271]
WATER_HZ = [33.588, 95.673, 150.561, 195.179, 219.352]


def test_fem_frequencies_match_the_paper():
    study = femup.load_study(str(EXAMPLES / "paper_chain_masses_1-3_wet.yaml"))
    modes = femup.solve_modes(study.model.stiffness, study.model.mass)
    np.testing.assert_allclose(modes.frequencies_hz, FEM_HZ, atol=0.005)
    result = femup.run_modes(study)
    np.testing.assert_allclose(result.nominal.frequencies_hz, FEM_HZ, atol=0.005)
    assert result.max_residual < 1e-10


def test_true_frequencies_in_air_and_water():
    study = femup.study_from_dict(paper_study_dict())
    d = study.truth
    air = femup.predict_modes(study.model, d, "dry", 5, "air")
    water = femup.predict_modes(study.model, d, "wet", 5, "water")
    np.testing.assert_allclose(air.frequencies_hz, AIR_HZ, atol=0.0005)
    np.testing.assert_allclose(water.frequencies_hz, WATER_HZ, atol=0.0005)


@pytest.mark.parametrize("example", ["paper_chain_masses_1-3_wet.yaml",
                                     "paper_chain_masses_1-3_wet_stacked.yaml"])
def test_fig2_every_factor_with_mass4_fixed(example):
    study = femup.load_study(str(EXAMPLES / example))
    result = femup.run_update(study)
    assert result.problem.A.shape == (20, 13)
    assert result.identifiability_unconstrained.rank == 12
    assert result.solution.summary.status == "solved"
    assert result.solution.identifiability.rank == 12
    factors = {f.name: f for f in result.factors}
    assert set(factors) == set(PAPER_TRUTH)
    for name, preset in PAPER_TRUTH.items():
        assert factors[name].estimate == pytest.approx(preset, abs=1e-10), name
        assert factors[name].preset == preset
        assert abs(factors[name].error) < 1e-10
    assert factors["mass[4]"].fixed and not factors["mass[1]"].fixed


def test_fig2_unconstrained_common_scaling_null_direction():
    study = femup.study_from_dict(paper_study_dict(fix=False))
    result = femup.run_update(study)
    assert result.solution.summary.status == "minimum_norm"
    ident = result.solution.identifiability
    assert ident.rank == 12
    assert len(ident.null_directions) == 1
    null = ident.null_directions[0]
    assert null.common_scaling and "common scaling" in null.description
    # Parallel to (1 + em, 1 + ek, ea) of the true factors.
    scaling = np.array([PAPER_TRUTH[n] for n in result.parameter_names])
    scaling[:10] += 1.0
    cosine = abs(null.coefficients @ scaling) / np.linalg.norm(scaling)
    assert cosine > 1 - 1e-10


def test_fig3_masses_1_2_wet():
    study = femup.load_study(str(EXAMPLES / "paper_chain_masses_1-2_wet.yaml"))
    result = femup.run_update(study)
    assert result.problem.A.shape == (20, 12)
    assert result.identifiability_unconstrained.rank == 11
    for f in result.factors:
        assert abs(f.error) < 1e-10, f.name


def test_stacked_condition_number_about_87():
    # method.md: condition number of the reduced stacked Z about 87.
    study = femup.study_from_dict(paper_study_dict(form="stacked"))
    result = femup.run_update(study)
    assert result.solution.identifiability.condition_number_unscaled == pytest.approx(
        87.0, abs=1.0)


def test_paper_study_step_by_step():
    # The same answer from the building blocks: chain, factors, FEM modes,
    # simulated measurements, Z d = F, lstsq.
    structure = femup.chain([50] * 5, [2.9e7] * 5, wet=[1, 2, 3])
    model = femup.build_model(structure)
    d = np.array([PAPER_TRUTH[n] for n in model.parameter_names])
    fem = femup.solve_modes(model.stiffness, model.mass)
    states = [femup.predict_modes(model, d, "dry", 2, "air"),
              femup.predict_modes(model, d, "wet", 2, "water")]
    problem = femup.correction_system(model, fem, states, form="summed")
    assert np.linalg.norm(problem.A @ d - problem.b) < 1e-9 * np.linalg.norm(problem.b)
    problem.fix("mass[4]", 0.0058)
    solution = femup.solve_linear(problem, "lstsq")
    assert solution.summary.status == "solved"
    np.testing.assert_allclose(solution.x, d, atol=1e-10)
