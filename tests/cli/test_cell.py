#!/usr/bin/env python3
"""End-to-end tests of `interfere cell` (issue #28, deliverables 2 and 3): the URDF arm's forward
kinematics against an independent composition of homogeneous transforms (the URDF's XML read here
with xml.etree, rpy and axis-angle written out with numpy), per-point and per-pair reports, and bad
input (exit 2, naming file, line or element and field, nothing written).

Usage: test_cell.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Needs numpy (skipped without).
"""
import json
import math
import os
import random
import shutil
import sys
import unittest
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, write_text as write, read_csv as table  # noqa: E402

try:
    import numpy as np
except ImportError:  # pragma: no cover
    np = None

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "probe")


def run(*args):
    return cli_common.run(*args, command=("cell",))


def copy_example():
    d = path("cell")
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(EXAMPLE, d, ignore=shutil.ignore_patterns("*.json.out", "cell_report.*", "*.pyc"))
    return d


def urdf_fk(urdf_file, q_by_name):
    """Link name -> 4x4 world <- link (mm), composing the URDF's joints by hand."""
    root = ET.parse(urdf_file).getroot()

    def rpy(r, p, y):
        cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
        return (np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]) @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
                @ np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]]))

    def rot(u, a):
        u = np.asarray(u, float) / np.linalg.norm(u)
        k = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
        return np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * (k @ k)

    joints = {j.find("parent").get("link"): j for j in root.findall("joint")}
    children = {j.find("child").get("link") for j in root.findall("joint")}
    link = [l.get("name") for l in root.findall("link") if l.get("name") not in children][0]
    frames = {link: np.eye(4)}
    while link in joints:
        j = joints[link]
        o = j.find("origin")
        xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
        r = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
        O = np.eye(4)
        O[:3, :3] = rpy(*r)
        O[:3, 3] = np.array(xyz) * 1000
        M = np.eye(4)
        if j.get("type") in ("revolute", "continuous"):
            M[:3, :3] = rot([float(v) for v in j.find("axis").get("xyz").split()], math.radians(q_by_name[j.get("name")]))
        elif j.get("type") == "prismatic":
            M[:3, 3] = np.array([float(v) for v in j.find("axis").get("xyz").split()]) * q_by_name[j.get("name")]
        child = j.find("child").get("link")
        frames[child] = frames[link] @ O @ M
        link = child
    return frames


