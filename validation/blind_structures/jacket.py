"""Blind cases for a jacket diagnosis (femup's `space_frame` model, in water).

The model femup diagnoses: a `space_frame` study like
examples/diagnosis/jacket.yaml: 1 x 1 bays (widths 10-15 m along X and Y, drawn
apart so that the two sway modes are not one repeated pair), 3-4 levels of
8-12 m, X-braced faces, steel tubes with a diameter-to-wall ratio of 40 (legs
1.0-1.4 m, braces and horizontals 0.5-0.7 m), Euler-Bernoulli members, two
elements per member (at most 768 DOF), one block per level, water over the
lowest 1-2 levels (`water_depth`).

How femup models the water there (docs/space_frame.md, studies/src/study.cc):
`water_depth` only flags the wet elements (midpoint below it); femup's nominal
space-frame model carries no hydrodynamic added mass (a study cannot give one:
the generator's factors are fixed, `parameters` may only fix, bound or relate
them). The water is femup's `added_mass` family: one ratio times the transverse
consistent mass of rho A per metre on the wet groups, region "wet elements".
The other classes femup tries on a space frame: stiffness_loss per group
"element l<level>:<legs|braces|horizontals><block>", attached_mass at the top
level's leg joints ("node n<k>"), material_scaling ("all elements") and none;
support_flexibility does not apply (the bases are clamped, without DOFs).

The truth is jacket3d.py's (frame3d's elements, not femup's): Timoshenko
members (shear coefficient 0.5), four elements per member, consistent mass with
rotary inertia, and, on the wet elements, the water by the law femup's family
uses (transverse only, on elements whose midpoint is below the water line).
Because femup's nominal model is dry, the truth's clean-tube water is, by
default (`water="as_model"`), left out as well, so that a "none" truth is what
the engineer's model says; only the water an effect adds (marine growth's
wider diameter) is there. With `water="full"` (run_suite.py --jacket-water
full) every truth also carries the potential-flow water of its clean tubes
(Ca 1, rho_w 1025 kg/m^3): femup's dry model then sees a large added mass in
every case (a form error of the study, not of the structure), and an
`added_mass` verdict on a "none" truth is what that water makes.

The effects (none is exactly a change femup's families make):
  marine_growth     a growth layer (density 1100-1400 kg/m^3) on every wet
                    element: its mass moves in all directions, and the
                    hydrodynamic added mass (transverse) grows with the grown
                    diameter D + 2 th by Ca rho_w pi ((D + 2 th)^2 - D^2) / 4;
                    in half the cases it thins linearly towards the surface
                    (to 20-70 % of its seabed thickness there). The size is the
                    seabed thickness, at most 150 mm: added_mass, "wet elements";
  brace_damage      ONE brace member (half of one X) loses axial and bending
                    stiffness (E times 1 - a) over 1 or 2 of its 4 elements
                    (25 or 50 % of its length: a dent or crack zone), or, in a
                    quarter of these cases, is severed-like (a = 0.9 over that
                    zone whatever the drawn shift): stiffness_loss of that
                    brace, "member brace n<a>-n<b>" (femup's name), or of the
                    group it belongs to, "element l<k>:braces1";
  deck_mass         a piece of equipment (a point mass with rotary inertia
                    m b^2 / 6, b 3-8 m) on the top level, at a leg joint or at
                    a quarter point of a top horizontal: attached_mass at that
                    joint, or at either end joint of that horizontal or
                    between its nodes (femup's segments "n<a>-n<inner>");
  material_scaling  E of every member times s (G, the shear and torsion
                    modulus, kept): material_scaling, "all elements";
  none.
  soft_foundation   (with --foundation springs only) every jacket, model and
                    truth, stands on springs under its legs (femup's
                    `model.base`: horizontal, vertical, rocking and torsion, at
                    the engineer's estimate of 2-20 times the leg's own
                    stiffness in that direction: 12 E I / h^3, E A / h,
                    4 E I / h, G J / h); the real ones are softer, each
                    direction by its own factor (k / (1 + a u), u uniform in
                    0.5-1.5: a pile group is not equally soft in shear, axially
                    and in rocking), which the model's support_flexibility (one
                    compliance ratio for all its springs) does not make exactly:
                    support_flexibility, "supports".
With the default --foundation clamped the bases are clamped in model and
truth; femup still tries support_flexibility, releasing the clamped feet
(springs on every restrained direction, condensed out), so a verdict naming it
is a false one here.

Sizes by the largest relative frequency shift in noise units (cases.py), as
for the other suites. Measurements: 4-6 modes, ux and uy at the leg joints
(all, or 2-4 of the 4 legs per level), a third of the cases frequencies only
(all with --design informative: with shapes), noise 0.1-0.5 % / 1-5 %.
"""
import numpy as np

