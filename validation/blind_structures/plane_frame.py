"""Blind cases for a plane-frame diagnosis (femup's `plane_frame` model).

The model femup diagnoses: a 1-4 storey, 1-3 bay steel moment frame of
Euler-Bernoulli members, two elements per member, the slab's mass smeared into
the beams' density, rigid joints, clamped bases (a `plane_frame` study model).
The truth is frame2d.py's: Timoshenko members (shear area 0.45 A, an I-section's
web), eight elements per member, consistent mass with rotary inertia, the slab
as a line mass, and the effects below, none of which is a change the model's
families make exactly:
  joint flexibility   both ends of one beam joined to their columns by
                      rotational springs (a bolted end plate, not a weld):
                      the diagnosis should name a stiffness loss of that beam;
  member damage       one column or beam loses bending stiffness over a zone of
                      10-50 % of its length (a dent, a crack, corrosion):
                      a stiffness loss of that member;
  added floor mass    a machine (a point mass) somewhere along one beam, or extra
                      mass along the whole beam (storage): an attached mass at a
                      node of that beam (either end or its middle);
  material_scaling    E of every member times s;
  soft_foundation     (with --foundation springs only) the column bases sit on
                      rotational springs that the model has too, at the
                      engineer's estimate (2-20 times a column's 4 E I / h);
                      the real ones are softer, each base by its own factor
                      (k / (1 + a u), u uniform in 0.5-1.5: soil under one
                      footing is not soil under the next), which the model's
                      support_flexibility (one factor for all) does not make
                      exactly: support_flexibility;
  none.
With --foundation springs every case's model and truth stand on those springs
(so their presence says nothing about the answer), and soft_foundation joins
the kinds. With --foundation soft the model is clamped, as an engineer who
takes the foundation as rigid would model it, and so is every truth but
soft_foundation's, whose column bases stand on rotational springs (horizontal
and vertical held) of k_c = (4 E I / h) / (a u_c), a column's own end stiffness
over a, u_c uniform in 0.5-1.5 per base: the model's support_flexibility
releases every restrained direction of every base by one factor, so this is
not its form either.
Sizes by the largest relative frequency shift in noise units, as for the shear
buildings. Sensors: horizontal (ux) at some joints, vertical (uy) at some beam
middles; 3-5 modes, some cases without shapes.

femup's node numbering (femup/core/fe/plane_frame.h): the joints column line by column
line bottom up, then each member's inner node, storey by storey (columns left
to right, then beams). Members are named s<storey>:col<line> and
s<storey>:beam<bay>.
"""

import numpy as np

from cases import draw_target, largest_shift, measured, measurements_yaml, size_for_shift
from frame2d import Frame

KINDS = ["none", "joint_flexibility", "member_damage", "added_floor_mass", "material_scaling"]
KINDS_ON_SPRINGS = KINDS + ["soft_foundation"]
# The family each truth should be named by.
EXPECTED_KIND = {"none": "none", "joint_flexibility": "stiffness_loss",
                 "member_damage": "stiffness_loss", "added_floor_mass": "attached_mass",
                 "material_scaling": "material_scaling",
                 "soft_foundation": "support_flexibility"}
E_STEEL, G_STEEL, RHO_STEEL = 210e9, 81e9, 7850.0
PARTS = 8  # truth elements per member (even: a node at each middle)
MODEL_PARTS = 2  # the model's elements per member (the study's elements_per_member)


def model_labels(S, B):
    """femup's node labels: joints[(line, level)], middles[(storey, member)]."""
    joints = {}
    for c in range(B + 1):
        for j in range(1, S + 1):
            joints[(c, j)] = "n%d" % (c * S + j)
    middles = {}
    k = (B + 1) * S + 1
    for s in range(1, S + 1):
        for c in range(B + 1):
            middles[(s, "col%d" % (c + 1))] = "n%d" % k
            k += 1
        for b in range(B):
            middles[(s, "beam%d" % (b + 1))] = "n%d" % k
            k += 1
    return joints, middles


