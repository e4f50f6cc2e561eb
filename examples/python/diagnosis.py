"""A diagnosis from Python: which unmodelled effect, where, how likely.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/diagnosis.py

Runs `femup diagnose` on two bundled studies: the six-storey shear building of
examples/diagnosis/shear_building.yaml (a chain) and the cantilever of
examples/diagnosis/added_mass.yaml, both on the default engine (effects as
changes of the model), and prints the ranked classes with their probabilities,
places, sizes and how much of the gap each explains; then the cantilever on its
own pipeline (run_diagnosis, `diagnosis.engine: cantilever`), with how far each
class shrinks the gap on fitted and held-out modes.
"""

import pathlib
import sys

import femup

DIAGNOSIS = pathlib.Path(__file__).resolve().parents[1] / "diagnosis"

shear = femup.diagnose(femup.load_study(str(DIAGNOSIS / "shear_building.yaml")))
print(f"{shear.study_name} ({shear.model_type}):")
for c in shear.classes[:4]:
    sizes = ", ".join(f"{m.name} {m.value:.3g} {m.unit}" for m in c.magnitudes)
    print(f"  P = {c.probability:.3f}  {c.kind} at {c.region or '-'}  chi2 {c.chi2:.1f}"
          + (f"  ({sizes})" if sizes else ""))

bar = femup.diagnose(femup.load_study(str(DIAGNOSIS / "added_mass.yaml")))
print(f"{bar.study_name} ({bar.model_type}):")
for c in bar.classes[:3]:
    sizes = ", ".join(f"{m.name} {m.value:.3g} {m.unit}" for m in c.magnitudes)
    print(f"  P = {c.probability:.3f}  {c.kind} at {c.region or '-'}  explains "
          f"{100 * c.explained:.0f} %" + (f"  ({sizes})" if sizes else ""))

beam = femup.run_diagnosis(femup.load_study(str(DIAGNOSIS / "added_mass.yaml")))
before = beam.gap(-1)
print(f"{beam.study_name} (cantilever, its own pipeline): {beam.verdict}")
print(f"  nominal model: rms frequency error {100 * before['rms_frequency_error']:.2f} %, "
      f"held out {100 * before['rms_frequency_error_held_out']:.2f} %")
for k, c in enumerate(beam.candidates[:3]):
    after = beam.gap(k)
    where = "; ".join(f"{loc.x:.2f} m" if loc.x == loc.x else f"{loc.x0:.2f}-{loc.x1:.2f} m"
                      for loc in c.locations)
    print(f"  P = {c.probability:.3f}  {c.label:<28} rms error {100 * after['rms_frequency_error']:.2f} %"
          f" (held out {100 * after['rms_frequency_error_held_out']:.2f} %)  at {where}")

top = shear.classes[0]
sys.exit(0 if (top.kind, top.region) == ("stiffness_loss", "element 3")
         and bar.classes[0].kind == "added_mass"
         and beam.candidates[0].label == "added_mass" else 1)