import frame3d
from cases import draw_target, largest_shift, measured, measurements_yaml, size_for_shift
from jacket3d import Jacket

KINDS = ["none", "marine_growth", "brace_damage", "deck_mass", "material_scaling"]
KINDS_ON_SPRINGS = KINDS + ["soft_foundation"]
EXPECTED_KIND = {"none": "none", "marine_growth": "added_mass",
                 "brace_damage": "stiffness_loss", "deck_mass": "attached_mass",
                 "material_scaling": "material_scaling",
                 "soft_foundation": "support_flexibility"}
# femup's base spring directions, and jacket3d's six DOFs each one sets.
BASE_DIRECTIONS = {"horizontal": (0, 1), "vertical": (2,), "rocking": (3, 4), "torsion": (5,)}
PARTS = 4  # truth elements per member
MODEL_PARTS = 2  # femup's elements per member in the study files (study_yaml)
RHO_W, CA = 1025.0, 1.0


def base_springs(base):
    """femup's `model.base` as jacket3d's six stiffnesses at every foot."""
    k = [0.0] * 6
    for name, dofs in BASE_DIRECTIONS.items():
        for d in dofs:
            k[d] = base[name]
    return tuple(k)


def random_base(rng, p):
    """Springs under the legs at an engineer's estimate: 2-20 times the leg's
    own stiffness over one level in each direction."""
    leg = frame3d.tube(p["legs"]["diameter"], p["legs"]["wall"])
    E, G, h = 210e9, 210e9 / 2.6, p["level_height"]
    own = dict(horizontal=12 * E * leg["Iy"] / h ** 3, vertical=E * leg["A"] / h,
               rocking=4 * E * leg["Iy"] / h, torsion=G * leg["J"] / h)
    return {name: float(k * 10 ** rng.uniform(np.log10(2), np.log10(20)))
            for name, k in own.items()}


def random_jacket(rng):
    """The case's structure, as femup's study model keys."""
    levels = int(rng.integers(3, 5))
    h = float(rng.uniform(8.0, 12.0))
    wet_levels = int(rng.integers(1, 3))
    dl, db = float(rng.uniform(1.0, 1.4)), float(rng.uniform(0.5, 0.7))
    return dict(type="space_frame", bays_x=1, bays_y=1, levels=levels, level_height=h,
                bay_width_x=float(rng.uniform(10.0, 15.0)),
                bay_width_y=float(rng.uniform(10.0, 15.0)), elements_per_member=2,
                blocks_per_level=1, bracing="x",
                water_depth=float(h * (wet_levels + rng.uniform(-0.1, 0.2))),
                legs=dict(diameter=dl, wall=dl / 40), braces=dict(diameter=db, wall=db / 40),
                horizontals=dict(diameter=db, wall=db / 40))


def label_of(jacket):
    """frame3d node -> femup's label "n<k>"."""
    return {node: name for name, node in jacket.labels.items()}


def members(jacket):
    """The jacket's members in femup's order: lists of PARTS element dicts (each
    member is meshed into consecutive elements)."""
    els = jacket.frame.elements
    return [els[i:i + PARTS] for i in range(0, len(els), PARTS)]


class Truth:
    """The truth's jacket (jacket3d, Timoshenko, PARTS elements per member) with
    `effect` of size a."""

    def __init__(self, p, effect=None, a=0.0, water="as_model"):
        self.p = p
        fields = dict(p, elements_per_member=PARTS)
        base = fields.pop("base", None)
        j = Jacket(**fields, base_springs=base_springs(base) if base else None,
                   added_mass_ratio=None if water == "full" else 0.0, Ca=CA, rho_w=RHO_W)
        self.jacket = j
        if effect is not None and a > 0:
            effect.apply(self, a)

    def modes(self, count, sensors):
        f, V = self.jacket.modes(count)
        rows = np.array([[V[self.jacket.dof(s), k] for s in sensors] for k in range(count)])
        return f, rows