@unittest.skipIf(np is None, "numpy not installed")
class CellForwardKinematics(unittest.TestCase):
    def test_link_poses_match_independent_composition(self):
        d = copy_example()
        # the UR5-type arm and the industrial arm (on a 300 mm pedestal: the cell's base pose)
        for cell, urdf, base_z in (("cell.json", "arm6r.urdf", 0.0), ("cell_industrial.json", "industrial_6r.urdf", 300.0)):
            with self.subTest(urdf=urdf):
                root = ET.parse(os.path.join(d, urdf)).getroot()
                movable = [j for j in root.findall("joint") if j.get("type") != "fixed"]
                names = [j.get("name") for j in movable]
                limits = [(math.degrees(float(j.find("limit").get("lower"))), math.degrees(float(j.find("limit").get("upper"))))
                          for j in movable]
                rng = random.Random(28)
                rows = [[rng.uniform(lo, hi) for lo, hi in limits] for _ in range(25)]
                order = [5, 0, 3, 1, 4, 2]  # columns in another order than the chain's: matched by name
                write(os.path.join(d, "random.csv"), ",".join(names[k] for k in order) + "\n" +
                      "".join(",".join("%.9f" % r[k] for k in order) + "\n" for r in rows))
                rc, out, err = run(os.path.join(d, cell), "--path", os.path.join(d, "random.csv"), "--poses",
                                   "--json", os.path.join(d, "random.json"))
                self.assertIn(rc, (0, 1), err)
                with open(os.path.join(d, "random.json")) as f:
                    report = json.load(f)
                self.assertEqual(len(report["points"]), len(rows))
                worst = 0.0
                base = np.eye(4)
                base[2, 3] = base_z
                for p, r in zip(report["points"], rows):
                    q = {n: float("%.9f" % v) for n, v in zip(names, r)}
                    self.assertEqual(set(p["joints"]), set(names))
                    for n in names:
                        self.assertAlmostEqual(p["joints"][n], q[n], places=9)
                    ref = {k: base @ m for k, m in urdf_fk(os.path.join(d, urdf), q).items()}
                    self.assertEqual(set(p["links"]), set(ref))
                    for link, m in p["links"].items():
                        got = np.array(m).reshape(3, 4)
                        worst = max(worst, float(np.abs(got - ref[link][:3, :]).max()))
                    tool = ref["tool0"]
                    tip = tool[:3, :3] @ np.array([0, 0, 130.0]) + tool[:3, 3]
                    self.assertLess(np.abs(np.array(p["tip"]) - tip).max(), 1e-9)
                    self.assertLess(np.abs(np.array(p["axis"]) - tool[:3, 2]).max(), 1e-12)
                self.assertLess(worst, 1e-9)  # mm (rotation entries: unitless), up to ~1e3 mm lengths

    def test_example_report_per_point_and_pair(self):
        d = copy_example()
        rc, out, err = run(os.path.join(d, "cell.json"), "--json", os.path.join(d, "r.json"), "--csv", os.path.join(d, "r.csv"))
        self.assertEqual(rc, 1, out + err)
        with open(os.path.join(d, "r.json")) as f:
            r = json.load(f)
        colliding = [p["index"] for p in r["points"] if p["verdict"] == "clash"]
        self.assertEqual(colliding, [5, 6, 7, 12, 13, 14])
        pairs = {(p["a"], p["b"]): p["points"] for p in r["pairs"]}
        self.assertEqual(pairs, {("probe", "workpiece"): [5, 6, 7], ("fixture:clamp", "holder"): [12, 13, 14]})
        self.assertEqual([t["name"] for t in r["tests"]], ["tool", "arm", "self"])
        # 6 link joints; probe and holder against wrist_3 (their mount); probe against holder
        self.assertEqual(len(r["tests"][2]["suppressed"]), 6 + 2 + 1)
        rows = table(os.path.join(d, "r.csv"))
        self.assertEqual(len(rows), 15)
        self.assertEqual(rows[5]["a"], "probe")
        self.assertEqual(rows[5]["line"], "9")
        # depth only with --depth; the same points and pairs, every clashing pair of the (closed) probe
        # and holder with a depth bound
        self.assertFalse(any("depth" in q for p in r["points"] for q in p.get("pairs", [])))
        rc, out, err = run(os.path.join(d, "cell.json"), "--depth", "--json", os.path.join(d, "rd.json"))
        self.assertEqual(rc, 1, out + err)
        with open(os.path.join(d, "rd.json")) as f:
            rd = json.load(f)
        self.assertEqual([p["index"] for p in rd["points"] if p["verdict"] == "clash"], colliding)
        found = [q for p in rd["points"] for q in p.get("pairs", []) if q["verdict"] == "clash"]
        self.assertTrue(found)
        for q in found:
            self.assertGreater(q["depth_bound"], 0, q)
            self.assertGreaterEqual(q["depth_bound"], q["depth"], q)


class CellContinuous(unittest.TestCase):
    def test_segments_proven_clear_or_colliding(self):
        d = copy_example()
        rc, out, err = run(os.path.join(d, "cell.json"), "--continuous", "--json", os.path.join(d, "c.json"))
        self.assertEqual(rc, 1, out + err)
        self.assertIn("7 of 14 segments collide, 0 unresolved", out)
        with open(os.path.join(d, "c.json")) as f:
            r = json.load(f)
        segs = r["between_points"]["segments"]
        self.assertEqual([s["from"] for s in segs if s["state"] == "collides"], [4, 5, 6, 7, 11, 12, 13])
        self.assertEqual([s["state"] for s in segs if s["from"] in (0, 1, 2, 3, 8, 9, 10)], ["clear"] * 7)
        s5 = [s for s in segs if s["from"] == 5][0]
        self.assertEqual([(p["a"], p["b"]) for p in s5["pairs"]], [("probe", "workpiece")])
        self.assertTrue(0 < s5["t"] < 1)
        self.assertEqual(r["summary"]["colliding_between"], 7)

    def test_between_only_collision(self):
        d = copy_example()
        with open(os.path.join(d, "path.csv")) as f:
            lines = [l for l in f if not l.startswith("#")]
        write(os.path.join(d, "jump.csv"), lines[0] + lines[5] + lines[9])  # x = 450 and 550: over the rib
        rc, out, err = run(os.path.join(d, "cell.json"), "--path", os.path.join(d, "jump.csv"))
        self.assertEqual(rc, 0, out + err)  # both points clear
        rc, out, err = run(os.path.join(d, "cell.json"), "--path", os.path.join(d, "jump.csv"), "--continuous")
        self.assertEqual(rc, 1, out + err)
        self.assertIn("0 of 2 path points collide", out)
        self.assertIn("1 of 1 segments collide", out)


