#!/usr/bin/env python3
"""End-to-end tests of --glb, --pvd and --html on every command (issue #25): each command's picture
read back by the independent readers of view_readers.py and checked against what the command's own
outputs (JSON report, CSV tables, written meshes) or the inputs' coordinates say, not against the
viewer document code. The FE series has its own file (test_fem_view.py).

Usage: test_views.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import csv
import json
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import load_json, path, run, write_text  # noqa: E402
from view_readers import read_glb, read_pvd, read_vtp  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "data", "examples")
DATA = os.path.join(HERE, "data")
ROBOT = os.path.join(EXAMPLES, "probe_5axis.json")
NO_VIEWER = "this build of interfere has no HTML viewer"
NO_CAD = "needs interfere built with OpenCASCADE"


def box_obj(name, lo, hi):
    """A closed, outward box [lo, hi] as an OBJ work file (12 triangles)."""
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    lines = ["v %r %r %r" % p for p in v]
    for a, b, c, d in quads:
        lines.append("f %d %d %d" % (a + 1, b + 1, c + 1))
        lines.append("f %d %d %d" % (a + 1, c + 1, d + 1))
    return write_text(name, "\n".join(lines) + "\n")


def nodes_under(doc, group):
    """The nodes that are children of the node named `group` (none when there is no such group)."""
    groups = [n for n in doc["nodes"] if n.get("name") == group]
    assert len(groups) <= 1, groups
    return [doc["nodes"][i] for g in groups for i in g.get("children", [])]


def scene_extras(doc):
    return doc["scenes"][doc.get("scene", 0)]["extras"]


def overlap(a, b):
    """Box of the intersection of two boxes (lo, hi), or None."""
    lo = [max(a[0][k], b[0][k]) for k in range(3)]
    hi = [min(a[1][k], b[1][k]) for k in range(3)]
    return (lo, hi) if all(lo[k] <= hi[k] for k in range(3)) else None


class Views(unittest.TestCase):
    def run_ok(self, *args, codes=(0, 1)):
        code, out, err = run(*args)
        self.assertIn(code, codes, "exit %d: %s %s" % (code, out, err))
        return code, out, err

    def test_scene_clash_picture_matches_the_report(self):
        a = box_obj("va.obj", (0, 0, 0), (10, 10, 10))
        b = box_obj("vb.obj", (8, 2, 2), (18, 8, 8))  # crosses a
        c = box_obj("vc.obj", (40, 0, 0), (50, 10, 10))  # apart
        code, out, err = self.run_ok("clash", a, b, c, "--json", path("vs.json"), "--glb", path("vs.glb"),
                                     "--pvd", path("vs.pvd"))
        self.assertEqual(code, 1, out + err)
        report = load_json("vs.json")
        doc, _ = read_glb(path("vs.glb"))
        bodies = nodes_under(doc, "bodies")
        self.assertEqual(sorted(n["name"] for n in bodies), ["va", "vb", "vc"])
        clashes = nodes_under(doc, "clashes")
        self.assertEqual(sorted(n["name"] for n in clashes), sorted(c["id"] for c in report["clashes"]))
        for n in clashes:
            self.assertEqual(n["extras"]["verdict"], "clash")
        self.assertEqual(scene_extras(doc)["verdict"], report["verdict"])
        # ParaView: one static step; every clash-region triangle of the series meets the boxes' overlap
        ((t, _, name, f), (_, _, name2, f2)) = read_pvd(path("vs.pvd"))
        self.assertEqual((t, name, name2), (0.0, "bodies", "clashes"))
        base = os.path.dirname(path("vs.pvd"))
        bodies_vtp = read_vtp(os.path.join(base, f))
        self.assertEqual(bodies_vtp["polys"], 36)
        self.assertEqual(sorted(set(bodies_vtp["cell"]["body"])), [0, 1, 2])
        # clash flags: only on the triangles of a and b, none on c
        flags = bodies_vtp["cell"]["clash"]
        by_body = {k: [flags[i] for i in range(36) if bodies_vtp["cell"]["body"][i] == k] for k in range(3)}
        self.assertGreater(sum(by_body[0]), 0)
        self.assertGreater(sum(by_body[1]), 0)
        self.assertEqual(sum(by_body[2]), 0)
        clash_vtp = read_vtp(os.path.join(base, f2))
        box = overlap(((0, 0, 0), (10, 10, 10)), ((8, 2, 2), (18, 8, 8)))
        self.assertGreater(clash_vtp["polys"], 0)
        for tri in clash_vtp["poly_points"]:
            pts = [clash_vtp["xyz"][i] for i in tri]
            lo = [min(p[k] for p in pts) for k in range(3)]
            hi = [max(p[k] for p in pts) for k in range(3)]
            self.assertIsNotNone(overlap((lo, hi), box), pts)

    def test_two_part_clash_has_its_curves_as_lines(self):
        plate, pin = os.path.join(EXAMPLES, "plate.stl"), os.path.join(EXAMPLES, "pin.obj")
        code, out, err = self.run_ok("clash", "--scene", os.path.join(EXAMPLES, "scene.json"), "--json", path("tp.json"),
                                     "--glb", path("tp.glb"))
        self.assertEqual(code, 1, out + err)
        doc, _ = read_glb(path("tp.glb"))
        self.assertEqual(len(nodes_under(doc, "bodies")), 2)
        report = load_json("tp.json")
        clashes = nodes_under(doc, "clashes")
        self.assertEqual(len(clashes), len(report["clashes"]))
        modes = []
        for n in clashes:
            for i in n.get("children", []):
                child = doc["nodes"][i]
                if "mesh" in child:
                    modes += [p.get("mode", 4) for p in doc["meshes"][child["mesh"]]["primitives"]]
        self.assertIn(1, modes)  # intersection curves as LINES
        self.assertIn(4, modes)  # the region as TRIANGLES
        self.assertTrue(plate and pin)

    def test_bearing_frames_and_rows_follow_its_csv(self):
        code, out, err = self.run_ok("bearing", "--pairs", "4", "--frames", "5", "--gap", "-0.2", "--out", path("br.csv"),
                                     "--glb", path("br.glb"), "--pvd", path("br.pvd"))
        self.assertEqual(code, 1, out + err)
        with open(path("br.csv")) as f:
            rows = list(csv.DictReader(f))
        # runs of consecutive non-clear frames per pair, from the CSV
        runs = 0
        for k in range(4):
            v = [r["verdict"] for r in rows if int(r["pair"]) == k]
            runs += sum(1 for i in range(len(v)) if v[i] != "clear" and (i == 0 or v[i - 1] != v[i]))
        doc, _ = read_glb(path("br.glb"))
        self.assertEqual(len(nodes_under(doc, "bodies")), 8)
        self.assertEqual(len(nodes_under(doc, "clashes")), runs)
        frames = scene_extras(doc)["frames"]
        self.assertEqual(len(frames["labels"]), 5)
        for f in range(5):
            worst = "clash" if any(r["verdict"] == "clash" for r in rows if int(r["frame"]) == f) else None
            if worst:
                self.assertEqual(frames["verdicts"][f], worst)
        self.assertTrue(doc.get("animations"), "frames as an animation")
        steps = [d for d in read_pvd(path("br.pvd")) if d[2] == "bodies"]
        self.assertEqual([d[0] for d in steps], [0.0, 1.0, 2.0, 3.0, 4.0])

    def test_sweep_frames_are_the_path_points(self):
        lines = []
        n = 4
        for j in range(n + 1):
            for i in range(n + 1):
                lines.append("v %r %r 0.0" % (-500.0 + 1000.0 * i / n, -500.0 + 1000.0 * j / n))
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                lines.append("f %d %d %d" % (a, a + 1, a + n + 2))
                lines.append("f %d %d %d" % (a, a + n + 2, a + n + 1))
        plate = write_text("sw_plate.obj", "\n".join(lines) + "\n")
        p = write_text("sw_path.csv", "x,y,z,a,b\n0,0,170,0,0\n0,0,148,0,0\n0,0,170,0,0\n10,0,147,0,0\n")
        code, out, err = self.run_ok("sweep", "--workpiece", plate, "--robot", ROBOT, "--path", p, "--probe-radius", "5",
                                     "--probe-length", "40", "--csv", path("sw.csv"), "--glb", path("sw.glb"),
                                     "--pvd", path("sw.pvd"))
        self.assertEqual(code, 1, out + err)
        with open(path("sw.csv")) as f:
            rows = list(csv.DictReader(f))
        doc, _ = read_glb(path("sw.glb"))
        frames = scene_extras(doc)["frames"]
        self.assertEqual(len(frames["labels"]), 4)
        self.assertEqual([v == "clash" for v in frames["verdicts"]], [r["collides"] == "1" for r in rows])
        self.assertEqual(sorted(n["name"] for n in nodes_under(doc, "bodies")), sorted(["workpiece", "probe"]))
        steps = [d for d in read_pvd(path("sw.pvd")) if d[2] == "bodies"]
        self.assertEqual(len(steps), 4)

    def test_simplify_draws_the_simplified_mesh_it_wrote(self):
        pin = os.path.join(EXAMPLES, "pin.obj")
        self.run_ok("simplify", pin, path("sp.obj"), "--target", "60", "--glb", path("sp.glb"), codes=(0,))
        with open(path("sp.obj")) as f:
            written = sum(1 for line in f if line.startswith("f "))
        with open(pin) as f:
            original = sum(1 for line in f if line.startswith("f "))
        doc, binary = read_glb(path("sp.glb"))
        by_name = {n["name"]: n for n in nodes_under(doc, "bodies")}
        self.assertEqual(len(by_name), 2)
        (simp,) = [n for k, n in by_name.items() if "simplified" in k]
        (orig,) = [n for k, n in by_name.items() if "original" in k]
        self.assertFalse(orig["extras"]["visible"])

        def triangles(node):
            return sum(doc["accessors"][p["indices"]]["count"] // 3 for p in doc["meshes"][node["mesh"]]["primitives"])
        self.assertEqual(triangles(simp), written)
        self.assertEqual(triangles(orig), original)

    def test_features_colour_faces_and_mark_the_steps_faces(self):
        casing = os.path.join(EXAMPLES, "casing.step")
        process = os.path.join(EXAMPLES, "casing_process.json")
        code, out, err = run("features", casing, "--process", process, "--step", "P1", "--glb", path("ft.glb"),
                             "--json", path("ft.json"))
        if code == 2 and NO_CAD in err:
            self.skipTest("built without OpenCASCADE")
        self.assertEqual(code, 0, out + err)
        doc, _ = read_glb(path("ft.glb"))
        legend = [e["label"] for e in scene_extras(doc)["legend"]]
        report = load_json("ft.json")
        types = {f["type"] for p in report["parts"] for f in p["features"]}
        for t in types:
            self.assertIn(t, legend)
        self.assertIn("assembly-feature face (step P1)", legend)
        for n in nodes_under(doc, "bodies"):
            attrs = doc["meshes"][n["mesh"]]["primitives"][0]["attributes"]
            self.assertIn("COLOR_0", attrs)
        code, out, err = run("features", casing, "--process", process, "--step", "all", "--glb", path("ft_all.glb"))
        self.assertEqual(code, 2)
        self.assertIn("--step all", err)
        self.assertFalse(os.path.exists(path("ft_all.glb")))

    def test_assembly_clash_rows_are_its_pairs(self):
        asm = os.path.join(DATA, "assembly.step")
        code, out, err = run("assembly-clash", asm, "--clearance", "100", "--json", path("ac.json"), "--glb", path("ac.glb"))
        if code == 2 and NO_CAD in err:
            self.skipTest("built without OpenCASCADE")
        self.assertIn(code, (0, 1), out + err)
        report = load_json("ac.json")
        doc, _ = read_glb(path("ac.glb"))
        self.assertEqual(len(nodes_under(doc, "bodies")), len(report["instances"]))
        self.assertGreater(len(report["pairs"]), 0)
        rows = {n["name"]: n["extras"] for n in nodes_under(doc, "clashes")}
        self.assertEqual(len(rows), len(report["pairs"]))
        for p in report["pairs"]:
            row = rows["I%d_%d" % (p["a"], p["b"])]
            self.assertEqual(row["verdict"], p["verdict"])
            self.assertAlmostEqual(row["distance"], p["min_clearance"], places=9)

    def test_bad_view_outputs_are_refused_before_any_work(self):
        a = box_obj("ba.obj", (0, 0, 0), (1, 1, 1))
        b = box_obj("bb.obj", (2, 0, 0), (3, 1, 1))
        for flag, name in (("--glb", "x.stl"), ("--pvd", "x.vtu"), ("--html", "x.txt"), ("--glb", "nodir/x.glb")):
            code, out, err = run("clash", a, b, "--json", path("bad.json"), flag, path(name))
            self.assertEqual(code, 2, out + err)
            self.assertIn(flag, err)
            self.assertFalse(os.path.exists(path("bad.json")))
        code, out, err = run("clash", a, b, "--glb", a)  # an input
        self.assertEqual(code, 2)
        code, out, err = run("bearing", "--pairs", "2", "--frames", "2", "--view-budget", "10", "--glb", path("vb.glb"))
        self.assertEqual(code, 2)
        self.assertIn("--view-budget", err)

    def test_html_page_holds_the_report(self):
        a = box_obj("ha.obj", (0, 0, 0), (10, 10, 10))
        b = box_obj("hb.obj", (8, 2, 2), (18, 8, 8))
        code, out, err = run("clash", a, b, "--json", path("h.json"), "--html", path("h.html"))
        if code == 2 and NO_VIEWER in err:
            self.assertFalse(os.path.exists(path("h.json")))  # refused before any work
            self.skipTest("this build has no HTML viewer")
        self.assertEqual(code, 1, out + err)
        with open(path("h.html"), encoding="utf-8") as f:
            page = f.read()
        m = re.search(r'<script id="interfere-data" type="application/json">(.*?)</script>', page, re.S)
        self.assertIsNotNone(m)
        data = json.loads(m.group(1))
        self.assertEqual((data["schema"], data["schema_version"]), ("interfere.viewer", 1))
        self.assertEqual(sorted(c["id"] for c in data["clashes"]), sorted(c["id"] for c in load_json("h.json")["clashes"]))
        self.assertNotIn("http://", page.replace("http://www.w3.org", ""))  # nothing fetched from a network


if __name__ == "__main__":
    cli_common.main()
