"""The plane-frame suite's generator (plane_frame.py): with --foundation soft the
model is clamped and only a soft_foundation truth stands on base springs, whose
stiffness falls as the effect's size grows (a -> 0 is the clamped frame)."""
import unittest

import numpy as np

import plane_frame


def _soft_foundation_case():
    """A soft-foundation case of the soft-foundation suite, and its rng's seed."""
    for seed in range(200):
        study, truth = plane_frame.make_case(np.random.default_rng(seed), "c", foundation="soft")
        if truth["truth_kind"] == "soft_foundation":
            return study, truth, seed
    raise AssertionError("no soft_foundation case in 200 seeds")


class SoftFoundationTest(unittest.TestCase):
    def test_the_model_is_clamped_and_says_nothing_of_the_springs(self):
        study, truth, _ = _soft_foundation_case()
        self.assertNotIn("base_rotation", study["p"])
        text = plane_frame.study_yaml(study)
        self.assertNotIn("base:", text)
        self.assertEqual(truth["kind"], "support_flexibility")
        self.assertEqual(truth["regions"], ["supports"])
        self.assertIn("base rotation springs (4 E I / h)", truth["description"])
        self.assertGreater(truth["size"], 0)

    def test_every_kind_is_drawn(self):
        kinds = {plane_frame.make_case(np.random.default_rng(s), "c", foundation="soft")[1][
            "truth_kind"] for s in range(30)}
        self.assertEqual(kinds, set(plane_frame.KINDS_ON_SPRINGS))

    def test_springs_soften_the_frame_and_vanish_as_the_size_does(self):
        study, _, _ = _soft_foundation_case()
        p = study["p"]
        effect = plane_frame.Effect("soft_foundation", np.random.default_rng(1), p)
        f0, _ = plane_frame.Truth(p).frame.modes(3)
        previous = f0
        # (Springs far stiffer than 1e3 times a column's end condition the
        # truth's eigenproblem badly: 1e-3 is the stiffest tried.)
        for a in (1e-3, 0.1, 1.0, 10.0):
            f, _ = plane_frame.Truth(p, effect, a).frame.modes(3)
            if a == 1e-3:
                np.testing.assert_allclose(f, f0, rtol=1e-3)
            else:
                self.assertTrue(np.all(f < previous), (a, f, previous))
            previous = f


class RegionsTest(unittest.TestCase):
    def test_a_beams_semi_rigid_ends_are_its_stiffness_loss_or_its_connections(self):
        for seed in range(200):
            _, truth = plane_frame.make_case(np.random.default_rng(seed), "c")
            if truth["truth_kind"] != "joint_flexibility":
                continue
            beam = truth["region"][len("element "):]
            self.assertEqual(truth["regions"],
                             ["element " + beam, "connections of " + beam])
            return
        raise AssertionError("no joint_flexibility case in 200 seeds")

    def test_member_damage_is_its_member_or_the_parts_its_zone_reaches(self):
        p = plane_frame.random_frame(np.random.default_rng(3), "clamped")
        seen = set()
        for seed in range(100):
            e = plane_frame.Effect("member_damage", np.random.default_rng(seed), p)
            member = "s%d:%s" % e.member
            z0, z1 = e.detail["zone"]
            halves = [k for k in (0, 1) if k / 2 < z1 and (k + 1) / 2 > z0]
            self.assertEqual(e.regions(p),
                             ["element " + member] +
                             ["member %s (%.2f-%.2f)" % (member, k / 2, (k + 1) / 2)
                              for k in halves])
            seen.add(len(halves))
        self.assertEqual(seen, {1, 2})  # within one half, and across the middle


if __name__ == "__main__":
    unittest.main()
