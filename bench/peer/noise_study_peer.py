#!/usr/bin/python3
"""The paper's noise study (femup noise) written with numpy/scipy, timed.

Reads what bench/noise_peer_compare.cc writes into DIR:
    study.json     parameter names and kinds, fixed factors, preset factors,
                   added-mass indices, levels, draws, seed, distribution,
                   shape level ratio, number of FEM modes, and the measured
                   states (name, immersion, clean frequencies in Hz, shape file)
    K.mtx, M.mtx   the nominal model (Matrix Market)
    basis_<k>.mtx  each parameter's basis matrix (Matrix Market)
    shapes_<s>.mtx each state's clean measured mode shapes (n x modes)
and computes, the way femup does for the summed form (the paper's Eq. 20-31):

  1. the FEM modes of (K, M), M-normalised (scipy.linalg.eigh), the first
     `fem_modes` of them (Phi, n x nf);
  2. for each level and each draw: every measured eigenvalue lambda and every
     shape entry multiplied by (1 + level * r) (shapes: 1 + level *
     shape_level_ratio * r), r ~ N(0, 1) (or U(-1, 1)) drawn per entry,
     eigenvalues first;
  3. per measured mode (lambda, phi): a block z (nf x parameters) with column k
     = Phi' B_k phi times 1 (stiffness), -lambda (mass) or -lambda (added
     mass, wet states; 0 in dry states), and f = -Phi' (K phi - lambda M phi);
  4. the summed system: one row per (FEM mode i, air mode j, water mode p),
     Z = z_air[j][i] + z_water[p][i], F = f_air[j][i] + f_water[p][i];
  5. the fixed factors moved to the right-hand side, their columns dropped,
     and numpy.linalg.lstsq (SVD; rcond None) on the rest;
  6. Rm = |d_est - d| / |d| * 100 % per added-mass factor, the draw's average
     over the factors, and per level the mean of those averages.

Two ways, both plain numpy (--mode):
  loop        (default) a Python loop over draws; inside a draw everything is
              vectorised over parameters and modes (one matmul B @ phi for all
              basis matrices, einsum for the projections): what a user
              writes from the paper's equations.
  vectorised  per level, the noise of all draws drawn at once and the blocks
              of all draws built with batched matmul/einsum; only lstsq
              (which numpy does not batch) stays in a loop over draws.

Prints one JSON object on stdout:
    {"numpy": version, "scipy": version, "mode": ..., "time": s,
     "rm_average": [per level], "usable": [per level]}
"time" covers steps 1-6 (best of --repeat runs); reading the files is not in it.

Run with Debian's /usr/bin/python3 (python3-scipy). Exit status 3, with the
reason on stderr, when numpy/scipy cannot be imported; 2 for bad arguments or
a study this script does not implement.
"""

import argparse
import json
import sys
import time

try:
    import numpy as np
    import scipy
    import scipy.linalg

    from peer_common import read_dense
except ImportError as error:
    print(f"numpy/scipy is not available to {sys.executable}: {error}", file=sys.stderr)
    sys.exit(3)


def load(directory):
    with open(f"{directory}/study.json") as f:
        study = json.load(f)
    k = read_dense(f"{directory}/K.mtx")
    m = read_dense(f"{directory}/M.mtx")
    basis = np.stack([read_dense(f"{directory}/basis_{i}.mtx")
                      for i in range(len(study["parameters"]))])
    states = []
    for s in study["states"]:
        shapes = read_dense(f"{directory}/{s['shapes']}")
        freqs = np.asarray(s["frequencies_hz"], dtype=float)
        states.append({"wet": s["immersion"] == "wet",
                       "lambda": (2 * np.pi * freqs) ** 2, "shapes": shapes})
    return study, k, m, basis, states


def draw_r(rng, distribution, shape):
    if distribution == "gaussian":
        return rng.standard_normal(shape)
    return rng.uniform(-1.0, 1.0, shape)


def setup(study, k, m, states):
    """Step 1 and what both variants need: the FEM modes, the parameter kinds, the
    fixed and free factors, the preset added-mass factors, the dry and wet states."""
    nf = study["fem_modes"]
    _, phi_fem = scipy.linalg.eigh(k, m)
    phi_fem = phi_fem[:, :nf]
    kinds = study["kinds"]
    is_stiffness = np.array([kd == "stiffness" for kd in kinds])
    is_added = np.array([kd == "added_mass" for kd in kinds])
    fixed = np.array(sorted(int(i) for i in study["fixed"]), dtype=int)
    fixed_values = np.array([study["fixed"][str(i)] for i in fixed])
    free = np.setdiff1d(np.arange(len(kinds)), fixed)
    preset = np.asarray(study["preset"])
    added = np.asarray(study["added_mass_indices"], dtype=int)
    dry, wet = (0, 1) if not states[0]["wet"] else (1, 0)
    return (phi_fem, kinds, is_stiffness, is_added, fixed, fixed_values, free, preset, added,
            dry, wet)


