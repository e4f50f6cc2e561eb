"""Blind cases for a shear-building (chain) diagnosis, made from plane frames.

The model femup diagnoses is what an engineer would write for a building: a
chain of floor masses on storey springs (a `chain` study model). The truth the
"measured" modes come from is a different thing altogether: a multi-bay plane
frame (frame2d.py: Timoshenko columns and beams with axial stiffness, consistent
mass with rotary inertia, slab mass along the beams, beams of finite stiffness),
so even an undamaged building differs from its chain model (form error).

The frames are shear buildings in the engineer's sense, not any frame: floors
10-100 times stiffer than the storey's columns (beam-to-column stiffness ratio),
and columns 100 times stiffer axially than their concrete section, so that the
global bending that column shortening causes in tall slender frames (which no
chain can represent: 5-15 % on the second to fourth modes of a 12-storey,
4-bay frame of real columns) stays out. What remains is the chain's real form
error: joint rotation, shear deformation and distributed mass of the columns,
the beams' mass and rotary inertia (0.1-1 % on the higher modes).

The chain is the frame's equivalent shear building, as an engineer derives it:
floor masses = the floor's slab and beams plus half the columns above and below;
storey stiffness = storey shear / inter-storey drift of the nominal frame under
an inverted-triangle lateral load.

Effects made in the frame (never in the chain):
  stiffness_loss       storey s: some of its columns cracked near their ends
                       (bending stiffness lost over an end zone of 15-50 % of the
                       column, at the bottom, the top or both);
  attached_mass        floor j: extra mass spread along one bay's beam or all of
                       the floor's beams (equipment, storage, a heavier slab);
  support_flexibility  rotational springs at every column base (a foundation
                       that is not fixed);
  material_scaling     every member's E times s (concrete stiffer or softer than
                       assumed);
  none.
With --design two_losses every case is two storeys damaged at once (the second's
loss a fraction 0.5-1 of the first's), for a diagnosis allowed pairs
(diagnosis.max_effects 2); the truth is "stiffness_loss+stiffness_loss" at
"element a + element b", in either order.
Each effect's size is set by the largest relative frequency shift it causes on
the measured modes, in multiples of the case's frequency noise (log-uniform in
[5, 50] for four cases in five, [1, 5] for the rest).

The chain model's names: spring k = storey k ("element k"), mass k = floor k
("node xk"), the ground spring is the support.
"""
import math

import numpy as np
import scipy.linalg as sl

from cases import (draw_target, largest_shift, measured, measurements_yaml, size_for_shift,
                   yaml_list)
from frame2d import Frame

KINDS = ["none", "stiffness_loss", "attached_mass", "support_flexibility", "material_scaling"]
E_CONCRETE = 30e9
RHO_CONCRETE = 2500.0


