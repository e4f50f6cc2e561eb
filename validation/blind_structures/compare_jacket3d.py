"""jacket3d (numpy, frame3d's elements) against femup's own space_frame model of a
study: the lowest modes side by side.

Unlike frame3d.py and jacket3d.py, this script calls femup (`femup modes`,
the nominal model's modal analysis), as run_suite.py does: it is the check
of the independent code against femup, not part of making truths.

Rows:
- femup: the study's model as written (examples/diagnosis/jacket.yaml:
  Euler-Bernoulli, 2 elements per member, no rotary inertia, dry: femup's
  added mass is a correction factor, 0 in the nominal model);
- numpy like-for-like: jacket3d with the same formulation (no shear, Hermite
  mass, no rotary inertia, 2 elements, dry): must agree to rounding, which
  checks the geometry, the node numbering (MAC over every labelled DOF) and
  the elements at once;
- numpy Timoshenko: 4 elements per member, shear deformation, Timoshenko
  consistent mass with rotary inertia, dry: the formulation of a truth;
- femup Timoshenko: the same study with `theory: timoshenko` and 4 elements per
  member (femup's Timoshenko element: no rotary inertia);
- numpy wet: the Timoshenko jacket with potential-flow added mass
  (Ca rho_w pi D^2 / 4, rho_w 1025) on the elements below the water line;
- femup wet: `femup run` of the Timoshenko variant with the truth
  `added_mass: r`, r = rho_w pi D^2 / 4 / (rho A) (femup's added-mass factors
  scale the transverse consistent mass of rho A on the wet elements: the same
  law), its simulated water-state frequencies. Only when the three sections
  give one r (same D / t), since the truth is set for all factors at once.

A study whose model stands on springs (model.base) puts the same springs
under the numpy jackets' legs (a rigid direction as a spring 1e20).

Usage (from the repository root):
  /usr/bin/python3 validation/blind_structures/compare_jacket3d.py \
      [--study examples/diagnosis/jacket.yaml] [--femup build/femup] [--modes 6] \
      [--check 1e-8]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from jacket3d import Jacket  # noqa: E402


def femup_modes(femup, study, count, tmp, name):
    out = os.path.join(tmp, name)
    subprocess.run([femup, "modes", study, "-o", out, "--no-plots", "-q", "-n", str(count)],
                   check=True)
    with open(os.path.join(out, "modes.json")) as fh:
        j = json.load(fh)
    return np.array(j["frequencies_hz"]), j["dof_labels"], np.array(j["shapes_mass_normalised"])


def femup_wet(femup, study, count, tmp, ratio):
    """femup's water-state frequencies of `study` with every added-mass factor
    at `ratio` (the truth), from `femup run`'s simulated measurements."""
    variant = dict(study, truth={"added_mass": float(ratio)},
                   measurements=[{"state": "water", "simulate_modes": count}],
                   solver={"method": "linear", "name": "lstsq"})
    variant.pop("diagnosis", None)
    path = os.path.join(tmp, "wet.yaml")
    with open(path, "w") as fh:
        yaml.safe_dump(variant, fh)
    out = os.path.join(tmp, "wet")
    subprocess.run([femup, "run", path, "-o", out, "--no-plots", "-q"], check=True)
    with open(os.path.join(out, "result.json")) as fh:
        return np.sort(np.array(json.load(fh)["states"][0]["measured_hz"]))


