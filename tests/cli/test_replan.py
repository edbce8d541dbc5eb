#!/usr/bin/env python3
"""`interfere sweep --replan-tilt` (issue #28, deliverable 4): colliding points re-planned to the
nearest collision-free pose aiming at the same surface point, the re-planned path written and checked
again; bad requests are input errors. The workpiece is two boxes written here (a plate with its top at
z = 0 and an overhang at x in [2, 20], z in [20, 30]); the oracle for "clear" is a dense sampling of the
probe cylinder's volume against those boxes (no engine code)."""
import math
import os

import cli_common as c

BOXES = [((-50, -50, -10), (50, 50, 0)), ((2, -50, 20), (20, 50, 30))]
RADIUS, LENGTH = 5.0, 40.0


def box_mesh(lo, hi, base):
    v = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    # corners indexed by (ix, iy, iz) bits: 4 ix + 2 iy + iz; faces outward
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = []
    for a, b, cc, d in quads:
        f += [(base + a, base + b, base + cc), (base + a, base + cc, base + d)]
    return v, f


def workpiece():
    v, f = [], []
    for lo, hi in BOXES:
        bv, bf = box_mesh(lo, hi, len(v))
        v += bv
        f += bf
    return c.write_obj("workpiece.obj", (v, f))


def sampled_hit(tip, axis):
    n = math.sqrt(sum(a * a for a in axis))
    a = [x / n for x in axis]
    u = [a[1], -a[0], 0.0] if abs(a[2]) < 0.9 else [0.0, a[2], -a[1]]
    un = math.sqrt(sum(x * x for x in u))
    u = [x / un for x in u]
    v = [a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2], a[0] * u[1] - a[1] * u[0]]
    for i in range(81):
        cen = [tip[k] - a[k] * LENGTH * i / 80 for k in range(3)]
        for r in range(6):
            for j in range(36):
                rad, phi = RADIUS * r / 5, 2 * math.pi * j / 36
                p = [cen[k] + u[k] * rad * math.cos(phi) + v[k] * rad * math.sin(phi) for k in range(3)]
                for lo, hi in BOXES:
                    if all(lo[k] + 1e-9 < p[k] < hi[k] - 1e-9 for k in range(3)):
                        return True
    return False


class Replan(c.unittest.TestCase):
    def setUp(self):
        self.wp = workpiece()
        # point 0 clear (far from the overhang), point 1 under the overhang (collides)
        self.path = c.write_text("path.csv", "px,py,pz,ax,ay,az\n-30,0,2,0,0,-1\n0,0,2,0,0,-1\n")
        self.base = ["sweep", "--workpiece", self.wp, "--path", self.path, "--probe-radius", str(RADIUS),
                     "--probe-length", str(LENGTH), "--no-continuous"]

    def test_colliding_point_replanned_and_path_clean(self):
        rc, out, err = c.run(*self.base, "--replan-tilt", "30", "--replanned-path", c.path("fixed.csv"),
                             "--json", c.path("r.json"))
        self.assertEqual(rc, 1, out + err)  # the path as given collides
        j = c.load_json("r.json")
        rp = j["replan"]
        self.assertEqual(rp["found"], 1)
        self.assertEqual(len(rp["points"]), 1)
        p = rp["points"][0]
        self.assertEqual((p["index"], p["line"]), (1, 3))
        self.assertTrue(p["found"])
        self.assertGreater(p["tilt_deg"], 0)
        self.assertLessEqual(p["tilt_deg"], 30 + 1e-9)
        self.assertEqual(rp["after"]["colliding_points"], 0)
        self.assertIn("re-planned 1 of 1 colliding points", out)
        rows = c.read_csv("fixed.csv")
        self.assertEqual(list(rows[0].keys()), ["px", "py", "pz", "ax", "ay", "az"])
        self.assertEqual([float(rows[0][k]) for k in ("px", "py", "pz", "ax", "ay", "az")], [-30, 0, 2, 0, 0, -1])
        tip = [float(rows[1][k]) for k in ("px", "py", "pz")]
        axis = [float(rows[1][k]) for k in ("ax", "ay", "az")]
        n = math.sqrt(sum(x * x for x in axis))
        aim = [tip[k] + axis[k] / n * 2 for k in range(3)]  # the same stand-off, the same surface point
        for k in range(3):
            self.assertAlmostEqual(aim[k], [0, 0, 0][k], places=6)
        self.assertAlmostEqual(math.degrees(math.acos(-axis[2] / n)), p["tilt_deg"], places=6)
        self.assertTrue(sampled_hit([0, 0, 2], [0, 0, -1]))
        self.assertFalse(sampled_hit(tip, axis))
        # the written path checks clean as a path of its own
        rc, out, err = c.run("sweep", "--workpiece", self.wp, "--path", c.path("fixed.csv"), "--probe-radius",
                             str(RADIUS), "--probe-length", str(LENGTH), "--no-continuous")
        self.assertEqual(rc, 0, out + err)

    def test_bad_requests(self):
        out = c.path("never.csv")
        c.assert_input_error(self, [*self.base, "--replanned-path", out], ["--replan-tilt"], [out])
        c.assert_input_error(self, [*self.base, "--replan-tilt", "95", "--replanned-path", out], ["tilt cone", "90"], [out])
        c.assert_input_error(self, [*self.base, "--replan-tilt", "-5", "--replanned-path", out], ["tilt cone"], [out])
        c.assert_input_error(self, [*self.base, "--replan-tilt", "10", "--replan-standoff", "3,1",
                                    "--replanned-path", out], ["stand-off range", "min 3 > max 1"], [out])
        c.assert_input_error(self, [*self.base, "--replan-tilt", "10", "--replan-standoff", "abc",
                                    "--replanned-path", out], ["--replan-standoff", "MIN,MAX"], [out])
        c.assert_input_error(self, [*self.base, "--replan-tilt", "10", "--replanned-path", c.path("x.txt")],
                             ["--replanned-path"], [c.path("x.txt")])


if __name__ == "__main__":
    c.main()
