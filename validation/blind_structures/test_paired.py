"""Checks of paired.py on hand-made result rows (run: python3 -m unittest, from
this folder; tests/scenario/blind_structures.sh runs it)."""
import json
import math
import os
import tempfile
import unittest

import paired


def row(name, truth, verdict, right, informative=True, probability=0.5, bic=False):
    return dict(name=name, truth_kind=truth, truth="t-" + name, verdict_kind=verdict,
                kind_right=right, class_right=right, bic_kind_right=bic,
                informative=informative, probability=probability,
                kind_probability=probability)


class SignTestTest(unittest.TestCase):
    def test_against_the_binomial_written_out(self):
        # 1 against 7: 2 (C(8,0) + C(8,1)) / 2^8 = 18 / 256.
        self.assertAlmostEqual(paired.sign_test(1, 7), 18 / 256)
        self.assertAlmostEqual(paired.sign_test(7, 1), 18 / 256)
        self.assertEqual(paired.sign_test(0, 0), 1.0)
        self.assertEqual(paired.sign_test(3, 3), 1.0)  # capped at 1
        # 0 against 10: 2 / 1024.
        self.assertAlmostEqual(paired.sign_test(0, 10), 2 / 1024)
        self.assertAlmostEqual(paired.sign_test(2, 5),
                               2 * sum(math.comb(7, i) for i in range(3)) / 128)


class CompareTest(unittest.TestCase):
    def setUp(self):
        self.a = {r["name"]: r for r in [
            row("c0", "stiffness_loss", "stiffness_loss", True, probability=0.95),
            row("c1", "attached_mass", "stiffness_loss", False, informative=False),
            row("c2", "none", "stiffness_loss", False, probability=0.8),
            row("c3", "none", "none", True, bic=True),
            row("c4", "material_scaling", "material_scaling", True, probability=0.75)]}
        self.b = {r["name"]: r for r in [
            row("c0", "stiffness_loss", "stiffness_loss", True, probability=0.92),
            row("c1", "attached_mass", "attached_mass", True, informative=False),
            row("c2", "none", "none", True, probability=0.8),
            row("c3", "none", "attached_mass", False, bic=True),
            row("c4", "material_scaling", "material_scaling", True, probability=0.95)]}

    def test_counts_each_runs_own_cases_and_the_changes(self):
        c = paired.compare(self.a, self.b)
        self.assertEqual(c["cases"], 5)
        kind = c["scores"][0]
        self.assertEqual((kind["a"], kind["b"], kind["a_only"], kind["b_only"]), (3, 4, 1, 2))
        self.assertAlmostEqual(kind["p"], 1.0)
        alarms = c["scores"][3]
        self.assertIn("of 2", alarms["score"])
        self.assertEqual((alarms["a"], alarms["b"], alarms["a_only"], alarms["b_only"]),
                         (1, 1, 1, 1))
        bic = c["scores"][2]
        self.assertEqual((bic["a"], bic["b"], bic["a_only"], bic["b_only"]), (1, 1, 0, 0))
        figures = {f["figure"]: (f["a"], f["b"]) for f in c["figures"]}
        self.assertEqual(figures["top-1 kind, all (5)"], (0.6, 0.8))
        self.assertEqual(figures["top-1 kind, informative (4)"], (0.75, 0.75))
        self.assertEqual(figures["top-1 kind, weak (1)"], (0.0, 1.0))
        stated = {(s["run"], s["lower"]): (s["cases"], s["right"]) for s in c["stated"]}
        self.assertEqual(stated[("a", 0.9)], (1, 1))
        self.assertEqual(stated[("b", 0.9)], (2, 2))
        self.assertEqual(stated[("a", 0.7)], (2, 1))
        self.assertEqual(stated[("b", 0.7)], (1, 1))
        self.assertEqual([ch["name"] for ch in c["changed"]], ["c1", "c2", "c3"])
        self.assertIn("c1 (attached_mass): stiffness_loss 0.50 - -> attached_mass 0.50 R",
                      paired.text(c, "A", "B"))

    def test_compares_the_cases_both_runs_have(self):
        del self.b["c4"]
        c = paired.compare(self.a, self.b)
        self.assertEqual((c["cases"], c["only_a"], c["only_b"]), (4, 1, 0))
        self.assertIn("1 in A only", paired.text(c, "A", "B"))

    def test_refuses_runs_of_other_cases(self):
        self.b["c2"] = row("c2", "attached_mass", "none", False)
        with self.assertRaises(SystemExit) as e:
            paired.compare(self.a, self.b)
        self.assertIn("c2", str(e.exception))

    def test_reads_folders_and_names_a_bad_line(self):
        with tempfile.TemporaryDirectory() as d:
            for name, rows in (("a", self.a), ("b", self.b)):
                os.makedirs(os.path.join(d, name))
                with open(os.path.join(d, name, "results.jsonl"), "w") as f:
                    for r in rows.values():
                        f.write(json.dumps(r) + "\n")
            self.assertEqual(len(paired.read(os.path.join(d, "a"))), 5)
            with open(os.path.join(d, "b", "results.jsonl"), "a") as f:
                f.write("{not json\n")
            with self.assertRaises(SystemExit) as e:
                paired.read(os.path.join(d, "b"))
            self.assertIn("line 6", str(e.exception))
            with self.assertRaises(SystemExit) as e:
                paired.read(os.path.join(d, "missing"))
            self.assertIn("no results.jsonl", str(e.exception))


if __name__ == "__main__":
    unittest.main()