def mac_diagonal(jacket, labels, femup_shapes, shapes):
    """MAC of each numpy mode with femup's same-numbered mode over femup's DOFs."""
    S = femup_shapes.T if femup_shapes.shape[0] != len(labels) else femup_shapes
    # Over the free nodes "n<k>" (a base on springs adds femup's "b<k>" DOFs).
    keep = [r for r, label in enumerate(labels) if label.split(":")[0] in jacket.labels]
    S = S[keep]
    W = shapes[[jacket.dof(labels[r]) for r in keep]]
    k = min(S.shape[1], W.shape[1])
    S, W = S[:, :k], W[:, :k]
    return (S * W).sum(0) ** 2 / ((S * S).sum(0) * (W * W).sum(0))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--study", default="examples/diagnosis/jacket.yaml")
    p.add_argument("--femup", default="build/femup")
    p.add_argument("--modes", type=int, default=6)
    p.add_argument("--check", type=float, default=None,
                   help="exit 1 unless the like-for-like frequencies agree with femup's "
                        "to this relative tolerance (e.g. 1e-8)")
    a = p.parse_args()
    n = a.modes
    with open(a.study) as fh:
        study = yaml.safe_load(fh)
    model = dict(study["model"])
    assert model.get("type") == "space_frame", "a space_frame study"
    # femup's springs under the legs (model.base) as jacket3d's six per foot.
    base = model.pop("base", None)
    if base:
        h, v = float(base.get("horizontal", 0)), float(base.get("vertical", 0))
        r, t = float(base.get("rocking", 0)), float(base.get("torsion", 0))
        # 0 is rigid in femup; a spring far stiffer than the frame stands for it.
        model["base_springs"] = tuple(k if k > 0 else 1e20 for k in (h, h, v, r, r, t))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        f_eb, labels, s_eb = femup_modes(a.femup, a.study, n, tmp, "eb")
        variant = dict(study, model=dict(study["model"], theory="timoshenko", elements_per_member=4))
        path = os.path.join(tmp, "timoshenko.yaml")
        with open(path, "w") as fh:
            yaml.safe_dump(variant, fh)
        f_t4, _, _ = femup_modes(a.femup, path, n, tmp, "t4")
        ratios = set()
        for kind in ("legs", "braces", "horizontals"):
            sec, D = Jacket(**dict(model, theory=None)).sections[kind]
            ratios.add(round(1025.0 * np.pi * D * D / 4 / (sec["rho"] * sec["A"]), 9))
        f_t4_wet = (femup_wet(a.femup, variant, n, tmp, ratios.pop())
                    if len(ratios) == 1 else None)

    like = Jacket(**dict(model, theory=None), shear=False, rotary=False, mass_kind="hermite",
                  added_mass_ratio=0.0)
    f_like, v_like = like.modes(n)
    timo = Jacket(**dict(model, elements_per_member=4), added_mass_ratio=0.0)
    f_timo, _ = timo.modes(n)
    wet = Jacket(**dict(model, elements_per_member=4))
    f_wet, _ = wet.modes(n)
    mac = mac_diagonal(like, labels, s_eb, v_like)

    rows = [("femup (EB, 2 el, dry)", f_eb), ("numpy like-for-like", f_like),
            ("numpy Timoshenko 4 el", f_timo), ("femup Timoshenko 4 el", f_t4),
            ("numpy Timoshenko 4 el, wet", f_wet)]
    if f_t4_wet is not None:
        rows.append(("femup Timoshenko 4 el, wet", f_t4_wet))
    print("mode  " + "  ".join("%28s" % r[0] for r in rows))
    for k in range(n):
        print("%4d  " % (k + 1) + "  ".join("%28.4f" % r[1][k] for r in rows))
    print("\nrelative to femup's model (EB, 2 el):")
    for name, f in rows[1:]:
        print("  %-28s %s" % (name, " ".join("%+8.2e" % x for x in f / f_eb - 1)))
    print("  numpy Timoshenko vs femup Timoshenko: %s"
          % " ".join("%+8.2e" % x for x in f_timo / f_t4 - 1))
    if f_t4_wet is not None:
        print("  numpy wet vs femup wet:               %s"
              % " ".join("%+8.2e" % x for x in f_wet / f_t4_wet - 1))
    print("MAC like-for-like vs femup, mode by mode (repeated frequencies mix): %s"
          % " ".join("%.4f" % x for x in mac))
    print("numpy DOFs: %d (femup: %d free)" % (like.frame.num_dofs(), len(labels)))
    if a.check is not None:
        worst = float(np.max(np.abs(f_like / f_eb - 1)))
        print("like-for-like: largest relative difference %.2e (tolerance %.0e)"
              % (worst, a.check))
        if not worst <= a.check:
            sys.exit(1)


if __name__ == "__main__":
    main()
