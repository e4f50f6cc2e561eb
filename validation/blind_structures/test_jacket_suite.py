"""Checks of the jacket suite's case generator (run: python3 -m unittest
test_jacket_suite, from this folder)."""
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np
import yaml

import jacket
import run_suite
from test_run_suite import diagnosis

FEMUP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "femup")


def case(seed, kind=None, **kw):
    """The first case of a seed whose effect is `kind` (any with None)."""
    rng = np.random.default_rng(seed)
    for i in range(200):
        study, truth = jacket.make_case(rng, "c%d" % i, **kw)
        if kind is None or truth["truth_kind"] == kind:
            return study, truth
    raise AssertionError("no %s case" % kind)


class JacketSuiteTest(unittest.TestCase):
    def test_reproducible_for_a_seed(self):
        # The same case to rounding: above 600 DOF frame3d solves by ARPACK, whose
        # start vector is its own random one, so the last digits may differ.
        a = [jacket.make_case(np.random.default_rng(5), "x") for _ in range(2)]
        ya, yb = (yaml.safe_load(jacket.study_yaml(c[0])) for c in a)
        self.assertEqual(ya["model"], yb["model"])
        ma, mb = ya["measurements"][0], yb["measurements"][0]
        self.assertEqual(ma.get("sensors"), mb.get("sensors"))
        np.testing.assert_allclose(ma["frequencies_hz"], mb["frequencies_hz"], rtol=1e-8)
        if "shapes" in ma:
            np.testing.assert_allclose(ma["shapes"], mb["shapes"], atol=1e-7)
        ta, tb = a[0][1], a[1][1]
        for key in ("kind", "truth_kind", "region", "regions", "modes", "sensors", "shapes",
                    "frequency_noise", "shape_noise", "building", "detail"):
            self.assertEqual(ta[key], tb[key], key)
        for key in ("size", "shift_in_noise", "nominal_gap"):
            self.assertAlmostEqual(ta[key], tb[key], delta=1e-6 * max(1.0, abs(ta[key])))

    def test_study_files_parse_and_say_nothing_of_the_effect(self):
        rng = np.random.default_rng(11)
        for i in range(4):
            study, truth = jacket.make_case(rng, "c%d" % i)
            text = jacket.study_yaml(study)
            y = yaml.safe_load(text)
            m = y["model"]
            self.assertEqual(m["type"], "space_frame")
            self.assertEqual(m["elements_per_member"], 2)
            self.assertIn(m["levels"], (3, 4))
            self.assertTrue(8 <= m["level_height"] <= 12)
            self.assertTrue(10 <= m["bay_width_x"] <= 15 and 10 <= m["bay_width_y"] <= 15)
            self.assertTrue(0.8 * m["level_height"] <= m["water_depth"]
                            <= 2.3 * m["level_height"])
            f = y["measurements"][0]["frequencies_hz"]
            self.assertEqual(len(f), truth["modes"])
            self.assertTrue(4 <= len(f) <= 6)
            self.assertEqual(f, sorted(f))
            if truth["shapes"]:
                sensors = y["measurements"][0]["sensors"]
                self.assertTrue(all(s.split(":")[1] in ("ux", "uy") for s in sensors))
                # Leg joints only: n1 .. n(4 levels).
                self.assertTrue(all(1 <= int(s[1:].split(":")[0]) <= 4 * m["levels"]
                                    for s in sensors))
            for word in ("stiffness_loss", "attached_mass", "material_scal", "damage", "growth",
                         "deck", "brace_", "added_mass"):
                self.assertNotIn(word, text.lower())
            # At most ~1000 DOF in femup's model (2 elements per member).
            self.assertLessEqual(6 * len(jacket.model_jacket(m).labels), 1000)

    def test_on_springs_the_model_states_them_and_soft_foundation_softens_them(self):
        # --foundation springs: the study's model stands on the springs (femup's
        # model.base), the nominal truth on the same ones; a softer foundation
        # lowers every mode and is scored as support_flexibility at "supports".
        study, truth = case(1, "soft_foundation", foundation="springs")
        y = yaml.safe_load(jacket.study_yaml(study))
        base = y["model"]["base"]
        self.assertEqual(sorted(base), ["horizontal", "rocking", "torsion", "vertical"])
        self.assertTrue(all(k > 0 for k in base.values()))
        self.assertEqual((truth["kind"], truth["region"]), ("support_flexibility", "supports"))
        self.assertGreater(truth["size"], 0)
        p = study["p"]
        e = jacket.Effect("soft_foundation", np.random.default_rng(4), p)
        f0, _ = jacket.Truth(p).jacket.modes(6)
        f1, _ = jacket.Truth(p, e, 1.0).jacket.modes(6)
        self.assertTrue(np.all(f1 < f0))
        # The springs are in the model too: femup's and the stand-in's agree.
        f_model, _ = jacket.model_jacket(p).modes(4)
        f_clamped, _ = jacket.model_jacket({k: v for k, v in p.items() if k != "base"}).modes(4)
        self.assertTrue(np.all(f_model < f_clamped))
        with self.assertRaisesRegex(ValueError, "clamped or springs"):
            jacket.make_case(np.random.default_rng(1), "x", foundation="piles")

    def test_nominal_truth_close_to_femups_model(self):
        # The no-effect truth (Timoshenko, 4 elements, rotary inertia) within a
        # few % of the model (Euler-Bernoulli, 2 elements; jacket3d stand-in, equal
        # to femup's to 1e-8 on the example, test_jacket3d); with femup itself
        # when it is built.
        rng = np.random.default_rng(3)
        for _ in range(3):
            p = jacket.random_jacket(rng)
            f_truth, _ = jacket.Truth(p).jacket.modes(6)
            f_model, _ = jacket.model_jacket(p).modes(6)
            rel = np.abs(f_model / f_truth - 1)
            self.assertLess(rel.max(), 0.05, rel)
        if not os.access(FEMUP, os.X_OK):
            self.skipTest("build/femup not built")
        study, truth = case(3, "none")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "s.yaml")
            with open(path, "w") as fh:
                fh.write(jacket.study_yaml(study))
            out = os.path.join(tmp, "m")
            subprocess.run([FEMUP, "modes", path, "-o", out, "--no-plots", "-q", "-n", "6"],
                           check=True)
            with open(os.path.join(out, "modes.json")) as fh:
                f_femup = np.array(json.load(fh)["frequencies_hz"])[:truth["modes"]]
        f_model, _ = jacket.model_jacket(study["p"]).modes(truth["modes"])
        np.testing.assert_allclose(f_femup, f_model, rtol=1e-6)
        f_truth, _ = jacket.Truth(study["p"]).jacket.modes(truth["modes"])
        self.assertLess(np.abs(f_femup / f_truth - 1).max(), 0.05)

    def effect(self, kind, a, seed=2):
        rng = np.random.default_rng(seed)
        p = jacket.random_jacket(rng)
        e = jacket.Effect(kind, rng, p)
        if kind == "brace_damage":
            e.level = 1  # in the water, below every sensor
        f0, _ = jacket.Truth(p).jacket.modes(6)
        f1, _ = jacket.Truth(p, e, a).jacket.modes(6)
        return f1 / f0, e, p

    def test_marine_growth_lowers_the_sway_modes(self):
        r, _, _ = self.effect("marine_growth", 0.1)
        self.assertTrue(np.all(r < 1))
        self.assertLess(r[0], 0.999)  # the two sway modes
        self.assertLess(r[1], 0.999)

    def test_brace_damage_lowers_a_mode_and_raises_none(self):
        r, _, _ = self.effect("brace_damage", 0.9)
        self.assertTrue(np.all(r <= 1 + 1e-9))
        self.assertLess(r.min(), 0.995)

    def test_deck_mass_lowers_every_mode(self):
        r, _, _ = self.effect("deck_mass", 0.5)
        self.assertTrue(np.all(r < 1))
        self.assertLess(r[0], 0.97)

    def test_material_scaling_moves_every_mode_one_way(self):
        r, e, _ = self.effect("material_scaling", 0.2)
        self.assertTrue(np.all((r - 1) * e.sign > 0))
        # The sway modes near sqrt(1 +- 0.2) (not exactly: G, in the shear terms
        # and the torsion, is kept; a torsional mode moves less).
        self.assertTrue(np.all(np.abs(r[:2] - np.sqrt(1 + 0.2 * e.sign)) < 0.01))

    def test_a_deck_mass_between_joints_names_femups_segments(self):
        # femup numbers a 1 x 1 bay jacket's free nodes: 4 leg joints per
        # level, 4 X centres per storey, then one inner node per member, 24
        # members per level (4 legs, 2 X and 2 Y horizontals, 16 half
        # braces). The top horizontal n9-n10 of 3 levels is member 53, inner
        # node n77, as femup itself names it (EffectRanking.
        # NamesADeckMassBetweenTheTopJointsOfAJacket, "n9-n77").
        rng = np.random.default_rng(5)
        for levels in (3, 4):
            p = dict(jacket.random_jacket(rng), levels=levels)
            truth = jacket.Truth(p)
            top = ["n%d" % k for k in range(4 * levels - 3, 4 * levels + 1)]
            order = [(top[0], top[1]), (top[2], top[3]), (top[0], top[2]), (top[1], top[3])]
            for h in range(4):
                e = jacket.Effect("deck_mass", rng, p)
                e.at_joint, e.horizontal, e.quarter = False, h, 1
                regions = e.regions(truth)
                a, b = order[h]
                inner = "n%d" % (8 * levels + 24 * (levels - 1) + 4 + h + 1)
                self.assertEqual(regions, ["node " + a, "node " + b, "%s-%s" % (a, inner),
                                           "%s-%s" % (inner, b)])

    def test_scoring_maps_each_effect_to_its_family_and_region(self):
        want = {"none": ("none", ""), "marine_growth": ("added_mass", "wet elements"),
                "material_scaling": ("material_scaling", "all elements")}
        for kind in jacket.KINDS:
            study, truth = case(17, kind)
            self.assertEqual(truth["kind"], jacket.EXPECTED_KIND[kind])
            if kind in want:
                self.assertEqual((truth["kind"], truth["region"]), want[kind])
            if kind == "brace_damage":
                self.assertRegex(truth["region"], r"^element l[1-4]:braces1$")
                self.assertEqual(truth["region"],
                                 "element l%d:braces1" % truth["detail"]["level"])
                # Or the damaged member itself, by femup's name, or those of
                # its two halves in femup's model that hold the damaged zone.
                self.assertRegex(truth["regions"][1], r"^member brace [nb]\d+-n\d+$")
                z0, z1 = truth["detail"]["zone"]
                halves = [k for k in range(2) if z0 < (k + 1) / 2 and z1 > k / 2]
                self.assertEqual(truth["regions"][2:],
                                 ["%s (%.2f-%.2f)" % (truth["regions"][1], k / 2, (k + 1) / 2)
                                  for k in halves])
            if kind == "deck_mass":
                top = {"node n%d" % k for k in range(4 * study["p"]["levels"] - 3,
                                                     4 * study["p"]["levels"] + 1)}
                nodes = [r for r in truth["regions"] if r.startswith("node ")]
                self.assertTrue(set(nodes) <= top)
                at_joint = truth["detail"]["at_joint"]
                self.assertEqual(len(nodes), 1 if at_joint else 2)
                # Between the joints: also that horizontal's two segments in
                # femup's model, through its inner node (after the 8 joints
                # and X centres per level, one per member).
                self.assertEqual(len(truth["regions"]), 1 if at_joint else 4)
                for r in truth["regions"][len(nodes):]:
                    a, b = r.split("-")
                    inner = b if a in {n[5:] for n in nodes} else a
                    self.assertGreater(int(inner[1:]), 8 * study["p"]["levels"])
            # A verdict naming the truth's family and any of its regions is right;
            # another family is not.
            for region in truth["regions"]:
                d = diagnosis((truth["kind"], region, 0.9),
                              [(truth["kind"], region, 10.0, 1), ("none", "", 90.0, 0)])
                r = run_suite.score(truth, d)
                self.assertTrue(r["kind_right"] and r["class_right"], (kind, region))
            other = "material_scaling" if truth["kind"] != "material_scaling" else "none"
            d = diagnosis((other, "all elements", 0.9), [(other, "all elements", 10.0, 1)])
            self.assertFalse(run_suite.score(truth, d)["kind_right"])
        # A brace of another level is the right family, the wrong class.
        study, truth = case(17, "brace_damage")
        wrong = "element l%d:braces1" % (1 + truth["detail"]["level"] % study["p"]["levels"])
        d = diagnosis(("stiffness_loss", wrong, 0.9), [("stiffness_loss", wrong, 10.0, 1)])
        r = run_suite.score(truth, d)
        self.assertTrue(r["kind_right"])
        self.assertFalse(r["class_right"])


if __name__ == "__main__":
    unittest.main()
