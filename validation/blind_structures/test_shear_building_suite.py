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


if __name__ == "__main__":
    unittest.main()
