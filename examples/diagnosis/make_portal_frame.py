#!/usr/bin/python3
"""Writes portal_frame.yaml: a two-storey, one-bay steel frame's "measured" modes.

The truth is made here with numpy/scipy and its own 2D frame elements (not
femup's): 12 elements per member (the model has 2), and on top of the drawing a
2.0 t machine on the middle of the first-floor beam (a lumped mass, translations
only). Noise: 0.2 % on frequencies, 2 % of the largest entry on shapes (seed 7).
Sensors: horizontal (ux) at the four joints and vertical (uy) at both beam
middles, at the model's nodes (joints n1..n4, members' middle nodes as femup
numbers them: see the comment in the YAML).

Also writes portal_frame_points.yaml: the same frame and truth, its sensors
points between the model's nodes (seed 8).

Run: /usr/bin/python3 examples/diagnosis/make_portal_frame.py
"""
import os

import numpy as np
import scipy.linalg as sl

H, W = 3.5, 6.0                      # storey height, bay width (m)
COL = dict(E=210e9, A=7.8e-3, I=8.4e-5, rho=7850)   # a HEB 200-ish column
BEAM = dict(E=210e9, A=5.4e-3, I=1.9e-4, rho=7850 + 1e5 / 5.4e-3 / 6.0 * 0.0)
FLOOR = 3000.0                       # kg/m of slab carried by each beam
PER = 12                             # elements per member in the truth
MACHINE = 2000.0                     # kg at the middle of the first-floor beam

def element(sec, xa, ya, xb, yb, extra_mass_per_length=0.0):
    L = np.hypot(xb - xa, yb - ya)
    c, s = (xb - xa) / L, (yb - ya) / L
    E, A, I = sec["E"], sec["A"], sec["I"]
    m = sec["rho"] * A + extra_mass_per_length
    k = np.zeros((6, 6))
    k[0, 0] = k[3, 3] = E * A / L
    k[0, 3] = k[3, 0] = -E * A / L
    b = E * I / L**3
    idx = [1, 2, 4, 5]
    kb = b * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                       [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
    mb = m * L / 420 * np.array([[156, 22 * L, 54, -13 * L], [22 * L, 4 * L * L, 13 * L, -3 * L * L],
                                 [54, 13 * L, 156, -22 * L], [-13 * L, -3 * L * L, -22 * L, 4 * L * L]])
    mm = np.zeros((6, 6))
    mm[0, 0] = mm[3, 3] = m * L / 3
    mm[0, 3] = mm[3, 0] = m * L / 6
    for i, p in enumerate(idx):
        for j, q in enumerate(idx):
            k[p, q] = kb[i, j]
            mm[p, q] = mb[i, j]
    T = np.zeros((6, 6))
    R = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
    T[:3, :3] = R
    T[3:, 3:] = R
    return T.T @ k @ T, T.T @ mm @ T

# Nodes: a dict from coordinates to an index; base nodes are clamped.
nodes = {}
def node(x, y):
    key = (round(x, 9), round(y, 9))
    if key not in nodes:
        nodes[key] = len(nodes)
    return nodes[key]

members = []
for s in (1, 2):
    for c in (0, 1):
        members.append(((c * W, (s - 1) * H), (c * W, s * H), COL, 0.0))
    members.append(((0.0, s * H), (W, s * H), BEAM, FLOOR))
pieces = []
for (a, b, sec, extra) in members:
    for k in range(PER):
        t0, t1 = k / PER, (k + 1) / PER
        pa = (a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1]))
        pb = (a[0] + t1 * (b[0] - a[0]), a[1] + t1 * (b[1] - a[1]))
        pieces.append((node(*pa), node(*pb), pa, pb, sec, extra))
n = 3 * len(nodes)
K = np.zeros((n, n)); M = np.zeros((n, n))
for (ia, ib, pa, pb, sec, extra) in pieces:
    ke, me = element(sec, *pa, *pb, extra)
    d = [3 * ia, 3 * ia + 1, 3 * ia + 2, 3 * ib, 3 * ib + 1, 3 * ib + 2]
    K[np.ix_(d, d)] += ke
    M[np.ix_(d, d)] += me
mid = node(W / 2, H)
M[3 * mid, 3 * mid] += MACHINE
M[3 * mid + 1, 3 * mid + 1] += MACHINE
free = [i for (x, y), k in nodes.items() if y > 0 for i in (3 * k, 3 * k + 1, 3 * k + 2)]
w, V = sl.eigh(K[np.ix_(free, free)], M[np.ix_(free, free)])
Vfull = np.zeros((n, len(w)))
Vfull[free, :] = V
def measured(seed, rows, count=4):
    """The truth's lowest `count` modes with noise drawn from `seed`: frequencies
    (0.2 %) and shapes at the truth DOFs `rows`, scaled to a largest entry of 1
    (2 % of it)."""
    rng = np.random.default_rng(seed)
    f = np.sqrt(w[:count]) / (2 * np.pi) * (1 + 0.002 * rng.standard_normal(count))
    shapes = []
    for j in range(count):
        v = Vfull[rows, j]
        shapes.append(v / np.abs(v).max() + 0.02 * rng.standard_normal(len(rows)))
    return f, shapes


