#!/usr/bin/env python3
"""End-to-end tests of `interfere sweep` (issue #5): exit status, JSON/CSV reports, OBJ/VTK output,
a collision found only between samples, and bad inputs naming file, row and field (and leaving no
output behind). Issue #23: a probe inside a closed workpiece collides (item 3), a constant 5 um gap is
unresolved or clear but never a collision (item 4), path columns and robot files are read by
meaning (item 9), verdicts and --fail-on (item 13).

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


def cube_obj(name, lo=0.0, hi=100.0, skip_top=False):
    """The closed cube [lo, hi]^3 (outward triangles); without its top face when skip_top."""
    v = [(x, y, z) for z in (lo, hi) for y in (lo, hi) for x in (lo, hi)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    if skip_top:
        quads = [q for q in quads if q != (4, 5, 7, 6)]
    lines = ["v %r %r %r" % p for p in v]
    for a, b, c, d in quads:
        lines.append("f %d %d %d" % (a + 1, b + 1, c + 1))
        lines.append("f %d %d %d" % (a + 1, c + 1, d + 1))
    return write(name, "\n".join(lines) + "\n")


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

    def test_probe_inside_closed_cube_collides(self):
        # Issue #23, item 3: cube 0-100, probe at its centre pointing down (body z in [50, 90]): it
        # touches no face but lies inside the solid. Was: collides false, clearance 10, exit 0.
        p = write("centre.csv", "px,py,pz,ax,ay,az\n50,50,50,0,0,-1\n")
        rc, out, err = run("--workpiece", cube_obj("cube.obj"), "--path", p, *BASE, "--json", path("cube.json"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("cube.json"))
        self.assertEqual(j["verdict"], "clash")
        self.assertEqual(j["warnings"], [])
        self.assertEqual(j["workpiece"]["solids"], 1)
        pt = j["points"][0]
        self.assertTrue(pt["collides"])
        self.assertTrue(pt["inside"])
        self.assertEqual(pt["verdict"], "clash")
        self.assertEqual(pt["clearance"], 0)
        self.assertEqual(j["summary"]["inside_points"], 1)
        # Open (no top face): inside is not checked; said on stderr and in the JSON.
        rc, out, err = run("--workpiece", cube_obj("open.obj", skip_top=True), "--path", p, *BASE, "--json",
                           path("open.json"))
        self.assertEqual(rc, 0, err + out)
        self.assertIn("not checked", err)
        j = load(path("open.json"))
        self.assertEqual(len(j["warnings"]), 1)
        self.assertIn("not checked", j["warnings"][0])
        self.assertFalse(j["points"][0]["inside"])

    def test_workpiece_units(self):
        # Issue #23, item 6: a workpiece in metres (the cube 0-0.1 m) is converted to the working
        # unit (mm) before the sweep: the probe at (50, 50, 50) mm is inside it.
        p = write("centre_m.csv", "px,py,pz,ax,ay,az\n50,50,50,0,0,-1\n")
        cube_m = cube_obj("cube_m.obj", 0.0, 0.1)
        rc, out, err = run("--workpiece", cube_m, "--path", p, *BASE, "--units-workpiece", "m", "--json",
                           path("cube_m.json"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("cube_m.json"))
        self.assertEqual(j["inputs"]["workpiece"]["units"], "m")
        self.assertEqual(j["inputs"]["workpiece"]["scale_to_working_unit"], 1000)
        self.assertTrue(j["points"][0]["inside"])
        # Without the unit the cube is 0.1 mm: the probe is far from it (what the flag is for).
        rc, out, err = run("--workpiece", cube_m, "--path", p, *BASE)
        self.assertEqual(rc, 0, err + out)
        rc, out, err = run("--workpiece", cube_m, "--path", p, *BASE, "--units-workpiece", "parsec")
        self.assertEqual(rc, 2, err + out)
        self.assertIn("--units-workpiece", err)

    def test_path_beyond_the_coordinate_range(self):
        # Issue #23, item 7: a pose at 1e200 was "clear" (clearance inf); it is an input error
        # naming the path file and line.
        p = write("far.csv", "px,py,pz,ax,ay,az\n0,0,50,0,0,-1\n1e200,0,50,0,0,-1\n")
        rc, out, err = run("--workpiece", cube_obj("far_cube.obj"), "--path", p, *BASE, "--json", path("far.json"))
        self.assertEqual(rc, 2, err + out)
        self.assertIn("far.csv:3", err)
        self.assertIn("coordinate range", err)
        self.assertFalse(os.path.exists(path("far.json")))

    def test_constant_gap_pass_is_not_a_collision(self):
        # Issue #23, item 4: a 100 mm pass with the end face 5 um above a plate (gap 0.005 all along).
        # Was: collision interval [0, 1], exit 1, only because the refinement depth ran out.
        work = plate_obj("gap_plate.obj", 0.0)
        p = write("gap.csv", "px,py,pz,ax,ay,az\n-50,0,0.005,0,0,-1\n50,0,0.005,0,0,-1\n")
        # Issue #28: the plane filter measures the motion along the plate's normal (none here), so the
        # pass is proven clear even at depth 12 (the isotropic bound alone left it unresolved there:
        # ProbeSweepStates.ConstantGapPassIsNeverACollision keeps that case with the filter off).
        for depth, name in (("12", "gap12.json"), ("16", "gap.json")):
            rc, out, err = run("--workpiece", work, "--path", p, *BASE, "--depth", depth, "--json", path(name))
            self.assertEqual(rc, 0, err + out)
            j = load(path(name))
            self.assertEqual(j["verdict"], "clear")
            self.assertEqual(j["colliding_segments"], [])
            self.assertEqual((j["summary"]["segments_checked"], j["summary"]["clear_segments"]), (1, 1))
        # A 10 um step under the pass is still a collision, between the samples.
        step = cube_obj("step.obj", -1.0, 0.01)
        rc, out, err = run("--workpiece", step, "--path", p, *BASE, "--depth", "12", "--json", path("step.json"))
        self.assertEqual(rc, 1, err + out)
        (seg,) = load(path("step.json"))["colliding_segments"]
        self.assertEqual(seg["state"], "collides")
        self.assertTrue(seg["between_samples"])

    def test_requested_clearance_and_fail_on(self):
        work = plate_obj("cl_plate.obj", 0.0)
        p = write("cl.csv", "x,y,z,a,b\n0,0,170,0,0\n10,0,170,0,0\n")  # tip 20 above the plate
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--clearance", "25", "--json",
                           path("cl.json"))
        self.assertEqual(rc, 0, err + out)
        j = load(path("cl.json"))
        self.assertEqual(j["verdict"], "clearance")
        self.assertEqual([pt["verdict"] for pt in j["points"]], ["clearance", "clearance"])
        self.assertEqual(j["segments"][0]["verdict"], "clearance")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--clearance", "25",
                           "--fail-on", "clearance")
        self.assertEqual(rc, 1, err + out)
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--clearance", "15",
                           "--fail-on", "clearance", "--json", path("cl15.json"))
        self.assertEqual(rc, 0, err + out)
        self.assertEqual(load(path("cl15.json"))["verdict"], "clear")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--fail-on", "nearly")
        self.assertEqual(rc, 2, err + out)
        self.assertIn("--fail-on", err)

    def test_joint_columns_by_name(self):
        # Issue #23, item 9: the header names the joints; "b,a,z,y,x" is not read as x..b. Analytic
        # clearance over a plate at z = 0: the rim's lowest point, 170 - 150 cos b - 5 sin b.
        import math
        work = plate_obj("name_plate.obj", 0.0)
        b = 10.0
        want = 170 - 150 * math.cos(math.radians(b)) - 5 * math.sin(math.radians(b))
        for name, text in (("xyzab.csv", "x,y,z,a,b\n0,0,170,0,%r\n" % b), ("bazyx.csv", "b,a,z,y,x\n%r,0,170,0,0\n" % b)):
            rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", write(name, text), *BASE, "--json",
                               path(name + ".json"))
            self.assertEqual(rc, 0, err + out)
            j = load(path(name + ".json"))
            self.assertAlmostEqual(j["points"][0]["clearance"], want, places=9)
            self.assertEqual(j["inputs"]["path"]["columns"], ["x", "y", "z", "a", "b"])

    def test_bad_path_and_robot_files_by_meaning(self):
        work = plate_obj("bm_plate.obj", 0.0)
        good = write("bm_good.csv", "x,y,z,a,b\n0,0,170,0,0\n")
        out_json = path("bm_out.json")

        def bad(robot, path_file, *expect):
            args = ["--workpiece", work, "--path", path_file, *BASE, "--json", out_json]
            if robot:
                args += ["--robot", robot]
            rc, out, err = run(*args)
            self.assertEqual(rc, 2, err + out)
            for e in expect:
                self.assertIn(e, err)
            self.assertFalse(os.path.exists(out_json), "a bad input must not write the report")

        bad(ROBOT, write("bm_q.csv", "x,y,z,a,q\n0,0,170,0,0\n"), "bm_q.csv:1", "column 5", "unknown column 'q'")
        bad(ROBOT, write("bm_miss.csv", "x,y,z,a\n0,0,170,0\n"), "bm_miss.csv:1", "missing column b")
        joints = '"joints": [{"name": "q", "type": "revolute", "a": 0, "alpha": 0, "d": 0, "theta": 0}]'
        tool = '"tool": {"tip": [0, 0, 10], "axis": [0, 0, -1]}'  # 10 above the plate, pointing down
        q_path = write("bm_q1.csv", "q\n0\n")
        scaled = write("bm_scaled.json", '{\n"base": [2,0,0,0, 0,2,0,0, 0,0,2,0],\n%s,\n%s}\n' % (joints, tool))
        bad(scaled, q_path, "bm_scaled.json:2", "base: not a rigid transform")
        typo = write("bm_typo.json", '{\n"bsae": [1,0,0,0, 0,1,0,0, 0,0,1,0],\n%s,\n%s}\n' % (joints, tool))
        bad(typo, q_path, "bm_typo.json:2", "bsae: unknown key")
        metres = write("bm_m.json", '{\n"units": "m",\n%s,\n%s}\n' % (joints, tool))
        bad(metres, q_path, "bm_m.json:2", "units: 'm'")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", good, *BASE, "--units", "in", "--json",
                           out_json)
        self.assertEqual(rc, 2, err + out)
        self.assertIn("--units in", err)
        self.assertFalse(os.path.exists(out_json))
        ok = write("bm_ok.json", '{\n"units": "mm",\n%s,\n%s}\n' % (joints, tool))
        rc, out, err = run("--workpiece", work, "--path", q_path, "--robot", ok, *BASE)
        self.assertEqual(rc, 0, err + out)

    def test_bad_input_keeps_existing_output(self):
        work = plate_obj("plate6.obj", 0.0)
        keep = write("keep.json", "previous\n")
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", write("k.csv", "x,y,z,a,b\n1,2\n"), *BASE,
                           "--json", keep)
        self.assertEqual(rc, 2)
        self.assertEqual(text(keep), "previous\n")


PAPER_ROBOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples",
                           "probe_paper_machine.json")
HALF_SQRT3 = 0.86602540378443865


class SweepPaperMachine(unittest.TestCase):
    """Issue #28: the paper's 3P+2R machine (§3.1), pose paths through its inverse kinematics, and the
    motion between points: joint interpolation (the machine's own, default) or pose interpolation."""

    def _case(self):
        # Tip fixed at T = (100, 200, -300), probe horizontal, turned from a = -60 to a = +60: the
        # machine's joint-interpolated middle puts the tip at T + (15, 80, 0) (d1 = 30, d2 + l = 160);
        # a small triangle there is struck only by that motion (pose interpolation keeps the tip at T).
        c = (115.0, 278.0, -300.0)
        work = write("ik_tri.obj", "v %r %r %r\nv %r %r %r\nv %r %r %r\nf 1 2 3\n" % (
            c[0] - 1, c[1], c[2] - 1, c[0] + 1, c[1], c[2] - 1, c[0], c[1], c[2] + 1))
        p = write("ik_path.csv", "px,py,pz,ax,ay,az\n100,200,-300,%r,0.5,0\n100,200,-300,%r,0.5,0\n"
                  % (-HALF_SQRT3, HALF_SQRT3))
        return work, p

    def test_joint_interpolation_is_the_default_for_the_paper_machine(self):
        work, p = self._case()
        rc, out, err = run("--workpiece", work, "--robot", PAPER_ROBOT, "--path", p, *BASE, "--json", path("ik_j.json"))
        self.assertEqual(rc, 1, err + out)
        j = load(path("ik_j.json"))
        self.assertEqual(j["options"]["interpolate"], "joint")
        self.assertTrue(j["inputs"]["path"]["inverse_kinematics"])
        self.assertEqual(j["inputs"]["path"]["kind"], "poses")
        self.assertEqual(j["summary"]["colliding_points"], 0)
        self.assertEqual(j["summary"]["colliding_segments"], 1)
        self.assertAlmostEqual(j["points"][0]["joints"][3], -60.0, places=9)
        self.assertAlmostEqual(j["points"][1]["joints"][3], 60.0, places=9)
        seg = j["colliding_segments"][0]
        self.assertTrue(any(a <= 0.5 <= b for a, b in seg["intervals"]), seg)
        # The same machine from --d1/--d2 (probe length from --probe-length).
        rc, out, err = run("--workpiece", work, "--d1", "30", "--d2", "120", "--path", p, *BASE, "--json",
                           path("ik_d.json"))
        self.assertEqual(rc, 1, err + out)
        self.assertEqual(load(path("ik_d.json"))["points"][1]["joints"], j["points"][1]["joints"])

    def test_pose_interpolation_on_request(self):
        work, p = self._case()
        rc, out, err = run("--workpiece", work, "--robot", PAPER_ROBOT, "--path", p, *BASE, "--interpolate", "pose",
                           "--json", path("ik_p.json"))
        self.assertEqual(rc, 0, err + out)
        j = load(path("ik_p.json"))
        self.assertEqual(j["options"]["interpolate"], "pose")
        self.assertEqual(j["summary"]["colliding_segments"], 0)
        # The same motion given as the machine's joint path, with --interpolate pose: also clear.
        q = write("ik_joints.csv", "x,y,z,a,b\n%r,%r,300,-60,0\n%r,%r,300,60,0\n" % (
            100 - 160 * -HALF_SQRT3 - 30 * 0.5, 200 - 160 * 0.5 - 30 * HALF_SQRT3,
            100 - 160 * HALF_SQRT3 - 30 * 0.5, 200 - 160 * 0.5 + 30 * HALF_SQRT3))
        rc, out, err = run("--workpiece", work, "--robot", PAPER_ROBOT, "--path", q, *BASE, "--interpolate", "pose")
        self.assertEqual(rc, 0, err + out)
        rc, out, err = run("--workpiece", work, "--robot", PAPER_ROBOT, "--path", q, *BASE)
        self.assertEqual(rc, 1, err + out)
        self.assertNotIn("joints", j["points"][0])

    def test_bad_input(self):
        work, p = self._case()
        far = write("ik_far.csv", "px,py,pz,ax,ay,az\n0,0,-300,0,1,0\n# comment\n0,0,-2500,0,1,0\n")
        cli_common.assert_input_error(
            self, ["sweep", "--workpiece", work, "--robot", PAPER_ROBOT, "--path", far, *BASE, "--json", path("ik_far.json")],
            ["ik_far.csv:4", "point 1", "not reachable", "joint z = 2500", "[-2000, 2000]"], [path("ik_far.json")])
        cli_common.assert_input_error(self, ["sweep", "--workpiece", work, "--path", p, *BASE, "--interpolate", "joint"],
                                      ["--interpolate joint", "no --robot"])
        # A robot without an analytic inverse (the pivot machine): --interpolate joint now goes through
        # the numerical inverse kinematics (SweepNumericalIk); the default stays pose interpolation.
        rc, out, err = run("--workpiece", work, "--robot", ROBOT, "--path", p, *BASE, "--interpolate", "joint",
                           "--json", path("pivot_j.json"))
        self.assertIn(rc, (0, 1), err + out)
        self.assertTrue(load(path("pivot_j.json"))["inputs"]["path"]["inverse_kinematics"])
        cli_common.assert_input_error(self, ["sweep", "--workpiece", work, "--robot", PAPER_ROBOT, "--path", p, *BASE,
                                             "--interpolate", "spline"], ["--interpolate", "spline"])
        cli_common.assert_input_error(self, ["sweep", "--workpiece", work, "--robot", PAPER_ROBOT, "--d1", "30", "--path", p,
                                             *BASE], ["--d1/--d2", "not both"])
        cli_common.assert_input_error(self, ["sweep", "--workpiece", work, "--d2", "-5", "--path", p, *BASE], ["--d2"])


class SweepNumericalIk(unittest.TestCase):
    """Issue #28: `--interpolate joint` with a DH 6-axis arm (no analytic inverse): the pose path goes
    through the numerical inverse kinematics; the joints reported put the tool at every pose by this
    test's own DH composition (Rz Tz Tx Rx written out here); the default stays pose interpolation."""

    D = [89.159, 0, 0, 109.15, 94.65, 82.3]
    A = [0, -425, -392.25, 0, 0, 0]
    ALPHA = [90, 0, 0, 90, -90, 0]

    def fk(self, q):
        import math
        m = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]
        for d, a, al, th in zip(self.D, self.A, self.ALPHA, q):
            t, al = math.radians(th), math.radians(al)
            ct, st, ca, sa = math.cos(t), math.sin(t), math.cos(al), math.sin(al)
            T = [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]]
            m = [[sum(m[i][k] * T[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
        tip = [m[i][0] * 0 + m[i][1] * 0 + m[i][2] * 150 + m[i][3] for i in range(3)]
        return tip, [m[i][2] for i in range(3)]

    def test_ur5_dh_pose_path(self):
        import json
        joints = [{"name": "q%d" % (i + 1), "type": "revolute", "a": self.A[i], "alpha": self.ALPHA[i], "d": self.D[i],
                   "theta": 0, "min": -360, "max": 360} for i in range(6)]
        robot = write("ur5_dh.json", json.dumps({"name": "ur5-dh", "units": "mm", "joints": joints,
                                                 "tool": {"tip": [0, 0, 150], "axis": [0, 0, 1]}}))
        poses = [self.fk(q) for q in ([10, -80, 90, -100, -90, 0], [14, -78, 88, -100, -90, 0], [18, -76, 86, -100, -90, 0])]
        p = write("ur5_poses.csv", "px,py,pz,ax,ay,az\n" + "".join(
            ",".join("%.17g" % v for v in t + a) + "\n" for t, a in poses))
        work = plate_obj("ur5_plate.obj", -2000.0)
        rc, out, err = run("--workpiece", work, "--robot", robot, "--path", p, *BASE, "--interpolate", "joint",
                           "--json", path("ur5_j.json"))
        self.assertEqual(rc, 0, err + out)
        j = load(path("ur5_j.json"))
        self.assertEqual(j["options"]["interpolate"], "joint")
        self.assertTrue(j["inputs"]["path"]["inverse_kinematics"])
        for pt, (t, a) in zip(j["points"], poses):
            tip, axis = self.fk(pt["joints"])
            self.assertLess(max(abs(x - y) for x, y in zip(tip, t)), 1e-9)
            self.assertLess(max(abs(x - y) for x, y in zip(axis, a)), 1e-9)
        rc, out, err = run("--workpiece", work, "--robot", robot, "--path", p, *BASE, "--json", path("ur5_p.json"))
        self.assertEqual(rc, 0, err + out)
        self.assertEqual(load(path("ur5_p.json"))["options"]["interpolate"], "pose")
        far = write("ur5_far.csv", "px,py,pz,ax,ay,az\n0,0,5000,0,0,1\n")
        cli_common.assert_input_error(self, ["sweep", "--workpiece", work, "--robot", robot, "--path", far, *BASE,
                                             "--interpolate", "joint"], ["ur5_far.csv:2:", "unreachable"])


class SweepPaperLevels(unittest.TestCase):
    """Issue #28: --paper-levels runs the paper's three levels as written (§3.2-3.4) beside the exact test
    and reports where they disagree; the exact test decides the verdict."""

    def test_false_positive_reported(self):
        # A clear triangle that all three of the paper's projections (edge 0, fixed diameter) call
        # overlapping with the probe cylinder (0,0,0)-(0,0,2), r = 1 (test_paper_tests.cpp).
        work = write("fp_tri.obj", "v -0.41762788177630833 -0.8210775298506976 2.0431113483579426\n"
                     "v -0.5255325554798489 -0.11186297107474368 3.2267138360446035\n"
                     "v -1.0452788651563281 -2.71650785719231 1.850198368577664\nf 1 2 3\n")
        p = write("fp_path.csv", "px,py,pz,ax,ay,az\n0,0,0,0,0,-1\n0,0,-5,0,0,-1\n")
        rc, out, err = run("--workpiece", work, "--path", p, "--probe-radius", "1", "--probe-length", "2",
                           "--paper-levels", "--json", path("fp.json"))
        self.assertEqual(rc, 0, err + out)  # the exact test decides: clear
        j = load(path("fp.json"))
        self.assertEqual(j["summary"]["colliding_points"], 0)
        self.assertEqual(j["summary"]["paper_levels"], {"colliding_points": 1, "false_positives": 1,
                                                        "false_negatives": 0})
        self.assertTrue(j["points"][0]["paper"]["false_positive"])
        self.assertEqual(j["points"][0]["paper"]["hits"], [0])
        self.assertFalse(j["points"][1]["paper"]["collides"])
        self.assertIn("1 false positives", out)
        # Without the flag the report has no paper section.
        rc, out, err = run("--workpiece", work, "--path", p, "--probe-radius", "1", "--probe-length", "2",
                           "--json", path("fp2.json"))
        self.assertEqual(rc, 0, err + out)
        self.assertNotIn("paper_levels", load(path("fp2.json"))["summary"])


class SweepQuickStart(unittest.TestCase):
    """Issue #28: the quick start of docs/probe.md names only shipped files and runs as written."""

    def test_quick_start_runs_as_written(self):
        import re
        import shlex
        import subprocess
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
        with open(os.path.join(root, "docs", "probe.md"), encoding="utf-8") as f:
            doc = f.read()
        section = doc[doc.index("## Quick start"):]
        block = re.search(r"```(?:sh)?\n(.*?)```", section, re.S).group(1)
        args = shlex.split(block.replace("\\\n", " "), comments=True)  # (the fence says sh; a comment gives the exit status)
        self.assertEqual(args[:2], ["interfere", "sweep"])
        for a in args:
            if a.startswith("data/"):
                self.assertTrue(os.path.isfile(os.path.join(root, a)), a + " is not shipped")
        # Inputs from the source tree, outputs in the work directory (as written, run from the root).
        args = [os.path.join(os.path.abspath(root), a) if a.startswith("data/") else a for a in args[2:]]
        work = path("quick_start")
        os.makedirs(work, exist_ok=True)
        r = subprocess.run([cli_common.EXE, "sweep"] + args, cwd=work, capture_output=True, text=True)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn("COLLISION: 1 of 6 points collide (0 inside the workpiece), 2 colliding segments "
                      "(0 only between samples), 0 unresolved; min clearance 0 mm", r.stdout)
        j = load(os.path.join(work, "report.json"))
        self.assertEqual(j["colliding_points"], [3])
        self.assertEqual(j["options"]["interpolate"], "joint")
        self.assertTrue(os.path.isfile(os.path.join(work, "points.csv")))
        self.assertTrue(os.path.isfile(os.path.join(work, "hits.obj")))


if __name__ == "__main__":
    cli_common.main()
