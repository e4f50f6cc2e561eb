"""From test records to correction factors, in Python: simulate, ERA, update.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/era_to_update.py

1. Records: examples/cantilever_experiment/real_beam.yaml describes the "real"
   beam (a finer mesh, a flexible base, accelerometers, strip-theory water);
   run_simulate strikes it and records ten accelerations per state (numpy).
2. Identification: ERA with a stabilisation diagram on each state's records;
   the two lowest stable modes (frequencies and shapes at the ten sensors).
3. Update: the nominal Model A (examples/cantilever_experiment/model_a.yaml)
   as a study dict, the identified modes given as measured, shapes expanded by
   SEREP; stiffness per element and added mass per wet element found together.
"""

import pathlib
import sys

import numpy as np

import femup

EXPERIMENT = pathlib.Path(__file__).resolve().parents[1] / "cantilever_experiment"

real = femup.load_study(str(EXPERIMENT / "real_beam.yaml"))
simulated = femup.run_simulate(real)

options = femup.StabilisationOptions()
options.max_order = 30
measurements = []
for state in simulated.states:
    diagram = femup.stabilisation_diagram(state.records, state.sample_rate_hz, options)
    poles = diagram.arrays()
    stable = femup.pick_stable_modes(diagram, options, 5)
    modes = [s.mode for s in stable if s.mode.frequency_hz < 100][:2]
    print(f"{state.state}: {len(poles['order'])} poles in the diagram, "
          f"{int(poles['stable'].sum())} stable; identified "
          + ", ".join(f"{m.frequency_hz:.3f} Hz (zeta {m.damping_ratio:.4f})" for m in modes)
          + "; in the records: "
          + ", ".join(f"{f:.3f} Hz" for f in state.frequencies_hz[:2]))
    measurements.append({
        "state": state.state, "immersion": state.immersion,
        "frequencies_hz": [m.frequency_hz for m in modes],
        # The real beam's node 4k is the 10-element model's node k (same height).
        "sensors": [f"n{int(label[1:label.index(':')]) // 4}:ux" for label in state.sensors],
        "shapes": [m.shape for m in modes],
        "expansion": {"method": "serep", "modes": 2},
    })

study = femup.study_from_dict({
    "name": "model_a_from_python",
    "model": {"type": "cantilever", "length": 1.9, "elements": 10,
              "section": {"E": 206e9, "A": 8.8e-4, "I": 8.53e-8, "rho": 7850},
              "water_depth": 1.5, "added_mass_basis": "transverse"},
    "parameters": {"mass": "none", "stiffness": "per_element", "added_mass": "per_element"},
    "measurements": measurements,
    "system": {"form": "stacked"},
})
result = femup.run_update(study)
print(f"update: {result.solution.summary.status}, Z {result.problem.A.shape}, "
      f"Sa = {result.added_mass_summary.sa:.3f}, "
      f"added mass {result.added_mass_summary.per_length:.3f} kg/m")
for s in result.states:
    print(f"  {s.state}: measured {np.round(s.measured_hz, 3)} Hz, nominal "
          f"{np.round(s.model_hz, 3)}, updated {np.round(s.updated_hz, 3)}")
before = max(np.max(np.abs(s.model_hz / s.measured_hz - 1)) for s in result.states)
after = max(np.max(np.abs(s.updated_hz / s.measured_hz - 1)) for s in result.states)
print(f"largest frequency error: nominal {100 * before:.2f} %, updated {100 * after:.2f} %")
sys.exit(0 if result.solution.summary.usable and after < before / 5 else 1)