class Building:
    """A plane frame building: storeys x bays, with the nodes of each floor."""

    def __init__(self, p):
        self.p = p
        f = Frame()
        nb, ns = p["bays"], p["storeys"]
        h, L = p["storey_height"], p["bay_width"]
        self.joints = []  # joints[j][c]: node of column line c at level j (0 = ground)
        for j in range(ns + 1):
            self.joints.append([f.add_node(c * L, j * h) for c in range(nb + 1)])
        self.column_elements = []  # [storey][column] -> element indices (bottom first)
        Ec, bc = p["E"], p["column_width"]
        Ac, Ic = bc * bc, bc**4 / 12
        for s in range(ns):
            row = []
            for c in range(nb + 1):
                els, _ = f.add_member(
                    self.joints[s][c], self.joints[s + 1][c], p["column_parts"],
                    E=Ec, G=Ec / 2.4, A=Ac, I=Ic, rho=RHO_CONCRETE,
                    axial_area=Ac * p["column_axial_factor"])
                row.append(els)
            self.column_elements.append(row)
        bw, bd = p["beam_width"], p["beam_depth"]
        Ab, Ib = bw * bd, bw * bd**3 / 12
        self.beam_elements = []  # [floor j-1][bay] -> element indices
        for j in range(1, ns + 1):
            row = []
            for c in range(nb):
                els, _ = f.add_member(
                    self.joints[j][c], self.joints[j][c + 1], p["beam_parts"],
                    E=Ec, G=Ec / 2.4, A=Ab, I=Ib, rho=RHO_CONCRETE,
                    line_mass=p["slab_line_mass"])
                row.append(els)
            self.beam_elements.append(row)
        for c in range(nb + 1):
            base = self.joints[0][c]
            f.fixed |= {(base, 0), (base, 1)}
            if p.get("base_spring") is None:
                f.fixed.add((base, 2))
            else:
                f.springs.append((base, 2, p["base_spring"]))
        self.frame = f

    def floor_displacement(self, u, j):
        """Mean horizontal displacement of floor j's joints."""
        return float(np.mean([u[3 * n] for n in self.joints[j]]))

    def sway_modes(self, count):
        """The lowest `count` sway modes (most of their kinetic energy in the
        floors' horizontal motion): frequencies and floor displacements."""
        want = count + 8
        horizontal = None
        while True:
            freqs, V, M, free = self.frame.solve(min(want, self.frame.num_dofs() - 4))
            if horizontal is None:
                horizontal = (np.asarray(free) % 3 == 0).astype(float)
            Vf = V[free, :]
            total = np.einsum("ik,ik->k", Vf, M @ Vf)
            Vh = Vf * horizontal[:, None]
            sway = np.einsum("ik,ik->k", Vh, M @ Vh) / total
            picked = np.flatnonzero(sway > 0.5)[:count]
            if len(picked) == count:
                shapes = np.array([[self.floor_displacement(V[:, k], j)
                                    for j in range(1, self.p["storeys"] + 1)] for k in picked])
                return freqs[picked], shapes
            if want >= self.frame.num_dofs() - 4:
                raise RuntimeError("fewer sway modes than asked for")
            want *= 2

    def equivalent_chain(self):
        """Floor masses and storey springs of the equivalent shear building."""
        p, f = self.p, self.frame
        ns = p["storeys"]
        col_mass = RHO_CONCRETE * p["column_width"] ** 2 * p["storey_height"] * (p["bays"] + 1)
        beam_mass = (RHO_CONCRETE * p["beam_width"] * p["beam_depth"] + p["slab_line_mass"]) * (
            p["bay_width"] * p["bays"])
        masses = []
        for j in range(1, ns + 1):
            m = beam_mass + col_mass * (0.5 if j == ns else 1.0)
            masses.append(m)
        loads = {}
        for j in range(1, ns + 1):
            force = masses[j - 1] * j / (p["bays"] + 1)
            for n in self.joints[j]:
                loads[(n, 0)] = force
        u = f.static(loads)
        disp = [0.0] + [self.floor_displacement(u, j) for j in range(1, ns + 1)]
        springs = []
        for s in range(1, ns + 1):
            shear = sum(masses[j - 1] * j for j in range(s, ns + 1))
            springs.append(shear / (disp[s] - disp[s - 1]))
        return masses, springs


def random_building(rng, floors="flexible"):
    """floors: "flexible" (beam-to-column stiffness ratio 10-100) or "stiff"
    (1000-10000: nearly rigid floors, the chain's idealisation almost exact)."""
    storeys = int(rng.integers(3, 21))
    bays = int(rng.integers(1, 4))
    h = float(rng.uniform(3.0, 4.0))
    L = float(rng.uniform(5.0, 8.0))
    bc = float(rng.uniform(0.35, 0.6)) * (1.0 + 0.02 * storeys)  # taller: stockier columns
    # Beam-to-column stiffness ratio (EI_b / L) / (EI_c / h) in [10, 100]: floors
    # much stiffer than columns (beams with the slab), as a shear-building
    # idealisation presumes, but not rigid: the joints still rotate.
    lo, hi = (10.0, 100.0) if floors == "flexible" else (1000.0, 10000.0)
    ratio = float(math.exp(rng.uniform(math.log(lo), math.log(hi))))
    bw = 0.3 + 0.1 * float(rng.random())
    Ic = bc**4 / 12
    Ib = ratio * Ic / h * L
    bd = (12 * Ib / bw) ** (1 / 3)
    return dict(storeys=storeys, bays=bays, storey_height=h, bay_width=L,
                column_width=bc, beam_width=bw, beam_depth=bd, E=E_CONCRETE,
                slab_line_mass=float(rng.uniform(3e3, 8e3)), column_parts=4, beam_parts=2,
                beam_column_ratio=ratio, column_axial_factor=100.0)


