#!/usr/bin/env python3
"""End-to-end tests of `interfere bearing` with raised and imported scars (issue #27, deliverable 2):
--raised, --scar-map (a CSV grid generated here from an analytic bump), --scar-points, and bad input
(exit 2, the file and line named, nothing written). The rows are checked against the bump evaluated
here at the roller's vertices (an independent evaluation).

Usage: test_bearing_scars.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, read_csv, load_json as load, write_text  # noqa: E402


def run(*args):
    return cli_common.run(*args, command=("bearing",))


R_ROLLER, R_PARTNER, HEIGHT, N = 10.0, 30.0, 31.0, 32  # --vertices 32: 32 columns, 31 rings of 1 mm


def bump(angle_deg, z):
    """0.5 mm raised bump about (0 degrees, z 15), support radius 6 mm on the unrolled surface."""
    a = math.remainder(math.radians(angle_deg), 2 * math.pi)
    d2 = (R_ROLLER * a) ** 2 + (z - 15) ** 2
    return 0.5 * (1 - d2 / 36) ** 2 if d2 < 36 else 0.0


ANGLES = [-45 + 11.25 * k for k in range(9)]  # on the vertex columns (360 / 32 = 11.25 degrees)
ZS = list(range(5, 26))                      # on the rings (1 mm)


def bump_csv():
    lines = ["# a raised bump, positive outward", "z\\angle_deg," + ",".join(repr(a) for a in ANGLES)]
    lines += [repr(float(z)) + "," + ",".join(repr(bump(a, z)) for a in ANGLES) for z in ZS]
    return "\n".join(lines) + "\n"


def vertex_height(i, j):
    a = 360.0 * i / N
    if a > 180:
        a -= 360
    return bump(a, j) if -45 <= a <= 45 and 5 <= j <= 25 else 0.0


BASE = ["--pairs", "2", "--frames", "12", "--vertices", str(N), "--radius", "10", "--height", "31", "--tilt", "0",
        "--spin", "30", "--gap", "0.2", "--scar-fraction", "1"]


class BearingScars(unittest.TestCase):
    def test_csv_map_rows_against_the_bump(self):
        write_text("bump.csv", bump_csv())
        rc, out, err = run(*BASE, "--scar-map", path("bump.csv"), "--json", path("m.json"), "--out", path("m.csv"))
        self.assertEqual(rc, 1, out + err)  # the bump (0.5 mm) reaches across the 0.2 mm gap
        s = load("m.json")
        imp = s["scar_import"]
        self.assertEqual(imp["kind"], "csv")
        self.assertEqual(imp["file"], path("bump.csv"))
        self.assertEqual((imp["rows"], imp["columns"]), (21, 9))
        self.assertEqual(imp["covered_vertices"], 21 * 9)
        self.assertAlmostEqual(imp["max_height"], 0.5, delta=1e-12)  # the peak is a vertex
        self.assertEqual(imp["min_height"], 0.0)
        self.assertAlmostEqual(imp["covered_window"]["angle_width_deg"], 90, delta=1e-9)
        self.assertEqual(s["results"]["scarred_rollers"], 2)
        rows = read_csv("m.csv")
        self.assertEqual(len(rows), 24)
        gap, d_axis = 0.2, R_PARTNER + R_ROLLER + 0.2
        hmax = 0.5
        reaching = 0
        for r in rows:
            d = float(r["distance"])
            spin = math.radians(float(r["spin_deg"]))
            # tilt 0: the roller's axis is parallel to the partner's, d_axis away along -x (world);
            # vertex (i, j) lies at world angle 2 pi i / n + spin about the roller's axis
            best = math.inf
            for j in range(N):
                for i in range(N):
                    rho = R_ROLLER + vertex_height(i, j)
                    t = 2 * math.pi * i / N + spin
                    best = min(best, math.hypot(d_axis + rho * math.cos(t), rho * math.sin(t)) - R_PARTNER)
            # the surface minimum is at most the vertices' and at least that of the cylinder grown by
            # the largest height
            self.assertLessEqual(d, best + 1e-9, r)
            self.assertGreaterEqual(d, gap - hmax - 1e-9, r)
            if best < -1e-6:
                reaching += 1
                self.assertEqual(r["solver"], "scarred", r)
                self.assertEqual(r["verdict"], "clash", r)
            if best > 1e-6 and d > 1e-6:
                self.assertEqual(r["verdict"], "clear", r)
        self.assertGreater(reaching, 0)
        self.assertLess(s["results"]["min_distance"], 0)

    def test_points_give_the_same_bump(self):
        # the bump's own vertices as a point cloud (exact hits): the same heights as the CSV map
        lines = ["# x y z, body frame"]
        for j in ZS:
            for a in ANGLES:
                rho, t = R_ROLLER + bump(a, j), math.radians(a)
                lines.append("%r %r %r" % (rho * math.cos(t), rho * math.sin(t), float(j)))
        write_text("bump.xyz", "\n".join(lines) + "\n")
        write_text("bump.csv", bump_csv())
        rc, out, err = run(*BASE, "--scar-points", path("bump.xyz"), "--scar-points-window", "0.5", "--out",
                           path("p.csv"), "--json", path("p.json"))
        self.assertEqual(rc, 1, out + err)
        imp = load("p.json")["scar_import"]
        self.assertEqual(imp["kind"], "points")
        self.assertEqual(imp["points"], len(ZS) * len(ANGLES))
        self.assertEqual(imp["covered_vertices"], 21 * 9)
        rc, out, err = run(*BASE, "--scar-map", path("bump.csv"), "--out", path("c.csv"))
        self.assertEqual(rc, 1, out + err)
        for a, b in zip(read_csv("p.csv"), read_csv("c.csv")):
            self.assertAlmostEqual(float(a["distance"]), float(b["distance"]), delta=1e-9)

    def test_raised_generated_scar(self):
        args = BASE + ["--scar", "0,359,2,29,0.5", "--json"]
        rc, out, err = run(*args, path("in.json"))
        s = load("in.json")
        self.assertFalse(s["parameters"]["scar"]["raised"])
        self.assertGreaterEqual(s["results"]["min_distance"], 0.2 - 1e-9)  # inward: never below the gap
        self.assertEqual(rc, 0, out + err)
        rc, out, err = run(*args, path("up.json"), "--raised")
        s = load("up.json")
        self.assertTrue(s["parameters"]["scar"]["raised"])
        self.assertLess(s["results"]["min_distance"], 0)  # up to 0.5 mm out: across the gap
        self.assertGreaterEqual(s["results"]["min_distance"], 0.2 - 0.5 - 1e-9)
        self.assertEqual(rc, 1, out + err)
        # the parameters file says the same
        write_text("raised.parameters", '{"scar": {"raised": true, "fraction": 1}}')
        rc, out, err = run("--params", path("raised.parameters"), *args, path("pf.json"))
        self.assertTrue(load("pf.json")["parameters"]["scar"]["raised"])
        write_text("bad_raised.parameters", '{"scar": {"raised": 1}}')
        cli_common.assert_input_error(self, ["bearing", "--params", path("bad_raised.parameters")], ["scar.raised"])

    def test_bad_input(self):
        write_text("ragged.csv", "z,0,10\n1,0,0\n2,0\n")
        write_text("nan.csv", "z,0,10\n1,0,0\n2,0,nan\n")
        write_text("axis.csv", "z,0,10\n10,0,0\n20,0,-10\n")
        write_text("one.csv", "z,0,10\n1,0,0\n")
        write_text("bump.csv", bump_csv())
        write_text("map.txt", "z,0,10\n1,0,0\n2,0,0\n")
        write_text("two.xyz", "1 2 3\n4 5\n")
        write_text("fake.png", "not a png")
        outs = [path("none.json")]
        cases = [
            (["--scar-map", path("ragged.csv")], ["ragged.csv:3:", "expected 3 fields"]),
            (["--scar-map", path("nan.csv")], ["nan.csv:3:", "field 3"]),
            (["--scar-map", path("axis.csv")], ["axis.csv:3:", "field 3", "axis"]),
            (["--scar-map", path("one.csv")], ["one.csv", "at least 2 rows"]),
            (["--scar-map", path("map.txt")], ["--scar-map", ".csv or .png"]),
            (["--scar-map", path("fake.png")], ["--scar-map-scale"]),
            (["--scar-map", path("fake.png"), "--scar-map-scale", "1e-5"], ["fake.png", "not a PNG"]),
            (["--scar-map", path("bump.csv"), "--scar-map-scale", "2"], ["PNG map only"]),
            (["--scar-map", path("missing.csv")], ["missing.csv", "cannot open"]),
            (["--scar-points", path("two.xyz")], ["two.xyz:2:", "expected 3 numbers"]),
            (["--scar-points", path("bump.csv"), "--scar-map", path("bump.csv")], ["exclude each other"]),
            (["--scar-map", path("bump.csv"), "--no-scar"], ["needs scarred rollers"]),
            (["--scar-map-scale", "2"], ["need --scar-map"]),
        ]
        for args, needles in cases:
            cli_common.assert_input_error(self, ["bearing", *BASE, *args, "--json", outs[0]], needles, outs)


if __name__ == "__main__":
    cli_common.main()
