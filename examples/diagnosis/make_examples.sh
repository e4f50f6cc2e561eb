#!/usr/bin/env bash
# Regenerates the diagnosis examples (examples/diagnosis/*.yaml) from their truth
# models (examples/diagnosis/truth/*.yaml):
#   1. `femup modes` solves each 60-element truth model;
#   2. the lowest 4 bending modes are kept: their frequencies, and their ux at 10
#      sensors (every 0.2 m, 0.2 m to the tip; truth node 3k = diagnosis node k),
#      scaled to a largest entry of 1;
#   3. noise is added with a fixed seed per example: 0.1 % (relative, normal) on
#      each frequency, 1 % of the largest entry on each shape entry;
#   4. each example is written as a study of the 20-element nominal model with
#      the noisy modes as its measurements. The truth files are never read by
#      the diagnosis.
# The output depends only on femup's eigen-solution and Python's Mersenne
# Twister (random.Random(seed).random()), so it is reproducible.
#
# Usage: examples/diagnosis/make_examples.sh [path/to/femup]
#        (default: femup on PATH)
set -euo pipefail
FEMUP="${1:-femup}"
HERE="$(cd "$(dirname "$0")" && pwd)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT

for truth in "$HERE"/truth/*.yaml; do
  name="$(basename "$truth" .yaml)"
  "$FEMUP" modes "$truth" -n 12 -o "$WORK/$name" --no-plots -q
done

python3 - "$HERE" "$WORK" <<'PY'
import json, math, random, sys

here, work = sys.argv[1], sys.argv[2]

ELEMENTS, REFINEMENT, MODES = 20, 3, 4
SENSORS = [2, 4, 6, 8, 10, 12, 14, 16, 18, 20]  # diagnosis nodes (0.1 m apart)
FREQ_NOISE, SHAPE_NOISE = 0.001, 0.01

# name: (seed, shapes, title, what the truth holds, the true class)
EXAMPLES = {
    "added_mass": (101, True,
        "Added mass of water up to 1.2 m",
        ["water's added mass, 2.83 kg/m (40 % of the bar's own 7.07 kg/m),",
         "from the base to 1.2 m, fading linearly to zero over the top 0.2 m"],
        "added_mass, to a depth of 1.2 m (fading from 1.0 m)"),
    "support_flexibility": (102, True,
        "A base that is not quite rigid",
        ["a rotational spring of 3.5e4 N m/rad (EI / (k_r L) = 0.05) and a",
         "transverse spring of 1.0e5 N/m at the base instead of a clamp"],
        "support_flexibility, at the base"),
    "attached_mass": (103, True,
        "A sensor housing bolted on at 1.63 m",
        ["a 1.5 kg mass (10.6 % of the bar) at 1.63 m, between nodes, with",
         "rotary inertia 2.4e-3 kg m^2 (radius of gyration 4 cm)"],
        "attached_mass, at x = 1.63 m"),
    "stiffness_loss": (104, True,
        "Local loss of bending stiffness (corrosion or a crack zone)",
        ["60 % of E I lost over 0.75-0.90 m (centre 0.825 m); the fitted",
         "family removes stiffness over a fixed L/10 region, so the form differs"],
        "stiffness_loss, centred at x = 0.825 m"),
    "no_gap": (105, True,
        "No gap: the model is right",
        ["no effect at all: the beam exactly as modelled (on the finer mesh)"],
        "none (no gap beyond noise and mesh)"),
    "frequencies_only": (106, False,
        "Added mass of water, frequencies only",
        ["water's added mass, 2.83 kg/m from the base to 1.5 m, fading over",
         "the top 0.15 m; only the 4 frequencies are measured (no shapes)"],
        "added_mass, to a depth of 1.5 m (fading from 1.35 m)"),
    "air_and_water": (107, True,
        "A bar with a material error, tested in air and in water",
        ["Young's modulus 3 % low (203.7 GPa) in both states, and in water",
         "water's added mass, 2.83 kg/m from the base to 1.2 m, fading to zero",
         "over the top 0.2 m"],
        "added_mass+material_scaling (depth 1.2 m, fading from 1.0 m; E 3 % low)"),
    "axial_load": (108, True,
        "A bar under tension",
        ["a tension of 3.0 kN along the axis (a riser's or tendon's top tension),",
         "1.37 times the bar's Euler load pi^2 E I / (4 L^2) = 2.19 kN"],
        "axial_load, a tension of 3.0 kN"),
}
# The candidates a study lists where the default five would not hold the truth.
CANDIDATES = {
    "axial_load": ["added_mass", "support_flexibility", "attached_mass",
                   "stiffness_loss", "material_scaling", "axial_load"],
}
# The measured states of each example and the truth model of each (default: one
# state "test" from truth/<name>.yaml).
STATES = {
    "air_and_water": [("air", "air_and_water_air"), ("water", "air_and_water_water")],
}


def num(v):
    return "%.10g" % v


for name, (seed, with_shapes, title, what, expected) in EXAMPLES.items():
    rng = random.Random(seed)

    def normal():  # Box-Muller on the Mersenne Twister: stable across versions
        u1, u2 = 1.0 - rng.random(), rng.random()
        return math.sqrt(-2 * math.log(u1)) * math.cos(2 * math.pi * u2)

    states = []  # (state, noisy frequencies, noisy shapes)
    for state, truth in STATES.get(name, [("test", name)]):
        m = json.load(open("%s/%s/modes.json" % (work, truth)))
        labels = m["dof_labels"]
        index = {l: i for i, l in enumerate(labels)}
        freqs, shapes = [], []
        for f, phi in zip(m["frequencies_hz"], m["shapes_mass_normalised"]):
            bending = sum(p * p for l, p in zip(labels, phi) if not l.endswith(":uy"))
            axial = sum(p * p for l, p in zip(labels, phi) if l.endswith(":uy"))
            if bending < axial:
                continue
            s = [phi[index["n%d:ux" % (k * REFINEMENT)]] for k in SENSORS]
            big = max(s, key=abs)
            freqs.append(f)
            shapes.append([v / big for v in s])
            if len(freqs) == MODES:
                break
        assert len(freqs) == MODES, name
        freqs = [f * (1 + FREQ_NOISE * normal()) for f in freqs]
        shapes = [[v + SHAPE_NOISE * normal() for v in s] for s in shapes]
        states.append((state, freqs, shapes))
    several = len(states) > 1

    y = []
    y.append("# %s (examples/diagnosis/%s.yaml)." % (title, name))
    y.append("#")
    y.append("# A 2 m steel flat bar (60 x 15 mm), clamped at its base, modelled with 20")
    if several:
        y.append("# Euler-Bernoulli elements. Its \"measured\" modes in %s (the %d"
                 % (" and in ".join(st[0] for st in states), MODES))
        y.append("# lowest bending modes of each, %s) were" % (
            "with shapes at 10 ux sensors every 0.2 m" if with_shapes else "frequencies only"))
        y.append("# generated by make_examples.sh from 60-element truth models")
        y.append("# (%s, never read by the diagnosis) with" % ", ".join(
            "truth/%s.yaml" % truth for _, truth in STATES[name]))
    else:
        y.append("# Euler-Bernoulli elements. Its \"measured\" modes (the %d lowest bending" % MODES)
        y.append("# modes, %s) were" % ("with shapes at 10 ux sensors every 0.2 m"
                                        if with_shapes else "frequencies only"))
        y.append("# generated by make_examples.sh from a 60-element truth model")
        y.append("# (truth/%s.yaml, never read by the diagnosis) with" % name)
    for line in what:
        y.append("#   " + line)
    y.append("# and noise: %g %% on frequencies%s (seed %d)."
             % (100 * FREQ_NOISE,
                ", %g %% on shapes" % (100 * SHAPE_NOISE) if with_shapes else "", seed))
    y.append("# Run: femup diagnose examples/diagnosis/%s.yaml -o out/%s" % (name, name))
    y.append("# The truth: %s. README.md lists what femup diagnose finds." % expected)
    y.append("# Generated by make_examples.sh: edit the truth or the script, not this file.")
    y.append("name: diagnosis_%s" % name)
    y.append("description: \"%s\"" % title)
    y.append("model:")
    y.append("  type: cantilever")
    y.append("  length: 2.0")
    y.append("  elements: %d" % ELEMENTS)
    y.append("  section: {E: 210e9, A: 9.0e-4, I: 1.6875e-8, rho: 7850}")
    y.append("measurements:")
    for state, freqs, shapes in states:
        y.append("  - state: %s" % state)
        y.append("    frequencies_hz: [%s]" % ", ".join(num(f) for f in freqs))
        if with_shapes:
            y.append("    sensors: [%s]" % ", ".join("\"n%d:ux\"" % k for k in SENSORS))
            y.append("    shapes:")
            for s in shapes:
                y.append("      - [%s]" % ", ".join(num(v) for v in s))
    y.append("diagnosis:")
    y.append("  noise: {frequency: %g, shape: %g}" % (FREQ_NOISE, SHAPE_NOISE))
    if name in CANDIDATES:
        y.append("  candidates: [%s]" % ", ".join(CANDIDATES[name]))
    open("%s/%s.yaml" % (here, name), "w").write("\n".join(y) + "\n")
    print("wrote %s.yaml: %s Hz" % (name, "; ".join(
        ", ".join("%.3f" % f for f in freqs) for _, freqs, _ in states)))
PY
