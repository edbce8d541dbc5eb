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
        self.assertEqual(rc, 0, err)
        rep = json.load(open(path("open.json")))
        self.assertEqual(rep["result"]["containment"], "not_checked")
        self.assertTrue(any("not closed" in w for w in rep["warnings"]))
        self.assertTrue(any("3 open edges" in w for w in rep["input_warnings"]), rep["input_warnings"])
        self.assertEqual(rep["inputs"]["b"]["open_edges"], 3)

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
        rc, _, err = run("clash", a, b, "--pairs", path("touch.pairs"))
        self.assertEqual(rc, 1, err)
        kinds = {line.split()[2] for line in open(path("touch.pairs"))}
        self.assertEqual(kinds, {"touch"})

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


if __name__ == "__main__":
    cli_common.main()
