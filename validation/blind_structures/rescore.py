#!/usr/bin/env python3
"""Rescores a blind suite's diagnoses (run_suite.py's OUT folder) under another
prior share of `none`, without running femup again.

femup's default gives `none` and every family tried one equal share of the
prior, 1 / (families + 1): before the data, a gap is `families` times as
probable as none. A share s for `none` instead reweights each case's
probabilities, `none`'s by
  f = s / (1 - s) * families
(families: the kinds other than `none` among the case's classes), and
renormalises them; the verdict is chosen again as femup chooses it (the most
probable family, within it its most probable fitted class) and scored with
run_suite.py's own scoring.

For the Laplace posterior this is exact: its probabilities are prior times
evidence, and the evidences do not depend on the prior. femup's stated
probability is the bagged posterior (bagged_posterior.h), the mean over
bootstrap copies of each copy's posterior; reweighting the mean is not the
mean of the reweighted copies, so for it the rescoring is an approximation
(exact at f = 1; `--check` confirms that f = 1 reproduces results.jsonl).

A gap threshold g instead keeps the prior and names a gap only where its
probability, 1 - P(none), is at least g (as femup does with the study's
diagnosis.gap_confidence; --gap-threshold 0 decides as femup did before it).
Either way, as femup does, an effect that explains less than the run's
diagnosis.gap_explained of the nominal misfit beyond the noise (its class's
"explained" in diagnosis.json; runs before session 57 have neither and are
decided without it) is not named: the verdict is none (--gap-explained E
decides with E instead).

Usage:
  python3 validation/blind_structures/rescore.py OUT [--none-share S | --gap-threshold G]
      [--gap-explained E] [--partial] [--check]
"""
import argparse
import glob
import json
import os
import sys
import types

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_suite  # noqa: E402


def reweighted(d, share, gap_threshold=None, gap_explained=None):
    """diagnosis.json d with none's prior share set to `share` (None: as run)
    and, with a gap threshold g, the verdict `none` unless the probability of
    any gap (1 - P(none)) is at least g (None: as run, the study's
    gap_confidence; 0: the most probable family); and `none` where the class
    chosen explains less than gap_explained of the gap (None: as run)."""
    if gap_threshold is None:
        gap_threshold = d.get("gap_confidence", 0)
    if gap_explained is None:
        gap_explained = d.get("gap_explained", 0)
    kinds = sorted({c["kind"] for c in d["classes"] if c["kind"] != "none"})
    f = 1.0 if share is None else share / (1.0 - share) * max(1, len(kinds))
    e = json.loads(json.dumps(d))
    for key in ("probability", "laplace_probability"):
        total = 0.0
        for c in e["classes"]:
            if c["kind"] == "none":
                c[key] *= f
            total += c[key]
        for c in e["classes"]:
            c[key] /= total
    by_kind = {}
    for c in e["classes"]:
        by_kind[c["kind"]] = by_kind.get(c["kind"], 0.0) + c["probability"]
    top_kind = max(by_kind, key=by_kind.get)
    if "none" in by_kind and 1 - by_kind["none"] < gap_threshold:
        top_kind = "none"
    members = [c for c in e["classes"] if c["kind"] == top_kind]
    fitted = [c for c in members if c.get("fitted", True)] or members
    top = max(fitted, key=lambda c: c["probability"])
    if top["kind"] != "none" and top.get("explained", 1.0) < gap_explained:
        nones = [c for c in e["classes"] if c["kind"] == "none"]
        if nones:
            top_kind, top = "none", nones[0]
    v = e["verdict"]
    if (top["kind"], top["region"]) != (v["kind"], v["region"]):
        v.update(kind=top["kind"], region=top["region"], equivalent=top.get("equivalent", []),
                 group_probability=top.get("group_probability", top["probability"]))
    v["probability"] = top["probability"]
    v["kind_probability"] = by_kind[top_kind]
    return e


