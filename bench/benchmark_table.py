#!/usr/bin/python3
"""Turns solvers_bench's Google Benchmark JSON (--benchmark_out) into a Markdown table.

Usage: benchmark_table.py solvers.json > solvers.md
One row per benchmark: wall time per solve, the solver's status (the
benchmark's label) and the counters solvers_bench.cc documents, printed in full
(Google Benchmark's console output abbreviates them with SI prefixes).
Standard library only.
"""

import json
import sys

SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
COUNTERS = [("solver_iters", "solver iterations", "{:.0f}"),
            ("error", "error", "{:.2e}"),
            ("rel_error", "relative error", "{:.3g}"),
            ("kkt", "KKT residual", "{:.1e}"),
            ("cost", "cost", "{:.4g}"),
            ("active", "active bounds", "{:.0f}"),
            ("peak_rss_kib", "peak RSS growth (KiB)", "{:.0f}")]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        report = json.load(f)
    context = report["context"]
    print(f"Google Benchmark run of {context['date']}, {context['num_cpus']} CPUs at "
          f"{context['mhz_per_cpu']} MHz, load average "
          f"{', '.join(f'{x:.2f}' for x in context.get('load_avg', []))}.\n")
    print("| benchmark | time per solve (ms) | runs timed | status | "
          + " | ".join(title for _, title, _ in COUNTERS) + " |")
    print("|---|---|---|---|" + "---|" * len(COUNTERS))
    for b in report["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue  # aggregates of --benchmark_repetitions
        ms = b["real_time"] * SECONDS[b["time_unit"]] * 1e3
        cells = [b["name"], f"{ms:.4g}", str(b["iterations"]), b.get("label", "")]
        cells += [fmt.format(b[key]) if key in b else "" for key, _, fmt in COUNTERS]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
