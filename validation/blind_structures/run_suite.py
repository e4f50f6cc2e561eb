#!/usr/bin/env python3
"""Blind suites of `femup diagnose` on structures other than the cantilever.

Generates cases (study files; the truth kept in a separate folder the diagnosis
never reads), runs `femup diagnose` on each, scores every verdict against its
truth and writes:
  OUT/cases/<case>.yaml     the study files (what the diagnosis sees)
  OUT/truth/<case>.json     the truths
  OUT/runs/<case>/          each diagnosis's output
  OUT/results.jsonl         one line per case: truth, verdict, scores
  OUT/summary.json          the suite's figures (below)
  OUT/reliability.png       stated probability against fraction right
  OUT/summary.md            the figures as a table a person reads

Figures: top-1 kind (overall, where the data are informative: >= 3 modes with
shapes and a largest shift >= 5 sigma, and where they are weak), top-1 class
(kind and region), false alarms on `none`, and calibration: the verdicts binned
by their stated probability against the fraction right. A flat information
criterion (BIC: chi2 + parameters x ln residuals, equal prior on every class)
is scored on the same fits, side by side.

Observational equivalence: on a chain, the ground spring's flexibility and the
first storey's stiffness loss are the same change of the model; a verdict
naming either, for a truth of either, is right (and counted apart as such).

Suites: shear_building, plane_frame, jacket (femup's space_frame in water; see
jacket.py for how its truths are made; --foundation springs stands every jacket
on springs under its legs and adds soft_foundation), cantilever (a bar; its
study files run on the one engine by default since session 59, and on the
cantilever's own pipeline with --diagnosis engine=cantilever: both are scored
alike).

Usage:
  python3 validation/blind_structures/run_suite.py --suite shear_building \
      --cases 100 --seed 20261126 --femup build/femup -o out/blind_shear_building
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cantilever  # noqa: E402
import jacket  # noqa: E402
import plane_frame  # noqa: E402
import shear_building  # noqa: E402

SUITES = {"shear_building": shear_building, "plane_frame": plane_frame, "jacket": jacket,
          "cantilever": cantilever}
# Classes that these models cannot tell apart (kind, region) -> group name.
EQUIVALENT = {
    ("support_flexibility", "supports"): "base",
    ("stiffness_loss", "element 1"): "base",
}


def group(kind, region):
    return EQUIVALENT.get((kind, region), kind + "@" + region)


def diagnose(femup, case_file, out_dir):
    if os.path.exists(out_dir):
        shutil.rmtree(out_dir)
    r = subprocess.run([femup, "diagnose", case_file, "-o", out_dir, "-q", "--no-plots"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr.strip()
    with open(os.path.join(out_dir, "diagnosis.json")) as f:
        return json.load(f), ""


def from_cantilever_pipeline(d):
    """A diagnosis.json of the cantilever's own pipeline (diagnosis.engine:
    cantilever) in the one engine's terms: each class's kind (a pair's label,
    "a+b", which no single truth matches), its region named as the one engine
    names it from the fitted location (an attached mass at the nearest node, a
    stiffness loss on the element holding the band's middle), its chi2 and
    parameters, and the verdict's family probability from the kinds'."""
    length = d["length"]
    le = length / cantilever.ELEMENTS

    def region(e):
        loc = e.get("location") or {}
        if e["kind"] == "attached_mass" and "x" in loc:
            return "node n%d" % max(1, min(cantilever.ELEMENTS, round(loc["x"] / le)))
        if e["kind"] == "stiffness_loss" and "x" in loc:
            return "element e%d" % max(1, min(cantilever.ELEMENTS, math.ceil(loc["x"] / le)))
        return {"added_mass": "below the water level", "support_flexibility": "supports",
                "material_scaling": "all elements"}.get(e["kind"], "")

    classes = [dict(kind=e["kind"], region=region(e), chi2=e["chi2"],
                    parameters=list(e["parameters"]), probability=e["probability"])
               for e in d["effects"]]
    top = classes[0]
    kp = d.get("kind_probabilities", {})
    v = dict(kind=top["kind"], region=top["region"], probability=top["probability"],
             kind_probability=kp.get(top["kind"], top["probability"]))
    return dict(verdict=v, classes=classes, residuals=d["noise"]["degrees_of_freedom"],
                temperature=d["noise"]["temperature"])


def score(truth, d):
    """The case's line of results.jsonl."""
    if "effects" in d and "classes" not in d:
        d = from_cantilever_pipeline(d)
    v = d["verdict"]
    kind_right = v["kind"] == truth["kind"]
    class_right = kind_right and v["region"] in truth.get("regions", [truth["region"]])
    # Equivalence-aware: the verdict's group (its equivalent classes) holds the truth.
    tg = group(truth["kind"], truth["region"])
    eq_right = class_right or (truth["kind"] != "none" and group(v["kind"], v["region"]) == tg)
    kind_eq_right = kind_right or eq_right
    # Flat BIC over the same fits.
    n = max(d["residuals"], 1)
    best = min(d["classes"], key=lambda c: c["chi2"] + len(c["parameters"]) * math.log(n))
    bic_kind_right = best["kind"] == truth["kind"] or (
        truth["kind"] != "none" and group(best["kind"], best["region"]) == tg)
    # The Laplace posterior on the same fits (diagnosis.json keeps it beside the
    # bagged probability): its own verdict, chosen as femup chooses (the most
    # probable class of the most probable family), scored alike.
    lp = lambda c: c.get("laplace_probability", c.get("probability", 0.0))
    by_kind = {}
    for c in d["classes"]:
        by_kind[c["kind"]] = by_kind.get(c["kind"], 0.0) + lp(c)
    lap_kind = max(by_kind, key=by_kind.get)
    lap = max((c for c in d["classes"] if c["kind"] == lap_kind), key=lp)
    # femup names no effect that explains less than gap_explained of the gap.
    nones = [c for c in d["classes"] if c["kind"] == "none"]
    if lap["kind"] != "none" and nones and lap.get("explained", 1.0) < d.get("gap_explained", 0):
        lap_kind, lap = "none", nones[0]
    lap_p = lp(lap)
    lap_kind_p = by_kind[lap_kind]
    lap_class_right = (lap["kind"] == truth["kind"] and
                       lap["region"] in truth.get("regions", [truth["region"]])) or (
        truth["kind"] != "none" and group(lap["kind"], lap["region"]) == tg)
    lap_kind_right = lap["kind"] == truth["kind"] or lap_class_right
    informative = (truth["modes"] >= 3 and truth["shapes"] and
                   (truth["kind"] == "none" or truth["shift_in_noise"] >= 5))
    return dict(
        name=truth["name"], truth_kind=truth["kind"], truth_region=truth["region"],
        truth_effect=truth.get("truth_kind", truth["kind"]),
        truth=truth["description"], shift_in_noise=truth["shift_in_noise"],
        modes=truth["modes"], shapes=truth["shapes"], sensors=truth["sensors"],
        frequency_noise=truth["frequency_noise"], nominal_gap=truth["nominal_gap"],
        nominal_gap_in_noise=truth["nominal_gap"] / truth["frequency_noise"],
        storeys=truth["building"]["storeys"], informative=informative,
        verdict_kind=v["kind"], verdict_region=v["region"], probability=v["probability"],
        kind_probability=v["kind_probability"],
        group_probability=v.get("group_probability", v["probability"]),
        equivalent=v.get("equivalent", []), temperature=d["temperature"],
        kind_right=kind_eq_right, class_right=eq_right, strict_class_right=class_right,
        bic_kind=best["kind"], bic_region=best["region"], bic_kind_right=bic_kind_right,
        laplace_kind=lap["kind"], laplace_probability=lap_p,
        laplace_kind_probability=lap_kind_p, laplace_kind_right=lap_kind_right,
        laplace_class_right=lap_class_right)


def with_diagnosis_keys(text, keys):
    """A study file's text with (key, value) pairs added at the top of its
    diagnosis section (run_suite --diagnosis)."""
    if not keys:
        return text
    if "\ndiagnosis:\n" not in text:
        raise ValueError("the study file has no diagnosis section for --diagnosis")
    lines = "".join("  %s: %s\n" % kv for kv in keys)
    return text.replace("\ndiagnosis:\n", "\ndiagnosis:\n" + lines, 1)


def fraction(rows, key):
    return (sum(1 for r in rows if r[key]) / len(rows)) if rows else float("nan")


def reliability(rows, prob_key, right_key, edges=(0.0, 0.5, 0.7, 0.9, 1.0001)):
    bins = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = [r for r in rows if lo <= r[prob_key] < hi]
        bins.append(dict(lower=lo, upper=min(hi, 1.0), cases=len(sel),
                         mean_stated=float(np.mean([r[prob_key] for r in sel])) if sel else None,
                         fraction_right=fraction(sel, right_key) if sel else None))
    return bins


def brier(rows, prob_key, right_key):
    """Mean squared difference of the verdict's stated probability and its being
    right (0 or 1): 0 is perfect, 0.25 what always stating 0.5 scores."""
    return float(np.mean([(r[prob_key] - (1.0 if r[right_key] else 0.0)) ** 2
                          for r in rows])) if rows else float("nan")


def summarise(rows, args):
    inf = [r for r in rows if r["informative"]]
    weak = [r for r in rows if not r["informative"]]
    none = [r for r in rows if r["truth_kind"] == "none"]
    s = dict(
        suite=args.suite, cases=len(rows), seed=args.seed, noise_free=args.noise_free,
        floors=args.floors, foundation=args.foundation, design=args.design,
        jacket_water=getattr(args, "jacket_water", None) if args.suite == "jacket" else None,
        stated_model_error=args.stated_model_error, diagnosis_keys=list(getattr(args, "diagnosis", [])),
        top1_kind=fraction(rows, "kind_right"), top1_class=fraction(rows, "class_right"),
        informative_cases=len(inf), top1_kind_informative=fraction(inf, "kind_right"),
        top1_class_informative=fraction(inf, "class_right"),
        weak_cases=len(weak), top1_kind_weak=fraction(weak, "kind_right"),
        bic_top1_kind=fraction(rows, "bic_kind_right"),
        bic_top1_kind_informative=fraction(inf, "bic_kind_right"),
        bic_top1_kind_weak=fraction(weak, "bic_kind_right"),
        none_cases=len(none),
        false_alarms_on_none=(sum(1 for r in none if r["verdict_kind"] != "none") / len(none))
        if none else float("nan"),
        # The model's own form error (its gap to the undamaged truth) within 3
        # noise units, or beyond: where it is beyond, a family that absorbs it is
        # named on "none" cases.
        none_small_gap=len([r for r in none if r["nominal_gap_in_noise"] < 3]),
        false_alarms_small_gap=fraction([dict(x=r["verdict_kind"] != "none") for r in none
                                         if r["nominal_gap_in_noise"] < 3], "x"),
        false_alarms_large_gap=fraction([dict(x=r["verdict_kind"] != "none") for r in none
                                         if r["nominal_gap_in_noise"] >= 3], "x"),
        noise_scaled=sum(1 for r in rows if r["temperature"] > 1),
        reliability_class=reliability(rows, "probability", "class_right"),
        brier_class=brier(rows, "probability", "class_right"),
        # The Laplace posterior on the same fits.
        laplace=dict(
            top1_kind=fraction(rows, "laplace_kind_right"),
            top1_kind_informative=fraction(inf, "laplace_kind_right"),
            top1_kind_weak=fraction(weak, "laplace_kind_right"),
            top1_class=fraction(rows, "laplace_class_right"),
            false_alarms_on_none=(sum(1 for r in none if r["laplace_kind"] != "none") /
                                  len(none)) if none else float("nan"),
            reliability_class=reliability(rows, "laplace_probability", "laplace_class_right"),
            brier_class=brier(rows, "laplace_probability", "laplace_class_right")),
        reliability_kind=reliability(rows, "kind_probability", "kind_right"),
        per_effect={k: dict(cases=len([r for r in rows if r["truth_effect"] == k]),
                            top1_kind=fraction([r for r in rows if r["truth_effect"] == k],
                                               "kind_right"))
                    for k in sorted(set(r["truth_effect"] for r in rows))},
        confusion={},
        median_nominal_gap=float(np.median([r["nominal_gap"] for r in rows])))
    for r in rows:
        s["confusion"].setdefault(r["truth_effect"], {}).setdefault(r["verdict_kind"], 0)
        s["confusion"][r["truth_effect"]][r["verdict_kind"]] += 1
    return s


def plot(summary, out):
    if shutil.which("gnuplot") is None:
        return "gnuplot not found: reliability.png not drawn"
    data = os.path.join(out, "reliability.dat")
    with open(data, "w") as f:
        for key in ("reliability_class", "reliability_kind"):
            for b in summary[key]:
                if b["cases"]:
                    f.write("%g %g %d\n" % (b["mean_stated"], b["fraction_right"], b["cases"]))
            f.write("\n\n")
    script = """set terminal pngcairo size 720,600
set output '%s'
set title "%s: stated probability against fraction right (%d cases)"
set xlabel 'stated probability of the verdict'
set ylabel 'fraction right'
set xrange [0:1]; set yrange [0:1.05]; set key left top; set grid
plot x title 'calibrated' lt 0, \\
  '%s' index 0 using 1:2 with linespoints pt 7 ps 1.5 title 'class (kind and region)', \\
  '' index 0 using 1:2:3 with labels offset 1.5,-0.8 notitle, \\
  '' index 1 using 1:2 with linespoints pt 5 ps 1.5 title 'kind'
""" % (os.path.join(out, "reliability.png"), summary["suite"], summary["cases"], data)
    r = subprocess.run(["gnuplot"], input=script, capture_output=True, text=True)
    return "" if r.returncode == 0 else "gnuplot: " + r.stderr.strip()


def table(s):
    pct = lambda x: "n/a" if x != x else "%.1f %%" % (100 * x)
    L = s["laplace"]
    lines = [
        "# Blind suite %s: %d cases (seed %d, %s design%s%s)" % (
            s["suite"], s["cases"], s["seed"], s["design"],
            ", %s floors" % s["floors"] if s["suite"] == "shear_building" else "",
            ", noise-free" if s["noise_free"] else "") + (
            ", stated model error %g" % s["stated_model_error"] if s["stated_model_error"] else "") + (
            ", diagnosis " + ", ".join(s["diagnosis_keys"]) if s.get("diagnosis_keys") else ""),
        "",
        "| figure | femup diagnose | Laplace posterior, same fits | flat BIC |",
        "|---|---|---|---|",
        "| top-1 kind, all | %s | %s | %s |" % (pct(s["top1_kind"]), pct(L["top1_kind"]),
                                             pct(s["bic_top1_kind"])),
        "| top-1 kind, informative (%d) | %s | %s | %s |" % (
            s["informative_cases"], pct(s["top1_kind_informative"]),
            pct(L["top1_kind_informative"]), pct(s["bic_top1_kind_informative"])),
        "| top-1 kind, weak (%d) | %s | %s | %s |" % (
            s["weak_cases"], pct(s["top1_kind_weak"]), pct(L["top1_kind_weak"]),
            pct(s["bic_top1_kind_weak"])),
        "| top-1 class (kind and region) | %s | %s | |" % (pct(s["top1_class"]),
                                                        pct(L["top1_class"])),
        "| false alarms on none (%d) | %s | %s | |" % (
            s["none_cases"], pct(s["false_alarms_on_none"]), pct(L["false_alarms_on_none"])),
        "| ... where the model's own gap < 3 noise units (%d) | %s | | |" % (
            s["none_small_gap"], pct(s["false_alarms_small_gap"])),
        "| ... where it is >= 3 noise units (%d) | %s | | |" % (
            s["none_cases"] - s["none_small_gap"], pct(s["false_alarms_large_gap"])),
        "| Brier score of the verdict's class probability | %.3f | %.3f | |" % (
            s["brier_class"], L["brier_class"]),
        "",
        "Calibration (the verdict's stated probability, class level; the diagnosis's, and "
        "the Laplace posterior's on the same fits):",
        "",
        "| stated | cases | mean stated | fraction right | Laplace: cases | mean stated | "
        "fraction right |",
        "|---|---|---|---|---|---|---|",
    ]
    for b, c in zip(s["reliability_class"], L["reliability_class"]):
        lines.append("| %.1f-%.1f | %d | %s | %s | %d | %s | %s |" % (
            b["lower"], b["upper"], b["cases"],
            "" if b["mean_stated"] is None else "%.2f" % b["mean_stated"],
            "" if b["fraction_right"] is None else pct(b["fraction_right"]), c["cases"],
            "" if c["mean_stated"] is None else "%.2f" % c["mean_stated"],
            "" if c["fraction_right"] is None else pct(c["fraction_right"])))
    lines += ["", "Confusion (truth's effect -> verdict kind):", ""]
    for t, row in sorted(s["confusion"].items()):
        lines.append("- %s: %s" % (t, ", ".join("%s %d" % kv for kv in sorted(row.items()))))
    lines += ["", "Median nominal gap (rms relative frequency error of the model against the "
              "undamaged truth, measured modes): %.2f %%" % (100 * s["median_nominal_gap"]),
              "Cases where the diagnosis scaled the noise: %d" % s["noise_scaled"]]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--suite", default="shear_building", choices=sorted(SUITES))
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--seed", type=int, default=20261126)
    ap.add_argument("--design", default="mixed", choices=["mixed", "informative", "two_losses"],
                    help="two_losses: every case two damaged storeys (shear_building "
                         "only; give --diagnosis max_effects=2)")
    ap.add_argument("--floors", default="flexible", choices=["flexible", "stiff"],
                    help="shear_building: beam-to-column stiffness 10-100 or 1000-10000")
    ap.add_argument("--foundation", default="clamped", choices=["clamped", "springs", "soft"],
                    help="plane_frame, jacket: bases clamped (default), or on springs in "
                         "model and truth, with soft_foundation among the kinds; "
                         "plane_frame: soft, the model clamped and soft_foundation's "
                         "truth alone on springs")
    ap.add_argument("--jacket-water", default="as_model", choices=["as_model", "full"],
                    help="jacket: the truth's clean-tube water left out as femup's dry "
                         "nominal model leaves it out (default), or in every truth "
                         "(potential flow, Ca 1); see jacket.py")
    ap.add_argument("--noise-free", action="store_true",
                    help="draw the noise but do not add it (the studies state it)")
    ap.add_argument("--stated-model-error", type=float, default=0.0,
                    help="the relative frequency error the engineer states for the model's "
                    "idealisation (e.g. 0.01), added in quadrature to the stated frequency "
                    "noise of every study file (the noise drawn stays the measurement's)")
    ap.add_argument("--chain-as-building", action="store_true",
                    help="shear_building: the chain models say `shear_building: true` (the "
                    "engineer states that the chain idealises a building; femup allows for "
                    "the building's flexural deformation as model form error)")
    ap.add_argument("--diagnosis", action="append", default=[], metavar="KEY=VALUE",
                    help="a key of the study files' diagnosis section, e.g. "
                    "members_fitted=-1 (repeatable), to compare settings on the same cases")
    ap.add_argument("--femup", default="build/femup")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 2)
    ap.add_argument("-o", "--out", default=None)
    args = ap.parse_args()
    if args.cases < 1:
        ap.error("--cases must be at least 1")
    if args.chain_as_building and args.suite != "shear_building":
        ap.error("--chain-as-building: only the shear_building suite has chain models")
    if args.foundation != "clamped" and args.suite not in ("plane_frame", "jacket"):
        ap.error("--foundation %s: only the plane_frame and jacket suites have "
                 "column bases" % args.foundation)
    if args.foundation == "soft" and args.suite != "plane_frame":
        ap.error("--foundation soft: only the plane_frame suite")
    if args.design == "two_losses" and args.suite != "shear_building":
        ap.error("--design two_losses: only the shear_building suite")
    if not (0 <= args.stated_model_error < 1):
        ap.error("--stated-model-error must be in [0, 1)")
    if not (os.path.isfile(args.femup) and os.access(args.femup, os.X_OK)):
        ap.error("--femup %s: not an executable file (build femup first)" % args.femup)
    extra_keys = []
    for kv in args.diagnosis:
        key, sep, value = kv.partition("=")
        if not sep or not key.strip() or not value.strip():
            ap.error("--diagnosis %r: expected KEY=VALUE" % kv)
        extra_keys.append((key.strip(), value.strip()))
    out = args.out or os.path.join("out", "blind_" + args.suite)
    for sub in ("cases", "truth", "runs"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    gen = SUITES[args.suite]
    rng = np.random.default_rng(args.seed)
    truths = []
    for i in range(args.cases):
        name = "%s_%03d" % (args.suite, i)
        extra = dict(water=args.jacket_water) if args.suite == "jacket" else {}
        study, truth = gen.make_case(rng, name, args.design, args.noise_free, args.floors,
                                     args.foundation, **extra)
        if args.chain_as_building:
            study["shear_building"] = True
        if args.stated_model_error > 0:
            study["frequency_noise"] = math.hypot(study["frequency_noise"],
                                                  args.stated_model_error)
        with open(os.path.join(out, "cases", name + ".yaml"), "w") as f:
            f.write(with_diagnosis_keys(gen.study_yaml(study), extra_keys))
        with open(os.path.join(out, "truth", name + ".json"), "w") as f:
            json.dump(truth, f, indent=1)
        truths.append(truth)
    rows, failures = [], []
    with cf.ThreadPoolExecutor(max_workers=max(1, args.threads)) as pool:
        futures = {pool.submit(diagnose, args.femup, os.path.join(out, "cases", t["name"] + ".yaml"),
                               os.path.join(out, "runs", t["name"])): t for t in truths}
        for fut in cf.as_completed(futures):
            t = futures[fut]
            d, err = fut.result()
            if d is None:
                failures.append((t["name"], err))
            else:
                rows.append(score(t, d))
    rows.sort(key=lambda r: r["name"])
    with open(os.path.join(out, "results.jsonl"), "w") as f:
        for r in rows:
            f.write(json.dumps(r) + "\n")
    if failures:
        for name, err in failures:
            print("%s: femup diagnose failed: %s" % (name, err), file=sys.stderr)
        return 1
    s = summarise(rows, args)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    note = plot(s, out)
    text = table(s)
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write(text)
    print(text, end="")
    if note:
        print(note, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
