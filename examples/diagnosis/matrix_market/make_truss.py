#!/usr/bin/python3
"""Writes a Warren truss bridge as another FE code would export it, and its "measured" modes.

The model (what a user brings from another program): 23 bar elements of a 30 m, 6-panel Warren
truss (steel; chords A 0.01 m^2, diagonals A 0.005 m^2), each element's stiffness and LUMPED mass
as a Matrix Market file in its 4 global DOFs, the global stiffness and mass (with 2 t of deck on
each inner bottom node), and the DOF labels. Pinned at b0, on a roller at b6.

The truth, never read by the diagnosis: the same truss with CONSISTENT bar masses (another mass
formulation than the exported model's) and bottom-chord member b4 with half its area lost (a
cracked splice). Its 4 lowest modes, seen vertically (uy) at the 5 inner bottom nodes and the 6 top
nodes, noise 0.2 % on frequencies and 2 % on shapes (seed 11), go into truss.yaml.

Run: /usr/bin/python3 examples/diagnosis/matrix_market/make_truss.py
"""
import os

import numpy as np
import scipy.io
import scipy.linalg as sl
import scipy.sparse as sp

HERE = os.path.dirname(os.path.abspath(__file__))
PANEL, HEIGHT, PANELS = 5.0, 4.0, 6
E, RHO = 210e9, 7850.0
A_CHORD, A_DIAG = 0.01, 0.005
DECK = 2000.0          # kg on each inner bottom node
DAMAGED, LOSS = "b4", 0.5

nodes = [("b%d" % i, i * PANEL, 0.0) for i in range(PANELS + 1)]
nodes += [("t%d" % (i + 1), (i + 0.5) * PANEL, HEIGHT) for i in range(PANELS)]
index = {name: k for k, (name, _, _) in enumerate(nodes)}
members = [("b%d" % (i + 1), "b%d" % i, "b%d" % (i + 1), A_CHORD) for i in range(PANELS)]
members += [("t%d" % (i + 1), "t%d" % (i + 1), "t%d" % (i + 2), A_CHORD) for i in range(PANELS - 1)]
for i in range(PANELS):
    members.append(("d%d" % (2 * i + 1), "b%d" % i, "t%d" % (i + 1), A_DIAG))
    members.append(("d%d" % (2 * i + 2), "t%d" % (i + 1), "b%d" % (i + 1), A_DIAG))
fixed = {("b0", 0), ("b0", 1), ("b%d" % PANELS, 1)}
dofs, labels = {}, []
for name, _, _ in nodes:
    for c, comp in enumerate(("ux", "uy")):
        if (name, c) not in fixed:
            dofs[(name, c)] = len(labels)
            labels.append(name + ":" + comp)
n = len(labels)


def bar(a, b, area, consistent):
    (_, xa, ya), (_, xb, yb) = nodes[index[a]], nodes[index[b]]
    L = np.hypot(xb - xa, yb - ya)
    c, s = (xb - xa) / L, (yb - ya) / L
    t = np.array([c, s])
    k = E * area / L * np.block([[np.outer(t, t), -np.outer(t, t)], [-np.outer(t, t), np.outer(t, t)]])
    m_total = RHO * area * L
    if consistent:  # translations in both directions: m/6 [[2 I, I], [I, 2 I]]
        m = m_total / 6 * np.block([[2 * np.eye(2), np.eye(2)], [np.eye(2), 2 * np.eye(2)]])
    else:
        m = m_total / 2 * np.eye(4)
    return k, m


def global_dofs(a, b):
    return [dofs.get((a, 0), -1), dofs.get((a, 1), -1), dofs.get((b, 0), -1), dofs.get((b, 1), -1)]


def assemble(consistent, damaged):
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for (label, a, b, area) in members:
        k, m = bar(a, b, area * (1 - LOSS if label == damaged else 1.0), consistent)
        g = global_dofs(a, b)
        for i in range(4):
            for j in range(4):
                if g[i] >= 0 and g[j] >= 0:
                    K[g[i], g[j]] += k[i, j]
                    M[g[i], g[j]] += m[i, j]
    for i in range(1, PANELS):
        for c in (0, 1):
            M[dofs[("b%d" % i, c)], dofs[("b%d" % i, c)]] += DECK
    return K, M