def run_loop(study, k, m, basis, states):
    """Steps 1-6, a Python loop over draws."""
    (phi_fem, kinds, is_stiffness, is_added, fixed, fixed_values, free, preset, added, dry,
     wet) = setup(study, k, m, states)

    def blocks(lam, phi, wet_state):
        bphi = basis @ phi                                  # (p, n, modes)
        proj = np.einsum("ni,pnj->jip", phi_fem, bphi)      # (modes, nf, p)
        coef = np.where(is_stiffness, 1.0, -lam[:, None])   # (modes, p)
        if not wet_state:
            coef = np.where(is_added, 0.0, coef)
        z = proj * coef[:, None, :]
        f = -(phi_fem.T @ (k @ phi - (m @ phi) * lam)).T    # (modes, nf)
        return z, f

    rm_average, usable = [], []
    for level_index, level in enumerate(study["levels"]):
        rng = np.random.default_rng([study["seed"], level_index])
        shape_level = level * study["shape_level_ratio"]
        averages = []
        for _ in range(study["draws"]):
            noisy = []
            for s in states:
                lam = s["lambda"] * (1 + level * draw_r(rng, study["distribution"],
                                                        s["lambda"].shape))
                shapes = s["shapes"] * (1 + shape_level * draw_r(
                    rng, study["distribution"], s["shapes"].shape))
                noisy.append(blocks(lam, shapes, s["wet"]))
            (za, fa), (zw, fw) = noisy[dry], noisy[wet]
            # Rows (FEM mode i, air mode j, water mode p), in that order.
            z = (za.transpose(1, 0, 2)[:, :, None, :] +
                 zw.transpose(1, 0, 2)[:, None, :, :]).reshape(-1, len(kinds))
            f = (fa.T[:, :, None] + fw.T[:, None, :]).reshape(-1)
            rhs = f - z[:, fixed] @ fixed_values
            x_free = np.linalg.lstsq(z[:, free], rhs, rcond=None)[0]
            x = np.empty(len(kinds))
            x[free] = x_free
            x[fixed] = fixed_values
            if np.all(np.isfinite(x)):
                averages.append(np.mean(np.abs(x[added] - preset[added]) /
                                        np.abs(preset[added])) * 100.0)
        rm_average.append(float(np.mean(averages)) if averages else float("nan"))
        usable.append(len(averages))
    return rm_average, usable


def run_vectorised(study, k, m, basis, states):
    """Steps 1-6 with the draws of a level batched; lstsq in a loop."""
    (phi_fem, kinds, is_stiffness, is_added, fixed, fixed_values, free, preset, added, dry,
     wet) = setup(study, k, m, states)
    draws = study["draws"]
    # Phi' B_k for every parameter: (p, nf, n), then Phi' B_k phi is one matmul.
    proj_basis = np.einsum("ni,pnm->pim", phi_fem, basis)

    def blocks(lam, phi, wet_state):
        # lam (D, modes), phi (D, n, modes)
        proj = np.einsum("pin,dnj->djip", proj_basis, phi)      # (D, modes, nf, p)
        coef = np.where(is_stiffness, 1.0, -lam[:, :, None])    # (D, modes, p)
        if not wet_state:
            coef = np.where(is_added, 0.0, coef)
        z = proj * coef[:, :, None, :]
        r = k @ phi - (m @ phi) * lam[:, None, :]               # (D, n, modes)
        f = -np.einsum("ni,dnj->dji", phi_fem, r)               # (D, modes, nf)
        return z, f

    rm_average, usable = [], []
    for level_index, level in enumerate(study["levels"]):
        rng = np.random.default_rng([study["seed"], level_index])
        shape_level = level * study["shape_level_ratio"]
        noisy = []
        for s in states:
            lam = s["lambda"] * (1 + level * draw_r(
                rng, study["distribution"], (draws,) + s["lambda"].shape))
            shapes = s["shapes"] * (1 + shape_level * draw_r(
                rng, study["distribution"], (draws,) + s["shapes"].shape))
            noisy.append(blocks(lam, shapes, s["wet"]))
        (za, fa), (zw, fw) = noisy[dry], noisy[wet]
        z = (za.transpose(0, 2, 1, 3)[:, :, :, None, :] +
             zw.transpose(0, 2, 1, 3)[:, :, None, :, :]).reshape(draws, -1, len(kinds))
        f = (fa.transpose(0, 2, 1)[:, :, :, None] +
             fw.transpose(0, 2, 1)[:, :, None, :]).reshape(draws, -1)
        rhs = f - z[:, :, fixed] @ fixed_values
        z_free = z[:, :, free]
        x = np.empty((draws, len(kinds)))
        x[:, fixed] = fixed_values
        for d in range(draws):
            x[d, free] = np.linalg.lstsq(z_free[d], rhs[d], rcond=None)[0]
        ok = np.all(np.isfinite(x), axis=1)
        averages = np.mean(np.abs(x[ok][:, added] - preset[added]) /
                           np.abs(preset[added]), axis=1) * 100.0
        rm_average.append(float(np.mean(averages)) if ok.any() else float("nan"))
        usable.append(int(ok.sum()))
    return rm_average, usable


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir", help="directory written by femup_noise_peer_compare")
    parser.add_argument("--mode", choices=["loop", "vectorised"], default="loop")
    parser.add_argument("--repeat", type=int, default=1, help="runs (best kept)")
    args = parser.parse_args()

    study, k, m, basis, states = load(args.dir)
    if study["form"] != "summed" or len(states) != 2 or \
            states[0]["wet"] == states[1]["wet"]:
        print("only the summed form with one dry and one wet state is implemented",
              file=sys.stderr)
        sys.exit(2)
    if study["shape_noise"] != "entry" or \
            study["distribution"] not in ("gaussian", "uniform"):
        print("only entry-relative shape noise, gaussian or uniform, is implemented",
              file=sys.stderr)
        sys.exit(2)
    run = run_loop if args.mode == "loop" else run_vectorised
    best = None
    for _ in range(max(1, args.repeat)):
        start = time.perf_counter()
        rm_average, usable = run(study, k, m, basis, states)
        elapsed = time.perf_counter() - start
        if best is None or elapsed < best[0]:
            best = (elapsed, rm_average, usable)
    elapsed, rm_average, usable = best
    print(json.dumps({"numpy": np.__version__, "scipy": scipy.__version__,
                      "mode": args.mode, "time": elapsed,
                      "rm_average": rm_average, "usable": usable}))


if __name__ == "__main__":
    main()