def random_frame(rng, foundation="clamped"):
    """A light steel frame whose members are slender enough for an engineer to
    model them without shear deformation: columns (HE-like, A = 0.9 r^2) of
    slenderness L / r 55-90, beams (IPE-like, A = 0.35 r^2) of 35-60, so the
    Timoshenko truth differs from the Euler-Bernoulli model by 0.2-2 % in
    frequency (the shear term 12 E I / (kappa G A L^2) of 0.01-0.06)."""
    S = int(rng.integers(1, 5))
    B = int(rng.integers(1, 4))
    h = float(rng.uniform(3.0, 4.5))
    L = float(rng.uniform(4.0, 8.0))
    rc = h / float(rng.uniform(55.0, 90.0))
    rb = L / float(rng.uniform(35.0, 60.0))
    Ac, Ab = 0.9 * rc * rc, 0.35 * rb * rb
    p = dict(storeys=S, bays=B, storey_height=h, bay_width=L, column_I=Ac * rc * rc,
             column_A=Ac, beam_I=Ab * rb * rb, beam_A=Ab,
             slab_line_mass=float(rng.uniform(500.0, 2500.0)))
    if foundation == "springs":
        p["base_rotation"] = float(rng.uniform(2.0, 20.0)) * 4 * E_STEEL * p["column_I"] / h
    return p


def add_bases(f, p, B, L, soften=None, springs=None):
    """Column base nodes: clamped, or on rotational springs k (each divided by
    soften[c] when given), or on the given rotational springs[c]."""
    base = [f.add_node(c * L, 0.0) for c in range(B + 1)]
    for c in range(B + 1):
        if "base_rotation" in p or springs is not None:
            f.fixed |= {(base[c], 0), (base[c], 1)}
            if springs is not None:
                k = springs[c]
            else:
                k = p["base_rotation"] / (soften[c] if soften is not None else 1.0)
            f.springs.append((base[c], 2, k))
        else:
            f.fixed |= {(base[c], 0), (base[c], 1), (base[c], 2)}
    return base


