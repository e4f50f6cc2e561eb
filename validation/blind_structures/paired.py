#!/usr/bin/env python3
"""Two runs of one blind suite compared case by case (run_suite.py outputs).

Two settings or two versions of the diagnosis run on the same cases (same suite,
seed and count; run_suite.py --diagnosis KEY=VALUE for a setting) differ in a
few verdicts; a suite figure's change is the balance of those. This prints, for
each score (kind right, class right, a false alarm on a `none` case, the flat
BIC's kind), how many cases each run alone got, and the exact two-sided sign
test on those discordant cases (binomial, p = 1/2): the chance of a split at
least as uneven if neither run were better. Then the figures of each run side by
side (overall, informative, weak; verdicts stated at >= 0.9 and 0.7-0.9 with the
fraction right), and every case whose verdict kind changed.

Usage:
  python3 validation/blind_structures/paired.py out/pf_soft out/pf_soft_fit \\
      [--names step fit] [--json]

Each folder needs results.jsonl, or, for a run stopped part-way, its truth/ and
runs/ (each case with a diagnosis scored as run_suite.py scores it); the runs are
compared on the cases both have, and the count says so. Cases with the same name must have the same
truth (else: an error naming the case, as the runs are not of the same cases).
"""
import argparse
import json
import math
import os
import sys

SCORES = (("kind_right", "top-1 kind"), ("class_right", "top-1 class"),
          ("bic_kind_right", "flat BIC's kind"))


def read(folder):
    """name -> result row: results.jsonl, or for a stopped run (truth/ and runs/
    without results.jsonl) every case with a diagnosis, scored as run_suite.py
    scores it."""
    path = os.path.join(folder, "results.jsonl")
    if not os.path.isfile(path):
        if os.path.isdir(os.path.join(folder, "truth")) and \
                os.path.isdir(os.path.join(folder, "runs")):
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            import rescore  # noqa: E402 (numpy: only for a stopped run)
            rows, _ = rescore.rescore(folder, None, None, partial=True)
            return {r["name"]: r for r in rows}
        raise SystemExit("paired: %s: no results.jsonl (a run_suite.py output folder?)" % folder)
    rows = {}
    with open(path) as f:
        for k, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                r = json.loads(line)
                rows[r["name"]] = r
            except (ValueError, KeyError) as e:
                raise SystemExit("paired: %s line %d: not a result row (%s)" % (path, k, e))
    return rows


def sign_test(a_only, b_only):
    """Exact two-sided sign test: P(a split at least as uneven | p = 1/2)."""
    n = a_only + b_only
    if n == 0:
        return 1.0
    k = min(a_only, b_only)
    tail = sum(math.comb(n, i) for i in range(k + 1)) / 2.0 ** n
    return min(1.0, 2 * tail)


def false_alarm(r):
    return r["truth_kind"] == "none" and r["verdict_kind"] != "none"