# The exported model: element files in their global DOFs (1-based in the study), lumped mass.
os.makedirs(os.path.join(HERE, "elements"), exist_ok=True)
element_entries = []
for (label, a, b, area) in members:
    k, m = bar(a, b, area, consistent=False)
    g = global_dofs(a, b)
    keep = [i for i in range(4) if g[i] >= 0]
    for kind, mat in (("k", k), ("m", m)):
        scipy.io.mmwrite(os.path.join(HERE, "elements", "%s_%s.mtx" % (label, kind)),
                         sp.coo_matrix(mat[np.ix_(keep, keep)]), symmetry="symmetric",
                         comment="femup example: bar %s (%s-%s), %s" % (label, a, b, kind), precision=12)
    element_entries.append((label, [g[i] + 1 for i in keep]))
K0, M0 = assemble(consistent=False, damaged=None)
scipy.io.mmwrite(os.path.join(HERE, "K.mtx"), sp.coo_matrix(K0), symmetry="symmetric", precision=12)
scipy.io.mmwrite(os.path.join(HERE, "M.mtx"), sp.coo_matrix(M0), symmetry="symmetric", precision=12)

# The truth and its modes.
K1, M1 = assemble(consistent=True, damaged=DAMAGED)
w, V = sl.eigh(K1, M1)
count = 4
rng = np.random.default_rng(11)
f = np.sqrt(w[:count]) / (2 * np.pi) * (1 + 0.002 * rng.standard_normal(count))
sensors = ["b%d:uy" % i for i in range(1, PANELS)] + ["t%d:uy" % (i + 1) for i in range(PANELS)]
rows = [labels.index(s) for s in sensors]
shapes = []
for j in range(count):
    v = V[rows, j]
    shapes.append(v / np.abs(v).max() + 0.02 * rng.standard_normal(len(rows)))

fmt = lambda v: "[" + ", ".join("%.10g" % x for x in v) + "]"
lines = ["# A Warren truss bridge brought from another FE code as Matrix Market files",
         "# (examples/diagnosis/matrix_market/truss.yaml). Made by make_truss.py: the model's",
         "# elements have lumped masses; the truth, which the diagnosis never reads, has",
         "# consistent masses and bottom-chord member b4 with half its area lost. 4 modes, uy at the",
         "# 5 inner bottom nodes and the 6 top nodes, noise 0.2 % / 2 % (seed 11).",
         "# Run: femup diagnose examples/diagnosis/matrix_market/truss.yaml -o out/truss",
         "# Generated by make_truss.py: edit the script, not this file.",
         "name: diagnosis_truss_matrix_market",
         'description: "A 30 m Warren truss from another FE code, a cracked bottom chord"',
         "model:",
         "  type: matrix_market",
         "  stiffness: K.mtx",
         "  mass: M.mtx",
         "  dof_labels: [" + ", ".join(labels) + "]",
         "  elements:"]
for k, (label, g) in enumerate(element_entries):
    lines.append("    - {id: %d, label: %s, stiffness: elements/%s_k.mtx, mass: elements/%s_m.mtx, dofs: %s}"
                 % (k + 1, label, label, label, "[" + ", ".join(map(str, g)) + "]"))
lines += ["measurements:",
          "  - state: test",
          "    frequencies_hz: " + fmt(f),
          "    sensors: [" + ", ".join(sensors) + "]",
          "    shapes:"]
lines += ["      - " + fmt(s) for s in shapes]
lines += ["diagnosis:", "  noise: {frequency: 0.002, shape: 0.02}", ""]
open(os.path.join(HERE, "truss.yaml"), "w").write("\n".join(lines))
print("wrote truss.yaml, frequencies", np.round(f, 3), "; undamaged truth",
      np.round(np.sqrt(sl.eigh(*assemble(True, None), eigvals_only=True)[:count]) / 2 / np.pi, 3),
      "; model", np.round(np.sqrt(sl.eigh(K0, M0, eigvals_only=True)[:count]) / 2 / np.pi, 3))