class CellReplay(unittest.TestCase):
    def test_pvd_series_marks_the_colliding_points(self):
        d = copy_example()
        pvd = os.path.join(d, "replay.pvd")
        rc, out, err = run(os.path.join(d, "cell.json"), "--pvd", pvd, "--html", os.path.join(d, "replay.html"))
        self.assertEqual(rc, 1, out + err)
        steps = ET.parse(pvd).getroot().findall("./Collection/DataSet")
        self.assertEqual(sorted({float(s.get("timestep")) for s in steps}), [float(i) for i in range(15)])
        try:
            import vtk
            from vtk.util.numpy_support import vtk_to_numpy
        except ImportError:
            self.skipTest("no VTK to read the series back")
        reader = vtk.vtkXMLPolyDataReader()
        with_clash = []
        for s in steps:
            if s.get("name") != "clashes":
                continue
            reader.SetFileName(os.path.join(d, s.get("file")))
            reader.Update()
            if reader.GetOutput().GetNumberOfCells():
                with_clash.append(int(float(s.get("timestep"))))
        self.assertEqual(with_clash, [5, 6, 7, 12, 13, 14])
        reader.SetFileName(os.path.join(d, [s.get("file") for s in steps if s.get("name") == "bodies"][12]))
        reader.Update()
        ids = reader.GetOutput().GetFieldData().GetAbstractArray("body_ids")
        self.assertIn("holder", [ids.GetValue(i) for i in range(ids.GetNumberOfValues())])
        self.assertGreater(reader.GetOutput().GetNumberOfCells(), 600)


