"""Checks of run_suite's scoring on hand-made diagnoses (run: python3 -m unittest,
from this folder; tests/scenario/blind_structures.sh runs it)."""
import math
import types
import unittest

import run_suite


def diagnosis(verdict, classes, residuals=20, temperature=1.0):
    """A diagnosis.json as femup writes it, reduced to what the scoring reads."""
    kind, region, p = verdict
    return dict(
        verdict=dict(kind=kind, region=region, probability=p, kind_probability=p,
                     group_probability=p, equivalent=[]),
        residuals=residuals, temperature=temperature,
        classes=[dict(kind=k, region=r, chi2=c, parameters=[{}] * n) for k, r, c, n in classes])


def truth(kind, region, regions=None, shift=10.0, modes=4, shapes=True):
    t = dict(name="case", kind=kind, region=region, description="", shift_in_noise=shift,
             modes=modes, shapes=shapes, sensors=4, frequency_noise=0.002, nominal_gap=0.004,
             building=dict(storeys=6))
    if regions is not None:
        t["regions"] = regions
    return t


class ScoreTest(unittest.TestCase):
    def test_laplace_verdict_scored_from_the_same_fits(self):
        d = diagnosis(("attached_mass", "node n4", 0.6),
                      [("attached_mass", "node n4", 10.0, 1), ("stiffness_loss", "element 3", 11.0, 1)])
        d["classes"][0]["laplace_probability"] = 0.3
        d["classes"][1]["laplace_probability"] = 0.7
        r = run_suite.score(truth("stiffness_loss", "element 3"), d)
        self.assertFalse(r["kind_right"])
        self.assertTrue(r["laplace_kind_right"])
        self.assertTrue(r["laplace_class_right"])
        self.assertAlmostEqual(r["laplace_probability"], 0.7)
        self.assertAlmostEqual(r["laplace_kind_probability"], 0.7)
        self.assertEqual(r["laplace_kind"], "stiffness_loss")

    def test_brier_score(self):
        rows = [dict(p=1.0, ok=True), dict(p=0.5, ok=False), dict(p=0.8, ok=False)]
        self.assertAlmostEqual(run_suite.brier(rows, "p", "ok"), (0 + 0.25 + 0.64) / 3)

    def test_right_kind_and_region(self):
        d = diagnosis(("stiffness_loss", "element 3", 0.95),
                      [("stiffness_loss", "element 3", 10.0, 1), ("none", "", 200.0, 0)])
        r = run_suite.score(truth("stiffness_loss", "element 3"), d)
        self.assertTrue(r["kind_right"])
        self.assertTrue(r["class_right"])
        self.assertTrue(r["strict_class_right"])
        self.assertTrue(r["informative"])
        self.assertAlmostEqual(r["nominal_gap_in_noise"], 2.0)

    def test_ground_spring_and_first_storey_are_one_group_on_a_chain(self):
        d = diagnosis(("stiffness_loss", "element 1", 0.6),
                      [("stiffness_loss", "element 1", 10.0, 1),
                       ("support_flexibility", "supports", 10.0, 1)])
        r = run_suite.score(truth("support_flexibility", "supports"), d)
        self.assertTrue(r["kind_right"])
        self.assertTrue(r["class_right"])
        self.assertFalse(r["strict_class_right"])
        # Another storey is not in the group.
        d2 = diagnosis(("stiffness_loss", "element 2", 0.6),
                       [("stiffness_loss", "element 2", 10.0, 1)])
        self.assertFalse(run_suite.score(truth("support_flexibility", "supports"), d2)["kind_right"])

    def test_any_listed_region_is_right(self):
        d = diagnosis(("attached_mass", "node n4", 0.9), [("attached_mass", "node n4", 5.0, 1)])
        t = truth("attached_mass", "node n7", regions=["node n7", "node n3", "node n4"])
        self.assertTrue(run_suite.score(t, d)["class_right"])

    def test_flat_bic_is_least_chi2_plus_k_ln_n(self):
        # ln 20 = 3.0: one parameter must buy more than 3.0 of chi2.
        classes = [("none", "", 12.0, 0), ("material_scaling", "all elements", 9.5, 1)]
        r = run_suite.score(truth("none", ""), diagnosis(("material_scaling", "all elements", 0.7),
                                                         classes))
        self.assertTrue(r["bic_kind_right"])  # 12.0 < 9.5 + 3.0
        self.assertFalse(r["kind_right"])
        classes[1] = ("material_scaling", "all elements", 8.0, 1)
        r = run_suite.score(truth("none", ""), diagnosis(("none", "", 0.7), classes))
        self.assertFalse(r["bic_kind_right"])  # 8.0 + 3.0 < 12.0
        self.assertTrue(r["kind_right"])

    def test_weak_data_are_not_informative(self):
        d = diagnosis(("none", "", 0.9), [("none", "", 1.0, 0)])
        self.assertFalse(run_suite.score(truth("none", "", modes=2), d)["informative"])
        self.assertFalse(run_suite.score(truth("none", "", shapes=False), d)["informative"])
        self.assertFalse(run_suite.score(truth("attached_mass", "node x2", shift=4.0), d)[
            "informative"])


class DiagnosisKeysTest(unittest.TestCase):
    def test_keys_go_at_the_top_of_the_diagnosis_section(self):
        text = "model:\n  type: chain\ndiagnosis:\n  use_shapes: true\n"
        self.assertEqual(run_suite.with_diagnosis_keys(text, [("members_fitted", "-1")]),
                         "model:\n  type: chain\ndiagnosis:\n  members_fitted: -1\n"
                         "  use_shapes: true\n")
        self.assertEqual(run_suite.with_diagnosis_keys(text, []), text)
        with self.assertRaises(ValueError):
            run_suite.with_diagnosis_keys("model:\n  type: chain\n", [("a", "1")])


class SummaryTest(unittest.TestCase):
    def test_figures_and_reliability_bins(self):
        rows = []
        for i, (kind, verdict, p) in enumerate([("none", "none", 0.95), ("none", "material_scaling", 0.8),
                                                ("stiffness_loss", "stiffness_loss", 0.99),
                                                ("attached_mass", "none", 0.4)]):
            region = "element 2" if kind == "stiffness_loss" else ""
            d = diagnosis((verdict, region if verdict == kind else "", p),
                          [(verdict, region if verdict == kind else "", 1.0, 0)])
            t = truth(kind, region)
            t["name"] = "c%d" % i
            rows.append(run_suite.score(t, d))
        args = types.SimpleNamespace(suite="shear_building", seed=1, noise_free=False,
                                     floors="flexible", foundation="clamped", design="mixed",
                                     stated_model_error=0.0)
        s = run_suite.summarise(rows, args)
        self.assertEqual(s["cases"], 4)
        self.assertAlmostEqual(s["top1_kind"], 0.5)
        self.assertAlmostEqual(s["false_alarms_on_none"], 0.5)
        bins = {b["lower"]: b for b in s["reliability_class"]}
        self.assertEqual(bins[0.9]["cases"], 2)
        self.assertAlmostEqual(bins[0.9]["fraction_right"], 1.0)
        self.assertEqual(bins[0.7]["cases"], 1)
        self.assertAlmostEqual(bins[0.7]["fraction_right"], 0.0)
        self.assertEqual(sum(b["cases"] for b in s["reliability_class"]), 4)
        self.assertEqual(s["confusion"]["none"], {"none": 1, "material_scaling": 1})
        self.assertTrue(math.isfinite(s["median_nominal_gap"]))
        self.assertIn("| top-1 kind, all | 50.0 % |", run_suite.table(s))


if __name__ == "__main__":
    unittest.main()
