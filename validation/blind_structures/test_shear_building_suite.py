"""The shear-building generator's two-losses design: two distinct storeys
damaged at once, named in either order, each softening the frame."""
import unittest

import numpy as np

import shear_building


class TwoLossesTest(unittest.TestCase):
    def test_two_distinct_storeys_in_either_order(self):
        rng = np.random.default_rng(11)
        for i in range(3):
            study, truth = shear_building.make_case(rng, "c%d" % i, "two_losses")
            self.assertEqual(truth["kind"], "stiffness_loss+stiffness_loss")
            first, second = truth["regions"]
            a, b = (int(r.split()[1]) for r in first.split(" + "))
            self.assertLess(a, b)
            self.assertEqual(second, "element %d + element %d" % (b, a))
            self.assertEqual(truth["region"], first)
            self.assertGreater(truth["size"], 0)
            self.assertTrue(0.5 <= truth["detail"]["ratio"] <= 1)
            self.assertNotIn("stiffness", shear_building.study_yaml(study))

    def test_both_losses_soften_the_frame(self):
        rng = np.random.default_rng(3)
        p = shear_building.random_building(rng)
        effect = shear_building.TwoLosses(rng, p)
        nominal, _ = shear_building.Building(p).sway_modes(3)
        first, _ = effect.first.building(p, 0.5).sway_modes(3)
        both, _ = effect.building(p, 0.5).sway_modes(3)
        self.assertTrue(np.all(first < nominal))
        self.assertTrue(np.all(both <= first))
        self.assertTrue(np.any(both < first * (1 - 1e-6)))


class ChainFormErrorTest(unittest.TestCase):
    """The chain's form error against its frame is mostly flexural: the
    frame's higher modes are stiffer than the chain's (mode 1 fitted), and
    springs on the change of drift between adjacent storeys, shared along the
    height as 1 - z and z (femup's shear_building form variants, builders.cc),
    take most of it (the frame is another formulation: Timoshenko members,
    rotating joints, distributed mass)."""

    def test_higher_modes_stiffer_and_mostly_flexural(self):
        rng = np.random.default_rng(7)
        for _ in range(4):
            p = shear_building.random_building(rng, "flexible")
            n = min(5, p["storeys"])
            frame, _ = shear_building.Building(p).sway_modes(n)
            masses, springs = shear_building.Building(p).equivalent_chain()
            chain = shear_building.chain_frequencies(masses, springs, n)
            gap = frame / chain - 1
            self.assertLess(abs(gap[0]), 1e-3)
            self.assertTrue(np.all(np.diff(gap) > 0), gap)
            ns = len(masses)
            K = shear_building.chain_stiffness(springs)
            directions = []
            for share in ("from_base", "to_roof"):
                C = np.zeros((ns, ns))
                for j in range(1, ns):
                    z = j / ns
                    g = np.zeros(ns)
                    g[j], g[j - 1] = 1.0, -2.0
                    if j >= 2:
                        g[j - 2] = 1.0
                    w = 1 - z if share == "from_base" else z
                    C += 0.05 * w * (springs[j - 1] + springs[j]) * np.outer(g, g)
                f = shear_building.chain_frequencies(masses, springs, n, stiffness=K + C)
                directions.append(f / chain - 1)
            U = np.array(directions).T
            left = gap - U @ np.linalg.lstsq(U, gap, rcond=None)[0]
            self.assertLess(np.linalg.norm(left), 0.3 * np.linalg.norm(gap))

    def test_the_study_says_shear_building_when_asked(self):
        rng = np.random.default_rng(5)
        study, _ = shear_building.make_case(rng, "c")
        self.assertNotIn("shear_building: true", shear_building.study_yaml(study))
        study["shear_building"] = True
        self.assertIn("  shear_building: true\n", shear_building.study_yaml(study))


if __name__ == "__main__":
    unittest.main()
