"""The paper's numerical study (Liu et al. 2014, section 4, Fig. 2) from Python.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/paper_study.py

Reads examples/paper_chain_masses_1-3_wet.yaml, identifies the 13 correction
factors from two simulated modes in air and two in water (summed form, mass 4
fixed), prints them against the paper's preset values, then drops the
constraint to show the rank deficiency and its null direction.
"""

import pathlib
import sys

import femup

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]

study = femup.load_study(str(EXAMPLES / "paper_chain_masses_1-3_wet.yaml"))
result = femup.run_update(study)
print(f"{study.name}: Z {result.problem.A.shape[0]} x {result.problem.A.shape[1]}, "
      f"rank {result.identifiability_unconstrained.rank} before fixing mass[4]; "
      f"{result.solution.summary.status}")
print(f"{'factor':>14} {'estimate':>12} {'preset':>10} {'error':>10}")
for f in result.factors:
    print(f"{f.name:>14} {f.estimate:12.6f} {f.preset:10.4f} {f.error:10.1e}"
          + ("  (fixed)" if f.fixed else ""))
worst = max(abs(f.error) for f in result.factors)
print(f"largest error: {worst:.1e}")

free = femup.load_study(str(EXAMPLES / "paper_chain_masses_1-3_wet_unconstrained.yaml"))
unconstrained = femup.run_update(free)
null = unconstrained.solution.identifiability.null_directions[0]
print(f"without the constraint: {unconstrained.solution.summary.status}, "
      f"rank {unconstrained.solution.identifiability.rank}; null direction: "
      f"{null.description.split(':')[0]}; best to fix: {null.best_to_fix}")
sys.exit(0 if worst < 1e-10 and null.common_scaling else 1)