def rescore(out, share, gap_threshold=None, partial=False, seed=0, gap_explained=None):
    """(rows, summary) of the folder's cases rescored; partial: only the cases
    with a diagnosis, in a folder whose run was stopped (no summary.json: the
    suite's name from the cases', its seed as given, its other settings the
    defaults)."""
    path = os.path.join(out, "summary.json")
    if os.path.isfile(path):
        with open(path) as f:
            s = json.load(f)
    elif partial:
        names = sorted(glob.glob(os.path.join(out, "truth", "*.json")))
        suite = os.path.basename(names[0]).rsplit("_", 1)[0] if names else "?"
        s = dict(suite=suite, seed=seed, noise_free=False, floors="flexible",
                 foundation="clamped", design="mixed", stated_model_error=0.0,
                 diagnosis_keys=["(a stopped run: the cases it finished)"])
    else:
        raise SystemExit("rescore: %s has no summary.json (not a finished run_suite.py "
                         "folder; --partial scores the cases it has)" % out)
    rows = []
    for path in sorted(glob.glob(os.path.join(out, "truth", "*.json"))):
        with open(path) as f:
            truth = json.load(f)
        run = os.path.join(out, "runs", truth["name"], "diagnosis.json")
        if not os.path.isfile(run) and partial:
            continue
        if not os.path.isfile(run):
            raise SystemExit("rescore: %s has no diagnosis (%s)" % (truth["name"], run))
        with open(run) as f:
            d = json.load(f)
        rows.append(run_suite.score(truth, reweighted(d, share, gap_threshold, gap_explained)))
    args = types.SimpleNamespace(
        suite=s["suite"], seed=s["seed"], noise_free=s["noise_free"], floors=s["floors"],
        foundation=s["foundation"], design=s["design"], jacket_water=s.get("jacket_water"),
        stated_model_error=s["stated_model_error"], diagnosis=s.get("diagnosis_keys", []))
    return rows, run_suite.summarise(rows, args)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="a run_suite.py output folder")
    ap.add_argument("--none-share", type=float, default=0.5,
                    help="none's share of the prior, in (0, 1) (default 0.5: a gap and "
                    "no gap equally probable before the data)")
    ap.add_argument("--gap-threshold", type=float, default=None,
                    help="with the prior as run: name a gap only where its probability "
                    "(1 - P(none)) is at least this, in [0, 1); else the verdict is none "
                    "(0: the most probable family, as femup decided before the gap's "
                    "confidence; default: as run)")
    ap.add_argument("--gap-explained", type=float, default=None,
                    help="name an effect only where it explains at least this share of "
                    "the nominal misfit beyond the noise, in [0, 1) (0: however little; "
                    "default: as run)")
    ap.add_argument("--partial", action="store_true",
                    help="score only the cases that have a diagnosis (a stopped run)")
    ap.add_argument("--seed", type=int, default=0,
                    help="with --partial: the suite's seed, for the table's title")
    ap.add_argument("--check", action="store_true",
                    help="rescore at the prior as run and compare with results.jsonl")
    args = ap.parse_args()
    if not (0 < args.none_share < 1):
        ap.error("--none-share must be in (0, 1)")
    if not os.path.isdir(os.path.join(args.out, "truth")):
        ap.error("%s: no truth folder (not a run_suite.py folder)" % args.out)
    if args.gap_explained is not None and not (0 <= args.gap_explained < 1):
        ap.error("--gap-explained must be in [0, 1)")
    if args.check and args.partial:
        ap.error("--check compares with results.jsonl, which a stopped run lacks")
    if args.check:
        rows, _ = rescore(args.out, None)
        with open(os.path.join(args.out, "results.jsonl")) as f:
            old = [json.loads(line) for line in f]
        keys = ("verdict_kind", "verdict_region", "kind_right", "class_right")
        bad = [r["name"] for r, o in zip(rows, old) if any(r[k] != o[k] for k in keys) or
               abs(r["probability"] - o["probability"]) > 1e-9]
        if len(rows) != len(old) or bad:
            print("rescore --check: differs from results.jsonl: %s" % (bad or "case count"))
            return 1
        print("rescore --check: %d cases as in results.jsonl" % len(rows))
        return 0
    if args.gap_threshold is not None:
        if not (0 <= args.gap_threshold < 1):
            ap.error("--gap-threshold must be in [0, 1)")
        _, s = rescore(args.out, None, args.gap_threshold, args.partial, args.seed,
                       args.gap_explained)
        how = "a gap named at P >= %g" % args.gap_threshold
    elif args.gap_explained is not None and "--none-share" not in sys.argv:
        _, s = rescore(args.out, None, None, args.partial, args.seed, args.gap_explained)
        how = "an effect named where it explains >= %g of the gap" % args.gap_explained
    else:
        _, s = rescore(args.out, args.none_share, 0, args.partial, args.seed,
                       args.gap_explained)
        how = "none's prior share %g" % args.none_share
    s["diagnosis_keys"] = s["diagnosis_keys"] + ["(rescored: %s)" % how]
    print(run_suite.table(s), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
