"""Blind cases for a cantilever diagnosis (femup's `cantilever` model).

The model femup diagnoses: a clamped steel or aluminium bar of rectangular
section, 1-4 m long and slender (length over radius of gyration 150-500), of
20 Euler-Bernoulli elements with consistent mass, as an engineer models a test
bar or a pile. The truth is frame2d.py's: Timoshenko elements (kappa 5/6) with
rotary inertia in the mass, 60 of them, and one of these effects, none of which
is a change the diagnosis's families make exactly:
  added_mass          water's added mass a rho A per metre up to a depth of
                      0.3-0.95 L, fading linearly to nothing over the top
                      0-20 % of that depth (the families fit a sharp or faded
                      level of their own form);
  support_flexibility the base on a translational spring 3 EI / (L^3 a u_t) and
                      a rotational one EI / (L a u_r), u_t and u_r log-uniform
                      in [0.2, 5] apart (a soil's two stiffnesses are not one
                      number);
  attached_mass       a point mass a rho A L with a rotary inertia (radius of
                      gyration 0-5 % of L) at a truth node at 0.2-1.0 L, most
                      of them between the model's nodes;
  stiffness_loss      E I times 1 - a over a band 5-20 % of L wide anywhere
                      along the bar (the model's instances are its elements);
  material_scaling    E times 1 +- a;
  none.
Sizes by the largest relative frequency shift in noise units (cases.py).
Sensors: ux at 4-10 of the model's nodes, the tip always among them; 2-5 modes,
a third of the cases without shapes.

femup's node numbering (femup/core/fe/builders.h): n0 at the base, nK at
K L / 20; element eK between n(K-1) and nK.
"""
import math

import numpy as np

from cases import draw_target, largest_shift, measured, measurements_yaml, size_for_shift
from frame2d import Frame

KINDS = ["none", "added_mass", "support_flexibility", "attached_mass", "stiffness_loss",
         "material_scaling"]
ELEMENTS = 20  # the model's
PARTS = 3  # truth elements per model element
MATERIALS = [dict(name="steel", E=210e9, G=81e9, rho=7850.0),
             dict(name="aluminium", E=70e9, G=26e9, rho=2700.0)]


def random_bar(rng):
    """A slender rectangular bar: L 1-4 m, L / r 150-500, width 2-6 times the
    thickness (bending about the thin axis)."""
    m = MATERIALS[int(rng.integers(0, len(MATERIALS)))]
    L = float(rng.uniform(1.0, 4.0))
    t = math.sqrt(12.0) * L / float(rng.uniform(150.0, 500.0))
    b = t * float(rng.uniform(2.0, 6.0))
    return dict(material=m["name"], E=m["E"], G=m["G"], rho=m["rho"], length=L,
                thickness=t, width=b, A=b * t, I=b * t ** 3 / 12.0)


class Truth:
    def __init__(self, p, effect=None, a=0.0):
        self.p = p
        f = Frame()
        L, n = p["length"], ELEMENTS * PARTS
        base = f.add_node(0.0, 0.0)
        E = p["E"] * (effect.e_factor(a) if effect else 1.0)
        top = f.add_node(0.0, L)
        self.elements, self.nodes = f.add_member(base, top, n, E=E, G=p["G"], A=p["A"],
                                                 I=p["I"], rho=p["rho"], kappa=5.0 / 6.0)
        if effect is not None and effect.kind == "support_flexibility" and a > 0:
            ei = p["E"] * p["I"]
            f.fixed |= {(base, 1)}
            f.springs.append((base, 0, 3 * ei / (L ** 3 * a * effect.u_t)))
            f.springs.append((base, 2, ei / (L * a * effect.u_r)))
        else:
            f.fixed |= {(base, 0), (base, 1), (base, 2)}
        if effect is not None:
            effect.apply(self, f, a)
        self.frame = f

    def modes(self, count, sensors):
        """Frequencies and ux shapes at the model nodes `sensors` (indices)."""
        freqs, V = self.frame.modes(count)
        rows = np.array([[V[3 * self.nodes[PARTS * k], k2] for k in sensors]
                         for k2 in range(count)])
        return freqs, rows


