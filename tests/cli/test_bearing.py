#!/usr/bin/env python3
"""End-to-end tests of `interfere bearing` (issue #4): exit status, CSV columns, JSON summary,
parameters file, determinism across thread counts, bad input (named parameter, exit 2, no output
written or overwritten); the verdict model and parts of different pairs (issue #23, items 5, 13).

Usage: test_bearing.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import json
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, read_csv, load_json as load, read_text as slurp  # noqa: E402


def run(*args):
    return cli_common.run(*args, command=("bearing",))


EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "bearing.parameters")

COLUMNS = ["frame", "pair", "distance", "interference", "ax", "ay", "az", "bx", "by", "bz", "solver", "path",
           "scarred", "scar_in_range", "box_overlap", "tilt_deg", "azimuth_deg", "spin_deg", "evaluated", "verdict"]


class Bearing(unittest.TestCase):
    def test_simulation_outputs(self):
        rc, out, err = run("--pairs", "12", "--frames", "20", "--vertices", "32", "--scar", "0,90,0,40,0.2",
                           "--gap", "-0.05", "--spin", "9", "--seed", "3", "--out", path("f.csv"), "--json",
                           path("s.json"))
        self.assertEqual(rc, 1, err)  # preload: interference
        self.assertTrue(out.startswith("clash:"), out)
        rows = read_csv("f.csv")
        self.assertEqual(len(rows), 12 * 20)
        self.assertEqual(slurp("f.csv").split("\n", 1)[0].split(","), COLUMNS)
        s = load("s.json")
        self.assertEqual(s["command"], "bearing")
        self.assertEqual(s["verdict"], "clash")
        self.assertEqual(s["exit_status"], 1)
        self.assertEqual(s["results"]["verdicts"]["clash"], sum(r["verdict"] == "clash" for r in rows))
        self.assertEqual(sum(s["results"]["verdicts"].values()), 240)
        self.assertEqual(s["results"]["rows"], 240)
        self.assertEqual(s["results"]["colliders"], 24)
        self.assertEqual(s["parameters"]["roller"]["radial_segments"], 32)
        self.assertEqual(s["parameters"]["roller"]["height_segments"], 31)
        dmin = min(float(r["distance"]) for r in rows)
        self.assertEqual(s["results"]["min_distance"], dmin)
        self.assertEqual(s["worst"]["distance"], dmin)
        worst = [r for r in rows if float(r["distance"]) == dmin][0]
        self.assertEqual((s["worst"]["frame"], s["worst"]["pair"]), (int(worst["frame"]), int(worst["pair"])))
        self.assertEqual(s["results"]["interfering_rows"], sum(float(r["distance"]) < 0 for r in rows))
        self.assertEqual(s["results"]["scarred_solves"], sum(r["solver"] == "scarred" for r in rows))
        self.assertGreater(s["results"]["scarred_solves"], 0)
        for r in rows:
            d = float(r["distance"])
            self.assertTrue(math.isfinite(d))
            self.assertEqual(float(r["interference"]), max(0.0, -d))
            # the witness pair: |a - b| is |distance| (b is the nearest boundary point of the partner)
            a = [float(r[k]) for k in ("ax", "ay", "az")]
            b = [float(r[k]) for k in ("bx", "by", "bz")]
            self.assertAlmostEqual(math.dist(a, b), abs(d), delta=1e-9)
            self.assertLessEqual(float(r["tilt_deg"]), 1.0 + 1e-12)
            # the verdict follows the sign of s, beyond the touch band (2^-36 of the coordinates)
            if d < -1e-6:
                self.assertEqual(r["verdict"], "clash", r)
            elif d > 1e-6:
                self.assertEqual(r["verdict"], "clear", r)

    def test_identical_for_one_and_two_threads_and_all_broad_phases(self):
        base = ["--pairs", "9", "--frames", "15", "--vertices", "24", "--scar", "0,120,0,40,0.2", "--gap", "-0.05"]
        self.assertEqual(run(*base, "--threads", "1", "--out", path("t1.csv"))[0], 1)
        ref = slurp("t1.csv")
        for extra in (["--threads", "2"], ["--broad-phase", "brute"], ["--broad-phase", "octree"],
                      ["--broad-phase", "bvh"]):
            rc, _, err = run(*base, *extra, "--out", path("t2.csv"))
            self.assertEqual(rc, 1, err)
            self.assertEqual(slurp("t2.csv"), ref, extra)

    def test_clear_when_apart_and_parameters_file(self):
        params = {"pairs": 4, "frames": 5, "seed": 9, "gap": 5.0, "max_tilt_deg": 0.5,
                  "roller": {"radius": 8, "height": 30, "radial_segments": 16, "height_segments": 15},
                  "partner": {"radius": 20, "height": 40}, "scar": None, "broad_phase": "octree"}
        with open(path("bearing.parameters"), "w") as f:
            json.dump(params, f)
        rc, out, err = run("--params", path("bearing.parameters"), "--json", path("p.json"))
        self.assertEqual(rc, 0, err)
        s = load("p.json")
        self.assertEqual(s["parameters"]["pairs"], 4)
        self.assertEqual(s["parameters"]["broad_phase"], "octree")
        self.assertEqual(s["results"]["scarred_rollers"], 0)
        self.assertGreater(s["results"]["min_distance"], 0)
        # command-line values override the file
        rc, _, err = run("--params", path("bearing.parameters"), "--pairs", "2", "--json", path("p2.json"))
        self.assertEqual(rc, 0, err)
        self.assertEqual(load("p2.json")["parameters"]["pairs"], 2)
        self.assertEqual(load("p2.json")["verdict"], "clear")

    def test_overlapping_neighbours_are_clash_and_listed(self):
        # issue #23, item 5: at --spacing 45 neighbouring partners (R = 30) overlap by 60 - 45 = 15 mm
        # and each roller lies inside the next partner; the own pairs are apart (gap 1). This used to
        # print "clear" and exit 0, the overlaps only counted in cross_pairs.
        rc, out, err = run("--pairs", "4", "--frames", "3", "--gap", "1", "--spacing", "45", "--vertices", "16",
                           "--json", path("x45.json"))
        self.assertEqual(rc, 1, out + err)
        self.assertTrue(out.startswith("clash:"), out)
        s = load("x45.json")
        self.assertEqual(s["verdict"], "clash")
        self.assertEqual(s["results"]["interfering_rows"], 0)  # no own pair interferes ...
        self.assertGreater(s["results"]["cross_verdicts"]["clash"], 0)  # ... parts of different pairs do
        listed = {(c["frame"], c["a"]["pair"], c["a"]["part"], c["b"]["pair"], c["b"]["part"]): c for c in s["cross"]}
        for frame in range(3):
            pp = listed[(frame, 0, "partner", 1, "partner")]
            self.assertEqual(pp["verdict"], "clash")
            self.assertAlmostEqual(pp["distance"], 45.0 - 60.0, delta=1e-9)  # parallel equal cylinders
            self.assertAlmostEqual(pp["interference"], 15.0, delta=1e-9)
            self.assertEqual(listed[(frame, 0, "roller", 1, "partner")]["verdict"], "clash")
        # every box overlap is decided: the listed ones plus the clear ones
        self.assertEqual(s["results"]["cross_pairs"], sum(s["results"]["cross_verdicts"].values()))
        self.assertEqual(len(s["cross"]), s["results"]["cross_pairs"] - s["results"]["cross_verdicts"]["clear"])
        # a spacing where nothing overlaps stays clear
        rc, out, err = run("--pairs", "4", "--frames", "3", "--gap", "1", "--spacing", "100", "--vertices", "16",
                           "--json", path("x100.json"))
        self.assertEqual(rc, 0, out + err)
        self.assertTrue(out.startswith("clear:"), out)
        s = load("x100.json")
        self.assertEqual(s["verdict"], "clear")
        self.assertEqual(s["cross"], [])

    def test_tapered_cross_pairs_are_exact(self):
        # issue #27: parts of different pairs that are tapered (or one scarred) get the exact solvers of
        # the tapered assemblies (two-sided cone_pair_distance, the scarred solver against a frustum),
        # not enclosing-cylinder bounds that left close pairs undecided. Four upright rollers (radius
        # 10 -> 8 over 40, no tilt) on a grid of pitch 19: rollers 0 and 2 (and 1 and 3) stand side by
        # side, their bottoms overlapping by o = 1. Two equal frustums (slope k = 0.05) translated
        # across: the rim at height z lies o - 2kz inside the other across its axis, so
        # S = -z* with z* (sqrt(1 + k^2) + 2k) = o (sd = max(-(o - 2kz) / sqrt(1 + k^2), -z)).
        common = ["--pairs", "4", "--frames", "2", "--radius", "10", "--top-radius", "8", "--height", "40",
                  "--partner-radius", "5", "--partner-height", "40", "--gap", "1", "--spacing", "19",
                  "--tilt", "0", "--vertices", "24"]
        rc, out, err = run(*common, "--no-scar", "--json", path("taper.json"))
        self.assertEqual(rc, 1, out + err)
        s = load("taper.json")
        k, o = 0.05, 1.0
        exact = -o / (math.sqrt(1 + k * k) + 2 * k)
        listed = {(c["frame"], c["a"]["pair"], c["a"]["part"], c["b"]["pair"], c["b"]["part"]): c for c in s["cross"]}
        for frame in range(2):
            for a, b in ((0, 2), (1, 3)):
                c = listed.get((frame, a, "roller", b, "roller")) or listed[(frame, b, "roller", a, "roller")]
                self.assertEqual(c["solver"], "standard")
                self.assertEqual(c["verdict"], "clash")
                self.assertAlmostEqual(c["distance"], exact, delta=1e-9)
        self.assertEqual(s["results"]["cross_verdicts"]["undecided"], 0)
        # a quarter scarred: roller 3 (scarred) against roller 1 (intact): the scarred solver on its
        # mesh against the intact frustum, decided (the mesh lies within the scar's depth 0.05 and the
        # facets' sagitta of the frustum: the value is within that of the intact one)
        rc, out, err = run(*common, "--scar-fraction", "0.25", "--scar", "0,359,0,40,0.05", "--json",
                           path("taper_scar.json"))
        self.assertEqual(rc, 1, out + err)
        s = load("taper_scar.json")
        listed = {(c["frame"], c["a"]["pair"], c["a"]["part"], c["b"]["pair"], c["b"]["part"]): c for c in s["cross"]}
        sagitta = 10 * (1 - math.cos(math.pi / 24))
        for frame in range(2):
            c = listed[(frame, 3, "roller", 1, "roller")]  # the scarred roller is A
            self.assertEqual(c["solver"], "scarred")
            self.assertEqual(c["verdict"], "clash")
            self.assertLess(abs(c["distance"] - exact), 0.05 + sagitta + 1e-9)
        self.assertEqual(s["results"]["cross_verdicts"]["undecided"], 0)

    def test_partner_inside_scarred_roller_is_clash(self):
        # a partner (R = 1, height 2) wholly inside its scarred roller: the scarred solver's surface
        # minimum is positive; the run used to exit 0
        rc, out, err = run("--pairs", "1", "--frames", "3", "--partner-radius", "1", "--partner-height", "2",
                           "--gap", "-10.5", "--scar", "0,359,0,40,0.05", "--scar-fraction", "1", "--vertices", "24",
                           "--out", path("in.csv"))
        self.assertEqual(rc, 1, out + err)
        rows = read_csv("in.csv")
        self.assertTrue(all(r["solver"] == "scarred" and float(r["distance"]) > 0 for r in rows))
        self.assertTrue(all(r["verdict"] == "clash" for r in rows))

    def test_contact_clearance_and_fail_on(self):
        base = ["--pairs", "4", "--frames", "2", "--tilt", "0", "--no-scar", "--vertices", "16"]
        # parallel axes at exactly R + r: line contact, exit 0 unless --fail-on contact
        rc, out, err = run(*base, "--gap", "0", "--json", path("c.json"), "--out", path("c.csv"))
        self.assertEqual(rc, 0, out + err)
        self.assertTrue(out.startswith("contact:"), out)
        self.assertEqual(load("c.json")["verdict"], "contact")
        self.assertEqual({r["verdict"] for r in read_csv("c.csv")}, {"contact"})
        self.assertEqual(run(*base, "--gap", "0", "--fail-on", "contact")[0], 1)
        # a 1 um preload is a clash, a 1 um gap is clear
        self.assertEqual(run(*base, "--gap", "-0.001")[0], 1)
        self.assertEqual(run(*base, "--gap", "0.001")[0], 0)
        # clearance: apart by 1, closer than 2
        rc, out, err = run(*base, "--gap", "1", "--clearance", "2", "--json", path("cl.json"))
        self.assertEqual(rc, 0, out + err)
        self.assertEqual(load("cl.json")["verdict"], "clearance")
        self.assertEqual(load("cl.json")["parameters"]["clearance"], 2)
        self.assertEqual(run(*base, "--gap", "1", "--clearance", "2", "--fail-on", "clearance")[0], 1)
        self.assertEqual(run(*base, "--gap", "1", "--clearance", "0.5", "--fail-on", "clearance")[0], 0)
        rc, _, err = run(*base, "--fail-on", "touching")
        self.assertEqual(rc, 2)
        self.assertIn("--fail-on", err)
        rc, _, err = run(*base, "--clearance", "-1")
        self.assertEqual(rc, 2)
        self.assertIn("clearance", err)

    def test_example_parameters_file(self):
        rc, out, err = run("--params", EXAMPLE, "--frames", "10", "--json", path("ex.json"), "--out", path("ex.csv"))
        self.assertEqual(rc, 1, err)  # the example is preloaded (gap -0.05): interference
        s = load("ex.json")
        self.assertEqual(s["parameters"]["pairs"], 16)
        self.assertEqual(s["parameters"]["frames"], 10)
        self.assertEqual(s["results"]["scarred_rollers"], 4)
        self.assertEqual(len(read_csv("ex.csv")), 160)

    def test_bad_input_names_the_parameter_and_writes_nothing(self):
        with open(path("keep.csv"), "w") as f:
            f.write("old\n")
        cases = [(["--radius", "-1"], "roller.radius"),
                 (["--height", "0"], "roller.height"),
                 (["--vertices", "2"], "--vertices"),
                 (["--tilt", "95"], "max_tilt"),
                 (["--tilt", "80", "--radius", "1", "--partner-radius", "1"], "Eq. (1)"),
                 (["--tilt", "60"], "Eq. (1)"),  # issue #27: beyond atan(2 min(r, R) / h_b) = 26.57 degrees
                 (["--tilt", "26.6"], "max_tilt"),
                 (["--scar", "0,40,30,50,0.1"], "scar.z_max"),
                 (["--scar", "0,40,-5,10,0.1"], "scar.z_min"),
                 (["--scar", "0,40,10"], "--scar"),
                 (["--scar", "0,400,10,20,0.1"], "angle_width"),
                 (["--pairs", "0"], "pairs"),
                 (["--broad-phase", "kd"], "--broad-phase"),
                 (["--partner-radius", "nan"], "partner.radius")]
        for args, needle in cases:
            rc, out, err = run(*args, "--out", path("keep.csv"), "--json", path("none.json"))
            self.assertEqual(rc, 2, (args, err))
            self.assertIn(needle, err, args)
            self.assertEqual(slurp("keep.csv"), "old\n")
            self.assertFalse(os.path.exists(path("none.json")))
        with open(path("bad.parameters"), "w") as f:
            f.write('{"pairs": 3, "roller": {"radius": 10, "colour": 1}}')
        rc, _, err = run("--params", path("bad.parameters"))
        self.assertEqual(rc, 2)
        self.assertIn("roller.colour", err)
        self.assertIn("bad.parameters", err)
        with open(path("broken.parameters"), "w") as f:
            f.write('{"pairs": 3,, }')
        rc, _, err = run("--params", path("broken.parameters"))
        self.assertEqual(rc, 2)
        self.assertIn("byte", err)
        with open(path("huge.parameters"), "w") as f:
            f.write('{"pairs": 3e999}')
        rc, _, err = run("--params", path("huge.parameters"))
        self.assertEqual(rc, 2)
        self.assertIn("huge.parameters", err)
        self.assertIn("invalid JSON", err)


if __name__ == "__main__":
    cli_common.main()
