#!/usr/bin/python3
"""Turns solvers_bench's Google Benchmark JSON (--benchmark_out) into a Markdown table.

Usage: benchmark_table.py solvers.json > solvers.md
One row per benchmark: wall time per solve (the median over repetitions when
the run had --benchmark_repetitions, with their coefficient of variation), the
solver's status (the benchmark's label) and the counters solvers_bench.cc
documents, printed in full (Google Benchmark's console output abbreviates them
with SI prefixes). Counters are the first repetition's (every repetition solves
the same problem), except the peak RSS growth: the largest over repetitions.
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
    runs = {}  # run name -> {"runs": [...], aggregate name -> entry}, in order
    for b in report["benchmarks"]:
        entry = runs.setdefault(b["run_name"], {"runs": []})
        if b.get("run_type", "iteration") == "iteration":
            entry["runs"].append(b)
        else:
            entry[b["aggregate_name"]] = b

    print("| benchmark | time per solve (ms) | CV | solves timed | status | "
          + " | ".join(title for _, title, _ in COUNTERS) + " |")
    print("|---|---|---|---|---|" + "---|" * len(COUNTERS))
    for name, entry in runs.items():
        first = entry["runs"][0]
        timed = entry.get("median", first)
        ms = timed["real_time"] * SECONDS[timed["time_unit"]] * 1e3
        cv = f"{100 * entry['cv']['real_time']:.1f} %" if "cv" in entry else ""
        solves = "+".join(str(b["iterations"]) for b in entry["runs"])
        cells = [name, f"{ms:.4g}", cv, solves, first.get("label", "")]
        for key, _, fmt in COUNTERS:
            if key == "peak_rss_kib" and key in first:
                cells.append(fmt.format(max(b[key] for b in entry["runs"])))
            else:
                cells.append(fmt.format(first[key]) if key in first else "")
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
