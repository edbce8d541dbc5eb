#!/usr/bin/env python3
"""End-to-end tests of --glb, --pvd and --html on the FE series clash (issue #25): `interfere clash`
of two FEM bodies over a displacement time series, its picture read back by small independent
readers here (the GLB container and its JSON chunk; the .pvd collection and its VTK XML PolyData
files with zlib-compressed base64 arrays) and checked against the model's analytic motion.

Usage: test_fem_view.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only. The
model is test_fem.py's: body "left" = [0,1]^3 (hex ids 1..8), body "right" = [1.5,2.5] x [0.2,0.8]^2
(hex ids 101..108) moving by -0.125 in x per step for 10 steps (times 0.5 s): clear at steps 0-3,
touching at step 4 (a contact), a clash from step 5.
"""
import json
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run  # noqa: E402
from test_fem import LEFT, RIGHT, STEPS, V, write_model  # noqa: E402  (the model generator only; its tests are not run here)
from view_readers import accessor_values, read_glb, read_pvd, read_vtp, vtk_array  # noqa: E402

SERIES = ["--part-a", "left", "--part-b", "right", "--field", "disp"]
LEFT_BOX = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


def right_box(k):
    return ((1.5 - V * k, 0.2, 0.2), (2.5 - V * k, 0.8, 0.8))


def inside_depth(p, lo, hi):
    """Distance of p to the surface of the box [lo, hi] when strictly inside it, else 0."""
    d = min(min(p[a] - lo[a], hi[a] - p[a]) for a in range(3))
    return d if d > 0 else 0.0
NO_VIEWER = "this build of interfere has no HTML viewer"