@unittest.skipIf(np is None, "numpy not installed")
class CellPosePath(unittest.TestCase):
    """`interfere cell --pose-path` (numerical inverse kinematics, robot/ik.h): the solved joints
    (--write-joints) put the tool at every pose by this file's own URDF composition (urdf_fk)."""

    def test_random_poses_reached_on_both_arms(self):
        d = copy_example()
        for cell, urdf, base_z in (("cell.json", "arm6r.urdf", 0.0), ("cell_industrial.json", "industrial_6r.urdf", 300.0)):
            with self.subTest(urdf=urdf):
                root = ET.parse(os.path.join(d, urdf)).getroot()
                movable = [j for j in root.findall("joint") if j.get("type") != "fixed"]
                names = [j.get("name") for j in movable]
                limits = [(math.degrees(float(j.find("limit").get("lower"))), math.degrees(float(j.find("limit").get("upper"))))
                          for j in movable]
                rng = random.Random(7)
                base = np.eye(4)
                base[2, 3] = base_z
                poses = []
                for _ in range(12):
                    q = {n: rng.uniform(max(lo, -180), min(hi, 180)) for n, (lo, hi) in zip(names, limits)}
                    tool = base @ urdf_fk(os.path.join(d, urdf), q)["tool0"]
                    poses.append((tool[:3, :3] @ np.array([0, 0, 130.0]) + tool[:3, 3], tool[:3, 2]))
                write(os.path.join(d, "poses.csv"), "# random poses\npx,py,pz,ax,ay,az\n" +
                      "".join(",".join("%.17g" % v for v in [*t, *a]) + "\n" for t, a in poses))
                joints = os.path.join(d, "solved.csv")
                rc, out, err = run(os.path.join(d, cell), "--pose-path", os.path.join(d, "poses.csv"),
                                   "--write-joints", joints, "--json", os.path.join(d, "poses.json"))
                self.assertIn(rc, (0, 1), err)
                with open(joints) as f:  # a comment line, the header, one row per point
                    lines = [l.strip().split(",") for l in f if not l.startswith("#")]
                rows = [dict(zip(lines[0], r)) for r in lines[1:]]
                self.assertEqual(len(rows), len(poses))
                for row, (t, a) in zip(rows, poses):
                    q = {n: float(row[n]) for n in names}
                    for n, (lo, hi) in zip(names, limits):
                        self.assertTrue(lo <= q[n] <= hi, (n, q[n]))
                    tool = base @ urdf_fk(os.path.join(d, urdf), q)["tool0"]
                    tip = tool[:3, :3] @ np.array([0, 0, 130.0]) + tool[:3, 3]
                    self.assertLess(np.linalg.norm(tip - t), 1e-9)
                    self.assertLess(np.linalg.norm(np.cross(tool[:3, 2], a)), 1e-9)
                    self.assertGreater(float(np.dot(tool[:3, 2], a)), 0)
                with open(os.path.join(d, "poses.json")) as f:
                    r = json.load(f)
                self.assertEqual(len(r["ik"]["points"]), len(poses))
                self.assertEqual([p["line"] for p in r["points"]], list(range(3, 3 + len(poses))))

    def test_example_line_from_the_shipped_branch(self):
        # The shipped pose path of the probe-only sweep, from the branch of path.csv's first row:
        # the same six colliding points as the joint path, each point seeded by the previous one.
        d = copy_example()
        rc, out, err = run(os.path.join(d, "cell.json"), "--pose-path", os.path.join(d, "paper_path.csv"),
                           "--ik-start=-18,-93,141,-138,-90,162", "--json", os.path.join(d, "pp.json"))
        self.assertEqual(rc, 1, out + err)
        with open(os.path.join(d, "pp.json")) as f:
            r = json.load(f)
        self.assertEqual([p["index"] for p in r["points"] if p["verdict"] == "clash"], [5, 6, 7, 12, 13, 14])
        self.assertEqual(r["ik"]["branch_changes"], 0)
        self.assertEqual([p["seed"] for p in r["ik"]["points"]], ["start"] + ["previous"] * 14)
        self.assertLess(max(p["jump"] for p in r["ik"]["points"]), 10)
        for p in r["points"]:
            self.assertLess(abs(p["tip"][2] - 10), 1e-9)
            self.assertLess(abs(p["axis"][2] + 1), 1e-12)

    def test_collision_free_first_branch(self):
        # --ik-start collision-free (issue #28): the first point solved from every seed, the first
        # solution clear of everything used as the start; without it the first converging seed
        # ("home") puts the elbow through the plate.
        d = copy_example()
        rc, out, err = run(os.path.join(d, "cell.json"), "--pose-path", os.path.join(d, "paper_path.csv"),
                           "--ik-start", "collision-free", "--json", os.path.join(d, "cf.json"))
        self.assertIn(rc, (0, 1), out + err)
        with open(os.path.join(d, "cf.json")) as f:
            r = json.load(f)
        fb = r["ik"]["first_branch"]
        self.assertEqual(fb["rule"], "collision-free")
        self.assertTrue(fb["collision_free"])
        self.assertGreaterEqual(fb["solutions_checked"], 2)
        self.assertGreaterEqual(fb["solutions_colliding"], 1)
        self.assertEqual(r["points"][0]["verdict"], "clear")
        self.assertEqual(r["ik"]["points"][0]["seed"], "start")
        rc, out, err = run(os.path.join(d, "cell.json"), "--pose-path", os.path.join(d, "paper_path.csv"),
                           "--json", os.path.join(d, "home.json"))
        with open(os.path.join(d, "home.json")) as f:
            self.assertEqual(json.load(f)["points"][0]["verdict"], "clash")


