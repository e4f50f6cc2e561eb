"""Checks of jacket3d (run: python3 -m unittest test_jacket3d, from this folder)."""
import unittest

import numpy as np

import frame3d
from jacket3d import Jacket

# examples/diagnosis/jacket.yaml's model.
STUDY = dict(type="space_frame", bays_x=1, bays_y=1, levels=3, level_height=10,
             bay_width_x=12, bay_width_y=12, elements_per_member=2, blocks_per_level=1,
             bracing="x", water_depth=12, legs=dict(diameter=1.2, wall=0.03),
             braces=dict(diameter=0.6, wall=0.015),
             horizontals=dict(diameter=0.6, wall=0.015))
RHO = 7850.0
LEG, TUBE = frame3d.tube(1.2, 0.03)["A"], frame3d.tube(0.6, 0.015)["A"]
DIAG = np.hypot(12.0, 10.0)


class JacketTest(unittest.TestCase):
    def test_femup_node_numbering(self):
        # femup's labels: leg joints level by level (X inner), then X centres
        # (faces Y = 0, Y = 12, then X = 0, X = 12, storey by storey), then
        # inner nodes; 576 free DOFs for this study (2 elements per member).
        j = Jacket(**STUDY)
        xyz = lambda label: j.frame.xyz[j.labels[label]]  # noqa: E731
        self.assertEqual(6 * len(j.labels), 576)
        self.assertEqual(xyz("n1"), (0.0, 0.0, 10.0))
        self.assertEqual(xyz("n2"), (12.0, 0.0, 10.0))
        self.assertEqual(xyz("n3"), (0.0, 12.0, 10.0))
        self.assertEqual(xyz("n12"), (12.0, 12.0, 30.0))
        self.assertEqual(xyz("n13"), (6.0, 0.0, 5.0))
        self.assertEqual(xyz("n15"), (0.0, 6.0, 5.0))
        self.assertEqual(xyz("n17"), (6.0, 0.0, 15.0))
        self.assertEqual(xyz("n25"), (0.0, 0.0, 5.0))  # first leg's middle
        self.assertEqual(j.dof("n2:uy"), 6 * j.labels["n2"] + 1)

    def test_dry_and_submerged_mass(self):
        # Dry: sum of rho A L over the members, exact (1e-10). Fully submerged
        # (water above the top), the added mass moving with a translation along
        # X counts by sin^2 of each member's angle with X: legs, Y horizontals
        # and the braces of the X = const faces fully, X horizontals not, the
        # braces of the Y = const faces by (10 / 15.62)^2.
        dry_mass = RHO * 3 * (4 * 10 * LEG + 4 * 12 * TUBE + 8 * DIAG * TUBE)
        j = Jacket(**dict(STUDY, added_mass_ratio=0.0))
        for d in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
            self.assertAlmostEqual(j.frame.rigid_translation_mass(d) / dry_mass, 1.0, places=10)
        wet = Jacket(**dict(STUDY, water_depth=40.0))
        ma_leg = frame3d.hydrodynamic_added_mass(1.2)
        ma_tube = frame3d.hydrodynamic_added_mass(0.6)
        added_x = 3 * (4 * 10 * ma_leg + 2 * 12 * ma_tube
                       + 4 * DIAG * ma_tube * (10 / DIAG) ** 2 + 4 * DIAG * ma_tube)
        self.assertAlmostEqual(wet.frame.rigid_translation_mass((1, 0, 0)) / (dry_mass + added_x),
                               1.0, places=10)
        # femup's factor form: the ratio times rho A.
        ratio = Jacket(**dict(STUDY, water_depth=40.0, added_mass_ratio=0.5))
        added_x = 0.5 * RHO * 3 * (4 * 10 * LEG + 2 * 12 * TUBE + 4 * DIAG * TUBE * (10 / DIAG) ** 2
                                   + 4 * DIAG * TUBE)
        self.assertAlmostEqual(ratio.frame.rigid_translation_mass((1, 0, 0))
                               / (dry_mass + added_x), 1.0, places=10)

    def test_wet_elements_below_the_water_line(self):
        # Wet when the element's midpoint is below water_depth (12 m): with 2
        # elements per member, all of level 1 and, at level 2, the lower
        # element of each brace half rising from a bottom corner (midpoint
        # 11.25 m); level 2's legs (midpoints 12.5, 17.5 m) stay dry.
        j = Jacket(**STUDY)
        for e in j.frame.elements:
            z = 0.5 * (j.frame.xyz[e["n1"]][2] + j.frame.xyz[e["n2"]][2])
            self.assertEqual("wet" in e["tags"], z < 12.0)
            self.assertEqual(e["added_mass"] > 0, z < 12.0)
        self.assertTrue(any("wet" in e["tags"] and "l2" in e["tags"] for e in j.frame.elements))

    def test_same_formulation_as_femup_gives_femup_frequencies(self):
        # With femup's formulation (Euler-Bernoulli, Hermite mass without rotary
        # inertia, 2 elements per member, dry), frequencies printed by
        # `build/femup modes examples/diagnosis/jacket.yaml` (2026-11-28, to
        # 8 decimals); compare_jacket3d.py reruns femup itself. 1e-8.
        femup = [7.28372098, 7.28372098, 8.02932603, 10.11707202, 10.22884651, 13.89337741]
        j = Jacket(**dict(STUDY, added_mass_ratio=0.0), shear=False, rotary=False,
                   mass_kind="hermite")
        f, _ = j.modes(6)
        np.testing.assert_allclose(f, femup, rtol=1e-8)

    def test_square_plan_sways_alike_in_x_and_y(self):
        # 1 x 1 bays, square: the two sway modes have one frequency (1e-9).
        f, _ = Jacket(**dict(STUDY, elements_per_member=4)).modes(2)
        self.assertAlmostEqual(f[1] / f[0], 1.0, places=9)


if __name__ == "__main__":
    unittest.main()