class FemView(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.model = write_model("model.msh")
        cls.rc, cls.out, cls.err = run("clash", cls.model, cls.model, *SERIES, "--glb", path("series.glb"),
                                       "--pvd", path("series.pvd"), "--json", path("series.json"))

    def test_series_runs_as_before(self):
        self.assertEqual(self.rc, 1, self.out + self.err)  # a clash: exit status 1
        self.assertIn("first clash at step 5", self.out)

    def test_pvd_has_one_bodies_dataset_per_step_at_its_time(self):
        sets = read_pvd(path("series.pvd"))
        bodies = [s for s in sets if s[2] == "bodies"]
        self.assertEqual([t for t, _, _, _ in bodies], [0.5 * k for k in range(STEPS)])
        for _, _, _, f in sets:
            self.assertTrue(os.path.isfile(os.path.join(os.path.dirname(path("series.pvd")), f)), f)

    def test_pvd_steps_hold_the_deformed_bodies_with_element_ids_and_clash_flags(self):
        base = os.path.dirname(path("series.pvd"))
        bodies = [s for s in read_pvd(path("series.pvd")) if s[2] == "bodies"]
        for k, (_, _, _, f) in enumerate(bodies):
            v = read_vtp(os.path.join(base, f))
            body, ids, flags = v["cell"]["body"], v["cell"]["source_id"], v["cell"]["clash"]
            # clash_region (issue #26, item 3): the step's region number on exactly the flagged cells
            region = v["cell"]["clash_region"]
            self.assertEqual([g >= 0 for g in region], [bool(fl) for fl in flags], k)
            self.assertEqual(len(body), v["polys"])
            # Every hex of a 2x2x2 block has a boundary face: the element ids of each body, exactly.
            self.assertEqual(sorted({i for b, i in zip(body, ids) if b == 0}), list(range(1, 9)))
            self.assertEqual(sorted({i for b, i in zip(body, ids) if b == 1}), list(range(101, 109)))
            # The bodies' x extents: left at rest, right shifted by -0.125 k.
            for b, (lo, hi) in ((0, (0.0, 1.0)), (1, (1.5 - V * k, 2.5 - V * k))):
                xs = [v["xyz"][p][0] for c, cell in enumerate(v["poly_points"]) if body[c] == b for p in cell]
                self.assertAlmostEqual(min(xs), lo, places=12)
                self.assertAlmostEqual(max(xs), hi, places=12)
            # Flags from the contact on, and only on triangles reaching the other body's box.
            flagged = [c for c, fl in enumerate(flags) if fl]
            self.assertEqual(bool(flagged), k >= 4, k)
            for c in flagged:
                xs = [v["xyz"][p][0] for p in v["poly_points"][c]]
                if body[c] == 0:
                    self.assertGreaterEqual(max(xs), 1.5 - V * k - 1e-12, (k, c))
                else:
                    self.assertLessEqual(min(xs), 1.0 + 1e-12, (k, c))

    def test_pvd_clash_files_have_geometry_from_the_contact_on(self):
        base = os.path.dirname(path("series.pvd"))
        clashes = [s for s in read_pvd(path("series.pvd")) if s[2] == "clashes"]
        self.assertEqual(len(clashes), STEPS)
        for k, (_, _, _, f) in enumerate(clashes):
            v = read_vtp(os.path.join(base, f))
            self.assertEqual(v["polys"] > 0, k >= 4, k)  # region triangles
            if k in (5, 6, 7, 9):  # crossing steps: the intersection curve, on A's face x = 1
                self.assertGreater(v["lines"], 0, k)

    def test_pvd_penetration_depth_is_each_points_depth_in_the_other_block(self):
        # Issue #26, item 3: per point of each body at each step, its distance to the other block's
        # surface when strictly inside it, 0 otherwise (the blocks' geometry is the oracle).
        base = os.path.dirname(path("series.pvd"))
        bodies = [s for s in read_pvd(path("series.pvd")) if s[2] == "bodies"]
        self.assertEqual(len(bodies), STEPS)
        for k, (_, _, _, f) in enumerate(bodies):
            v = read_vtp(os.path.join(base, f))
            depth = v["point"]["penetration_depth"]
            self.assertEqual(len(depth), v["points"])
            body_of = {}
            for c, cell in enumerate(v["poly_points"]):
                for p in cell:
                    body_of[p] = v["cell"]["body"][c]
            self.assertEqual(len(body_of), v["points"])
            for p, b in body_of.items():
                expected = inside_depth(v["xyz"][p], *(right_box(k) if b == 0 else LEFT_BOX))
                self.assertAlmostEqual(depth[p], expected, places=12, msg=(k, p, b, v["xyz"][p]))
            self.assertEqual(max(depth) > 0, k >= 5, k)  # something inside from the first clash on

    def test_json_steps_name_the_deepest_node(self):
        with open(path("series.json")) as f:
            j = json.load(f)
        rest = {0: LEFT_BOX, 1: right_box(0)}

        def on_boundary(part, xyz):
            return any(xyz[a] in (rest[part][0][a], rest[part][1][a]) for a in range(3))
        ids = {part: {n: xyz for n, xyz in block[0] if on_boundary(part, xyz)} for part, block in ((0, LEFT), (1, RIGHT))}
        elements = {0: {e: v for e, v, _ in LEFT[1]}, 1: {e: v for e, v, _ in RIGHT[1]}}
        steps = j["series"]["steps"]
        for row in steps:
            k = row["step"]
            if row["verdict"] != "clash":
                self.assertIsNone(row["depth"], k)
                self.assertIsNone(row["deepest"], k)
                continue
            # The oracle's deepest surface node (the nodes of both blocks on their boundaries).
            def node_depth(part, n):
                x, y, z = ids[part][n]
                if part == 1:
                    x -= V * k
                return inside_depth((x, y, z), *(right_box(k) if part == 0 else LEFT_BOX))
            best = max(node_depth(part, n) for part in (0, 1) for n in ids[part])
            d = row["deepest"]
            part = {"a": 0, "b": 1}[d["part"]]
            self.assertIn(d["node"], ids[part], k)
            self.assertAlmostEqual(d["depth"], best, places=12, msg=k)
            self.assertAlmostEqual(node_depth(part, d["node"]), best, places=12, msg=k)
            self.assertIn(d["node"], elements[part][d["element"]], k)  # the element has the node
            self.assertGreaterEqual(row["depth"], d["depth"] - 1e-12)
            self.assertGreaterEqual(row["depth_bound"], row["depth"] - 1e-12)
            self.assertIsNone(row["depth_note"], k)
        first = j["result"]  # the first clash (step 5): A's face x = 1 is 0.125 inside B
        self.assertEqual(j["result_step"], 5)
        self.assertAlmostEqual(first["deepest"]["depth"], 0.125, places=12)
        self.assertAlmostEqual(first["depth"], 0.125, places=12)
        deepest = max(steps, key=lambda r: r["depth"] or -1)
        self.assertEqual(j["series"]["deepest_step"], deepest["step"])
        self.assertEqual(j["series"]["max_depth"], deepest["depth"])
        self.assertIn("max depth %g mm at step %d" % (deepest["depth"], deepest["step"]), self.out)
        self.assertIn("deepest node %d of part %s" % (deepest["deepest"]["node"], deepest["deepest"]["part"].upper()),
                      self.out)

    def test_glb_has_both_bodies_frames_and_a_row_per_step_that_is_not_clear(self):
        doc, binary = read_glb(path("series.glb"))
        names = [n.get("name") for n in doc["nodes"]]
        self.assertIn("left", names)
        self.assertIn("right", names)
        right = doc["nodes"][names.index("right")]
        self.assertEqual(right["extras"]["path"], "/model/right")
        extras = doc["scenes"][doc.get("scene", 0)]["extras"]
        frames = extras["frames"]
        self.assertEqual(frames["labels"], ["step %d (time %g)" % (k, 0.5 * k) for k in range(STEPS)])
        self.assertEqual(frames["verdicts"][:6], ["clear"] * 4 + ["contact", "clash"])
        self.assertEqual(extras["verdict"], "clash")
        rows = {n["extras"]["clash_id"]: n for n in doc["nodes"] if "clash_id" in n.get("extras", {}) and "children" in n}
        self.assertEqual(sorted(rows), ["step %d" % k for k in range(4, STEPS)])
        self.assertEqual(rows["step 4"]["extras"]["verdict"], "contact")
        self.assertEqual(rows["step 5"]["extras"]["verdict"], "clash")
        self.assertEqual(rows["step 5"]["extras"]["frames"], [5])
        # The first clash's region, at full resolution in world coordinates: the region node's
        # POSITION values plus the clash node's translation reach A's face x = 1 and stay within
        # the overlap of the two boxes at step 5 (x in [0.875, 1.5]: triangles of both sides).
        row = rows["step 5"]
        t = row.get("translation", [0, 0, 0])
        region = next(doc["nodes"][c] for c in row["children"] if doc["nodes"][c]["name"] == "step 5 region")
        prim = doc["meshes"][region["mesh"]]["primitives"][0]
        xs = [p[0] + t[0] for p in accessor_values(doc, binary, prim["attributes"]["POSITION"])]
        self.assertGreater(len(xs), 0)
        self.assertLessEqual(min(xs), 1.0 + 1e-6)
        self.assertGreaterEqual(min(xs), 0.5 - 1e-6)  # A's triangles touching x = 1 start at x = 0.5
        self.assertLessEqual(max(xs), 2.0 + 1e-6)     # B's at step 5: [0.875, 1.875]

    def test_a_single_step_is_one_frame(self):
        rc, out, err = run("clash", self.model, self.model, *SERIES, "--step", "5", "--pvd", path("one.pvd"),
                           "--glb", path("one.glb"))
        self.assertEqual(rc, 1, out + err)
        sets = read_pvd(path("one.pvd"))
        self.assertEqual([(t, n) for t, _, n, _ in sets if n == "bodies"], [(2.5, "bodies")])
        doc, _ = read_glb(path("one.glb"))
        self.assertEqual(doc["scenes"][doc.get("scene", 0)]["extras"]["frames"]["labels"], ["step 5 (time 2.5)"])

    def test_outputs_are_checked_before_any_work(self):
        for args, needle in ((["--json", path("same.glb"), "--glb", path("same.glb")], "is also the file of"),
                             (["--pvd", path("bad.vtp")], "--pvd"),
                             (["--glb", self.model], "--glb")):
            rc, out, err = run("clash", self.model, self.model, *SERIES, *args)
            self.assertEqual(rc, 2, out + err)
            self.assertIn(needle, err)
        self.assertFalse(os.path.exists(path("same.glb")))
        self.assertFalse(os.path.exists(path("bad.vtp")))

    def test_html_page_when_the_build_has_the_viewer(self):
        rc, out, err = run("clash", self.model, self.model, *SERIES, "--html", path("series.html"))
        if NO_VIEWER in err:
            self.assertEqual(rc, 2, out + err)
            self.assertFalse(os.path.exists(path("series.html")))
            self.skipTest("this build has no HTML viewer")
        self.assertEqual(rc, 1, out + err)
        with open(path("series.html"), encoding="utf-8") as f:
            page = f.read()
        for k in range(STEPS):
            self.assertIn("step %d (time %g)" % (k, 0.5 * k), page)


if __name__ == "__main__":
    cli_common.main()