class Effect:
    def __init__(self, kind, rng, p):
        self.kind = kind
        self.detail = {}
        L = p["length"]
        if kind == "added_mass":
            self.depth = float(rng.uniform(0.3, 0.95)) * L
            self.fade = float(rng.uniform(0.0, 0.2)) * self.depth
            self.a_max = 2.0  # added mass per metre over the bar's
            self.detail = dict(depth=self.depth, fade=self.fade)
        elif kind == "support_flexibility":
            self.u_t = math.exp(float(rng.uniform(math.log(0.2), math.log(5.0))))
            self.u_r = math.exp(float(rng.uniform(math.log(0.2), math.log(5.0))))
            self.a_max = 2.0
            self.detail = dict(u_t=self.u_t, u_r=self.u_r)
        elif kind == "attached_mass":
            self.at = int(rng.integers(int(0.2 * ELEMENTS * PARTS), ELEMENTS * PARTS + 1))
            self.radius = float(rng.uniform(0.0, 0.05)) * L
            self.a_max = 1.0  # the mass over the bar's
            self.detail = dict(x=self.at * L / (ELEMENTS * PARTS), radius=self.radius)
        elif kind == "stiffness_loss":
            n = ELEMENTS * PARTS
            width = int(rng.integers(max(1, round(0.05 * n)), round(0.2 * n) + 1))
            start = int(rng.integers(0, n - width + 1))
            self.band = (start, start + width)
            self.a_max = 0.9
            self.detail = dict(x0=start * L / n, x1=(start + width) * L / n)
        elif kind == "material_scaling":
            self.sign = 1 if rng.random() < 0.5 else -1
            self.a_max = 0.3
        else:
            self.a_max = 0.0
        self.expected = kind

    def e_factor(self, a):
        return 1 + self.sign * a if self.kind == "material_scaling" else 1.0

    def apply(self, truth, f, a):
        p = truth.p
        rho_a = p["rho"] * p["A"]
        if self.kind == "added_mass":
            for e in truth.elements:
                el = f.elements[e]
                z = 0.5 * (f.xy[el["n1"]][1] + f.xy[el["n2"]][1])
                full = self.depth - self.fade
                w = 1.0 if z <= full else (max(0.0, (self.depth - z) / self.fade)
                                           if self.fade > 0 else 0.0)
                el["line_mass"] += a * rho_a * w
        elif self.kind == "attached_mass":
            m = a * rho_a * p["length"]
            f.point_masses.append((truth.nodes[self.at], m, m * self.radius ** 2))
        elif self.kind == "stiffness_loss":
            for e in truth.elements[self.band[0]:self.band[1]]:
                f.elements[e]["I"] *= 1 - a

    def regions(self, p):
        """The model regions a right verdict may name."""
        le = p["length"] / ELEMENTS
        if self.kind == "added_mass":
            return ["below the water level"]
        if self.kind == "support_flexibility":
            return ["supports"]
        if self.kind == "material_scaling":
            return ["all elements"]
        if self.kind == "attached_mass":
            x = self.detail["x"]
            # Its nodes within an element's length, and the segments within
            # half of one (femup's instances "node nK" and "nJ-nK").
            nodes = ["node n%d" % k for k in range(1, ELEMENTS + 1) if abs(k * le - x) <= le]
            segs = ["n%d-n%d" % (k - 1, k) for k in range(1, ELEMENTS + 1)
                    if max((k - 1) * le - x, x - k * le, 0.0) <= 0.5 * le]
            return sorted(nodes, key=lambda r: abs(int(r[6:]) * le - x)) + segs
        if self.kind == "stiffness_loss":
            x0, x1 = self.detail["x0"], self.detail["x1"]
            els = [k for k in range(1, ELEMENTS + 1) if (k - 1) * le < x1 - 1e-9 and
                   k * le > x0 + 1e-9]
            mid = 0.5 * (x0 + x1)
            els.sort(key=lambda k: abs((k - 0.5) * le - mid))
            return ["element e%d" % k for k in els]
        return [""]

    def describe(self, p, a):
        if self.kind == "added_mass":
            return "added mass %.3g rho A per metre to %.3f m, fading over %.3f m" % (
                a, self.depth, self.fade)
        if self.kind == "support_flexibility":
            return "base springs: translation 3 EI / (L^3 %.3g), rotation EI / (L %.3g)" % (
                a * self.u_t, a * self.u_r)
        if self.kind == "attached_mass":
            return "%.3g kg at %.3f m, radius of gyration %.3f m" % (
                a * p["rho"] * p["A"] * p["length"], self.detail["x"], self.radius)
        if self.kind == "stiffness_loss":
            return "EI lost %.3g over %.3f-%.3f m" % (a, self.detail["x0"], self.detail["x1"])
        if self.kind == "material_scaling":
            return "E factor %.4f" % self.e_factor(a)
        return "no effect"


