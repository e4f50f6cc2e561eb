"""The cantilever suite's generator (cantilever.py) and the scoring of the
cantilever's own pipeline in the one engine's terms (run_suite.py)."""
import math
import unittest

import numpy as np

import cantilever
import run_suite

# Roots in beta L of 1 + cos b cosh b = 0: the clamped-free Euler-Bernoulli beam.
CLAMPED_FREE = [1.8751040687, 4.6940911330, 7.8547574382]


class TruthTest(unittest.TestCase):
    def test_the_undamaged_bar_is_the_continuous_beam_to_its_shear_and_rotary_inertia(self):
        p = cantilever.random_bar(np.random.default_rng(3))
        f, _ = cantilever.Truth(p).modes(3, [cantilever.ELEMENTS])
        L, ei, m = p["length"], p["E"] * p["I"], p["rho"] * p["A"]
        r2 = p["I"] / p["A"]
        for k, b in enumerate(CLAMPED_FREE):
            exact = b * b / (2 * math.pi * L * L) * math.sqrt(ei / m)
            # Timoshenko's and the rotary inertia's lowering, to first order:
            # (beta r / L)^2 (1 + E / (kappa G)) / 2 of the frequency, at most.
            bound = 0.5 * (b * b * r2 / L ** 2) * (1 + p["E"] / (5 / 6 * p["G"]))
            self.assertLess(f[k], exact * (1 + 1e-6), k)
            self.assertGreater(f[k], exact * (1 - 1.5 * bound - 1e-5), k)

    def test_each_effect_moves_the_modes_and_vanishes_with_its_size(self):
        rng = np.random.default_rng(11)
        p = cantilever.random_bar(rng)
        f0, _ = cantilever.Truth(p).modes(3, [cantilever.ELEMENTS])
        for kind in cantilever.KINDS[1:]:
            e = cantilever.Effect(kind, rng, p)
            f, _ = cantilever.Truth(p, e, 0.0).modes(3, [cantilever.ELEMENTS])
            np.testing.assert_allclose(f, f0, rtol=1e-9, err_msg=kind)
            f, _ = cantilever.Truth(p, e, 0.5 * e.a_max).modes(3, [cantilever.ELEMENTS])
            self.assertGreater(np.max(np.abs(f / f0 - 1)), 1e-3, kind)

    def test_regions_are_the_model_instances_at_the_effect(self):
        p = dict(length=2.0)
        e = cantilever.Effect.__new__(cantilever.Effect)
        e.kind, e.detail = "stiffness_loss", dict(x0=0.75, x1=0.90)
        self.assertEqual(e.regions(p), ["element e9", "element e8"])
        e.kind, e.detail = "attached_mass", dict(x=1.63)
        r = e.regions(p)
        self.assertEqual(r[0], "node n16")
        self.assertIn("node n17", r)
        self.assertIn("n16-n17", r)
        self.assertNotIn("node n18", r)


class CaseTest(unittest.TestCase):
    def test_the_study_file_is_a_cantilever_model_and_hides_the_truth(self):
        kinds = set()
        for seed in range(40):
            study, truth = cantilever.make_case(np.random.default_rng(seed), "c")
            kinds.add(truth["truth_kind"])
            text = cantilever.study_yaml(study)
            self.assertIn("type: cantilever", text)
            if study["shapes"]:
                self.assertIn('"n%d:ux"' % cantilever.ELEMENTS, text)
            for word in ("added", "support", "attached", "loss", "scaling", "water"):
                self.assertNotIn(word, text)
        self.assertEqual(kinds, set(cantilever.KINDS))


class CantileverPipelineScoreTest(unittest.TestCase):
    def test_its_classes_are_named_as_the_one_engine_names_them(self):
        d = dict(length=2.0, noise=dict(degrees_of_freedom=30, temperature=1.0),
                 kind_probabilities={"attached_mass": 0.9, "none": 0.1},
                 effects=[dict(kind="attached_mass", location=dict(x=1.63), chi2=30.0,
                               parameters={"a": 1, "b": 2}, probability=0.8),
                          dict(kind="none", location=None, chi2=300.0, parameters={},
                               probability=0.1)])
        r = run_suite.from_cantilever_pipeline(d)
        self.assertEqual(r["verdict"]["kind"], "attached_mass")
        self.assertEqual(r["verdict"]["region"], "node n16")
        self.assertEqual(r["verdict"]["kind_probability"], 0.9)
        self.assertEqual(r["classes"][1]["region"], "")
        self.assertEqual(r["residuals"], 30)


if __name__ == "__main__":
    unittest.main()
