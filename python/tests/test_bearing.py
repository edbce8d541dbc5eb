"""Python API of the bearing module (issue #4): make a roller, compute the maximum interference
distance of a pair, run a small simulation, bad parameters raise ValueError naming them."""
import math
import unittest

import interfere
from interfere import bearing



def sampled_cylinder_distance(mesh, pose, base, height, radius, k):
    """Independent oracle (issue #23, item 14): the smallest signed distance of the posed mesh's
    surface to a z-axis cylinder (negative inside), by a barycentric grid of k steps on every
    triangle, written here from scratch. Returns (lo, hi): hi is a sampled value (>= the minimum);
    the distance is 1-Lipschitz, so lo = hi - (the largest covering radius: longest edge / k)."""
    rot, t = pose.r, pose.t
    pts = [tuple(sum(rot[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)) for p in mesh.positions]
    zb, zt = base[2], base[2] + height

    def signed(p):
        rho = math.hypot(p[0] - base[0], p[1] - base[1])
        if rho <= radius and zb <= p[2] <= zt:
            return -min(radius - rho, p[2] - zb, zt - p[2])
        return math.hypot(max(rho - radius, 0.0), max(zb - p[2], p[2] - zt, 0.0))

    best, cover = math.inf, 0.0
    for tri in mesh.triangles:
        a, b, c = (pts[i] for i in tri)
        cover = max(cover, max(math.dist(a, b), math.dist(b, c), math.dist(c, a)) / k)
        for i in range(k + 1):
            for j in range(k + 1 - i):
                u, v = i / k, j / k
                w = 1 - u - v
                best = min(best, signed(tuple(w * a[m] + u * b[m] + v * c[m] for m in range(3))))
    return best - cover, best

class BearingTest(unittest.TestCase):
    def test_make_roller(self):
        r = bearing.make_roller(bearing.RollerParams(radius=5, height=20, radial_segments=16, height_segments=7))
        self.assertEqual(len(r.mesh.triangles), 2 * 16 * 7 + 2 * 16)
        self.assertFalse(r.has_scar)
        s = bearing.make_roller(bearing.RollerParams(radius=5, height=20, radial_segments=16, height_segments=7),
                                bearing.ScarParams(angle_center_deg=0, angle_width_deg=90, z_min=5, z_max=15,
                                                   depth=0.5, seed=3))
        self.assertTrue(s.has_scar)
        self.assertGreater(max(s.displacement), 0)
        self.assertLessEqual(max(s.displacement), 0.5)
        self.assertEqual(s.max_raise, 0.0)
        # a raised scar (issue #27): the same map outward
        up = bearing.make_roller(bearing.RollerParams(radius=5, height=20, radial_segments=16, height_segments=7),
                                 bearing.ScarParams(angle_center_deg=0, angle_width_deg=90, z_min=5, z_max=15,
                                                    depth=0.5, seed=3, raised=True))
        self.assertFalse(bearing.ScarParams().raised)
        self.assertEqual(list(up.displacement), [-d for d in s.displacement])
        self.assertEqual(up.max_raise, max(s.displacement))

    def test_max_interference_distance_of_a_pair(self):
        b = bearing.Cylinder(base=(0, 0, 0), axis=(0, 0, 1), height=60, radius=30)
        a = bearing.Cylinder(base=(39.5, 0, 10), axis=(0, 0, 1), height=40, radius=10)
        d = bearing.max_interference_distance(a, b)
        self.assertAlmostEqual(d.distance, -0.5, delta=1e-12)
        self.assertAlmostEqual(d.interference, 0.5, delta=1e-12)
        self.assertAlmostEqual(math.dist(d.point_a, d.point_b), 0.5, delta=1e-12)
        # tilted by alpha about the bottom rim contact: interference h_b tan(alpha)
        al = math.radians(2)
        a = bearing.Cylinder(base=(30 + 10 * math.cos(al), 0, 10 * math.sin(al)), axis=(-math.sin(al), 0, math.cos(al)),
                             height=40 / math.cos(al), radius=10)
        b = bearing.Cylinder(base=(0, 0, -100), axis=(0, 0, 1), height=300, radius=30)
        self.assertAlmostEqual(bearing.max_interference_distance(a, b).distance, -40 * math.tan(al), delta=1e-12)

    def test_window_and_surface_reference(self):
        # Eq. (1) (issue #27): the arc of the roller's top-view circle (radius 10) inside the partner's
        # (radius 30, centre at 40 - 40 tan(1 degree)), found here by bisection: 37.4 degrees
        d = 40 - 40 * math.tan(math.radians(1))
        lo, hi = 0.0, math.pi
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            inside = (10 * math.cos(mid) - d) ** 2 + (10 * math.sin(mid)) ** 2 <= 30 ** 2
            lo, hi = (mid, hi) if inside else (lo, mid)
        self.assertAlmostEqual(bearing.ideal_interference_range(10, 30, 40, 1.0), math.degrees(2 * lo), delta=1e-9)
        self.assertAlmostEqual(bearing.ideal_interference_range(10, 30, 40, 1.0), 37.36, delta=0.01)
        self.assertAlmostEqual(bearing.interference_window(10, 30, 40, 1.0), math.degrees(lo), delta=1e-9)
        self.assertAlmostEqual(bearing.contact_turn_bound(10, 30, 40, 1.0),
                               math.degrees(math.asin(40 * math.sin(math.radians(1)) / 40)), delta=1e-12)
        for bad in (95, 60, -1):  # beyond atan(2 min(r, R) / h_b) = 26.57 degrees
            with self.assertRaisesRegex(ValueError, "max_tilt"):
                bearing.interference_window(10, 30, 40, bad)
        p = bearing.RollerParams(radius=10, height=40, radial_segments=24, height_segments=23)
        r = bearing.make_roller(p, bearing.ScarParams(angle_center_deg=180, angle_width_deg=60, z_min=0, z_max=40,
                                                      depth=0.3, seed=2))
        pose = bearing.roller_pose((39.8, 0, 0), tilt_deg=0.5, azimuth_deg=30, spin_deg=0)
        partner = bearing.Cylinder(base=(0, 0, -10), axis=(0, 0, 1), height=60, radius=30)
        ref = bearing.surface_reference(r, pose, partner)
        fast = bearing.scarred_distance(r, pose, partner)
        # surface_reference shares its triangle minimum with the fast solver: this checks only that
        # the pruning loses nothing. The value itself against an independent oracle below.
        self.assertAlmostEqual(fast.distance, ref.distance, delta=1e-12)
        self.assertLess(fast.evaluated, ref.evaluated)
        lo, hi = sampled_cylinder_distance(r.mesh, pose, (0, 0, -10), 60, 30, k=6)
        self.assertLessEqual(fast.distance, hi + 1e-12)
        self.assertGreaterEqual(fast.distance, lo - 1e-12)
        self.assertLess(fast.distance, 0)  # the pose presses the scarred roller into the partner

    def test_small_simulation(self):
        res = bearing.simulate(pairs=6, frames=8, roller=bearing.RollerParams(radial_segments=24, height_segments=23),
                               gap=-0.05, scar_fraction=0.5,
                               scar=bearing.ScarParams(angle_center_deg=0, angle_width_deg=120, z_min=0, z_max=40,
                                                       depth=0.2), seed=4)
        self.assertEqual(len(res.rows), 48)
        self.assertEqual(res.scarred_rollers, 3)
        self.assertEqual(res.min_distance, min(r.distance for r in res.rows))
        again = bearing.simulate(pairs=6, frames=8, roller=bearing.RollerParams(radial_segments=24, height_segments=23),
                                 gap=-0.05, scar_fraction=0.5,
                                 scar=bearing.ScarParams(angle_center_deg=0, angle_width_deg=120, z_min=0, z_max=40,
                                                         depth=0.2), seed=4, broad_phase="bvh")
        self.assertEqual([r.distance for r in res.rows], [r.distance for r in again.rows])
        self.assertEqual(res.verdict, "clash")  # preload
        self.assertTrue(all(r.verdict == "clash" for r in res.rows if r.distance < -1e-6))
        # issue #23, item 5: at spacing 45 neighbouring partners (R = 30) overlap by 15 mm; the own
        # pairs are apart (gap 1): the cross pair decides the verdict
        x = bearing.simulate(pairs=4, frames=2, roller=bearing.RollerParams(radial_segments=16, height_segments=15),
                             gap=1.0, scar_fraction=0, spacing=45)
        self.assertEqual(x.interfering_rows, 0)
        self.assertEqual(x.verdict, "clash")
        pp = [c for c in x.cross_results if (c.part_a, c.part_b) == (1, 3)]
        self.assertEqual(len(pp), 2)
        self.assertAlmostEqual(pp[0].distance, 45 - 60, delta=1e-9)
        self.assertEqual(pp[0].verdict, "clash")
        y = bearing.simulate(pairs=4, frames=2, roller=bearing.RollerParams(radial_segments=16, height_segments=15),
                             gap=1.0, scar_fraction=0, spacing=100, clearance=2.0)
        self.assertEqual(y.verdict, "clearance")
        self.assertEqual(y.cross_results, [])
        with self.assertRaisesRegex(ValueError, "roller.radius"):
            bearing.simulate(roller=bearing.RollerParams(radius=-1))
        with self.assertRaisesRegex(ValueError, "scar.z_max"):
            bearing.simulate(scar=bearing.ScarParams(z_max=99))


if __name__ == "__main__":
    unittest.main()