def compare(a, b):
    """a, b: name -> row. Returns the comparison as a dict."""
    names = sorted(set(a) & set(b))
    for n in names:
        if (a[n]["truth_kind"], a[n].get("truth")) != (b[n]["truth_kind"], b[n].get("truth")):
            raise SystemExit("paired: case %s has another truth in the two runs "
                             "(%s against %s): not the same cases" %
                             (n, a[n].get("truth"), b[n].get("truth")))
    out = dict(cases=len(names), only_a=len(set(a) - set(b)), only_b=len(set(b) - set(a)),
               scores=[], figures=[], changed=[])
    for key, label in SCORES:
        ra = [n for n in names if a[n][key]]
        rb = [n for n in names if b[n][key]]
        a_only = len(set(ra) - set(rb))
        b_only = len(set(rb) - set(ra))
        out["scores"].append(dict(score=label, a=len(ra), b=len(rb), a_only=a_only,
                                  b_only=b_only, p=sign_test(a_only, b_only)))
    nones = [n for n in names if a[n]["truth_kind"] == "none"]
    fa = [n for n in nones if false_alarm(a[n])]
    fb = [n for n in nones if false_alarm(b[n])]
    out["scores"].append(dict(score="false alarm on none (of %d)" % len(nones), a=len(fa),
                              b=len(fb), a_only=len(set(fa) - set(fb)),
                              b_only=len(set(fb) - set(fa)),
                              p=sign_test(len(set(fa) - set(fb)), len(set(fb) - set(fa)))))

    def figure(label, select, key):
        sel = [n for n in names if select(n)]
        out["figures"].append(dict(
            figure="%s (%d)" % (label, len(sel)),
            a=sum(1 for n in sel if a[n][key]) / len(sel) if sel else None,
            b=sum(1 for n in sel if b[n][key]) / len(sel) if sel else None))

    figure("top-1 kind, all", lambda n: True, "kind_right")
    figure("top-1 kind, informative", lambda n: a[n]["informative"], "kind_right")
    figure("top-1 kind, weak", lambda n: not a[n]["informative"], "kind_right")
    for lo, hi in ((0.9, 1.0001), (0.7, 0.9)):
        for run, rows in (("a", a), ("b", b)):
            sel = [n for n in names if lo <= rows[n]["probability"] < hi]
            out.setdefault("stated", []).append(dict(
                run=run, lower=lo, upper=min(hi, 1.0), cases=len(sel),
                right=sum(1 for n in sel if rows[n]["class_right"])))
    for n in names:
        if a[n]["verdict_kind"] != b[n]["verdict_kind"]:
            out["changed"].append(dict(
                name=n, truth=a[n]["truth_kind"], a=a[n]["verdict_kind"],
                a_probability=a[n]["kind_probability"], a_right=a[n]["kind_right"],
                b=b[n]["verdict_kind"], b_probability=b[n]["kind_probability"],
                b_right=b[n]["kind_right"]))
    return out


def text(c, name_a, name_b):
    pct = lambda x: "n/a" if x is None else "%.1f %%" % (100 * x)
    lines = ["%d cases in both runs%s" % (
        c["cases"], "" if not (c["only_a"] or c["only_b"]) else
        " (%d in %s only, %d in %s only: left out)" % (c["only_a"], name_a, c["only_b"], name_b)),
        "", "| score | %s | %s | %s only | %s only | sign test p |" % (
            name_a, name_b, name_a, name_b), "|---|---|---|---|---|---|"]
    for s in c["scores"]:
        lines.append("| %s | %d | %d | %d | %d | %.3g |" % (
            s["score"], s["a"], s["b"], s["a_only"], s["b_only"], s["p"]))
    lines += ["", "| figure | %s | %s |" % (name_a, name_b), "|---|---|---|"]
    for f in c["figures"]:
        lines.append("| %s | %s | %s |" % (f["figure"], pct(f["a"]), pct(f["b"])))
    for lo in (0.9, 0.7):
        st = {s["run"]: s for s in c["stated"] if s["lower"] == lo}
        cell = lambda s: "%d of %d (%s)" % (s["right"], s["cases"],
                                            pct(s["right"] / s["cases"] if s["cases"] else None))
        lines.append("| verdicts stated %s right | %s | %s |" % (
            ">= 0.9" if lo == 0.9 else "0.7-0.9", cell(st["a"]), cell(st["b"])))
    lines += ["", "Verdict kind changed in %d cases (truth: %s -> %s; kind probability; "
              "R right, - wrong):" % (len(c["changed"]), name_a, name_b)]
    for ch in c["changed"]:
        lines.append("- %s (%s): %s %.2f %s -> %s %.2f %s" % (
            ch["name"], ch["truth"], ch["a"], ch["a_probability"], "R" if ch["a_right"] else "-",
            ch["b"], ch["b_probability"], "R" if ch["b_right"] else "-"))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("a", help="run_suite.py output folder (the reference)")
    ap.add_argument("b", help="run_suite.py output folder (the change)")
    ap.add_argument("--names", nargs=2, default=["A", "B"], metavar=("A", "B"))
    ap.add_argument("--json", action="store_true", help="the comparison as JSON")
    args = ap.parse_args(argv)
    c = compare(read(args.a), read(args.b))
    if c["cases"] == 0:
        raise SystemExit("paired: no case is in both runs")
    print(json.dumps(c, indent=1) if args.json else text(c, *args.names))
    return 0


if __name__ == "__main__":
    sys.exit(main())
