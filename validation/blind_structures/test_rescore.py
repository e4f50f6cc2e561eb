"""Checks of rescore's reweighting on hand-made diagnoses (run: python3 -m
unittest, from this folder; tests/scenario/blind_structures.sh runs it)."""
import unittest

import rescore


def diagnosis(classes, verdict, **extra):
    """classes: (kind, region, probability, laplace); verdict: (kind, region)."""
    cs = [dict(kind=k, region=r, probability=p, laplace_probability=q, fitted=True)
          for k, r, p, q in classes]
    v = dict(kind=verdict[0], region=verdict[1], probability=0, kind_probability=0,
             group_probability=0, equivalent=[])
    v.update(extra)
    return dict(verdict=v, classes=cs)


# none 0.3; stiffness_loss 0.5 over two storeys; attached_mass 0.2.
CLASSES = [("none", "", 0.3, 0.2), ("stiffness_loss", "element 1", 0.3, 0.4),
           ("stiffness_loss", "element 2", 0.2, 0.2), ("attached_mass", "node x2", 0.2, 0.2)]


class ReweightedTest(unittest.TestCase):
    def test_as_run_keeps_the_most_probable_family(self):
        e = rescore.reweighted(diagnosis(CLASSES, ("stiffness_loss", "element 1")), None)
        self.assertEqual((e["verdict"]["kind"], e["verdict"]["region"]),
                         ("stiffness_loss", "element 1"))
        self.assertAlmostEqual(e["verdict"]["probability"], 0.3)
        self.assertAlmostEqual(e["verdict"]["kind_probability"], 0.5)

    def test_a_share_of_one_half_multiplies_none_by_the_number_of_families(self):
        e = rescore.reweighted(diagnosis(CLASSES, ("stiffness_loss", "element 1")), 0.5)
        # none 0.3 x 2 = 0.6 against 0.7: 0.6 / 1.3.
        self.assertAlmostEqual(e["classes"][0]["probability"], 0.6 / 1.3)
        self.assertAlmostEqual(e["classes"][0]["laplace_probability"], 0.4 / 1.2)
        self.assertAlmostEqual(sum(c["probability"] for c in e["classes"]), 1.0)
        self.assertEqual(e["verdict"]["kind"], "none")
        self.assertEqual(e["verdict"]["region"], "")

    def test_a_gap_below_the_threshold_is_not_named(self):
        d = diagnosis(CLASSES, ("stiffness_loss", "element 1"))
        self.assertEqual(rescore.reweighted(d, None, 0.75)["verdict"]["kind"], "none")
        self.assertEqual(rescore.reweighted(d, None, 0.65)["verdict"]["kind"], "stiffness_loss")
        self.assertAlmostEqual(rescore.reweighted(d, None, 0.75)["verdict"]["probability"], 0.3)

    def test_as_run_follows_the_recorded_gap_confidence(self):
        d = diagnosis(CLASSES, ("none", ""), gap_probability=0.7)
        d["gap_confidence"] = 0.9
        self.assertEqual(rescore.reweighted(d, None)["verdict"]["kind"], "none")
        self.assertEqual(rescore.reweighted(d, None, 0)["verdict"]["kind"], "stiffness_loss")

    def test_an_effect_that_explains_too_little_is_not_named(self):
        d = diagnosis(CLASSES, ("none", ""))
        d["classes"][1]["explained"] = 0.3
        d["gap_explained"] = 0.5
        e = rescore.reweighted(d, None)
        self.assertEqual((e["verdict"]["kind"], e["verdict"]["region"]), ("none", ""))
        self.assertAlmostEqual(e["verdict"]["probability"], 0.3)  # none's, as run
        self.assertEqual(rescore.reweighted(d, None, None, 0)["verdict"]["kind"],
                         "stiffness_loss")
        self.assertEqual(rescore.reweighted(d, None, None, 0.25)["verdict"]["kind"],
                         "stiffness_loss")
        # A run before the rule (no gap_explained recorded) is decided without it.
        del d["gap_explained"]
        self.assertEqual(rescore.reweighted(d, None)["verdict"]["kind"], "stiffness_loss")


if __name__ == "__main__":
    unittest.main()