class Truth:
    def __init__(self, p, effect=None, a=0.0):
        self.p = p
        S, B, h, L = p["storeys"], p["bays"], p["storey_height"], p["bay_width"]
        E = E_STEEL * (effect.e_factor(a) if effect else 1.0)
        f = Frame()
        self.joint = {}
        soften, springs = None, None
        if effect is not None and effect.kind == "soft_foundation":
            if "base_rotation" in p:
                soften = [1 + a * u for u in effect.spread]
            elif a > 0:  # a clamped model: springs only under the truth
                springs = [4 * E_STEEL * p["column_I"] / h / (a * u) for u in effect.spread]
        base = add_bases(f, p, B, L, soften, springs)
        for c in range(B + 1):
            for j in range(1, S + 1):
                self.joint[(c, j)] = f.add_node(c * L, j * h)
        self.middle = {}
        col = dict(E=E, G=G_STEEL, A=p["column_A"], I=p["column_I"], rho=RHO_STEEL, kappa=0.45)
        beam = dict(E=E, G=G_STEEL, A=p["beam_A"], I=p["beam_I"], rho=RHO_STEEL, kappa=0.45,
                    line_mass=p["slab_line_mass"])
        self.members = {}
        for s in range(1, S + 1):
            for c in range(B + 1):
                a0 = base[c] if s == 1 else self.joint[(c, s - 1)]
                els, nodes = f.add_member(a0, self.joint[(c, s)], PARTS, **col)
                self.members[(s, "col%d" % (c + 1))] = els
                self.middle[(s, "col%d" % (c + 1))] = nodes[PARTS // 2]
            for b in range(B):
                left, right = self.joint[(b, s)], self.joint[(b + 1, s)]
                if effect is not None and effect.kind == "joint_flexibility" and \
                        effect.member == (s, "beam%d" % (b + 1)):
                    kr = E_STEEL * p["beam_I"] / L / a if a > 0 else None
                    if kr is not None:
                        left = f.semi_rigid_end(left, kr)
                        right = f.semi_rigid_end(right, kr)
                els, nodes = f.add_member(left, right, PARTS, **beam)
                self.members[(s, "beam%d" % (b + 1))] = els
                self.middle[(s, "beam%d" % (b + 1))] = nodes[PARTS // 2]
        if effect is not None:
            effect.apply(self, f, a)
        self.frame = f

    def modes(self, count, sensors):
        """Frequencies and shapes at sensors [(node, dof)] of the lowest modes."""
        freqs, V = self.frame.modes(count)
        shapes = np.array([[V[3 * n + d, k] for (n, d) in sensors] for k in range(count)])
        return freqs, shapes


class Effect:
    def __init__(self, kind, rng, p):
        self.kind = kind
        S, B = p["storeys"], p["bays"]
        self.member = None
        self.detail = {}
        if kind == "joint_flexibility":
            self.member = (int(rng.integers(1, S + 1)), "beam%d" % int(rng.integers(1, B + 1)))
            self.a_max = 50.0  # beam EI/L over k_r
        elif kind == "member_damage":
            s = int(rng.integers(1, S + 1))
            if rng.random() < 0.5:
                self.member = (s, "col%d" % int(rng.integers(1, B + 2)))
            else:
                self.member = (s, "beam%d" % int(rng.integers(1, B + 1)))
            width = int(rng.integers(1, PARTS // 2 + 1))  # 1-4 of 8 elements
            start = int(rng.integers(0, PARTS - width + 1))
            self.zone = (start, start + width)
            self.a_max = 0.9
            self.detail = dict(zone=[start / PARTS, (start + width) / PARTS])
        elif kind == "added_floor_mass":
            self.member = (int(rng.integers(1, S + 1)), "beam%d" % int(rng.integers(1, B + 1)))
            self.point = rng.random() < 0.5
            self.at = int(rng.integers(1, PARTS))  # inner node of the beam
            self.a_max = 3.0  # extra mass / the beam's slab mass
            self.detail = dict(point=self.point, at=self.at / PARTS if self.point else None)
        elif kind == "material_scaling":
            self.sign = 1 if rng.random() < 0.5 else -1
            self.a_max = 0.5
        elif kind == "soft_foundation":
            self.spread = [float(u) for u in rng.uniform(0.5, 1.5, B + 1)]
            self.a_max = 50.0  # added compliance over the springs' own (mean)
            self.detail = dict(spread=self.spread)
        else:
            self.a_max = 0.0
        self.expected = EXPECTED_KIND[kind]

    def e_factor(self, a):
        return 1 + self.sign * a if self.kind == "material_scaling" else 1.0

    def apply(self, truth, f, a):
        p = truth.p
        if self.kind == "member_damage":
            els = truth.members[self.member]
            for e in els[self.zone[0]:self.zone[1]]:
                f.elements[e]["I"] *= 1 - a
        if self.kind == "added_floor_mass":
            els = truth.members[self.member]
            slab = p["slab_line_mass"] * p["bay_width"]
            if self.point:
                node = f.elements[els[self.at]]["n1"]
                f.point_masses.append((node, a * slab, 0.0))
            else:
                for e in els:
                    f.elements[e]["line_mass"] += a * p["slab_line_mass"]

    def regions(self, p):
        """The model regions a right verdict may name (kind, region)."""
        S, B = p["storeys"], p["bays"]
        joints, middles = model_labels(S, B)
        if self.kind in ("joint_flexibility", "member_damage"):
            s, m = self.member
            # A beam's semi-rigid ends: its stiffness loss, or its connections'
            # (femup's instance "connections of <beam>").
            extra = ["connections of s%d:%s" % (s, m)] if self.kind == "joint_flexibility" else []
            if self.kind == "member_damage":
                # The model's elements of the member the damaged zone reaches
                # (femup's instances "member <member> (from-to)", fractions from
                # the column's foot or the beam's left end).
                z0, z1 = self.detail["zone"]
                extra = ["member s%d:%s (%.2f-%.2f)" % (s, m, k / MODEL_PARTS,
                                                         (k + 1) / MODEL_PARTS)
                         for k in range(MODEL_PARTS)
                         if k / MODEL_PARTS < z1 and (k + 1) / MODEL_PARTS > z0]
            return ["element s%d:%s" % (s, m)] + extra
        if self.kind == "added_floor_mass":
            s, m = self.member
            b = int(m[4:]) - 1
            ends, mid = (joints[(b, s)], joints[(b + 1, s)]), middles[(s, m)]
            # The beam's nodes, and the masses between them on its two elements
            # (femup's segment instances, named "<node>-<node>").
            return (["node " + ends[0], "node " + ends[1], "node " + mid] +
                    ["%s-%s" % pair for e in ends for pair in ((e, mid), (mid, e))])
        if self.kind == "material_scaling":
            return ["all elements"]
        if self.kind == "soft_foundation":
            return ["supports"]
        return [""]

    def describe(self, p, a):
        if self.kind == "joint_flexibility":
            return "s%d:%s ends semi-rigid, beam EI/L over k_r = %.3g" % (*self.member, a)
        if self.kind == "member_damage":
            return "s%d:%s EI lost %.3g over %.2f-%.2f of its length" % (
                *self.member, a, *self.detail["zone"])
        if self.kind == "added_floor_mass":
            m = a * p["slab_line_mass"] * p["bay_width"]
            where = ("a point at %.2f of the beam" % self.detail["at"]) if self.point else \
                "along the beam"
            return "s%d:%s carries %.0f kg, %s" % (*self.member, m, where)
        if self.kind == "material_scaling":
            return "E factor %.4f" % self.e_factor(a)
        if self.kind == "soft_foundation":
            u = ", ".join("%.2f" % v for v in self.spread)
            if "base_rotation" not in p:
                return "base rotation springs (4 E I / h) / (%.3g u), u = %s" % (a, u)
            return "base springs softer: k / (1 + %.3g u), u = %s" % (a, u)
        return "no effect"


def make_case(rng, name, design="mixed", noise_free=False, floors=None, foundation="clamped"):
    p = random_frame(rng, foundation)
    S, B = p["storeys"], p["bays"]
    kinds = KINDS_ON_SPRINGS if foundation in ("springs", "soft") else KINDS
    kind = kinds[int(rng.integers(0, len(kinds)))]
    modes = int(rng.integers(3, 6)) if design == "informative" else int(rng.integers(2, 6))
    shapes = True if design == "informative" else rng.random() < 2 / 3
    fnoise = [0.001, 0.002, 0.005][int(rng.integers(0, 3))]
    snoise = [0.01, 0.02, 0.05][int(rng.integers(0, 3))]
    joints, middles = model_labels(S, B)
    # Sensors: ux at one joint per floor at least (random line), and at random
    # others; uy at half the beam middles (at least one).
    chosen = []
    for j in range(1, S + 1):
        lines = rng.permutation(B + 1)[: int(rng.integers(1, B + 2))]
        chosen += [("j", (int(c), j), 0) for c in sorted(lines)]
    beams = [(s, "beam%d" % (b + 1)) for s in range(1, S + 1) for b in range(B)]
    picked = rng.permutation(len(beams))[: max(1, len(beams) // 2)]
    chosen += [("m", beams[int(i)], 1) for i in sorted(picked)]
    effect = Effect(kind, rng, p)
    target = draw_target(rng)

    def sensors_of(t):
        return [(t.joint[key] if typ == "j" else t.middle[key], d) for typ, key, d in chosen]

    def truth_modes(t):
        return t.modes(modes, sensors_of(t))

    nominal = Truth(p)
    f0, _ = truth_modes(nominal)
    a = 0.0
    if kind != "none":
        a = size_for_shift(
            lambda x: largest_shift(truth_modes(Truth(p, effect, x))[0], f0, fnoise),
            effect.a_max, target)
    truth = Truth(p, effect, a) if kind != "none" else nominal
    f1, S1 = truth_modes(truth)
    achieved = largest_shift(f1, f0, fnoise) if kind != "none" else 0.0
    freqs, rows = measured(rng, f1, [S1[k] / np.max(np.abs(S1[k])) for k in range(modes)],
                           fnoise, snoise, noise_free)
    labels = [(joints[key] if typ == "j" else middles[key]) + (":ux" if d == 0 else ":uy")
              for typ, key, d in chosen]
    study = dict(name=name, p=p, frequencies=freqs, sensors=labels,
                 shapes=rows if shapes else None, frequency_noise=fnoise, shape_noise=snoise)
    truth_rec = dict(name=name, kind=effect.expected, truth_kind=kind,
                     region=effect.regions(p)[0], regions=effect.regions(p), size=a,
                     description=effect.describe(p, a), detail=effect.detail,
                     shift_in_noise=achieved, target_shift_in_noise=target, modes=modes,
                     sensors=len(labels), shapes=bool(shapes), frequency_noise=fnoise,
                     shape_noise=snoise, building=dict(p),
                     nominal_gap=nominal_gap(p, f0, modes))
    return study, truth_rec


def nominal_gap(p, f_truth, modes):
    """rms relative frequency error of femup's model against the undamaged truth,
    from a frame2d model built as femup builds it (Euler-Bernoulli, 2 elements,
    slab smeared): a close stand-in for femup's own numbers."""
    f = Frame()
    S, B, h, L = p["storeys"], p["bays"], p["storey_height"], p["bay_width"]
    base = add_bases(f, p, B, L)
    joint = {}
    for c in range(B + 1):
        for j in range(1, S + 1):
            joint[(c, j)] = f.add_node(c * L, j * h)
    for s in range(1, S + 1):
        for c in range(B + 1):
            f.add_member(base[c] if s == 1 else joint[(c, s - 1)], joint[(c, s)], 2, E=E_STEEL,
                         G=0.0, A=p["column_A"], I=p["column_I"], rho=RHO_STEEL)
        for b in range(B):
            f.add_member(joint[(b, s)], joint[(b + 1, s)], 2, E=E_STEEL, G=0.0, A=p["beam_A"],
                         I=p["beam_I"], rho=RHO_STEEL + p["slab_line_mass"] / p["beam_A"])
    fm, _ = f.modes(modes)
    return float(np.sqrt(np.mean((fm / f_truth - 1) ** 2)))


def study_yaml(s):
    p = s["p"]
    lines = [
        "# A blind case of validation/blind_structures (plane_frame suite): a steel",
        "# frame's model and the frame's measured modes.",
        "name: %s" % s["name"],
        "model:",
        "  type: plane_frame",
        "  storeys: %d" % p["storeys"],
        "  bays: %d" % p["bays"],
        "  storey_height: %.10g" % p["storey_height"],
        "  bay_width: %.10g" % p["bay_width"],
        "  elements_per_member: %d" % MODEL_PARTS,
        "  column: {E: %.10g, A: %.10g, I: %.10g, rho: %.10g}" % (
            E_STEEL, p["column_A"], p["column_I"], RHO_STEEL),
        "  beam: {E: %.10g, A: %.10g, I: %.10g, rho: %.10g}" % (
            E_STEEL, p["beam_A"], p["beam_I"], RHO_STEEL + p["slab_line_mass"] / p["beam_A"]),
    ]
    if "base_rotation" in p:
        lines.append("  base: {rotation: %.10g}" % p["base_rotation"])
    lines += measurements_yaml(s, quote_sensors=True)
    return "\n".join(lines) + "\n"