class Effect:
    def __init__(self, kind, rng, p):
        self.kind = kind
        self.detail = {}
        L = p["levels"]
        if kind == "marine_growth":
            self.density = float(rng.uniform(1100.0, 1400.0))
            self.surface = float(rng.uniform(0.2, 0.7)) if rng.random() < 0.5 else 1.0
            self.a_max = 0.15  # seabed thickness (m)
            self.detail = dict(density=self.density, surface_fraction=self.surface)
        elif kind == "brace_damage":
            # Member index among the braces of the chosen level: 4 faces x 4
            # halves of the X each.
            self.level = int(rng.integers(1, L + 1))
            self.brace = int(rng.integers(0, 16))
            width = int(rng.integers(1, 3))  # 1-2 of 4 elements: 25 or 50 %
            start = int(rng.integers(0, PARTS - width + 1))
            self.zone = (start, start + width)
            self.severed = rng.random() < 0.25
            self.a_max = 0.9
            self.detail = dict(level=self.level, brace=self.brace,
                               zone=[start / PARTS, (start + width) / PARTS],
                               severed=self.severed)
        elif kind == "deck_mass":
            self.at_joint = rng.random() < 0.5
            if self.at_joint:
                self.corner = int(rng.integers(0, 4))
            else:
                self.horizontal = int(rng.integers(0, 4))
                self.quarter = int(rng.integers(1, PARTS))
            self.radius = float(rng.uniform(3.0, 8.0))
            self.a_max = 3.0  # the mass over the top level's steel mass
            self.detail = dict(at_joint=self.at_joint, side=self.radius)
        elif kind == "material_scaling":
            self.sign = 1 if rng.random() < 0.5 else -1
            self.a_max = 0.5
        elif kind == "soft_foundation":
            self.u = {name: float(rng.uniform(0.5, 1.5)) for name in BASE_DIRECTIONS}
            self.a_max = 50.0
            self.detail = dict(u=self.u)
        else:
            self.a_max = 0.0
        self.expected = EXPECTED_KIND[kind]

    # The members this effect acts on, from the truth's jacket.
    def _level_members(self, j, kind, level):
        tag = "l%d" % level
        return [m for m in members(j) if kind in m[0]["tags"] and tag in m[0]["tags"]]

    def _deck_node_and_ends(self, j):
        L = self.p_levels
        top = [j.joints[(i, jj, L)] for jj in range(2) for i in range(2)]
        if self.at_joint:
            node = top[self.corner]
            return node, [node]
        m = self._level_members(j, "horizontals", L)[self.horizontal]
        return m[self.quarter]["n1"], [m[0]["n1"], m[-1]["n2"]]

    def top_steel_mass(self, j):
        f = j.frame
        return sum(e["rho"] * e["A"] * f.element_length(e) for e in f.elements
                   if "l%d" % self.p_levels in e["tags"])

    def apply(self, truth, a):
        j, f = truth.jacket, truth.jacket.frame
        self.p_levels = truth.p["levels"]
        if self.kind == "marine_growth":
            depth = truth.p["water_depth"]
            for e in f.elements:
                if "wet" not in e["tags"]:
                    continue
                kind = next(k for k in ("legs", "braces", "horizontals") if k in e["tags"])
                D = j.sections[kind][1]
                z = 0.5 * (f.xyz[e["n1"]][2] + f.xyz[e["n2"]][2])
                th = a * (1 - (1 - self.surface) * min(max(z / depth, 0.0), 1.0))
                e["line_mass"] += frame3d.marine_growth_mass(D, th, self.density)
                e["added_mass"] += (frame3d.hydrodynamic_added_mass(D + 2 * th, CA, RHO_W) -
                                    frame3d.hydrodynamic_added_mass(D, CA, RHO_W))
        elif self.kind == "brace_damage":
            m = self._level_members(j, "braces", self.level)[self.brace]
            for e in m[self.zone[0]:self.zone[1]]:
                e["E"] *= 1 - a
        elif self.kind == "deck_mass":
            node, _ = self._deck_node_and_ends(j)
            mass = a * self.top_steel_mass(j)
            f.point_masses.append((node, mass, mass * self.radius ** 2 / 6))
        elif self.kind == "material_scaling":
            for e in f.elements:
                e["E"] *= 1 + self.sign * a
        elif self.kind == "soft_foundation":
            u = {d: self.u[name] for name, dofs in BASE_DIRECTIONS.items() for d in dofs}
            f.springs = [(node, d, k / (1 + a * u[d])) for node, d, k in f.springs]

    def regions(self, truth):
        """The model regions a right verdict may name."""
        j = truth.jacket
        self.p_levels = truth.p["levels"]
        if self.kind == "marine_growth":
            return ["wet elements"]
        if self.kind == "brace_damage":
            # Its level's brace group, or the member itself by femup's name
            # (a base end is its base joint "b<k>", clamped or on springs).
            m = self._level_members(j, "braces", self.level)[self.brace]
            lab, p = label_of(j), truth.p

            def name(n):
                if n in lab:
                    return lab[n]
                x, y, _ = j.frame.xyz[n]
                return "b%d" % (round(y / p["bay_width_y"]) * (p["bays_x"] + 1) +
                                round(x / p["bay_width_x"]) + 1)
            member = "member brace %s-%s" % (name(m[0]["n1"]), name(m[-1]["n2"]))
            # Or the part of it (femup's finite elements of the member, named by
            # their span from its first joint) that holds the damaged zone.
            z0, z1 = self.zone[0] / PARTS, self.zone[1] / PARTS
            parts = ["%s (%.2f-%.2f)" % (member, k / MODEL_PARTS, (k + 1) / MODEL_PARTS)
                     for k in range(MODEL_PARTS)
                     if z0 < (k + 1) / MODEL_PARTS and z1 > k / MODEL_PARTS]
            return ["element l%d:braces1" % self.level, member] + parts
        if self.kind == "deck_mass":
            lab = label_of(j)
            _, ends = self._deck_node_and_ends(j)
            out = ["node " + lab[n] for n in ends]
            if not self.at_joint:
                # Or a mass between the nodes of that horizontal in femup's
                # model: its two segments, to and from its inner node (the
                # model's one inner node per member is numbered after the
                # labelled joints, which are not the base's, and the X
                # centres, member by member, as in jacket3d).
                m = self._level_members(j, "horizontals", self.p_levels)[self.horizontal]
                index = next(i for i, x in enumerate(members(j)) if x[0] is m[0])
                joints = sum(1 for key in j.joints if key[2] > 0)
                inner = "n%d" % (joints + len(j.centres) + index + 1)
                out += ["%s-%s" % (lab[ends[0]], inner), "%s-%s" % (inner, lab[ends[1]])]
            return out
        if self.kind == "material_scaling":
            return ["all elements"]
        if self.kind == "soft_foundation":
            return ["supports"]
        return [""]

    def describe(self, truth, a):
        j = truth.jacket
        self.p_levels = truth.p["levels"]
        if self.kind == "marine_growth":
            return ("marine growth %.0f mm at the seabed (%s), %.0f kg/m^3, on the wet members"
                    % (1000 * a, "uniform" if self.surface == 1.0 else
                       "%.0f %% of it at the surface" % (100 * self.surface), self.density))
        if self.kind == "brace_damage":
            m = self._level_members(j, "braces", self.level)[self.brace]
            ends = label_of(j)
            a_n, b_n = m[0]["n1"], m[-1]["n2"]
            name = lambda n: ends.get(n, "base(%g,%g,%g)" % j.frame.xyz[n])  # noqa: E731
            return ("brace %s-%s of level %d: E x %.3g over %.2f-%.2f of its length%s" % (
                name(a_n), name(b_n), self.level, 1 - a, *self.detail["zone"],
                " (severed-like)" if self.severed else ""))
        if self.kind == "deck_mass":
            node, ends = self._deck_node_and_ends(j)
            lab = label_of(j)
            where = ("at joint %s" % lab[node]) if self.at_joint else \
                "at %d/4 of the top horizontal %s-%s" % (self.quarter, lab[ends[0]], lab[ends[1]])
            return "deck equipment %.0f kg %s, rotary inertia m (%.1f m)^2 / 6" % (
                a * self.top_steel_mass(j), where, self.radius)
        if self.kind == "material_scaling":
            return "E factor %.4f" % (1 + self.sign * a)
        if self.kind == "soft_foundation":
            return "foundation softer: " + ", ".join(
                "%s k / %.3g" % (name, 1 + a * u) for name, u in self.u.items())
        return "no effect"


