#!/usr/bin/python3
"""Times scipy.optimize.lsq_linear on one bounded least-squares problem.

Reads A.mtx, b.mtx, lower.mtx and upper.mtx (Matrix Market, as femup's
WriteMatrixMarket writes them) from DIR, solves
    min 0.5 ||A x - b||^2  s.t.  lower <= x <= upper
with method 'bvls' and 'trf' (scipy's defaults otherwise), and prints one JSON
object on stdout:
    {"scipy": version, "numpy": version,
     "results": {"bvls": {...}, "trf": {...}}}
each result holding "time" (best wall time of the runs, seconds, the
lsq_linear call only), "runs", "cost" (0.5 ||A x - b||^2), "status", "nit",
"optimality" and "x".

Run with Debian's /usr/bin/python3 (python3-scipy). Exit status 3, with the
reason on stderr, when scipy cannot be imported; 2 for bad arguments.
"""

import argparse
import sys
import time

try:
    from scipy.optimize import lsq_linear

    from peer_common import print_result, read_dense, read_vector
except ImportError as error:
    print(f"scipy is not available to {sys.executable}: {error}", file=sys.stderr)
    sys.exit(3)


# lsq_linear's status codes.
TERMINATION = {-1: "no progress", 0: "iteration limit", 1: "optimality < tol",
               2: "cost change < tol", 3: "unconstrained optimum"}


def solve(a, b, lower, upper, method, repeat, budget):
    """Best of up to `repeat` runs; stops repeating once `budget` seconds are spent."""
    best = None
    runs = 0
    spent = 0.0
    while runs < repeat and (runs == 0 or spent < budget):
        start = time.perf_counter()
        result = lsq_linear(a, b, bounds=(lower, upper), method=method)
        elapsed = time.perf_counter() - start
        spent += elapsed
        runs += 1
        if best is None or elapsed < best[0]:
            best = (elapsed, result)
    elapsed, result = best
    return {
        "time": elapsed,
        "runs": runs,
        "cost": float(result.cost),
        "status": int(result.status),
        "termination": TERMINATION.get(int(result.status), "unknown"),
        "nit": int(result.nit),
        "optimality": float(result.optimality),
        "x": result.x.tolist(),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir", help="directory holding A.mtx, b.mtx, lower.mtx, upper.mtx")
    parser.add_argument("--repeat", type=int, default=3, help="most runs per method")
    parser.add_argument("--budget", type=float, default=10.0,
                        help="seconds after which no further run is started")
    args = parser.parse_args()

    a = read_dense(f"{args.dir}/A.mtx")
    b = read_vector(f"{args.dir}/b.mtx")
    lower = read_vector(f"{args.dir}/lower.mtx")
    upper = read_vector(f"{args.dir}/upper.mtx")
    results = {method: solve(a, b, lower, upper, method, args.repeat, args.budget)
               for method in ("bvls", "trf")}
    print_result({"results": results})


if __name__ == "__main__":
    main()
