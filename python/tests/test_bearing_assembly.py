"""Bearing assemblies from Python (issue #27): interfere.bearing.run_assembly runs a JSON description
(data/examples/bearing_axle.json) and returns its rows as parallel lists, the same rows as the CLI's
CSV. Checked: lengths, frame-major order, the worst row is the smallest distance, the verdict is the
worst row verdict, two_sided by pair kind, and a bad path raises ValueError naming the file."""

import math
import os
import unittest

import interfere as itf

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "bearing_axle.json")
ORDER = ["clear", "clearance", "contact", "undecided", "clash"]


class BearingAssembly(unittest.TestCase):
    def test_example_rows(self):
        r = itf.bearing.run_assembly(EXAMPLE, frames=2, seed=7)
        n = r["frames"] * r["pairs_per_frame"]
        self.assertEqual(r["frames"], 2)
        for key in ("frame", "kind", "a", "b", "distance", "point_a", "point_b", "solver", "scar", "exact",
                    "two_sided", "row_verdict"):
            self.assertEqual(len(r[key]), n, key)
        self.assertEqual(r["frame"], sorted(r["frame"]))
        self.assertTrue(all(math.isfinite(d) for d in r["distance"]))
        self.assertEqual(r["distance"][r["worst"]], min(r["distance"]))
        self.assertEqual(r["verdict"], max(r["row_verdict"], key=ORDER.index))
        scarred = {a for a, k, sc in zip(r["a"], r["kind"], r["scar"]) if k == "roller-outer" and sc}
        for kind, a, d, exact, two in zip(r["kind"], r["a"], r["distance"], r["exact"], r["two_sided"]):
            if kind in ("roller-inner", "roller-roller", "roller-cone"):
                self.assertTrue(two)
            elif d <= 0 and exact and a not in scarred:  # intact rollers' overlapping ring rows (issue #27)
                self.assertTrue(two, (kind, a, d))
        self.assertIn("seed 7", r["motion"])
        # the same seed, the same rows
        self.assertEqual(itf.bearing.run_assembly(EXAMPLE, frames=2, seed=7)["distance"], r["distance"])

    def test_bad_input(self):
        with self.assertRaises(ValueError) as cm:
            itf.bearing.run_assembly("/nonexistent/bearing.json")
        self.assertIn("bearing.json", str(cm.exception))
        with self.assertRaises(ValueError):
            itf.bearing.run_assembly(EXAMPLE, frames=0)


if __name__ == "__main__":
    unittest.main()