def make_case(rng, name, design="mixed", noise_free=False, floors=None, foundation="clamped",
              water="as_model"):
    if foundation not in ("clamped", "springs"):
        raise ValueError("foundation: clamped or springs")
    if water not in ("as_model", "full"):
        raise ValueError("water: as_model or full")
    p = random_jacket(rng)
    kinds = KINDS
    if foundation == "springs":
        p["base"] = random_base(rng, p)
        kinds = KINDS_ON_SPRINGS
    L = p["levels"]
    kind = kinds[int(rng.integers(0, len(kinds)))]
    modes = int(rng.integers(4, 7))
    shapes = True if design == "informative" else rng.random() < 2 / 3
    fnoise = [0.001, 0.002, 0.005][int(rng.integers(0, 3))]
    snoise = [0.01, 0.02, 0.05][int(rng.integers(0, 3))]
    # Sensors: ux and uy at the leg joints, all of them or 2-4 legs per level.
    nominal = Truth(p, water=water)
    lab = label_of(nominal.jacket)
    every = rng.random() < 0.5
    sensors = []
    for k in range(1, L + 1):
        legs = [(i, jj) for jj in range(2) for i in range(2)]
        pick = range(4) if every else sorted(rng.permutation(4)[: int(rng.integers(2, 5))])
        for q in pick:
            node = lab[nominal.jacket.joints[(*legs[int(q)], k)]]
            sensors += [node + ":ux", node + ":uy"]
    effect = Effect(kind, rng, p)
    target = draw_target(rng)
    f0, _ = nominal.modes(modes, sensors)
    a = 0.0
    if kind != "none":
        if kind == "brace_damage" and effect.severed:
            a = 0.9
        else:
            a = size_for_shift(
                lambda x: largest_shift(Truth(p, effect, x, water).modes(modes, sensors)[0],
                                        f0, fnoise), effect.a_max, target)
    truth = Truth(p, effect, a, water) if kind != "none" else nominal
    f1, S1 = truth.modes(modes, sensors)
    achieved = largest_shift(f1, f0, fnoise) if kind != "none" else 0.0
    # Each shape scaled to 1 at its largest reading, signed so that its first
    # reading above a tenth of that is positive: ARPACK (frame3d above 600
    # DOFs) starts from a random vector of its own, so a mode's sign is its,
    # and a torsion mode's largest readings tie in size.
    def signed(v):
        big = np.max(np.abs(v))
        return v / big * np.sign(v[np.argmax(np.abs(v) > 0.1 * big)])
    freqs, rows = measured(rng, f1, [signed(S1[k]) for k in range(modes)], fnoise, snoise,
                           noise_free)
    # Measured frequencies in ascending order (femup's reader asks for it).
    order = np.argsort(freqs)
    freqs = [freqs[i] for i in order]
    rows = [rows[i] for i in order]
    study = dict(name=name, p=p, frequencies=freqs, sensors=sensors,
                 shapes=rows if shapes else None, frequency_noise=fnoise, shape_noise=snoise)
    regions = effect.regions(truth)
    truth_rec = dict(name=name, kind=effect.expected, truth_kind=kind, region=regions[0],
                     regions=regions, size=a, description=effect.describe(truth, a),
                     detail=effect.detail, shift_in_noise=achieved,
                     target_shift_in_noise=target, modes=modes, sensors=len(sensors),
                     shapes=bool(shapes), frequency_noise=fnoise, shape_noise=snoise,
                     water=water, building=dict(p, storeys=L),
                     nominal_gap=nominal_gap(p, f0, modes))
    return study, truth_rec


