#!/usr/bin/env python3
"""Writes a UFF file of complex mode shapes, as modal test software exports them,
from the modes.json of `femup modes` on a cantilever (10 equal elements over
1.9 m; DOF labels n<k>:ux / n<k>:uy / n<k>:rz):

  dataset 15  nodes 100 + k at (0, 0.19 k, 0), k = 0..10 (node 100 is the clamp)
  dataset 55  one complex mode (analysis type 3) per mode of modes.json: the
              eigenvalue lambda = -zeta w + i w sqrt(1 - zeta^2) (rad/s) of
              the mode's frequency and a damping ratio (1 %, 0.8 %, 0.6 %,
              0.5 %), and at each node the translations X = ux, Y = uy, Z = 0
              times e^{i phase} (zero at the clamp, node 100); mode 2 also carries a small out-of-phase part
              (0.02 i times mode 3's shape), as non-proportional damping gives.

Independent of femup's own UFF writer: every record is formatted here to the
dataset's Fortran layout (I10, E13.5).

usage: make_modes_uff.py modes.json out.uff [--drop-node N --in-mode K]
"""
import cmath
import json
import math
import sys

DAMPING = [0.01, 0.008, 0.006, 0.005]
PHASE = [0.3, -2.0, 1.2, 2.6]  # rad, any: the phase of a complex mode is arbitrary


def main():
    args = sys.argv[1:]
    drop = None
    if "--drop-node" in args:
        i = args.index("--drop-node")
        drop = (int(args[i + 1]), int(args[args.index("--in-mode") + 1]))
    source, target = args[0], args[1]
    modes = json.load(open(source))
    labels = modes["dof_labels"]
    shapes = modes["shapes_mass_normalised"]
    hz = modes["frequencies_hz"]
    out = []

    def line(text):
        out.append(text)

    line("%6d" % -1)
    line("%6d" % 15 + " " * 74)
    for k in range(11):
        line("%10d%10d%10d%10d%13.5E%13.5E%13.5E" % (100 + k, 0, 0, 0, 0.0, 0.19 * k, 0.0))
    line("%6d" % -1)
    for j in range(len(hz)):
        w = 2 * math.pi * hz[j]
        z = DAMPING[min(j, len(DAMPING) - 1)]
        lam = complex(-z * w, w * math.sqrt(1 - z * z))
        rot = cmath.exp(1j * PHASE[j % len(PHASE)])
        line("%6d" % -1)
        line("%6d" % 55 + " " * 74)
        line("femup example: modes of the tested beam, in air".ljust(80))
        line("mode %d, complex (analysis type 3)" % (j + 1))
        for _ in range(3):
            line("NONE")
        line("%10d%10d%10d%10d%10d%10d" % (1, 3, 2, 8, 5, 3))
        line("%10d%10d%10d%10d" % (2, 6, 0, j + 1))
        line("%13.5E%13.5E%13.5E%13.5E%13.5E%13.5E" % (lam.real, lam.imag, 0, 0, 0, 0))
        for k in range(0, 11):
            if drop and drop == (100 + k, j + 1):
                continue
            values = []
            for axis in ("ux", "uy"):
                if k == 0:  # the clamp: no motion
                    values += [0.0, 0.0]
                    continue
                v = shapes[j][labels.index("n%d:%s" % (k, axis))]
                c = v * rot
                if j == 1 and len(hz) > 2:
                    c += 0.02j * shapes[2][labels.index("n%d:%s" % (k, axis))]
                values += [c.real, c.imag]
            values += [0.0, 0.0]
            line("%10d" % (100 + k))
            line("".join("%13.5E" % v for v in values))
        line("%6d" % -1)
    with open(target, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
