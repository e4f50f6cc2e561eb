"""A jacket in water, built with frame3d, to make blind truths for femup's
`space_frame` model.

The geometry is the one femup's space_frame study model describes
(docs/space_frame.md, `model.type: space_frame`), rebuilt here from that
description with frame3d's own elements:

- legs at every point of the (bays_x + 1) x (bays_y + 1) plan grid (spacing
  bay_width_x, bay_width_y), from Z = 0 (clamped, or on foundation springs) up
  `levels` levels of `level_height`;
- horizontals along X and Y at every level 1..levels;
- braces in every storey panel of the four outer faces: an X whose two halves
  meet rigidly at a centre joint (bracing "x"), one diagonal alternating in
  direction from panel to panel and storey to storey ("diagonal"), or none;
- every member (each half of an X counts as two members) split into
  `elements_per_member` elements;
- circular steel tubes: legs, braces, horizontals as {diameter, wall, E, nu,
  rho} (femup's defaults: legs 1.2 m x 30 mm, the others 0.6 m x 15 mm, steel
  E 210 GPa, nu 0.3, rho 7850 kg/m^3), G = E / 2 (1 + nu), shear coefficient
  0.5 (thin tube, frame3d.KAPPA_THIN_TUBE).

Water follows the same physical law as femup's space frame: an element is wet
when its midpoint lies below `water_depth` (m above the base), and a wet element
carries an added line mass acting only transverse to its axis (frame3d's
`added_mass`, consistent with the element's transverse interpolation). femup
scales rho A of the member per metre by an added-mass factor; here the line
mass per metre is either that (`added_mass_ratio` times rho A) or the potential
flow value of a circular cylinder, Ca rho_w pi D^2 / 4 (`Ca`, `rho_w`). Marine
growth (`growth_thickness`, `growth_density`) is a line mass on the wet
elements moving in all directions, and widens the diameter the water sees.
Members are not flooded (no entrained water inside the tubes).

Node numbering: femup labels its free nodes n1, n2, ...: the leg joints level
by level (j along Y outer, i along X inner), then the X-brace centres storey by
storey (faces Y = 0 and Y = max along X, then X = 0 and X = max along Y), then
the inner nodes member by member (per level: legs, X horizontals, Y
horizontals, braces). `Jacket.labels` maps those labels to frame3d nodes (the
members are laid out in femup's order, so the inner nodes match as well); the
base nodes have no label. Sensors such as "n1:ux" (femup's leg joints) read
`Jacket.dof("n1:ux")`.

Units: SI. Nothing here reads or calls femup.
"""
import numpy as np

import frame3d
from frame3d import Frame3d

STEEL = dict(E=210e9, nu=0.3, rho=7850.0)
DEFAULT_SECTIONS = dict(
    legs=dict(diameter=1.2, wall=0.03),
    braces=dict(diameter=0.6, wall=0.015),
    horizontals=dict(diameter=0.6, wall=0.015),
)


