#!/usr/bin/env python3
"""End-to-end tests of the `interfere` CLI: exit status, reports, outputs and bad input.

Usage: test_cli.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import json
import os
import struct
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run, write_obj  # noqa: E402

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples")


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    return v, f


def write_stl(name, mesh):
    v, f = mesh
    with open(path(name), "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(f)))
        for t in f:
            out.write(struct.pack("<12fH", 0, 0, 0, *v[t[0]], *v[t[1]], *v[t[2]], 0))
    return path(name)


class Cli(unittest.TestCase):
    def test_example_scene_clashes(self):
        rc, out, err = run("clash", "--scene", os.path.join(EXAMPLES, "scene.json"), "--json", path("ex.json"),
                           "--pairs", path("ex.pairs"), "--curves", path("ex.obj"), "--curves", path("ex.vtk"),
                           "--region-a", path("ex_a.stl"), "--region-b", path("ex_b.ply"))
        self.assertEqual(rc, 1, err)
        rep = json.load(open(path("ex.json")))
        res = rep["result"]
        self.assertTrue(res["interference"])
        self.assertGreater(res["cross_pairs"], 0)
        self.assertEqual(res["pairs"], res["cross_pairs"] + res["touch_pairs"])
        # The tilted pin pierces the plate's top and bottom faces: two closed curves, each close to an
        # ellipse of semi-axes 6 and 6/cos(5deg) (perimeter ~ 37.8 mm), inscribed in a 48-gon.
        curves = [c for r in res["regions"] for c in r["curves"]]
        self.assertEqual(len(curves), 2)
        for c in curves:
            self.assertTrue(c["closed"])
            self.assertAlmostEqual(c["length"], 37.7, delta=0.6)
        lines = open(path("ex.pairs")).read().split("\n")[:-1]
        self.assertEqual(len(lines), res["pairs"])
        keys = []
        for line in lines:
            i, j, kind = line.split(" ")
            self.assertIn(kind, ("cross", "touch"))
            keys.append((int(i), int(j)))
        self.assertEqual(keys, sorted(keys))
        self.assertEqual(len(set(keys)), len(keys))
        obj = open(path("ex.obj")).read()
        self.assertEqual(obj.count("\nl "), 2)
        vtk = open(path("ex.vtk")).read()
        self.assertIn("DATASET POLYDATA", vtk)
        self.assertIn("LINES 2 ", vtk)
        self.assertGreater(os.path.getsize(path("ex_a.stl")), 84)
        self.assertTrue(open(path("ex_b.ply"), "rb").read().startswith(b"ply"))

    def test_threads_do_not_change_result(self):
        outs = []
        for n in ("1", "2"):
            rc, _, err = run("clash", "--scene", os.path.join(EXAMPLES, "scene.json"), "--threads", n,
                             "--pairs", path("t%s.pairs" % n))
            self.assertEqual(rc, 1, err)
            outs.append(open(path("t%s.pairs" % n)).read())
        self.assertEqual(outs[0], outs[1])

    def test_separated_parts_are_clear_and_distance_is_exact(self):
        a = write_obj("a.obj", box((0, 0, 0), (1, 1, 1)))
        b = write_stl("b.stl", box((3.5, 0.25, 0.25), (4, 0.75, 0.75)))
        rc, out, err = run("clash", a, b, "--json", path("sep.json"), "--region-a", path("sep_a.stl"))
        self.assertEqual(rc, 0, err)
        self.assertFalse(os.path.exists(path("sep_a.stl")))
        self.assertIn("clear", out)
        rep = json.load(open(path("sep.json")))
        self.assertFalse(rep["result"]["interference"])
        self.assertEqual(rep["result"]["containment"], "none")
        rc, out, err = run("distance", a, b, "--json", path("dist.json"))
        self.assertEqual(rc, 0, err)
        d = json.load(open(path("dist.json")))["result"]
        self.assertAlmostEqual(d["distance"], 2.5, places=12)
        self.assertAlmostEqual(d["point_a"][0], 1.0, places=12)
        self.assertAlmostEqual(d["point_b"][0], 3.5, places=12)

    def test_transform_moves_part_b(self):
        a = write_obj("ta.obj", box((0, 0, 0), (1, 1, 1)))
        b = write_obj("tb.obj", box((3.5, 0.25, 0.25), (4, 0.75, 0.75)))
        rc, _, err = run("clash", a, b, "--transform-b", "1 0 0 -2.75 0 1 0 0 0 0 1 0", "--json", path("tr.json"))
        self.assertEqual(rc, 1, err)
        self.assertGreater(json.load(open(path("tr.json")))["result"]["cross_pairs"], 0)

    def test_containment(self):
        big = write_obj("big.obj", box((0, 0, 0), (10, 10, 10)))
        small = write_stl("small.stl", box((2, 3, 4), (5, 6, 7)))
        rc, out, err = run("clash", small, big, "--json", path("cont.json"))
        self.assertEqual(rc, 1, err)
        self.assertEqual(json.load(open(path("cont.json")))["result"]["containment"], "a_inside_b")
        rc, _, err = run("clash", big, small, "--json", path("cont2.json"))
        self.assertEqual(rc, 1, err)
        self.assertEqual(json.load(open(path("cont2.json")))["result"]["containment"], "b_inside_a")

    def test_open_mesh_skips_containment_with_warning(self):
        v, f = box((0, 0, 0), (10, 10, 10))
        opened = write_obj("open.obj", (v, f[:-1]))
        small = write_obj("small2.obj", box((2, 3, 4), (5, 6, 7)))
        rc, _, err = run("clash", small, opened, "--json", path("open.json"))
        # The small box lies inside the open box: whether it is inside cannot be decided, so the
        # verdict is undecided, exit 3 -- never clear (issue #23: it was "clear", exit 0).
        self.assertEqual(rc, 3, err)
        rep = json.load(open(path("open.json")))
        self.assertEqual(rep["verdict"], "undecided")
        self.assertEqual(rep["result"]["verdict"], "undecided")
        self.assertTrue(any("part B is not closed" in w for w in rep["result"]["verdict_reasons"]), rep["result"])
        self.assertEqual(rep["result"]["containment"], "not_checked")
        self.assertTrue(any("not closed" in w for w in rep["warnings"]))
        self.assertTrue(any("3 open edges" in w for w in rep["input_warnings"]), rep["input_warnings"])
        self.assertEqual(rep["inputs"]["b"]["open_edges"], 3)
        # Skipping containment on purpose (--no-containment) is the user's choice: clear, exit 0.
        rc, _, err = run("clash", small, opened, "--no-containment", "--json", path("open_nc.json"))
        self.assertEqual(rc, 0, err)
        self.assertEqual(json.load(open(path("open_nc.json")))["verdict"], "clear")
        # A closed part still decides an open part inside it: the open box within a bigger box clashes.
        huge = write_obj("huge.obj", box((-5, -5, -5), (20, 20, 20)))
        rc, _, err = run("clash", opened, huge, "--json", path("open_in.json"))
        self.assertEqual(rc, 1, err)
        self.assertEqual(json.load(open(path("open_in.json")))["result"]["containment"], "a_inside_b")

    def test_clash_statistics_only_where_needed(self):
        # Issue #24, item 8: crossing surfaces decide a clash without closedness, so the parts'
        # statistics are not computed (nor their input warnings given); check computes them all.
        v, f = box((0, 0, 0), (10, 10, 10))
        opened = write_obj("open_x.obj", (v, f[:-1]))  # 3 open edges
        crossing = write_obj("cross_x.obj", box((5, 5, 5), (15, 15, 15)))
        rc, _, err = run("clash", crossing, opened, "--json", path("stats_x.json"))
        self.assertEqual(rc, 1, err)
        rep = json.load(open(path("stats_x.json")))
        self.assertEqual(rep["verdict"], "clash")
        for part in ("a", "b"):
            self.assertEqual(rep["inputs"][part]["statistics"], "not needed")
            self.assertNotIn("open_edges", rep["inputs"][part])
        self.assertEqual(rep["inputs"]["b"]["triangles"], len(f) - 1)
        self.assertFalse(any("open edges" in w for w in rep["input_warnings"]), rep["input_warnings"])
        # --depth needs both parts closed: then they are computed, with their warnings.
        rc, _, err = run("clash", crossing, opened, "--depth", "--json", path("stats_d.json"))
        self.assertEqual(rc, 1, err)
        rep = json.load(open(path("stats_d.json")))
        self.assertEqual(rep["inputs"]["b"]["open_edges"], 3)
        self.assertTrue(any("3 open edges" in w for w in rep["input_warnings"]), rep["input_warnings"])
        rc, _, err = run("check", opened, "--json", path("stats_c.json"))
        self.assertEqual(json.load(open(path("stats_c.json")))["open_edges"], 3, err)

    def test_concurrent_reads_name_a_first(self):
        # Both files are read at once (issue #24, item 8); when both are bad the error names A,
        # whichever read fails first (B's, an empty OBJ, is the quicker here), every time.
        bad_a = path("bad_a.stl")
        with open(bad_a, "w") as f:
            f.write("solid x\nfacet normal 0 0 1\nbad\n")
        bad_b = path("bad_b.obj")
        with open(bad_b, "w") as f:
            f.write("garbage\n")
        for _ in range(5):
            rc, _, err = run("clash", bad_a, bad_b, "--json", path("bad_ab.json"))
            self.assertEqual(rc, 2, err)
            self.assertIn("bad_a.stl:3", err)
            self.assertNotIn("bad_b.obj", err)
            self.assertFalse(os.path.exists(path("bad_ab.json")))
        rc, _, err = run("clash", bad_b, bad_a)
        self.assertEqual(rc, 2, err)
        self.assertIn("bad_b.obj", err)

    def test_distance_sees_containment(self):
        # Nested closed parts are apart by 2 yet their interiors overlap: a clash (was exit 0, "clear").
        big = write_obj("dbig.obj", box((0, 0, 0), (10, 10, 10)))
        small = write_obj("dsmall.obj", box((2, 3, 4), (5, 6, 7)))
        rc, out, err = run("distance", small, big, "--json", path("dnest.json"))
        self.assertEqual(rc, 1, err)
        rep = json.load(open(path("dnest.json")))
        self.assertEqual(rep["verdict"], "clash")
        self.assertAlmostEqual(rep["result"]["distance"], 2.0, places=12)
        self.assertIn("CLASH", out)
        # Touching faces: distance 0, a contact (exit 0), not a clash.
        b = write_obj("dtouch.obj", box((10, 0, 0), (12, 10, 10)))
        rc, out, err = run("distance", big, b, "--json", path("dtouch.json"))
        self.assertEqual(rc, 0, err)
        self.assertEqual(json.load(open(path("dtouch.json")))["verdict"], "contact")

    def test_units_per_input(self):
        # Issue #23, item 6: one part in metres (given here with --units-a on an OBJ), the other in
        # millimetres. Both are converted to the working unit before the query.
        metres = write_obj("m_box.obj", box((0, 0, 0), (0.010, 0.010, 0.010)))   # 10 mm cube, in m
        mm = write_obj("mm_box.obj", box((5, 5, 5), (15, 15, 15)))               # overlaps it, in mm
        rc, _, err = run("clash", metres, mm, "--json", path("u0.json"))
        self.assertEqual(rc, 0, err)  # without units: a 0.01 mm cube against 10 mm: apart
        self.assertTrue(any("differ by more than 100x" in w for w in json.load(open(path("u0.json")))["input_warnings"]))
        rc, _, err = run("clash", metres, mm, "--units-a", "m", "--json", path("u1.json"))
        self.assertEqual(rc, 1, err)
        rep = json.load(open(path("u1.json")))
        self.assertEqual(rep["units"], "mm")
        self.assertEqual(rep["inputs"]["a"]["units"], "m")
        self.assertEqual(rep["inputs"]["a"]["scale_to_working_unit"], 1000)
        self.assertEqual(rep["inputs"]["b"]["units"], "mm")
        # Working unit metres: the same verdict, the report in metres.
        rc, _, err = run("clash", metres, mm, "--units-a", "m", "--units", "m", "--json", path("u2.json"))
        self.assertEqual(rc, 1, err)
        self.assertAlmostEqual(json.load(open(path("u2.json")))["inputs"]["b"]["scale_to_working_unit"], 1e-3, places=15)
        # A glTF file is in metres by its specification: simplify writes the mm box scaled to metres,
        # and clash reads it back as metres (no flag), so it overlaps the mm box exactly.
        glb = path("mm_box.glb")
        rc, _, err = run("simplify", mm, glb, "--ratio", "1")
        self.assertEqual(rc, 0, err)
        rc, out, err = run("clash", glb, mm, "--json", path("u3.json"))
        self.assertEqual(rc, 1, out + err)
        rep = json.load(open(path("u3.json")))
        self.assertEqual(rep["inputs"]["a"]["units"], "m")
        self.assertEqual(rep["verdict"], "clash")
        # Scene files give each part's unit; unknown keys and units are errors naming them.
        scene = path("units_scene.json")
        with open(scene, "w") as f:
            json.dump({"a": {"file": metres, "units": "m"}, "b": {"file": mm}}, f)
        rc, _, err = run("clash", "--scene", scene)
        self.assertEqual(rc, 1, err)
        with open(scene, "w") as f:
            json.dump({"a": {"file": metres, "unit": "m"}, "b": {"file": mm}}, f)
        rc, _, err = run("clash", "--scene", scene)
        self.assertEqual(rc, 2, err)
        self.assertIn('unknown key "unit"', err)
        rc, _, err = run("clash", metres, mm, "--units-a", "furlong")
        self.assertEqual(rc, 2, err)
        self.assertIn("--units-a", err)

    def test_clearance(self):
        a = write_obj("ca.obj", box((0, 0, 0), (1, 1, 1)))
        b = write_obj("cb.obj", box((1.5, 0, 0), (2, 1, 1)))
        rc, _, err = run("clash", a, b, "--clearance", "0.6", "--json", path("cl.json"))
        self.assertEqual(rc, 0, err)
        cl = json.load(open(path("cl.json")))["result"]["clearance"]
        self.assertGreater(cl["pairs"], 0)
        self.assertAlmostEqual(cl["min_distance"], 0.5, places=12)
        rc, _, err = run("clash", a, b, "--clearance", "0.4", "--json", path("cl2.json"))
        self.assertEqual(json.load(open(path("cl2.json")))["result"]["clearance"]["pairs"], 0)

    def test_touching_faces_are_touch_pairs(self):
        a = write_obj("fa.obj", box((0, 0, 0), (1, 1, 1)))
        b = write_obj("fb.obj", box((1, 0, 0), (2, 1, 1)))
        rc, out, err = run("clash", a, b, "--pairs", path("touch.pairs"), "--json", path("touch.json"))
        # Contact is not clash (issue #23, item 13: was exit 1, "INTERFERENCE").
        self.assertEqual(rc, 0, err)
        self.assertTrue(out.startswith("contact:"), out)
        self.assertEqual(json.load(open(path("touch.json")))["verdict"], "contact")
        kinds = {line.split()[2] for line in open(path("touch.pairs"))}
        self.assertEqual(kinds, {"touch"})
        rc, _, err = run("clash", a, b, "--fail-on", "contact")
        self.assertEqual(rc, 1, err)
        rc, _, err = run("clash", a, b, "--fail-on", "contacts")
        self.assertEqual(rc, 2, err)
        self.assertIn("--fail-on", err)
        # Shifted along the face, the solids overlap behind coincident faces: a clash.
        c = write_obj("fc.obj", box((0.5, 0, 0), (2, 1, 1)))
        rc, out, err = run("clash", a, c)
        self.assertEqual(rc, 1, err)
        self.assertTrue(out.startswith("CLASH:"), out)

    # ---- bad input: exit 2, a clear message, nothing written ----
    def assert_input_error(self, args, must_contain):
        target = path("must_not_exist.json")
        if os.path.exists(target):
            os.remove(target)
        keep = path("keep.pairs")
        with open(keep, "w") as f:
            f.write("precious\n")
        rc, out, err = run(*args, "--json", target, "--pairs", keep)
        self.assertEqual(rc, 2, (out, err))
        for m in must_contain:
            self.assertIn(m, err)
        self.assertFalse(os.path.exists(target))
        self.assertEqual(open(keep).read(), "precious\n")
        self.assertEqual([n for n in os.listdir(cli_common.WORK) if ".tmp-" in n], [])

    def test_outputs_never_replace_inputs_or_each_other(self):
        # An output naming an input file (by its path, another spelling of it, a symbolic or a hard
        # link) would lose the input; two outputs naming one file would overwrite each other. Every
        # command refuses before any work, and the files stay as they were.
        import hashlib
        import shutil
        shutil.copy(os.path.join(EXAMPLES, "plate.stl"), path("own_plate.stl"))
        shutil.copy(os.path.join(EXAMPLES, "pin.obj"), path("own_pin.obj"))
        shutil.copy(os.path.join(EXAMPLES, "bearing.parameters"), path("own_bearing.parameters"))
        for link in ("plate_soft.stl", "plate_hard.stl"):
            if os.path.lexists(path(link)):
                os.remove(path(link))
        os.symlink(path("own_plate.stl"), path("plate_soft.stl"))
        os.link(path("own_plate.stl"), path("plate_hard.stl"))
        def digest(name):
            with open(path(name), "rb") as f:
                return hashlib.sha256(f.read()).hexdigest()
        before = {n: digest(n) for n in ("own_plate.stl", "own_pin.obj", "own_bearing.parameters")}
        sub = os.path.join(cli_common.WORK, "sub")
        os.makedirs(sub, exist_ok=True)
        cases = [
            (["check", path("own_plate.stl"), "--json", path("own_plate.stl")], "input file of FILE"),
            (["check", path("own_plate.stl"), "--json", path("plate_hard.stl")], "input file of FILE"),
            (["clash", path("own_plate.stl"), path("own_pin.obj"), "--json", path("plate_soft.stl")], "input file of A"),
            (["clash", path("own_plate.stl"), path("own_pin.obj"), "--pairs", os.path.join(sub, "..", "own_pin.obj")],
             "input file of B"),
            (["clash", path("own_plate.stl"), path("own_pin.obj"), "--json", path("x.json"), "--pairs", path("x.json")],
             "also the file of --json"),
            (["distance", path("own_plate.stl"), path("own_pin.obj"), "--json", path("own_pin.obj")], "input file of B"),
            (["simplify", path("own_plate.stl"), path("own_plate.stl"), "--ratio", "0.5"], "input file of IN"),
            (["simplify", path("own_plate.stl"), path("s.ply"), "--ratio", "0.5", "--json", path("s.ply")],
             "also the file of OUT"),
            (["bearing", "--params", path("own_bearing.parameters"), "--json", path("own_bearing.parameters")],
             "input file of --params"),
            (["simplify", path("own_plate.stl"), path("s.ply"), "--ratio", "0.5", "--json", sub], "is a directory"),
            (["check", path("own_plate.stl"), "--json", sub], "is a directory"),
        ]
        for args, message in cases:
            rc, out, err = run(*args)
            self.assertEqual(rc, 2, (args, out, err))
            self.assertIn(message, err, args)
        self.assertEqual({n: digest(n) for n in before}, before)
        for name in ("x.json", "s.ply"):
            self.assertFalse(os.path.exists(path(name)), name)

    def test_missing_file(self):
        self.assert_input_error(["clash", path("nope.stl"), os.path.join(EXAMPLES, "pin.obj")], ["nope.stl"])

    def test_truncated_stl(self):
        with open(os.path.join(EXAMPLES, "plate.stl"), "rb") as f:
            src = f.read()
        with open(path("trunc.stl"), "wb") as f:
            f.write(src[: len(src) - 30])
        self.assert_input_error(["clash", path("trunc.stl"), os.path.join(EXAMPLES, "pin.obj")], ["trunc.stl"])

    def test_nan_in_obj(self):
        with open(path("nan.obj"), "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
        self.assert_input_error(["clash", path("nan.obj"), os.path.join(EXAMPLES, "pin.obj")], ["nan.obj:3"])

    def test_index_out_of_range(self):
        with open(path("idx.obj"), "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
        self.assert_input_error(["clash", path("idx.obj"), os.path.join(EXAMPLES, "pin.obj")], ["idx.obj:4"])

    def test_empty_file(self):
        open(path("empty.off"), "w").close()
        self.assert_input_error(["clash", path("empty.off"), os.path.join(EXAMPLES, "pin.obj")], ["empty.off"])

    def test_bad_transform(self):
        self.assert_input_error(["clash", os.path.join(EXAMPLES, "plate.stl"), os.path.join(EXAMPLES, "pin.obj"),
                                 "--transform-b", "1 0 0 0 1"], ["transform"])

    def test_bad_units_and_options(self):
        ex = [os.path.join(EXAMPLES, "plate.stl"), os.path.join(EXAMPLES, "pin.obj")]
        self.assert_input_error(["clash", *ex, "--units", "furlong"], ["furlong"])
        self.assert_input_error(["clash", *ex, "--test", "fast"], ["fast"])
        self.assert_input_error(["clash", *ex, "--clearance", "-1"], ["clearance"])
        self.assert_input_error(["clash", *ex, "--frobnicate"], ["frobnicate"])

    def test_bad_scene(self):
        with open(path("bad_scene.json"), "w") as f:
            f.write('{"a": {"file": "plate.stl"}, "b": ')
        self.assert_input_error(["clash", "--scene", path("bad_scene.json")], ["bad_scene.json", "byte"])
        with open(path("huge_scene.json"), "w") as f:
            f.write('{"a": {"file": "plate.stl"}, "units": 9e308}')
        self.assert_input_error(["clash", "--scene", path("huge_scene.json")], ["huge_scene.json", "invalid JSON"])

    def test_check_command(self):
        rc, out, err = run("check", os.path.join(EXAMPLES, "plate.stl"))
        self.assertEqual(rc, 0, err)
        s = json.loads(out)
        self.assertTrue(s["closed"])
        self.assertEqual(s["open_edges"], 0)
        self.assertEqual(s["triangles"], 6 * 12 * 12 * 2)


# ------------------------------------------------------------------------------------------------
# Issue #23, items 8 and 11: transforms that are checked, outputs that respect the file system.
def _tet_vtk(name):
    """One linear tetrahedron as a legacy VTK file (a FEM input for `surface`)."""
    return cli_common.write_text(name, "# vtk DataFile Version 2.0\ntet\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                                 "POINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\n"
                                 "CELL_TYPES 1\n10\n")


class TransformsAndOutputs(unittest.TestCase):
    def setUp(self):
        self.a = write_stl("to_a.stl", box((0, 0, 0), (1, 1, 1)))
        self.b = write_stl("to_b.stl", box((3, 0, 0), (4, 1, 1)))       # 2 mm from A along x
        self.b_in = write_stl("to_b_in.stl", box((0.5, 0.25, 0.25), (1.5, 0.75, 0.75)))  # crosses A's face

    def assert_input_error(self, args, must_contain):
        target = path("to_must_not_exist.json")
        if os.path.exists(target):
            os.remove(target)
        rc, out, err = run(*args, "--json", target)
        self.assertEqual(rc, 2, (args, out, err))
        for m in must_contain:
            self.assertIn(m, err, args)
        self.assertFalse(os.path.exists(target), args)

    # ---- item 8: transforms ----
    def test_empty_transform_is_an_error_not_the_identity(self):
        # Before: "" was the identity, so B stayed 2 mm away and the run said clear.
        for cmd in ("clash", "distance"):
            for flag in ("--transform-a", "--transform-b"):
                self.assert_input_error([cmd, self.a, self.b, flag, ""], [flag, "empty"])
                self.assert_input_error([cmd, self.a, self.b, flag, " , "], [flag, "empty"])

    def test_singular_and_non_finite_transforms_are_errors(self):
        # Before: the all-zero matrix collapsed B to the point (0, 0, 0), a corner of A, and the run
        # reported a verdict on that point.
        zeros = "0 0 0 0 0 0 0 0 0 0 0 0"
        self.assert_input_error(["clash", self.a, self.b, "--transform-b", zeros], ["--transform-b", "singular", zeros])
        flat = "1 0 0 0 0 1 0 0 0 0 0 0"  # z squashed to 0: B becomes a flat sheet
        self.assert_input_error(["distance", self.a, self.b, "--transform-a", flat], ["--transform-a", "singular", flat])
        self.assert_input_error(["clash", self.a, self.b, "--transform-b", "1 0 0 nan 0 1 0 0 0 0 1 0"],
                                ["--transform-b", "not finite"])

    def test_scene_transforms_are_checked(self):
        for value, message in (([], "empty"), ("", "empty"), ([0] * 12, "singular"), ([1, 0, 0, 0] * 3, "singular"),
                               ([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "got 11")):
            scene = cli_common.write_text("to_scene.json", json.dumps(
                {"a": {"file": self.a}, "b": {"file": self.b, "transform": value}}))
            self.assert_input_error(["clash", "--scene", scene], ["to_scene.json", '"b"', "transform", message])
        # Checked even when the command line gives the transform that wins.
        scene = cli_common.write_text("to_scene.json", json.dumps(
            {"a": {"file": self.a}, "b": {"file": self.b, "transform": [0] * 12}}))
        self.assert_input_error(["clash", "--scene", scene, "--transform-b", "1 0 0 0 0 1 0 0 0 0 1 0"], ["singular"])

    def test_surface_transform_checked(self):
        tet = _tet_vtk("to_tet.vtk")
        for value, message in (("", "empty"), ("0 0 0 0 0 0 0 0 0 0 0 0", "singular")):
            rc, out, err = run("surface", tet, path("to_tet.stl"), "--transform", value)
            self.assertEqual(rc, 2, (value, out, err))
            self.assertIn("--transform", err)
            self.assertIn(message, err)
            self.assertFalse(os.path.exists(path("to_tet.stl")))

    def test_scaled_transform_warns_and_measures_in_the_transformed_space(self):
        # B = [3, 4] x [0, 1] x [0, 1] scaled by 0.5 about the origin lies at x in [1.5, 2]: 0.5 from A
        # (hand computation), where the untransformed B is 2 away.
        rc, out, err = run("distance", self.a, self.b, "--transform-b", "0.5 0 0 0 0 0.5 0 0 0 0 0.5 0",
                           "--json", path("to_scaled.json"))
        self.assertEqual(rc, 0, err)
        self.assertIn("not rigid", err)
        self.assertIn("transformed space", err)
        rep = json.load(open(path("to_scaled.json")))
        self.assertAlmostEqual(rep["result"]["distance"], 0.5, delta=1e-12)
        self.assertTrue(any("not rigid" in w for w in rep["input_warnings"]), rep["input_warnings"])
        # A mirror (x -> -x, then +5: B at x in [1, 2]) keeps lengths, and is said to mirror.
        rc, out, err = run("distance", self.a, self.b, "--transform-b", "-1 0 0 5 0 1 0 0 0 0 1 0",
                           "--json", path("to_mirror.json"))
        self.assertEqual(rc, 0, err)
        self.assertIn("mirrors", err)
        self.assertAlmostEqual(json.load(open(path("to_mirror.json")))["result"]["distance"], 0.0, delta=1e-12)
        # A rigid pose gives no such warning.
        rc, out, err = run("distance", self.a, self.b, "--transform-b", "0 -1 0 0 1 0 0 0 0 0 1 0")
        self.assertEqual(rc, 0, err)
        self.assertNotIn("not rigid", err)

    # ---- item 11: outputs ----
    def test_json_dash_is_standard_output(self):
        # Before: a file named "-" was created and stdout held the summary line.
        cwd = os.path.join(cli_common.WORK, "dash_cwd")
        os.makedirs(cwd, exist_ok=True)
        p = cli_common.subprocess.run([cli_common.EXE, "--quiet", "clash", self.a, self.b_in, "--json", "-"],
                                      capture_output=True, text=True, timeout=120, cwd=cwd)
        self.assertEqual(p.returncode, 1, p.stderr)
        rep = json.loads(p.stdout)  # stdout holds the report alone
        cli_common.report_schema.validate(rep, "clash --json -")
        self.assertEqual(rep["verdict"], "clash")
        self.assertIn("CLASH", p.stderr)  # the summary line moved to stderr
        self.assertFalse(os.path.exists(os.path.join(cwd, "-")))
        # The other commands' text reports too.
        for args in (["check", self.a], ["distance", self.a, self.b]):
            p = cli_common.subprocess.run([cli_common.EXE, "--quiet", *args, "--json", "-"], capture_output=True,
                                          text=True, timeout=120, cwd=cwd)
            self.assertEqual(p.returncode, 0, (args, p.stderr))
            rep = json.loads(p.stdout)
            self.assertIsInstance(rep, dict)
            cli_common.report_schema.validate(rep, "%s --json -" % args[0])
            self.assertFalse(os.path.exists(os.path.join(cwd, "-")), args)
        rep = json.loads(cli_common.subprocess.run([cli_common.EXE, "--quiet", "distance", self.a, self.b, "--json", "-"],
                                                   capture_output=True, text=True, timeout=120, cwd=cwd).stdout)
        self.assertAlmostEqual(rep["result"]["distance"], 2.0, delta=1e-12)

    def test_pairs_dash_and_simplify_json_dash(self):
        rc, out, err = run("clash", self.a, self.b_in, "--pairs", "-")
        self.assertEqual(rc, 1, err)
        lines = out.split("\n")[:-1]
        self.assertGreater(len(lines), 0)
        for line in lines:  # nothing but "i j kind" lines
            i, j, kind = line.split(" ")
            self.assertIn(kind, ("cross", "touch"))
        rc, out, err = run("simplify", self.a, path("to_s.stl"), "--ratio", "0.5", "--json", "-")
        self.assertEqual(rc, 0, err)
        self.assertIsInstance(json.loads(out), dict)
        self.assertTrue(os.path.exists(path("to_s.stl")))

    def test_dev_stdout_works(self):
        # Before: the rename over /dev/stdout failed.
        rc, out, err = run("clash", self.a, self.b_in, "--json", "/dev/stdout")
        self.assertEqual(rc, 1, err)
        self.assertEqual(json.loads(out)["verdict"], "clash")

    def test_dash_misuse_is_refused(self):
        rc, out, err = run("clash", self.a, self.b_in, "--json", "-", "--pairs", "-")
        self.assertEqual(rc, 2, err)
        self.assertIn("standard output", err)
        self.assertEqual(out, "")
        rc, out, err = run("clash", self.a, self.b_in, "--region-a", "-")
        self.assertEqual(rc, 2, err)
        self.assertIn("standard output", err)
        rc, out, err = run("simplify", self.a, "-", "--ratio", "0.5", "--format", "stl")
        self.assertEqual(rc, 2, err)
        self.assertIn("standard output", err)

    def test_symlink_written_through(self):
        # Before: the link was replaced by a regular file and its target kept the old report.
        os.makedirs(path("to_reports"), exist_ok=True)
        target = path("to_reports/real.json")
        link = path("to_link.json")
        with open(target, "w") as f:
            f.write("old\n")
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.join("to_reports", "real.json"), link)
        rc, out, err = run("clash", self.a, self.b_in, "--json", link)
        self.assertEqual(rc, 1, err)
        self.assertTrue(os.path.islink(link))
        self.assertEqual(os.readlink(link), os.path.join("to_reports", "real.json"))
        self.assertEqual(json.load(open(target))["verdict"], "clash")
        self.assertEqual([n for n in os.listdir(path("to_reports")) if ".tmp-" in n], [])
        # An output linked to an input is still refused, and the input is kept.
        with open(self.a, "rb") as f:
            before = f.read()
        os.remove(link)
        os.symlink(self.a, link)
        rc, out, err = run("clash", self.a, self.b_in, "--json", link)
        self.assertEqual(rc, 2, err)
        self.assertIn("input file of A", err)
        with open(self.a, "rb") as f:
            self.assertEqual(f.read(), before)

    def test_fifo_is_written_into(self):
        # Before: the FIFO was replaced by a regular file and its reader waited forever.
        import stat
        import threading
        fifo = path("to_fifo")
        if os.path.lexists(fifo):
            os.remove(fifo)
        os.mkfifo(fifo)
        got = []
        def reader():
            with open(fifo) as f:  # blocks until the writer opens it
                got.append(f.read())
        t = threading.Thread(target=reader, daemon=True)
        t.start()
        rc, out, err = run("clash", self.a, self.b_in, "--json", fifo)
        if rc != 1:  # unblock the reader before failing
            with open(fifo, "w"):
                pass
        t.join(30)
        self.assertEqual(rc, 1, err)
        self.assertFalse(t.is_alive())
        self.assertTrue(stat.S_ISFIFO(os.lstat(fifo).st_mode))
        self.assertEqual(json.loads(got[0])["verdict"], "clash")


if __name__ == "__main__":
    cli_common.main()