class CellBadInput(unittest.TestCase):
    def bad(self, args, needles):
        d = path("cell")
        out = os.path.join(d, "bad.json")
        cli_common.assert_input_error(self, ["cell", *args, "--json", out], needles, outputs=[out])

    def test_unknown_and_missing_columns_and_limits(self):
        d = copy_example()
        cell = os.path.join(d, "cell.json")
        write(os.path.join(d, "p1.csv"), "shoulder_pan,shoulder_lift,elbow,wrist_1,wrist_2,wrist_9\n0,0,0,0,0,0\n")
        self.bad([cell, "--path", os.path.join(d, "p1.csv")], ["p1.csv:1:", "column 6 'wrist_9'", "not a movable joint"])
        write(os.path.join(d, "p2.csv"), "shoulder_pan,shoulder_lift,elbow,wrist_1,wrist_2\n0,0,0,0,0\n")
        self.bad([cell, "--path", os.path.join(d, "p2.csv")], ["p2.csv:1:", "joint 'wrist_3' has no column"])
        write(os.path.join(d, "p3.csv"), "shoulder_pan,shoulder_lift,elbow,wrist_1,wrist_2,wrist_3\n0,0,0,0,0,0\n0,0,400,0,0,0\n")
        self.bad([cell, "--path", os.path.join(d, "p3.csv")], ["p3.csv:3:", "'elbow'", "outside the joint's limits"])

    def test_pose_path_unreachable_and_bad_start(self):
        d = copy_example()
        cell = os.path.join(d, "cell.json")
        write(os.path.join(d, "far.csv"), "px,py,pz,ax,ay,az\n400,0,10,0,0,-1\n# too far\n9000,0,10,0,0,-1\n")
        self.bad([cell, "--pose-path", os.path.join(d, "far.csv")], ["far.csv:4:", "point 1", "unreachable"])
        self.bad([cell, "--pose-path", os.path.join(d, "paper_path.csv"), "--ik-start", "0,0,0"],
                 ["--ik-start", "3 values", "6 movable joints"])
        self.bad([cell, "--pose-path", os.path.join(d, "path.csv")], ["path.csv:3:", "px,py,pz,ax,ay,az"])
        with open(os.path.join(d, "industrial_6r.urdf")) as f:
            write(os.path.join(d, "tight.urdf"), f.read().replace('lower="-1.919860000" upper="1.919860000"',
                                                                   'lower="-0.1" upper="0.1"'))
        with open(os.path.join(d, "cell_industrial.json")) as f:
            c = json.load(f)
        c["robot"]["urdf"] = "tight.urdf"
        write(os.path.join(d, "tight.json"), json.dumps(c))
        write(os.path.join(d, "one.csv"), "px,py,pz,ax,ay,az\n350,0,10,0,0,-1\n")
        self.bad([os.path.join(d, "tight.json"), "--pose-path", os.path.join(d, "one.csv")],
                 ["one.csv:2:", "point 0", "outside its limits"])

    def test_bad_urdf(self):
        d = copy_example()
        with open(os.path.join(d, "arm6r.urdf")) as f:
            urdf = f.read()
        write(os.path.join(d, "screw.urdf"), urdf.replace('name="elbow" type="revolute"', 'name="elbow" type="screw"'))
        write(os.path.join(d, "nomesh.urdf"), urdf.replace("meshes/forearm_link.obj", "meshes/gone.obj"))
        branch = urdf.replace("</robot>", '<link name="extra"/><joint name="side" type="fixed"><parent link="upper_arm_link"/>'
                                          '<child link="extra"/></joint></robot>')
        write(os.path.join(d, "branch.urdf"), branch)
        for name, needles in [("screw.urdf", ["screw.urdf", "elbow", "screw"]),
                              ("nomesh.urdf", ["nomesh.urdf", "link 'forearm_link'", "meshes/gone.obj", "not found"]),
                              ("branch.urdf", ["branch.urdf", "link 'upper_arm_link'", "side", "serial"])]:
            with open(os.path.join(d, "cell.json")) as f:
                cell = json.load(f)
            cell["robot"]["urdf"] = name
            write(os.path.join(d, "c_" + name + ".json"), json.dumps(cell))
            self.bad([os.path.join(d, "c_" + name + ".json")], needles)

    def test_bad_cell_fields(self):
        d = copy_example()
        with open(os.path.join(d, "cell.json")) as f:
            cell = json.load(f)
        cell["tool"]["probe_radius"] = -1
        write(os.path.join(d, "neg.json"), json.dumps(cell, indent=1))
        self.bad([os.path.join(d, "neg.json")], ["neg.json:", "tool.probe_radius: must be > 0"])


if __name__ == "__main__":
    cli_common.main()