def write_nodes_example():
    """portal_frame.yaml: sensors on the model's nodes."""
    # Sensors: (truth DOF, model label). femup numbers the joints n1 (x 0, y H),
    # n2 (0, 2H), n3 (W, H), n4 (W, 2H), then each member's inner nodes member by
    # member (storey 1: col1, col2, beam1; storey 2: col1, col2, beam1), one inner
    # node per member with elements_per_member 2: beam1 of storey 1 -> n7, of
    # storey 2 -> n10.
    sensors = [((0, H), 0, "n1:ux"), ((0, 2 * H), 0, "n2:ux"), ((W, H), 0, "n3:ux"),
               ((W, 2 * H), 0, "n4:ux"), ((W / 2, H), 1, "n7:uy"), ((W / 2, 2 * H), 1, "n10:uy")]
    f, shapes = measured(7, [3 * node(*xy) + comp for (xy, comp, _) in sensors])
    labels = ", ".join('"%s"' % s[2] for s in sensors)
    text = """# A two-storey, one-bay steel frame with an unmodelled machine (examples/diagnosis/portal_frame.yaml).
#
# The model: columns 210 GPa, A 7.8e-3 m^2, I 8.4e-5 m^4; beams carrying 3 t/m of
# slab (its mass smeared into the beam's density), storeys 3.5 m, bay 6 m, 2
# elements per member, clamped bases. The "measured" modes (4 lowest; ux at the
# four joints, uy at both beam middles) were made by make_portal_frame.py with
# numpy and its own frame elements, 12 per member: the frame also carries a
# 2.0 t machine at the middle of the first-floor beam (node n7 in the model).
# Noise 0.2 % on frequencies, 2 % on shapes (seed 7).
# Run: femup diagnose examples/diagnosis/portal_frame.yaml -o out/portal_frame
# Generated by make_portal_frame.py: edit the script, not this file.
name: diagnosis_portal_frame
description: "Two-storey portal frame with an unmodelled 2 t machine"
""" + model_text() + measurements_text(f, labels, shapes)
    save("portal_frame.yaml", text, f)


def write_points_example():
    """portal_frame_points.yaml: sensors between the model's nodes (points on
    the members, read through the elements' shape functions), none on a node."""
    # (point, truth component, direction): ux at three quarters of each column
    # of both storeys, uy at the quarter points of both beams. The model's nodes
    # are at the members' ends and middles; the truth has a node every 1/12.
    sensors = [((0, 0.75 * H), 0, "x"), ((W, 0.75 * H), 0, "x"),
               ((0, 1.75 * H), 0, "x"), ((W, 1.75 * H), 0, "x"),
               ((W / 4, H), 1, "y"), ((3 * W / 4, H), 1, "y"),
               ((W / 4, 2 * H), 1, "y"), ((3 * W / 4, 2 * H), 1, "y")]
    f, shapes = measured(8, [3 * node(*xy) + comp for (xy, comp, _) in sensors])
    points = ", ".join("{at: [%g, %g], direction: %s}" % (xy[0], xy[1], d)
                       for (xy, _, d) in sensors)
    text = """# The portal frame of portal_frame.yaml with its sensors between the model's
# nodes (examples/diagnosis/portal_frame_points.yaml).
#
# The same model (2 elements per member) and the same truth (numpy's own frame
# elements, 12 per member, a 2.0 t machine at the middle of the first-floor
# beam: node n7 in the model). The sensors are points on the members, none of
# them a node of the model: ux at three quarters of each column's height, uy at
# the quarter points of both beams. femup reads the model's modes there through
# the elements' shape functions (cubic Hermite across, linear along).
# Noise 0.2 % on frequencies, 2 % on shapes (seed 8).
# Run: femup diagnose examples/diagnosis/portal_frame_points.yaml -o out/portal_frame_points
# Generated by make_portal_frame.py: edit the script, not this file.
name: diagnosis_portal_frame_points
description: "Portal frame with an unmodelled 2 t machine, sensors between nodes"
""" + model_text() + measurements_text(f, points, shapes)
    save("portal_frame_points.yaml", text, f)


fmt = lambda v: "[" + ", ".join("%.10g" % x for x in v) + "]"


def model_text():
    beam_rho = BEAM["rho"] + FLOOR / BEAM["A"]
    return f"""model:
  type: plane_frame
  storeys: 2
  bays: 1
  storey_height: {H}
  bay_width: {W}
  elements_per_member: 2
  column: {{E: 210e9, A: 7.8e-3, I: 8.4e-5, rho: 7850}}
  beam: {{E: 210e9, A: 5.4e-3, I: 1.9e-4, rho: {beam_rho:.10g}}}
"""


def measurements_text(f, sensors, shapes):
    """The study's measurements (frequencies `f`, `shapes` at `sensors`, the
    sensors already written as YAML) and its diagnosis noise, as YAML."""
    return f"""measurements:
  - state: test
    frequencies_hz: {fmt(f)}
    sensors: [{sensors}]
    shapes:
""" + "".join(f"      - {fmt(s)}\n" for s in shapes) + """diagnosis:
  noise: {frequency: 0.002, shape: 0.02}
"""


def save(name, text, f):
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    open(out, "w").write(text)
    print("wrote", out, "frequencies", np.round(f, 3))


write_nodes_example()
write_points_example()
