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
        # scarred rollers (cylindrical and, issue #27, tapered): their bore / cup rows measure the mesh
        scarred = {a for a, k, sc in zip(r["a"], r["kind"], r["scar"]) if k in ("roller-outer", "roller-cup") and sc}
        for kind, a, d, exact, two in zip(r["kind"], r["a"], r["distance"], r["exact"], r["two_sided"]):
            if kind in ("roller-inner", "roller-roller", "roller-cone"):
                self.assertTrue(two)
            elif d <= 0 and exact and a not in scarred:  # intact rollers' overlapping ring rows (issue #27)
                self.assertTrue(two, (kind, a, d))
        self.assertIn("seed 7", r["motion"])
        # the same seed, the same rows
        self.assertEqual(itf.bearing.run_assembly(EXAMPLE, frames=2, seed=7)["distance"], r["distance"])

    def test_raceway_scars(self):
        # issue #27: scars on raceways (bearings[i].scars): rows of rollers in range of the inner
        # raceway's raised scar are solved by the scarred raceway solver and name the ring in scar_part
        import json
        import tempfile
        with open(EXAMPLE) as f:
            d = json.load(f)
        d["scar"] = None
        cyl = next(b for b in d["bearings"] if b["type"] == "cylindrical")
        cyl["scars"] = [{"part": "inner", "angle_center_deg": 0, "angle_width_deg": 120, "depth": 0.04,
                         "raised": True, "seed": 3, "radial_segments": 256, "height_segments": 31}]
        d["bearings"] = [cyl]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "raceway_scar.json")
            with open(path, "w") as f:
                json.dump(d, f)
            r = itf.bearing.run_assembly(path, frames=3, seed=2)
            n = r["frames"] * r["pairs_per_frame"]
            self.assertEqual(len(r["scar_part"]), n)
            inner = cyl["id"] + "/inner"
            rows = [i for i in range(n) if r["scar_part"][i] == inner]
            self.assertTrue(rows)
            for i in rows:
                self.assertEqual(r["kind"][i], "roller-inner")
                self.assertEqual(r["solver"][i], "scarred")
                self.assertTrue(r["scar"][i])
            self.assertTrue(all(p is None for p, sc in zip(r["scar_part"], r["scar"]) if not sc))
            bad = dict(d, bearings=[dict(cyl, scars=[{"part": "cone"}])])
            with open(path, "w") as f:
                json.dump(bad, f)
            with self.assertRaises(ValueError) as cm:
                itf.bearing.run_assembly(path)
            self.assertIn("scars[0].part", str(cm.exception))

    def test_imported_roller_scars(self):
        # issue #27: an imported roller scar (the top-level scar with map / png / points): every
        # scarred roller carries the measured scar; their bore / cup rows measure the mesh
        import json
        import tempfile
        with open(EXAMPLE) as f:
            d = json.load(f)
        d["scar"] = {"fraction": 0.25, "map": "roller_bump.csv"}
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(tmp, "roller_bump.csv"), "w") as f:
                f.write("z\\angle_deg, -45, 0, 45\n10, 0, 0, 0\n15, 0, 0.03, 0\n20, 0, 0, 0\n")
            path = os.path.join(tmp, "roller_scar.json")
            with open(path, "w") as f:
                json.dump(d, f)
            r = itf.bearing.run_assembly(path, frames=1, seed=2)
            scarred = {a for a, k, sc in zip(r["a"], r["kind"], r["scar"]) if k in ("roller-outer", "roller-cup") and sc}
            self.assertTrue(scarred)
            d["scar"]["depth"] = 0.1  # a generated-only key with an import
            with open(path, "w") as f:
                json.dump(d, f)
            with self.assertRaises(ValueError) as cm:
                itf.bearing.run_assembly(path)
            self.assertIn("scar.depth", str(cm.exception))

    def test_bad_input(self):
        with self.assertRaises(ValueError) as cm:
            itf.bearing.run_assembly("/nonexistent/bearing.json")
        self.assertIn("bearing.json", str(cm.exception))
        with self.assertRaises(ValueError):
            itf.bearing.run_assembly(EXAMPLE, frames=0)


if __name__ == "__main__":
    unittest.main()
