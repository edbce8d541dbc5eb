#!/usr/bin/env python3
"""End-to-end tests of `interfere sweep` (issue #5): exit status, JSON/CSV reports, OBJ/VTK output,
a collision found only between samples, and bad inputs naming file, row and field (and leaving no
output behind).

Usage: test_sweep.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, write_text as write, load_json as load, read_text as text, read_csv as table  # noqa: E402


def run(*args):
    return cli_common.run(*args, command=("sweep",))


ROBOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "probe_5axis.json")


def plate_obj(name, z, half=500.0, n=4):
    """An n x n grid plate at height z (2 n^2 triangles), normals up."""
    lines = []
    for j in range(n + 1):
        for i in range(n + 1):
            lines.append("v %r %r %r" % (-half + 2 * half * i / n, -half + 2 * half * j / n, z))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            lines.append("f %d %d %d" % (a, a + 1, a + n + 2))
            lines.append("f %d %d %d" % (a, a + n + 2, a + n + 1))
    return write(name, "\n".join(lines) + "\n")


BASE = ["--probe-radius", "5", "--probe-length", "40"]


class Sweep(unittest.TestCase):
    def test_clear_path(self):
        work = plate_obj("plate.obj", 0.0)
        # Pivot at z = 170, tip 150 below it: 20 above the plate; the probe points down.
        p = write("clear.csv", "x,y,z,a,b\n0,0,170,0,0\n10,0,170,0,0\n20,0,170,0,10\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--json", path("clear.json"),
                           "--csv", path("clear_table.csv"))
        self.assertEqual(rc, 0, err + out)
        j = load(path("clear.json"))
        self.assertEqual(j["command"], "sweep")
        self.assertEqual(j["summary"]["colliding_points"], 0)
        self.assertFalse(j["summary"]["collision"])
        self.assertAlmostEqual(j["points"][0]["clearance"], 20.0, places=9)
        self.assertEqual(j["points"][0]["line"], 2)
        rows = table(path("clear_table.csv"))
        self.assertEqual(len(rows), 3)
        self.assertEqual(rows[1]["collides"], "0")
        self.assertAlmostEqual(float(rows[1]["clearance"]), 20.0, places=9)

    def test_colliding_points_and_outputs(self):
        work = plate_obj("plate2.obj", 0.0)
        # Second point: tip at z = -2 (below the plate).
        p = write("hit.csv", "x,y,z,a,b\n0,0,170,0,0\n0,0,148,0,0\n0,0,170,0,0\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--json", path("hit.json"),
                           "--hits-obj", path("hits.obj"), "--probes-vtk", path("probes.vtk"), "--threads", "1")
        self.assertEqual(rc, 1, err + out)
        self.assertIn("COLLISION", out)
        j = load(path("hit.json"))
        self.assertEqual(j["colliding_points"], [1])
        self.assertTrue(j["points"][1]["collides"])
        self.assertEqual(j["points"][1]["clearance"], 0)
        self.assertGreater(len(j["points"][1]["hits"]), 0)
        segs = j["colliding_segments"]
        self.assertEqual([s["from"] for s in segs], [0, 1])
        self.assertEqual(segs[0]["intervals"][-1][1], 1.0)
        self.assertEqual(segs[1]["intervals"][0][0], 0.0)
        obj = text(path("hits.obj"))
        self.assertIn("g hits", obj)
        self.assertIn("g probe_1", obj)
        vtk = text(path("probes.vtk"))
        self.assertIn("DATASET POLYDATA", vtk)
        self.assertIn("SCALARS kind int 1", vtk)

    def test_collision_only_between_samples(self):
        work = plate_obj("plate3.obj", 80.0)
        p = write("swing.csv", "x,y,z,a,b\n0,0,200,0,-60\n0,0,200,0,60\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--json", path("swing.json"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("swing.json"))
        self.assertEqual(j["summary"]["colliding_points"], 0)
        self.assertEqual(j["summary"]["between_samples_segments"], 1)
        (seg,) = j["colliding_segments"]
        self.assertTrue(seg["between_samples"])
        lo, hi = seg["intervals"][0]
        self.assertTrue(0.1 < lo < 0.5 < hi < 0.9, seg)
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--no-continuous")
        self.assertEqual(rc, 0, err + out)

    def test_pose_path_and_hierarchies_agree(self):
        work = plate_obj("plate4.obj", 0.0, n=10)
        rows = ["px,py,pz,ax,ay,az"]
        for i in range(30):
            z = 3.0 if i % 7 else -1.0
            rows.append("%r,%r,%r,0.1,0,-1" % (-140.0 + 10 * i, 5.0, z))
        p = write("poses.csv", "\n".join(rows) + "\n")
        results = {}
        for h in ("bvh", "patches", "grid", "distance-field", "brute"):
            rc, out, err = run("--workpiece", work, "--path", p, *BASE, "--hierarchy", h, "--json", path(h + ".json"))
            self.assertEqual(rc, 1, err)
            j = load(path(h + ".json"))
            results[h] = ([pt["collides"] for pt in j["points"]], [pt["hits"] for pt in j["points"]])
        for h in results:
            self.assertEqual(results[h], results["bvh"], h)
        self.assertEqual(sum(results["bvh"][0]), 5)

    def test_patch_options(self):
        work = plate_obj("plate7.obj", 0.0, n=16)
        p = write("patch.csv", "x,y,z,a,b\n0,0,170,0,0\n0,0,148,0,0\n")
        counts = []
        for args in (["--patch-rule", "8"], ["--patch-rule", "33"], ["--patch-rule", "100"], ["--patch-size", "1e9"]):
            rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--hierarchy", "patches",
                               *args, "--json", path("patch.json"), "--no-continuous")
            self.assertEqual(rc, 1, err)
            j = load(path("patch.json"))
            self.assertEqual(j["colliding_points"], [1])
            counts.append(j["workpiece"]["patches"])
        self.assertGreater(counts[0], counts[1])
        self.assertGreaterEqual(counts[1], counts[2])
        self.assertEqual(counts[3], 1)  # one box holds the whole plate

    def test_bad_inputs_name_file_row_field(self):
        work = plate_obj("plate5.obj", 0.0)
        good = write("good.csv", "x,y,z,a,b\n0,0,170,0,0\n")
        out_json = path("bad_out.json")

        def bad(args, *expect):
            rc, out, err = run(*args, "--json", out_json)
            self.assertEqual(rc, 2, err + out)
            for e in expect:
                self.assertIn(e, err)
            self.assertFalse(os.path.exists(out_json), "a bad input must not write the report")

        bad(["--workpiece", work, "--robot", ROBOT, "--path", write("short.csv", "x,y,z,a,b\n0,0,170,0,0\n1,2,3\n"),
             *BASE], "short.csv:3", "3 values, expected 5")
        bad(["--workpiece", work, "--robot", ROBOT, "--path", write("lim.csv", "x,y,z,a,b\n0,0,170,0,0\n0,0,170,0,130\n"),
             *BASE], "lim.csv:3", "field 'b'", "limits")
        bad(["--workpiece", work, "--robot", ROBOT, "--path", write("nan.csv", "x,y,z,a,b\n0,zz,170,0,0\n"), *BASE],
            "nan.csv:2", "field 'y'")
        robot = write("r.json", '{"joints": [\n {"type": "telescopic", "a": 0, "alpha": 0, "d": 0, "theta": 0}\n],'
                                ' "tool": {"tip": [0,0,0], "axis": [0,0,1]}}\n')
        bad(["--workpiece", work, "--robot", robot, "--path", good, *BASE], "r.json:2", "joints[0].type", "telescopic")
        robot2 = write("r2.json", '{"joints": [\n {"type": "revolute", "a": 0, "d": 0, "theta": 0}\n],'
                                  ' "tool": {"tip": [0,0,0], "axis": [0,0,1]}}\n')
        bad(["--workpiece", work, "--robot", robot2, "--path", good, *BASE], "r2.json:2", "joints[0].alpha: missing")
        bad(["--workpiece", work, "--robot", ROBOT, "--path", good, "--probe-radius", "0", "--probe-length", "40"],
            "--probe-radius", "> 0")
        bad(["--workpiece", work, "--robot", ROBOT, "--path", good, "--probe-radius", "5", "--probe-length", "-1"],
            "--probe-length")
        bad(["--workpiece", work, "--path", good, *BASE], "needs a robot")
        bad(["--workpiece", work, "--robot", ROBOT, "--path", good, *BASE, "--hierarchy", "octree"], "--hierarchy")
        # STEP tessellation flags with a mesh workpiece would do nothing: an error.
        bad(["--workpiece", work, "--robot", ROBOT, "--path", good, *BASE, "--linear-deflection", "0.1"], "STEP")

    def test_holder_box(self):
        # Probe down from tip z = 100, length 40; the box (40 wide along ref, 20 deep, 30 long) spans
        # z in [140, 170] and x in [-20, 20] with ref = x: the wall x = 18 is hit by the box only.
        # Turned by 90 degrees (ref = y) it spans x in [-10, 10]: clear by 8.
        work = write("wall.obj", "v 18 -100 -100\nv 18 100 -100\nv 18 100 300\nv 18 -100 300\nf 1 2 3\nf 1 3 4\n")
        p = write("frames.csv", "px,py,pz,ax,ay,az,rx,ry,rz\n0,0,100,0,0,-1,1,0,0\n0,0,100,0,0,-1,0,1,0\n")
        rc, out, err = run("--workpiece", work, "--path", p, *BASE, "--holder-box", "40,20,30", "--json",
                           path("box.json"), "--csv", path("box.csv"), "--hits-obj", path("box.obj"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("box.json"))
        self.assertEqual(j["probe"]["holder_kind"], "box")
        self.assertEqual([j["probe"][k] for k in ("holder_box_width", "holder_box_depth", "holder_box_length")],
                         [40, 20, 30])
        self.assertEqual(j["probe"]["holder_radius"], 0)
        self.assertEqual(j["colliding_points"], [0])
        self.assertTrue(j["points"][0]["holder"])
        self.assertEqual(j["points"][0]["hits"], [1])
        self.assertAlmostEqual(j["points"][1]["clearance"], 8.0, places=9)
        self.assertAlmostEqual(j["points"][1]["point_probe"][0], 10.0, places=9)
        rows = table(path("box.csv"))
        self.assertEqual([r["holder"] for r in rows], ["1", "0"])
        self.assertEqual(list(rows[0].keys())[:5], ["index", "line", "collides", "holder", "clearance"])
        obj = text(path("box.obj"))
        self.assertIn("g probe_0", obj)
        self.assertEqual(obj.count("\nf "), 1 + 4 * 24 + 12)  # hit triangle, probe cylinder, box
        # A holder cylinder inscribed in the box (radius 10) misses the wall.
        rc, out, err = run("--workpiece", work, "--path", p, *BASE, "--holder-radius", "10", "--holder-length", "30")
        self.assertEqual(rc, 0, err + out)

    def test_holder_box_joint_path_between_samples(self):
        # The paper machine turns a from 0 to 90 degrees (probe down, tip at z = 50): the box's width
        # direction (the last frame's x axis) turns with it and sweeps through a post at radius 15,
        # azimuth 45 degrees, that both samples clear.
        c = 15 * 0.5 ** 0.5
        work = write("post.obj", "v %r %r 100\nv %r %r 110\nv %r %r 105\nf 1 2 3\n" % (c, c, c, c, c + 0.01, c - 0.01))
        p = write("turn.csv", "x,y,z,a,b\n0,0,200,0,0\n0,0,200,90,0\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--holder-box", "40,10,30",
                           "--json", path("turn.json"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("turn.json"))
        self.assertEqual(j["summary"]["colliding_points"], 0)
        self.assertEqual(j["summary"]["between_samples_segments"], 1)
        lo, hi = j["colliding_segments"][0]["intervals"][0]
        self.assertTrue(0.27 < lo < 0.29 and 0.71 < hi < 0.73, (lo, hi))  # 0.5 -+ asin(1/3) / (pi/2)

    def test_holder_box_bad_inputs(self):
        work = plate_obj("plate8.obj", 0.0)
        frames = write("f.csv", "px,py,pz,ax,ay,az,rx,ry,rz\n0,0,100,0,0,-1,1,0,0\n")
        out_json = path("bad_box.json")

        def bad(args, *expect):
            rc, out, err = run("--workpiece", work, *BASE, *args, "--json", out_json)
            self.assertEqual(rc, 2, err + out)
            for e in expect:
                self.assertIn(e, err)
            self.assertFalse(os.path.exists(out_json), "a bad input must not write the report")

        bad(["--path", frames, "--holder-box", "40,0,30"], "--holder-box", "> 0", "40,0,30")
        bad(["--path", frames, "--holder-box", "40,-2,30"], "--holder-box")
        bad(["--path", frames, "--holder-box", "40,20"], "--holder-box", "W,D,L")
        bad(["--path", frames, "--holder-box", "40,20,30,5"], "--holder-box")
        bad(["--path", frames, "--holder-box", "40,x,30"], "--holder-box")
        bad(["--path", frames, "--holder-box", "40,20,30", "--holder-radius", "10", "--holder-length", "30"],
            "--holder-box", "--holder-radius", "one holder")
        bare = write("bare.csv", "# poses without reference directions\npx,py,pz,ax,ay,az\n0,0,100,0,0,-1\n")
        bad(["--path", bare, "--holder-box", "40,20,30"], "bare.csv:3", "field 'rx,ry,rz'", "missing")
        par = write("par.csv", "px,py,pz,ax,ay,az,rx,ry,rz\n0,0,100,0,0,-1,1,0,0\n0,0,100,0,0,-1,0,0,5\n")
        bad(["--path", par, "--holder-box", "40,20,30"], "par.csv:3", "field 'rx,ry,rz'", "parallel")

    def test_bad_input_keeps_existing_output(self):
        work = plate_obj("plate6.obj", 0.0)
        keep = write("keep.json", "previous\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", write("k.csv", "x,y,z,a,b\n1,2\n"), *BASE,
                           "--json", keep)
        self.assertEqual(rc, 2)
        self.assertEqual(text(keep), "previous\n")


if __name__ == "__main__":
    cli_common.main()