class TwoLosses:
    """Two storeys damaged at once (design "two_losses"): the second storey's
    loss is a fixed fraction (0.5-1) of the first's, both grown together by
    the size `a` (monotone)."""

    def __init__(self, rng, p):
        self.kind = "stiffness_loss+stiffness_loss"
        self.first = Effect("stiffness_loss", rng, p)
        self.second = Effect("stiffness_loss", rng, p)
        while self.second.storey == self.first.storey:
            self.second = Effect("stiffness_loss", rng, p)
        self.ratio = float(rng.uniform(0.5, 1.0))
        self.a_max = 0.9
        low, high = sorted([self.first.storey, self.second.storey])
        self.region = "element %d + element %d" % (low, high)
        self.regions = [self.region, "element %d + element %d" % (high, low)]
        self.detail = dict(first=self.first.detail, second=self.second.detail,
                           ratio=self.ratio)

    def building(self, p, a):
        b = self.first.building(p, a)
        self.second.damage(b, p, a * self.ratio)
        return b

    def size_description(self, p, a):
        return "%s; %s" % (self.first.size_description(p, a),
                           self.second.size_description(p, a * self.ratio))


class Effect:
    """An effect in a Building at a size `a` in (0, a_max] (monotone)."""

    def __init__(self, kind, rng, p):
        self.kind = kind
        ns, nb = p["storeys"], p["bays"]
        self.detail = {}
        if kind == "stiffness_loss":
            self.storey = int(rng.integers(1, ns + 1))
            k = int(rng.integers(1, nb + 2))
            self.columns = sorted(rng.choice(nb + 1, size=k, replace=False).tolist())
            self.zone = float(rng.uniform(0.15, 0.5))
            self.ends = ["bottom", "top", "both"][int(rng.integers(0, 3))]
            self.a_max = 0.9
            self.detail = dict(storey=self.storey, columns=self.columns, zone=self.zone,
                               ends=self.ends)
            self.region = "element %d" % self.storey
        elif kind == "attached_mass":
            self.floor = int(rng.integers(1, ns + 1))
            self.bay = None if rng.random() < 0.5 else int(rng.integers(0, nb))
            self.a_max = 2.0  # extra line mass / the slab's
            self.detail = dict(floor=self.floor, bay=self.bay)
            self.region = "node x%d" % self.floor
        elif kind == "support_flexibility":
            self.a_max = 20.0  # column EI/h over the spring's stiffness
            self.region = "supports"
        elif kind == "material_scaling":
            self.sign = 1 if rng.random() < 0.5 else -1
            self.a_max = 0.5
            self.region = "all elements"
        else:
            self.a_max = 0
            self.region = ""

    def building(self, p, a):
        q = dict(p)
        if self.kind == "support_flexibility":
            Ic = p["column_width"] ** 4 / 12
            q["base_spring"] = p["E"] * Ic / p["storey_height"] / a
        if self.kind == "material_scaling":
            q["E"] = p["E"] * (1 + self.sign * a)
        b = Building(q)
        f = b.frame
        if self.kind == "stiffness_loss":
            self.damage(b, p, a)
        if self.kind == "attached_mass":
            bays = range(p["bays"]) if self.bay is None else [self.bay]
            extra = a * p["slab_line_mass"] * (p["bays"] / len(bays))
            for bay in bays:
                for e in b.beam_elements[self.floor - 1][bay]:
                    f.elements[e]["line_mass"] += extra
        return b

    def damage(self, b, p, a):
        """A stiffness loss's cracked column ends, made in Building b's frame."""
        f = b.frame
        parts = p["column_parts"]
        for c in self.columns:
            els = b.column_elements[self.storey - 1][c]
            for k, e in enumerate(els):
                centre = (k + 0.5) / parts
                hit = ((self.ends in ("bottom", "both") and centre < self.zone) or
                       (self.ends in ("top", "both") and centre > 1 - self.zone))
                if hit:
                    f.elements[e]["I"] *= 1 - a
            # A zone shorter than an element still damages the end element.
            if self.ends in ("bottom", "both") and self.zone < 0.5 / parts:
                f.elements[els[0]]["I"] *= 1 - a * self.zone * parts
            if self.ends in ("top", "both") and self.zone < 0.5 / parts:
                f.elements[els[-1]]["I"] *= 1 - a * self.zone * parts

    def size_description(self, p, a):
        if self.kind == "stiffness_loss":
            return "storey %d, columns %s, EI lost %.3g over the %s %.0f %%" % (
                self.storey, self.columns, a, self.ends, 100 * self.zone)
        if self.kind == "attached_mass":
            bays = p["bays"] if self.bay is None else 1
            m = a * p["slab_line_mass"] * p["bay_width"] * p["bays"]
            return "floor %d, %.0f kg on %s" % (self.floor, m, "all bays" if bays > 1 or
                                               self.bay is None else "bay %d" % (self.bay + 1))
        if self.kind == "support_flexibility":
            return "base rotational springs, EI_c/h over k_r = %.3g" % a
        if self.kind == "material_scaling":
            return "E factor %.4f" % (1 + self.sign * a)
        return "no effect"