class Jacket:
    """A jacket-like space frame (see the module docstring).

    Attributes after construction: `frame` (a frame3d.Frame3d), `labels`
    ({"n<k>": node}), `joints` ({(i, j, k): node}, k = 0 the base), `centres`
    ({(k, panel): node}), and each element's tags hold its kind ("legs",
    "braces", "horizontals"), its level "l<k>" and "wet" when wet."""

    def __init__(self, bays_x=1, bays_y=1, levels=3, level_height=10.0, bay_width_x=15.0,
                 bay_width_y=15.0, elements_per_member=4, bracing="x", water_depth=0.0,
                 legs=None, braces=None, horizontals=None, shear=True, rotary=True,
                 mass_kind="timoshenko", added_mass_ratio=None, Ca=1.0, rho_w=1025.0,
                 growth_thickness=0.0, growth_density=1325.0, base_springs=None,
                 deck_mass=0.0, **ignored):
        """Study-like fields (femup's names); `ignored` swallows femup's other
        model keys (type, blocks_per_level, theory), which do not change the
        structure. shear/rotary/mass_kind: frame3d element options.
        added_mass_ratio: None for potential flow (Ca rho_w pi D^2 / 4), else the
        added mass per metre as a multiple of the member's rho A (femup's
        factor form). base_springs: None (clamped) or six stiffnesses
        (ux, uy, uz, rx, ry, rz) at every leg foot. deck_mass (kg): shared
        equally by the top level's leg joints as point masses."""
        if bracing not in ("x", "diagonal", "none"):
            raise ValueError("bracing must be x, diagonal or none")
        sections = dict(DEFAULT_SECTIONS)
        for name, given in (("legs", legs), ("braces", braces), ("horizontals", horizontals)):
            if given:
                sections[name] = dict(sections[name], **given)
        self.sections = {}
        for name, s in sections.items():
            mat = dict(STEEL, **{k: s[k] for k in ("E", "nu", "rho") if k in s})
            sec = frame3d.tube(s["diameter"], s["wall"])
            sec.update(E=mat["E"], G=mat["E"] / (2 * (1 + mat["nu"])), rho=mat["rho"],
                       shear=shear, rotary=rotary)
            self.sections[name] = (sec, s["diameter"])
        self.water_depth = water_depth
        self.added_mass_ratio, self.Ca, self.rho_w = added_mass_ratio, Ca, rho_w
        self.growth = (growth_thickness, growth_density)

        f = Frame3d()
        f.mass_kind = mass_kind
        self.frame = f
        bx, by, nx, ny = bays_x, bays_y, bays_x + 1, bays_y + 1
        h, wx, wy = level_height, bay_width_x, bay_width_y
        pos = lambda i, j, k: (i * wx, j * wy, k * h)  # noqa: E731
        self.labels, self.joints, self.centres = {}, {}, {}
        count = [0]

        def label(node):
            count[0] += 1
            self.labels["n%d" % count[0]] = node

        for k in range(1, levels + 1):
            for j in range(ny):
                for i in range(nx):
                    self.joints[(i, j, k)] = f.add_node(*pos(i, j, k))
                    label(self.joints[(i, j, k)])
        panels = []  # (ai, aj, bi, bj, index along the face)
        if bracing != "none":
            panels += [(i, j, i + 1, j, i) for j in (0, by) for i in range(bx)]
            panels += [(i, j, i, j + 1, j) for i in (0, bx) for j in range(by)]
        if bracing == "x":
            for k in range(1, levels + 1):
                for q, (ai, aj, bi, bj, _) in enumerate(panels):
                    c = np.mean([pos(ai, aj, k - 1), pos(bi, bj, k - 1), pos(ai, aj, k),
                                 pos(bi, bj, k)], axis=0)
                    self.centres[(k, q)] = f.add_node(*c)
                    label(self.centres[(k, q)])
        for j in range(ny):
            for i in range(nx):
                self.joints[(i, j, 0)] = f.add_node(*pos(i, j, 0))
                foot = self.joints[(i, j, 0)]
                if base_springs is None:
                    f.fix(foot)
                else:
                    f.springs += [(foot, d, kd) for d, kd in enumerate(base_springs)]

        def member(a, b, kind, level):
            sec, D = self.sections[kind]
            els, nodes = f.add_member(a, b, elements_per_member, tags={kind, "l%d" % level},
                                      **sec)
            for node in nodes[1:-1]:
                label(node)
            for e in els:
                self._wet(f.elements[e], D)

        J = self.joints
        for k in range(1, levels + 1):
            for j in range(ny):
                for i in range(nx):
                    member(J[(i, j, k - 1)], J[(i, j, k)], "legs", k)
            for j in range(ny):
                for i in range(bx):
                    member(J[(i, j, k)], J[(i + 1, j, k)], "horizontals", k)
            for i in range(nx):
                for j in range(by):
                    member(J[(i, j, k)], J[(i, j + 1, k)], "horizontals", k)
            for q, (ai, aj, bi, bj, index) in enumerate(panels):
                if bracing == "diagonal":
                    if (index + k) % 2 == 0:
                        member(J[(ai, aj, k - 1)], J[(bi, bj, k)], "braces", k)
                    else:
                        member(J[(bi, bj, k - 1)], J[(ai, aj, k)], "braces", k)
                    continue
                c = self.centres[(k, q)]
                # Bottom corners towards the centre, the centre towards the top.
                member(J[(ai, aj, k - 1)], c, "braces", k)
                member(c, J[(bi, bj, k)], "braces", k)
                member(J[(bi, bj, k - 1)], c, "braces", k)
                member(c, J[(ai, aj, k)], "braces", k)
        if deck_mass > 0:
            top = [J[(i, j, levels)] for j in range(ny) for i in range(nx)]
            for node in top:
                f.point_masses.append((node, deck_mass / len(top), 0.0))

    def _wet(self, e, D):
        """Water on element e (outer diameter D) if its midpoint is below the
        water line: marine growth (all directions) and added mass (transverse)."""
        z = 0.5 * (self.frame.xyz[e["n1"]][2] + self.frame.xyz[e["n2"]][2])
        if not z < self.water_depth:
            return
        e["tags"].add("wet")
        th, rho_g = self.growth
        if th > 0:
            e["line_mass"] += frame3d.marine_growth_mass(D, th, rho_g)
        if self.added_mass_ratio is not None:
            e["added_mass"] += self.added_mass_ratio * e["rho"] * e["A"]
        else:
            e["added_mass"] += frame3d.hydrodynamic_added_mass(D + 2 * th, self.Ca, self.rho_w)

    def dof(self, label):
        """Global DOF index of a femup-style label "n<k>:ux" (ux uy uz rx ry rz)."""
        node, name = label.split(":")
        return 6 * self.labels[node] + frame3d.DOF_NAMES.index(name)

    def modes(self, count, **kw):
        """frame3d's lowest modes: frequencies (Hz), shapes over all DOFs."""
        return self.frame.modes(count, **kw)


def from_study_model(model, **options):
    """A Jacket from a femup study's `model:` mapping (already parsed, e.g.
    examples/diagnosis/jacket.yaml's), with frame3d options on top (e.g.
    elements_per_member=4 to refine, shear=False)."""
    fields = dict(model)
    fields.update(options)
    return Jacket(**fields)
