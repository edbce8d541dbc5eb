#!/usr/bin/env python3
"""End-to-end tests of `interfere bearing --assembly` (issue #27): the shipped example, the CSV rows
and the JSON summary (schema_version 1) agreeing with each other, determinism across thread counts,
a motion file, and bad input (exit 2, the JSON path / file and line named, no output written).

Usage: test_bearing_assembly.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import json
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, read_csv, load_json as load, read_text as slurp, write_text  # noqa: E402
from view_readers import read_glb, read_pvd  # noqa: E402

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "bearing_axle.json")

COLUMNS = ["frame", "bearing", "kind", "a", "b", "distance", "interference", "ax", "ay", "az", "bx", "by", "bz",
           "solver", "path", "scar", "exact", "verdict", "two_sided", "scar_part"]

SMALL = {
    "frames": 3, "seed": 4, "clearance": 0.05,
    "motion": {"inner_deg_per_frame": 7, "max_tilt_deg": 0.1, "load": {"direction_deg": 270, "displacement": 0.08},
               "pocket_play": 1.3, "axial_play": 1.05},
    "scar": {"fraction": 0.25, "angle_width_deg": 90, "seed": 2},
    "bearings": [
        {"id": "cyl", "type": "cylindrical", "position": [0, 0, 0], "axis": [0, 0, 1],
         "inner_ring": {"bore_radius": 20, "raceway_radius": 30, "width": 30, "rib": {"height": 3, "width": 4}},
         "outer_ring": {"raceway_radius": 50.1, "outer_radius": 58, "width": 30},
         "rollers": {"count": 8, "radius": 10, "length": 20, "pitch_radius": 40.05, "radial_segments": 16,
                     "height_segments": 15},
         "cage": {"pocket_clearance": 0.25, "web_thickness": 6}},
        {"id": "tap", "type": "tapered", "position": [300, 0, 0], "axis": [1, 0, 0], "contact_angle_deg": 20,
         "cone": {"bore_radius": 25, "clearance": 0.02}, "cup": {"outer_radius": 75, "clearance": 0.02},
         "rollers": {"count": 10, "radius": 8, "top_radius": 9.5, "length": 30, "radial_segments": 16,
                     "height_segments": 15},
         "cage": {"pocket_clearance": 0.3, "web_thickness": 6}}]}


def run(*args):
    return cli_common.run(*args, command=("bearing",))


def write_png16(name, w, h, samples):
    """A 16-bit grayscale PNG (rows top first), written with zlib only."""
    import struct
    import zlib

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    raw = b"".join(b"\x00" + b"".join(struct.pack(">H", v) for v in samples[y * w:(y + 1) * w]) for y in range(h))
    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
    with open(path(name), "wb") as f:
        f.write(data)
    return path(name)


def small(name="small.json", **changes):
    d = json.loads(json.dumps(SMALL))
    d.update(changes)
    return write_text(name, json.dumps(d))


class BearingAssembly(unittest.TestCase):
    def test_example(self):
        rc, out, err = run("--assembly", EXAMPLE, "--frames", "1", "--out", path("ex.csv"), "--json", path("ex.json"))
        s = load("ex.json")
        self.assertEqual(rc, s["exit_status"], err)
        self.assertEqual(s["schema_version"], 1)
        self.assertEqual(s["mode"], "assembly")
        self.assertEqual(len(s["bearings"]), 4)
        self.assertEqual(s["frames"], 1)
        rows = read_csv("ex.csv")
        self.assertEqual(len(rows), s["pairs_per_frame"])
        self.assertEqual(s["parts"], sum(b["parts"] for b in s["bearings"]))
        self.assertEqual(s["pairs_per_frame"], sum(b["pairs"] for b in s["bearings"]))
        self.assertTrue(out.startswith(s["verdict"] + ":"), out)

    def test_rows_and_summary(self):
        rc, out, err = run("--assembly", small(), "--out", path("r.csv"), "--json", path("r.json"))
        s = load("r.json")
        self.assertEqual(rc, 1, err)  # the load presses rollers into the inner ring: clash
        self.assertEqual(s["verdict"], "clash")
        self.assertEqual(slurp("r.csv").split("\n", 1)[0].split(","), COLUMNS)
        rows = read_csv("r.csv")
        self.assertEqual(len(rows), 3 * s["pairs_per_frame"])
        self.assertEqual(s["results"]["rows"], len(rows))
        kinds = {r["kind"] for r in rows}
        self.assertEqual(kinds, {"roller-inner", "roller-outer", "roller-rib", "roller-cage", "roller-roller",
                                 "roller-cone", "roller-cup", "cage-inner", "cage-outer", "bearing-bearing"})
        # scarred rollers: their roller-outer / roller-cup rows measure the scarred mesh (scar 1)
        scarred = {r["a"] for r in rows if r["kind"] in ("roller-outer", "roller-cup") and r["scar"] == "1"}
        for r in rows:
            d = float(r["distance"])
            self.assertTrue(math.isfinite(d))
            self.assertEqual(float(r["interference"]), max(0.0, -d))
            for c in ("ax", "ay", "az", "bx", "by", "bz"):
                self.assertTrue(math.isfinite(float(r[c])))
            # which rows are two-sided S = min(s(A,B), s(B,A)) (issue #27): the roller pairs, the inner
            # raceways and cones always; the ring and web rows of intact rollers whenever they overlap
            # (ring_two_sided.h); one-sided: scarred rollers' overlapping ring/web rows, and cup/rib
            # clearances that are not the Euclidean distance
            if r["kind"] in ("cage-inner", "cage-outer", "bearing-bearing"):
                # structural rows (issue #27, item 2): a lower bound; clear here, nothing is displaced
                self.assertEqual((r["solver"], r["exact"], r["verdict"]), ("bound", "0", "clear"), r)
                self.assertGreater(d, 0)
            elif r["kind"] in ("roller-inner", "roller-roller", "roller-cone"):
                self.assertEqual(r["two_sided"], "1", r)
            elif d <= 0 and r["exact"] == "1" and r["a"] not in scarred:
                self.assertEqual(r["two_sided"], "1", r)
            elif d <= 0 and r["two_sided"] == "0":
                self.assertIn(r["a"], scarred, r)
        for v in ("clash", "contact", "clearance", "clear", "undecided"):
            self.assertEqual(s["results"]["verdicts"][v], sum(r["verdict"] == v for r in rows))
        dmin = min(float(r["distance"]) for r in rows)
        self.assertEqual(s["results"]["min_distance"], dmin)
        self.assertEqual(s["worst"]["distance"], dmin)
        self.assertEqual(s["results"]["scar_rows"], sum(r["scar"] == "1" for r in rows))
        self.assertGreater(s["results"]["scar_rows"], 0)
        self.assertEqual(len(s["frame_worst"]), 3)
        for f, w in enumerate(s["frame_worst"]):
            self.assertEqual(w["frame"], f)
            self.assertEqual(w["distance"], min(float(r["distance"]) for r in rows if int(r["frame"]) == f))
        self.assertEqual(s["bearings"][0]["scarred_rollers"], 2)
        self.assertEqual(s["bearings"][1]["scarred_rollers"], 2)  # tapered rollers carry scars too (issue #27)

    def test_threads_and_seed(self):
        run("--assembly", small(), "--threads", "1", "--out", path("t1.csv"))
        run("--assembly", small(), "--threads", "2", "--out", path("t2.csv"))
        self.assertEqual(slurp("t1.csv"), slurp("t2.csv"))
        run("--assembly", small(), "--seed", "99", "--frames", "1", "--out", path("t3.csv"))
        self.assertNotEqual(slurp("t1.csv").split("\n")[1:20], slurp("t3.csv").split("\n")[1:20])

    def test_motion_file(self):
        # every part still: its rest pose (body frame -> world) given for frame 0 only
        rest = {"cyl": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]}
        lines = ["frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz",
                 "0,cyl/inner," + ",".join(map(str, rest["cyl"])),
                 "1,cyl/inner,1,0,0,0,0,1,0,-0.2,0,0,1,0"]
        motion = write_text("m.csv", "\n".join(lines) + "\n")
        rc, out, err = run("--assembly", small(), "--motion", motion, "--out", path("m_rows.csv"), "--json",
                           path("m.json"))
        s = load("m.json")
        self.assertEqual(s["frames"], 2)
        self.assertEqual(s["motion"], motion)
        rows = read_csv("m_rows.csv")
        inner = [r for r in rows if r["kind"] == "roller-inner" and r["a"] == "cyl/roller6"]  # at 270 degrees
        self.assertEqual(len(inner), 2)
        # the inner ring moved 0.2 towards roller 6 in frame 1: 0.2 less clearance
        self.assertAlmostEqual(float(inner[0]["distance"]) - float(inner[1]["distance"]), 0.2, delta=1e-9)
        self.assertAlmostEqual(float(inner[0]["distance"]), 0.05, delta=1e-9)

    def test_views_follow_the_csv(self):
        rc, out, err = run("--assembly", small(), "--out", path("v.csv"), "--json", path("v.json"), "--glb",
                           path("v.glb"), "--pvd", path("v.pvd"))
        self.assertEqual(rc, 1, err)
        s = load("v.json")
        rows = read_csv("v.csv")
        # runs of consecutive non-clear frames per pair (a, b and its feature), from the CSV
        pairs = {}
        for r in rows:
            pairs.setdefault((r["a"], r["b"]), []).append(r["verdict"])
        runs = sum(1 for v in pairs.values() for i in range(len(v)) if v[i] != "clear" and (i == 0 or v[i - 1] != v[i]))
        doc, _ = read_glb(path("v.glb"))
        groups = [n for n in doc["nodes"] if n.get("name") in ("bodies", "clashes")]
        children = {g["name"]: g.get("children", []) for g in groups}
        self.assertEqual(len(children["bodies"]), s["parts"])
        self.assertEqual(len(children.get("clashes", [])), runs)
        extras = doc["scenes"][doc.get("scene", 0)]["extras"]
        self.assertEqual(len(extras["frames"]["labels"]), 3)
        for f in range(3):
            if any(r["verdict"] == "clash" for r in rows if int(r["frame"]) == f):
                self.assertEqual(extras["frames"]["verdicts"][f], "clash")
        steps = [d for d in read_pvd(path("v.pvd")) if d[2] == "bodies"]
        self.assertEqual([d[0] for d in steps], [0.0, 1.0, 2.0])

    def test_bad_input(self):
        outputs = [path("bad.csv"), path("bad.json")]
        bad = small("bad1.json", bearings=[dict(SMALL["bearings"][0], rollers=dict(SMALL["bearings"][0]["rollers"],
                                                                                      pitch_radius=45))])
        cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0], "--json", outputs[1]],
                                      ["bad1.json", "bearings[0].rollers.pitch_radius", "do not fit"], outputs)
        bad = small("bad2.json", bearings=[dict(SMALL["bearings"][0], cage={"pocket_clearance": -0.1,
                                                                           "web_thickness": 6})])
        cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0]],
                                      ["bearings[0].cage.pocket_clearance", "smaller than its roller"], outputs)
        bad = small("bad3.json", motion={"max_tilt_deg": 60})
        cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0]],
                                      ["motion.max_tilt_deg", "Eq. (1)"], outputs)
        bad = small("bad4.json", frame=3)
        cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0]],
                                      ["bad4.json", "frame: unknown key"], outputs)
        motion = write_text("bad.csv.in", "frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n"
                                          "0,cyl/roller42,1,0,0,0,0,1,0,0,0,0,1,0\n")
        cli_common.assert_input_error(self, ["bearing", "--assembly", small(), "--motion", motion, "--out", outputs[0]],
                                      ["bad.csv.in:2", "cyl/roller42"], outputs)
        cli_common.assert_input_error(self, ["bearing", "--motion", motion, "--out", outputs[0]],
                                      ["--motion needs --assembly"], outputs)
        cli_common.assert_input_error(self, ["bearing", "--assembly", small(), "--pairs", "3", "--out", outputs[0]],
                                      ["--assembly cannot be combined"], outputs)

    def test_raceway_scars(self):
        # issue #27: scars on the raceways (bearing_assembly: bearings[i].scars, raceway_scar.h): a
        # raised generated scar on the inner raceway, a CSV map (a pit) on the outer bore; the rows of
        # rollers in range use the scarred raceway solver and name the scarred ring in scar_part
        write_text("bore_pit.csv", "z\\angle_deg, -20, 0, 20\n5, 0, 0, 0\n15, 0, -0.03, 0\n25, 0, 0, 0\n")
        cyl = dict(SMALL["bearings"][0], scars=[
            {"part": "inner", "angle_center_deg": 0, "angle_width_deg": 120, "depth": 0.04, "raised": True,
             "seed": 3, "radial_segments": 256, "height_segments": 31},
            {"part": "outer", "map": "bore_pit.csv", "radial_segments": 256, "height_segments": 31}])
        f = small("raceway_scars.json", bearings=[cyl, SMALL["bearings"][1]], frames=4)
        rc, out, err = run("--assembly", f, "--out", path("rs.csv"), "--json", path("rs.json"))
        s = load("rs.json")
        self.assertEqual(rc, s["exit_status"], err)
        self.assertEqual(s["bearings"][0]["scarred_raceways"], ["cyl/inner", "cyl/outer"])
        self.assertEqual(s["bearings"][1]["scarred_raceways"], [])
        rows = read_csv(path("rs.csv"))
        self.assertEqual(list(rows[0].keys()), COLUMNS)
        race = [r for r in rows if r["kind"] in ("roller-inner", "roller-outer") and r["b"] in ("cyl/inner", "cyl/outer")
                and r["solver"] == "scarred" and r["scar_part"] == r["b"]]
        self.assertTrue(any(r["kind"] == "roller-inner" for r in race), "no inner raceway scar row")
        self.assertTrue(any(r["kind"] == "roller-outer" for r in race), "no outer raceway scar row")
        for r in rows:
            self.assertIn(r["scar_part"], ("-", r["a"], r["b"].split("#")[0]), r)
            self.assertEqual(r["scar_part"] != "-", r["scar"] == "1", r)
        # bad input: the wrong raceway for the type, an unknown key, a window off the raceway, a map row off it
        outputs = [path("bad.csv"), path("bad.json")]
        for name, scar, expect in [
                ("rs_bad1.json", {"part": "cone"}, ["bearings[0].scars[0].part", "inner"]),
                ("rs_bad2.json", {"part": "inner", "bogus": 1}, ["bearings[0].scars[0].bogus: unknown key"]),
                ("rs_bad3.json", {"part": "inner", "z_min": 10, "z_max": 31}, ["bearings[0].scars[0].z_max", "raceway"]),
                ("rs_bad4.json", {"part": "outer", "map": "bore_off.csv"}, ["bore_off.csv:3", "outside the outer raceway"])]:
            write_text("bore_off.csv", "z\\angle_deg, -20, 0, 20\n5, 0, 0, 0\n45, 0, -0.03, 0\n")
            bad = small(name, bearings=[dict(SMALL["bearings"][0], scars=[scar]), SMALL["bearings"][1]])
            cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0], "--json", outputs[1]],
                                          expect, outputs)

    def test_imported_roller_scars(self):
        # issue #27, item 2 (scars on any part, generated or imported): the top-level scar with map (CSV),
        # png (16-bit gray) or points puts one measured scar on every scarred roller of every bearing
        # (resampled onto each bearing's roller grid); their rows measure the mesh (scar 1 on the
        # roller-outer / roller-cup rows, the vertex maximum)
        write_text("roller_bump.csv", "z\\angle_deg, -45, 0, 45\n5, 0, 0, 0\n10, 0, 0.03, 0\n15, 0, 0, 0\n")
        write_png16("roller_bump.png", 5, 4, [0, 0, 0, 0, 0, 0, 1000, 3000, 1000, 0, 0, 1000, 3000, 1000, 0, 0, 0, 0, 0, 0])
        for name, scar in [("csv", {"fraction": 0.25, "map": "roller_bump.csv"}),
                           ("png", {"fraction": 0.25, "png": "roller_bump.png", "scale": 1e-5, "angle_center_deg": 0,
                                    "angle_width_deg": 90, "z_min": 5, "z_max": 15})]:
            f = small("roller_scar_%s.json" % name, scar=scar)
            rc, out, err = run("--assembly", f, "--out", path("rsi.csv"), "--json", path("rsi.json"))
            s = load("rsi.json")
            self.assertEqual(rc, s["exit_status"], err)
            self.assertEqual([b["scarred_rollers"] for b in s["bearings"]], [2, 2], name)  # a quarter of 8 and of 10
            rows = read_csv(path("rsi.csv"))
            scarred = {r["a"] for r in rows if r["kind"] in ("roller-outer", "roller-cup") and r["scar"] == "1"}
            self.assertEqual(len(scarred), 4, name)
        # bad input: generated-only keys with an import, two imports, a PNG without its scale, a file
        # that is not a PNG, a map through the roller's axis (the file and line)
        write_text("not.png", "not a png")
        write_text("roller_deep.csv", "z\\angle_deg, -45, 0, 45\n5, 0, 0, 0\n10, 0, -10.5, 0\n")
        outputs = [path("bad.csv"), path("bad.json")]
        for name, scar, expect in [
                ("rsi_bad1.json", {"fraction": 0.25, "map": "roller_bump.csv", "depth": 0.1}, ["scar.depth", "generated"]),
                ("rsi_bad2.json", {"fraction": 0.25, "map": "roller_bump.csv", "points": "p.xyz"}, ["scar", "exclude"]),
                ("rsi_bad3.json", {"fraction": 0.25, "png": "roller_bump.png"}, ["scar.scale: missing"]),
                ("rsi_bad4.json", {"fraction": 0.25, "png": "not.png", "scale": 1e-5}, ["not.png", "not a PNG"]),
                ("rsi_bad5.json", {"fraction": 0.25, "map": "roller_deep.csv"}, ["roller_deep.csv:3"])]:
            cli_common.assert_input_error(self, ["bearing", "--assembly", small(name, scar=scar), "--out", outputs[0],
                                                 "--json", outputs[1]], expect, outputs)

    def test_tapered_roller_scars(self):
        # issue #27: scar.fraction scars tapered rollers too; their cone and neighbour rows are the
        # scarred solver against the intact frustum (exact, or a two-sided bracket: exact 0 with a
        # verdict both ends agree on, else undecided), their cup rows the exact vertex maximum (one-sided)
        for raised in (False, True):
            name = "tap_scars_%d" % raised
            f = small(name + ".json", bearings=[SMALL["bearings"][1]],
                      scar={"fraction": 0.5, "angle_width_deg": 120, "seed": 2, "raised": raised})
            rc, out, err = run("--assembly", f, "--out", path(name + ".csv"), "--json", path(name + ".json.out"))
            s = load(name + ".json.out")
            self.assertEqual(rc, s["exit_status"], err)
            self.assertIn(rc, (0, 1), err)
            self.assertEqual(s["bearings"][0]["scarred_rollers"], 5)
            rows = read_csv(path(name + ".csv"))
            scarred = {r["a"] for r in rows if r["kind"] == "roller-cup" and r["scar"] == "1"}
            self.assertEqual(len(scarred), 5)
            cone = [r for r in rows if r["kind"] == "roller-cone" and r["a"] in scarred]
            self.assertEqual(len(cone), 5 * 3)
            for r in cone:
                self.assertEqual((r["solver"], r["scar"], r["scar_part"], r["two_sided"]), ("scarred", "1", r["a"], "1"), r)
                if r["exact"] == "0":  # a bracket: a verdict only where both ends agree
                    self.assertNotEqual(r["verdict"], "clear", r)
            pairs = [r for r in rows if r["kind"] == "roller-roller" and (r["a"] in scarred or r["b"] in scarred)]
            self.assertEqual(len(pairs), 10 * 3)  # every roller pair has one scarred roller (every other one)
            for r in pairs:
                self.assertEqual((r["solver"], r["scar"]), ("scarred", "1"), r)
                self.assertEqual(r["scar_part"], r["a"] if r["a"] in scarred else r["b"], r)
            for r in rows:
                if r["kind"] == "roller-cup" and r["a"] in scarred:
                    self.assertEqual(r["solver"], "vertex", r)
                    # two-sided only where certified (issue #27, scarred_two_sided.h): exact; an overlap's
                    # S, or apart the Euclidean distance, which the witness pair realises
                    if r["two_sided"] == "1":
                        self.assertEqual(r["exact"], "1", r)
                        if float(r["distance"]) > 0:
                            gap = math.dist([float(r[c]) for c in ("ax", "ay", "az")], [float(r[c]) for c in ("bx", "by", "bz")])
                            self.assertAlmostEqual(gap, float(r["distance"]), delta=1e-9 * 300, msg=r)
                self.assertTrue(math.isfinite(float(r["distance"])), r)
            self.assertEqual(s["results"]["scar_rows"], sum(r["scar"] == "1" for r in rows))
        # a scar deeper than the tapered rollers' small-end radius: exit 2 naming the parameter
        outputs = [path("tap_bad.csv"), path("tap_bad.json")]
        bad = small("tap_bad.json.in", bearings=[SMALL["bearings"][1]], scar={"fraction": 0.5, "depth": 8.5})
        cli_common.assert_input_error(self, ["bearing", "--assembly", bad, "--out", outputs[0], "--json", outputs[1]],
                                      ["depth"], outputs)


if __name__ == "__main__":
    cli_common.main()