def make_case(rng, name, design="mixed", noise_free=False, floors="flexible",
              foundation="clamped"):
    """One case: the study's data (chain model + measured modes) and its truth."""
    p = random_building(rng, floors)
    ns = p["storeys"]
    kind = KINDS[int(rng.integers(0, len(KINDS)))]
    if design == "two_losses":
        kind = "stiffness_loss+stiffness_loss"
    if design == "informative":
        modes = int(rng.integers(3, 6))
        shapes = True
    else:
        modes = int(rng.integers(2, 6))
        shapes = rng.random() < 2 / 3
    modes = min(modes, ns)
    nsens = int(rng.integers(min(3, ns), ns + 1))
    sensors = sorted(rng.choice(ns, size=nsens, replace=False).tolist())
    if ns - 1 not in sensors:  # the roof is always instrumented
        sensors[-1] = ns - 1
        sensors = sorted(set(sensors))
    fnoise = [0.001, 0.002, 0.005][int(rng.integers(0, 3))]
    snoise = [0.01, 0.02, 0.05][int(rng.integers(0, 3))]
    effect = TwoLosses(rng, p) if design == "two_losses" else Effect(kind, rng, p)
    target = draw_target(rng)
    nominal = Building(p)
    f0, _ = nominal.sway_modes(modes)
    masses, springs = nominal.equivalent_chain()
    a = 0.0
    if kind != "none":
        a = size_for_shift(
            lambda x: largest_shift(effect.building(p, x).sway_modes(modes)[0], f0, fnoise),
            effect.a_max, target)
    truth_building = effect.building(p, a) if kind != "none" else nominal
    f1, S1 = truth_building.sway_modes(modes)
    achieved = largest_shift(f1, f0, fnoise) if kind != "none" else 0.0
    freqs, shape_rows = measured(rng, f1, [(S1[k] / np.max(np.abs(S1[k])))[sensors]
                                           for k in range(modes)], fnoise, snoise, noise_free)
    study = dict(name=name, masses=masses, springs=springs, frequencies=freqs,
                 sensors=["x%d" % (i + 1) for i in sensors],
                 shapes=shape_rows if shapes else None, frequency_noise=fnoise,
                 shape_noise=snoise)
    truth = dict(name=name, kind=kind, region=effect.region,
                 regions=getattr(effect, "regions", [effect.region]), size=a,
                 description=effect.size_description(p, a), detail=effect.detail,
                 shift_in_noise=achieved, target_shift_in_noise=target, modes=modes,
                 sensors=len(sensors), shapes=bool(shapes), frequency_noise=fnoise,
                 shape_noise=snoise, building=dict(p),
                 nominal_gap=float(np.sqrt(np.mean((f0 / chain_frequencies(masses, springs,
                                                                         modes) - 1) ** 2))))
    return study, truth


def chain_stiffness(springs):
    """The chain's stiffness matrix (spring 1 joins the ground and floor 1)."""
    n = len(springs)
    K = np.zeros((n, n))
    for i, k in enumerate(springs):
        K[i, i] += k
        if i > 0:
            K[i - 1, i - 1] += k
            K[i - 1, i] -= k
            K[i, i - 1] -= k
    return K


def chain_frequencies(masses, springs, count, stiffness=None):
    """The chain's lowest `count` frequencies (Hz), of `stiffness` in place of
    its own where given."""
    K = chain_stiffness(springs) if stiffness is None else stiffness
    w = sl.eigh(K, np.diag(masses), eigvals_only=True)
    return np.sqrt(w[:count]) / (2 * np.pi)


def study_yaml(s):
    lines = [
        "# A blind case of validation/blind_structures (shear_building suite): the",
        "# chain model of a plane-frame building and the building's measured modes.",
        "name: %s" % s["name"],
        "model:",
        "  type: chain",
        "  masses: %s" % yaml_list(s["masses"]),
        "  springs: %s" % yaml_list(s["springs"]),
    ] + (["  shear_building: true"] if s.get("shear_building") else []) + measurements_yaml(s)
    return "\n".join(lines) + "\n"
