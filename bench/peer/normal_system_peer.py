#!/usr/bin/python3
"""Builds and solves the linear correction-factor system with scipy.

The SciPy counterpart of femup's BuildNormalCorrectionSystem + "lstsq" solver
(bench/system_peer_compare.cc writes the inputs). Reads from DIR:
  K.mtx, M.mtx          stiffness and mass (symmetric Matrix Market),
  bases.mtx             every correction factor's basis matrix B_k, basis k's
                        entry (r, c) stored at column k * n + c,
  problem.json          the factor kinds ("stiffness", "mass", "added_mass"),
                        the preset factors, and per measured state its name,
                        whether it is wet, its eigenvalues and the file of its
                        shapes (n x modes, Matrix Market array).
For every measured mode (lambda, phi), the residual of the updated model is
F - Z d with
  Z[:, k] = c_k B_k phi,  c_k = 1 (stiffness), -lambda (mass; added mass when
  wet, else 0),          F = -(K phi - lambda M phi),
weighted by M^-1 (the "all FEM modes" projection). The script accumulates
  G = sum Z' M^-1 Z,  h = sum Z' M^-1 F
the straightforward way: Z as a dense n x p array per mode, M^-1 Z by SuperLU
(splu with a symmetric ordering and no pivoting, as suits a symmetric
positive definite M, factorised once), then solves G d = h with
numpy.linalg.lstsq (SVD), the factor named in problem.json's "fixed" held at
its value (scaling K and M together changes no residual). Prints one JSON object:
  {"scipy", "numpy", "read_time", "assembly_time", "solve_time", "time",
   "x", "error_vs_truth", "rss_before_solve_mb", "solve_peak_rss_mb", "maxrss_mb"}
Times in seconds (reading not included in "time"). Exit status 3, with the
reason on stderr, when scipy cannot be imported.
"""

import argparse
import gc
import json
import sys
import time

try:
    import numpy as np
    import scipy
    import scipy.io
    import scipy.sparse
    from scipy.sparse.linalg import splu

    from peer_common import print_result, read_csc, read_dense, reset_peak_rss, status_mb
except ImportError as error:
    print(f"scipy is not available to {sys.executable}: {error}", file=sys.stderr)
    sys.exit(3)


def read_bases(path, n, p):
    """The p basis matrices (CSR, n x n) from the stacked coordinate file."""
    stacked = scipy.io.mmread(path).tocoo()
    which = stacked.col // n
    column = stacked.col % n
    order = np.argsort(which, kind="stable")
    which, rows, column, values = which[order], stacked.row[order], column[order], \
        stacked.data[order]
    bounds = np.searchsorted(which, np.arange(p + 1))
    return [scipy.sparse.csr_matrix(
        (values[bounds[k]:bounds[k + 1]],
         (rows[bounds[k]:bounds[k + 1]], column[bounds[k]:bounds[k + 1]])),
        shape=(n, n)) for k in range(p)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir", help="directory written by femup_system_peer_compare")
    args = parser.parse_args()

    start = time.perf_counter()
    with open(f"{args.dir}/problem.json") as file:
        problem = json.load(file)
    k_matrix = read_csc(f"{args.dir}/K.mtx")
    m_matrix = read_csc(f"{args.dir}/M.mtx")
    n = k_matrix.shape[0]
    kinds = problem["kinds"]
    p = len(kinds)
    bases = read_bases(f"{args.dir}/bases.mtx", n, p)
    states = []
    for state in problem["states"]:
        shapes = read_dense(f"{args.dir}/{state['shapes']}")
        states.append((state["wet"], np.asarray(state["eigenvalues"]), shapes))
    truth = np.asarray(problem["truth"])
    read_time = time.perf_counter() - start
    gc.collect()

    have_peak = reset_peak_rss()
    rss_before = status_mb("VmRSS")
    start = time.perf_counter()
    lu = splu(m_matrix, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    g = np.zeros((p, p))
    h = np.zeros(p)
    stiffness = np.array([kind == "stiffness" for kind in kinds])
    mass = np.array([kind == "mass" for kind in kinds])
    added = np.array([kind == "added_mass" for kind in kinds])
    for wet, eigenvalues, shapes in states:
        for j, lam in enumerate(eigenvalues):
            phi = shapes[:, j]
            factors = np.where(stiffness, 1.0, 0.0) - lam * mass - (lam if wet else 0.0) * added
            z = np.empty((n, p))
            for k in range(p):
                z[:, k] = factors[k] * (bases[k] @ phi)
            f = -(k_matrix @ phi - lam * (m_matrix @ phi))
            minv_z = lu.solve(z)
            g += z.T @ minv_z
            h += minv_z.T @ f
            del z, minv_z
    g = 0.5 * (g + g.T)
    assembly_time = time.perf_counter() - start
    solve_start = time.perf_counter()
    fixed, value = problem["fixed"]["index"], problem["fixed"]["value"]
    free = np.array([k for k in range(p) if k != fixed])
    x = np.empty(p)
    x[fixed] = value
    x[free] = np.linalg.lstsq(g[np.ix_(free, free)], h[free] - g[free, fixed] * value,
                              rcond=None)[0]
    solve_time = time.perf_counter() - solve_start
    elapsed = time.perf_counter() - start
    solve_peak = status_mb("VmHWM") if have_peak else None

    print_result({
        "read_time": read_time,
        "assembly_time": assembly_time,
        "solve_time": solve_time,
        "time": elapsed,
        "x": x.tolist(),
        "error_vs_truth": float(np.max(np.abs(x - truth))),
    }, memory=(rss_before, solve_peak))


if __name__ == "__main__":
    main()