def make_case(rng, name, design="mixed", noise_free=False, floors=None, foundation="clamped"):
    p = random_bar(rng)
    kind = KINDS[int(rng.integers(0, len(KINDS)))]
    modes = int(rng.integers(3, 6)) if design == "informative" else int(rng.integers(2, 6))
    shapes = True if design == "informative" else rng.random() < 2 / 3
    fnoise = [0.001, 0.002, 0.005][int(rng.integers(0, 3))]
    snoise = [0.01, 0.02, 0.05][int(rng.integers(0, 3))]
    count = int(rng.integers(4, 11))
    sensors = sorted([int(k) for k in rng.choice(np.arange(1, ELEMENTS), count - 1,
                                                 replace=False)] + [ELEMENTS])
    effect = Effect(kind, rng, p)
    target = draw_target(rng)
    nominal = Truth(p)
    f0, _ = nominal.modes(modes, sensors)
    a = 0.0
    if kind != "none":
        a = size_for_shift(
            lambda x: largest_shift(Truth(p, effect, x).modes(modes, sensors)[0], f0, fnoise),
            effect.a_max, target)
    truth = Truth(p, effect, a) if kind != "none" else nominal
    f1, S1 = truth.modes(modes, sensors)
    achieved = largest_shift(f1, f0, fnoise) if kind != "none" else 0.0
    freqs, rows = measured(rng, f1, [S1[k] / np.max(np.abs(S1[k])) for k in range(modes)],
                           fnoise, snoise, noise_free)
    labels = ["n%d:ux" % k for k in sensors]
    study = dict(name=name, p=p, frequencies=freqs, sensors=labels,
                 shapes=rows if shapes else None, frequency_noise=fnoise, shape_noise=snoise)
    regions = effect.regions(p)
    truth_rec = dict(name=name, kind=effect.expected, truth_kind=kind, region=regions[0],
                     regions=regions, size=a, description=effect.describe(p, a),
                     detail=effect.detail, shift_in_noise=achieved,
                     target_shift_in_noise=target, modes=modes, sensors=len(labels),
                     shapes=bool(shapes), frequency_noise=fnoise, shape_noise=snoise,
                     building=dict(p, storeys=1), nominal_gap=nominal_gap(p, f0, modes))
    return study, truth_rec


def nominal_gap(p, f_truth, modes):
    """rms relative frequency error of femup's model against the undamaged
    truth, from a frame2d bar built as femup builds it (Euler-Bernoulli, 20
    elements): a close stand-in for femup's own numbers."""
    f = Frame()
    base = f.add_node(0.0, 0.0)
    top = f.add_node(0.0, p["length"])
    f.add_member(base, top, ELEMENTS, E=p["E"], G=0.0, A=p["A"], I=p["I"], rho=p["rho"])
    f.fixed |= {(base, 0), (base, 1), (base, 2)}
    fm, _ = f.modes(modes)
    return float(np.sqrt(np.mean((fm / f_truth - 1) ** 2)))


def study_yaml(s):
    p = s["p"]
    lines = [
        "# A blind case of validation/blind_structures (cantilever suite): a %s" % p["material"],
        "# bar's model and the bar's measured modes.",
        "name: %s" % s["name"],
        "model:",
        "  type: cantilever",
        "  length: %.10g" % p["length"],
        "  elements: %d" % ELEMENTS,
        "  section: {E: %.10g, A: %.10g, I: %.10g, rho: %.10g}" % (
            p["E"], p["A"], p["I"], p["rho"]),
    ]
    lines += measurements_yaml(s, quote_sensors=True)
    return "\n".join(lines) + "\n"