def model_jacket(p):
    """femup's model of the study rebuilt with jacket3d (Euler-Bernoulli, Hermite
    mass without rotary inertia, 2 elements per member, dry): a close stand-in
    for femup's own numbers (test_jacket3d: equal to 1e-8 on the example)."""
    fields = dict(p)
    base = fields.pop("base", None)
    return Jacket(**fields, base_springs=base_springs(base) if base else None, shear=False,
                  rotary=False, mass_kind="hermite", added_mass_ratio=0.0)


def nominal_gap(p, f_truth, modes):
    """rms relative frequency error of femup's model against the no-effect truth."""
    fm, _ = model_jacket(p).modes(modes)
    return float(np.sqrt(np.mean((fm / f_truth - 1) ** 2)))


def study_yaml(s):
    p = s["p"]
    tube = lambda t: "{diameter: %.10g, wall: %.10g}" % (t["diameter"], t["wall"])  # noqa: E731
    lines = [
        "# A blind case of validation/blind_structures (jacket suite): a steel",
        "# jacket's model and its measured modes.",
        "name: %s" % s["name"],
        "model:",
        "  type: space_frame",
        "  bays_x: 1",
        "  bays_y: 1",
        "  levels: %d" % p["levels"],
        "  level_height: %.10g" % p["level_height"],
        "  bay_width_x: %.10g" % p["bay_width_x"],
        "  bay_width_y: %.10g" % p["bay_width_y"],
        "  elements_per_member: %d" % MODEL_PARTS,
        "  blocks_per_level: 1",
        "  bracing: x",
        "  water_depth: %.10g" % p["water_depth"],
        "  legs: %s" % tube(p["legs"]),
        "  braces: %s" % tube(p["braces"]),
        "  horizontals: %s" % tube(p["horizontals"]),
    ]
    if p.get("base"):
        lines.append("  base: {%s}" % ", ".join(
            "%s: %.10g" % (name, p["base"][name]) for name in BASE_DIRECTIONS))
    lines += measurements_yaml(s, quote_sensors=True)
    return "\n".join(lines) + "\n"
