#!/usr/bin/env python3
"""An independent output-error fit of the paper's chain under noise (issue 3).

Written from the problem statement alone (not from femup's code), with numpy and
scipy as Debian ships them, to check femup's figure for the output-error fit in
docs/solvers.md ("Noisy data: the paper's linear solve against the others"):
the chain of examples/paper_chain_solver_comparison.yaml (five 50 kg masses,
springs 2.9e7 N/m, spring 1 to the ground; masses 1-3 wet), the preset factors,
12 unknowns with mass 4 fixed at its preset, the 2 lowest modes in air and in
water with shapes at every DOF. Per draw: eigenvalues times (1 + level r),
shape entries times (1 + 10 level r), r ~ N(0, 1) per entry. The fit: scipy's
Levenberg-Marquardt from zero factors on the residuals
  (lambda / lambda_meas - 1) / level  and  (c s_i - t_i) / sigma_i,
t the measured shape over its largest entry, c the weighted least-squares
modal scale factor, model modes paired by MAC. Shape weights:
  entry: sigma_i = 10 level max(|t_i|, 0.05)   (femup's shape_noise: entry)
  model: sigma_i = 10 level max(|c s_i|, 0.05) (the model's prediction, as the
         noise is proportional to the true entry; eigenvalue residual
         (1 - lambda_meas / lambda) / level)
Prints the mean and median added-mass error Rm and the draws above 100 %.

  python3 validation/peer/output_error_fit.py --level 0.002 --draws 1000
"""
import argparse

import numpy as np
import scipy.linalg as sl
from scipy.optimize import least_squares

N = 5
MASS, SPRING = 50.0, 2.9e7
WET = [0, 1, 2]
TRUE_MASS = np.array([-0.0087, -0.0333, 0.0025, 0.0058, -0.0230])
TRUE_STIFFNESS = np.array([0.0119, 0.0119, -0.0004, 0.0033, 0.0017])
TRUE_ADDED = np.array([0.15, 0.25, 0.20])
MODES = 2


def matrices(dm, dk, a):
    k_mat = np.zeros((N, N))
    for j in range(N):
        k = SPRING * (1 + dk[j])
        k_mat[j, j] += k
        if j > 0:
            k_mat[j - 1, j - 1] += k
            k_mat[j - 1, j] -= k
            k_mat[j, j - 1] -= k
    dry = np.diag(MASS * (1 + dm))
    wet = dry.copy()
    for i, w in enumerate(WET):
        wet[w, w] += MASS * a[i]
    return k_mat, dry, wet


def unpack(x):
    dm = np.array([x[0], x[1], x[2], TRUE_MASS[3], x[3]])
    return dm, x[4:9], x[9:12]


def residuals(x, data, level, weights):
    try:
        k_mat, dry, wet = matrices(*unpack(x))
        out = []
        for (lam_meas, psi), m_mat in zip(data, [dry, wet]):
            lam, vec = sl.eigh(k_mat, m_mat)
            used = set()
            for j in range(MODES):
                p = psi[:, j]
                mac = [-1.0 if q in used else
                       (vec[:, q] @ p) ** 2 / ((vec[:, q] @ vec[:, q]) * (p @ p))
                       for q in range(N)]
                q = int(np.argmax(mac))
                used.add(q)
                s, t = vec[:, q], p / np.max(np.abs(p))
                sigma = 10 * level * np.maximum(np.abs(t), 0.05)
                c = np.sum(s * t / sigma**2) / np.sum(s * s / sigma**2)
                if weights == "entry":
                    out.append((lam[q] / lam_meas[j] - 1) / level)
                else:
                    out.append((1 - lam_meas[j] / lam[q]) / level)
                    for _ in range(3):
                        sigma = 10 * level * np.maximum(np.abs(c * s), 0.05)
                        c = np.sum(s * t / sigma**2) / np.sum(s * s / sigma**2)
                out.extend((c * s - t) / sigma)
        return np.array(out)
    except np.linalg.LinAlgError:  # a step made a mass matrix indefinite
        return np.full(2 * MODES * (1 + N), 1e6)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--level", type=float, default=0.002)
    parser.add_argument("--draws", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=20261125)
    args = parser.parse_args()
    k_mat, dry, wet = matrices(TRUE_MASS, TRUE_STIFFNESS, TRUE_ADDED)
    clean = []
    for m_mat in (dry, wet):
        lam, vec = sl.eigh(k_mat, m_mat)
        clean.append((lam[:MODES], vec[:, :MODES]))
    rng = np.random.default_rng(args.seed)
    rm = {"entry": [], "model": []}
    for _ in range(args.draws):
        data = [(lam * (1 + args.level * rng.standard_normal(MODES)),
                 vec * (1 + 10 * args.level * rng.standard_normal(vec.shape)))
                for lam, vec in clean]
        for weights, values in rm.items():
            fit = least_squares(residuals, np.zeros(12), args=(data, args.level, weights),
                                method="lm", xtol=1e-12, ftol=1e-12, max_nfev=4000)
            values.append(np.mean(np.abs(fit.x[9:12] - TRUE_ADDED) / TRUE_ADDED))
    print(f"level {args.level} (shapes {10 * args.level}), {args.draws} draws, "
          f"seed {args.seed}")
    print("shape weights | mean Rm | median Rm | draws with Rm > 100 %")
    for weights, values in rm.items():
        v = np.array(values)
        print(f"{weights} | {100 * v.mean():.1f} % | {100 * np.median(v):.1f} % | "
              f"{int(np.sum(v > 1))}")


if __name__ == "__main__":
    main()
