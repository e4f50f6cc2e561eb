"""Measurements: ModalData, UFF and CSV files, ERA and its stabilisation
data as arrays, identification from a record file, simulated records."""

import numpy as np
import pytest

import femup
from conftest import EXAMPLES

# Two modes of a free decay: frequencies (Hz), damping ratios, shapes at 3 sensors.
F_HZ = np.array([5.0, 13.0])
ZETA = np.array([0.01, 0.02])
SHAPES = np.array([[1.0, 0.6], [0.7, -0.8], [0.3, 1.0]])
FS = 200.0


def free_decay(samples=800):
    t = np.arange(samples) / FS
    w = 2 * np.pi * F_HZ
    wd = w * np.sqrt(1 - ZETA ** 2)
    modal = np.exp(-np.outer(ZETA * w, t)) * np.cos(np.outer(wd, t))
    return SHAPES @ modal  # channels x samples


def test_modal_data_from_arrays():
    d = femup.ModalData("air", "dry", [10.0, 20.0], np.ones((2, 2)), [0, 2])
    assert d.num_modes == 2 and d.immersion == "dry" and d.sensor_dofs == [0, 2]
    np.testing.assert_allclose(d.eigenvalues, (2 * np.pi * np.array([10.0, 20.0])) ** 2)
    d.validate(3, "measurements[1]")
    with pytest.raises(femup.InputError, match=r"measurements\[1\]"):
        femup.ModalData("air", "dry", [-1.0]).validate(3, "measurements[1]")
    with pytest.raises(femup.InputError, match="immersion"):
        femup.ModalData("air", "humid", [1.0])
    full = femup.ModalData("w", "wet", [1.0], np.array([[1.0], [2.0]]))
    np.testing.assert_array_equal(full.full_shapes(2), [[1.0], [2.0]])


def test_read_uff_functions_and_modes():
    frf = femup.read_uff(str(EXAMPLES / "data" / "pyuff_beam_frf.uff"))
    functions = frf.functions
    assert functions and all(f.function_type == 4 for f in functions)
    f0 = functions[0]
    assert f0.is_complex and f0.y.dtype == np.complex128 and len(f0.x) == len(f0.y)
    assert f0.x[1] - f0.x[0] == pytest.approx(f0.abscissa_increment)
    modes_file = next((EXAMPLES / "uff_modes").glob("*.uff"))
    uff = femup.read_uff(str(modes_file))
    assert uff.mode_shapes and uff.nodes
    shape = uff.mode_shapes[0]
    assert shape.values.shape[0] == len(shape.nodes)
    assert len(uff.nodes[0].nodes) > 0
    with pytest.raises(femup.InputError, match="not found"):
        femup.read_uff("no_such_file.uff")


def test_impulse_response_from_frf():
    frf = femup.read_uff(str(EXAMPLES / "data" / "pyuff_beam_frf.uff")).functions
    h = np.array([f.y for f in frf[:2]])
    data, rate = femup.impulse_response_from_frf(h, frf[0].abscissa_increment)
    n = h.shape[1]
    assert data.shape == (2, 2 * (n - 1))
    assert rate == pytest.approx(2 * (n - 1) * frf[0].abscissa_increment)


def test_csv_round_trip_and_errors(tmp_path):
    t = np.arange(5) / 100.0
    values = np.arange(10.0).reshape(5, 2)
    path = tmp_path / "r.csv"
    femup.write_csv_series(str(path), t, values, ["a1", "a2"])
    s = femup.read_csv_series(str(path))
    assert s.channel_names == ["a1", "a2"] and s.time_name == "time"
    np.testing.assert_array_equal(s.values, values)
    assert s.sample_rate_hz == pytest.approx(100.0)
    bad = tmp_path / "bad.csv"
    bad.write_text("time,a\n0,1\n0.01,nan\n")
    with pytest.raises(femup.InputError, match=r"bad\.csv.*line 3"):
        femup.read_csv_series(str(bad))


def test_era_recovers_frequencies_damping_and_shapes():
    options = femup.EraOptions()
    options.order = 4
    options.first_sample = 0
    result = femup.era(free_decay(), FS, options)
    assert len(result.modes) == 2
    np.testing.assert_allclose([m.frequency_hz for m in result.modes], F_HZ, rtol=1e-6)
    np.testing.assert_allclose([m.damping_ratio for m in result.modes], ZETA, rtol=1e-4)
    for m, j in zip(result.modes, range(2)):
        assert femup.mac(m.shape, SHAPES[:, j]) > 1 - 1e-8
        assert m.status == "accepted" and m.emac > 0.99
    assert result.a.shape == (4, 4) and result.c.shape == (3, 4)
    # Several references: a list of arrays.
    two = femup.era([free_decay(), 0.5 * free_decay()], FS, options)
    np.testing.assert_allclose([m.frequency_hz for m in two.modes], F_HZ, rtol=1e-6)
    options.order = 0
    with pytest.raises(femup.InputError, match="order"):
        femup.era(free_decay(), FS, options)


def test_stabilisation_arrays_and_stable_modes():
    rng = np.random.default_rng(20140613)
    y = free_decay()
    y = y + 0.001 * rng.standard_normal(y.shape)
    options = femup.StabilisationOptions()
    options.era.first_sample = 0
    options.min_order, options.max_order = 2, 20
    diagram = femup.stabilisation_diagram(y, FS, options)
    arrays = diagram.arrays()
    n = sum(len(o.poles) for o in diagram.orders)
    assert all(len(v) == n for v in arrays.values())
    assert set(np.unique(arrays["order"])) <= set(range(2, 21, 2))
    stable = arrays["stable"]
    assert np.all(arrays["accepted"][stable])
    stable_f = arrays["frequency_hz"][stable]
    assert np.min(np.abs(stable_f - 5.0)) < 0.01 and np.min(np.abs(stable_f - 13.0)) < 0.01
    modes = femup.pick_stable_modes(diagram, options, 3)
    np.testing.assert_allclose([m.mode.frequency_hz for m in modes], F_HZ, rtol=1e-3)


def test_identify_from_a_csv_file(tmp_path):
    y = free_decay()
    y = y + 0.001 * np.random.default_rng(7).standard_normal(y.shape)
    path = tmp_path / "decay.csv"
    femup.write_csv_series(str(path), np.arange(y.shape[1]) / FS, y.T, ["s1", "s2", "s3"])
    options = femup.IdentifyOptions()
    options.file = str(path)
    options.stabilisation.era.first_sample = 0
    options.stabilisation.max_order = 16
    result = femup.identify(options)
    assert result.data_kind == "time" and result.channels == ["s1", "s2", "s3"]
    np.testing.assert_allclose([m.mode.frequency_hz for m in result.modes], F_HZ, rtol=1e-3)
    assert "Hz" in result.report()


def test_simulated_records_of_the_real_beam():
    study = femup.load_study(str(EXAMPLES / "cantilever_experiment" / "real_beam.yaml"))
    sim = femup.run_simulate(study)
    assert [s.state for s in sim.states] == ["air", "water"]
    air = sim.states[0]
    assert air.records.shape == (10, 5000) and air.sample_rate_hz == 500
    assert air.sensors[0] == "n40:ux"
    assert np.all(sim.states[1].frequencies_hz[:2] < air.frequencies_hz[:2])
