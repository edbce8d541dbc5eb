"""Tests of `interfere.probe` (issue #5): forward kinematics against the pivot machine's closed form and a
hand-computed pose, the exact cylinder-triangle test (touching configurations, the paper's
three-projection counterexample), the box holder (reference direction, exact box-triangle test, a
pose only the box hits), a small sweep (hierarchies agree, a collision between samples).

Run:  PYTHONPATH=<build>/python python3 -m unittest discover -s python/tests -p 'test_probe.py'
"""

import math
import os
import tempfile
import unittest

import interfere as itf

probe = itf.probe
ROBOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "examples", "probe_5axis.json")


class Kinematics(unittest.TestCase):
    def test_bundled_robot_matches_closed_form(self):
        r = probe.read_robot(ROBOT)
        self.assertEqual(r.joint_names, ["x", "y", "z", "a", "b"])
        for q in ([0, 0, 0, 0, 0], [10, -20, 300, 35, 50], [-5, 7, 1, -170, -100]):
            tip, axis = probe.forward_kinematics(r, q)
            tip2, axis2 = probe.paper_end_circle(q, 150.0)
            for a, b in zip(tip + axis, tip2 + axis2):
                self.assertAlmostEqual(a, b, places=9)

    def test_hand_computed_pose(self):
        r = probe.paper_machine(100.0)
        tip, axis = probe.forward_kinematics(r, [1, 2, 3, 0, 90])  # b = 90: probe along -x
        self.assertAlmostEqual(axis[0], -1.0, places=12)
        self.assertAlmostEqual(tip[0], 1 - 100.0, places=9)
        self.assertAlmostEqual(tip[2], 3.0, places=9)

    def test_bad_robot_names_field(self):
        with self.assertRaises(itf.InputError) as cm:
            probe.parse_robot('{"joints": [\n{"type": "cam", "a": 0, "alpha": 0, "d": 0, "theta": 0}],'
                              '"tool": {"tip": [0,0,0], "axis": [0,0,1]}}')
        self.assertEqual(cm.exception.line, 2)
        self.assertIn("joints[0].type", cm.exception.reason)

    def test_bad_path_names_row_and_field(self):
        r = probe.paper_machine()
        with tempfile.TemporaryDirectory() as d:
            f = os.path.join(d, "p.csv")
            with open(f, "w") as out:
                out.write("x,y,z,a,b\n0,0,0,0,0\n0,0,0,0,150\n")
            with self.assertRaises(itf.InputError) as cm:
                probe.read_path(f, r)
            self.assertEqual(cm.exception.line, 3)
            self.assertIn("field 'b'", cm.exception.reason)


class CylinderTriangle(unittest.TestCase):
    C0, C1, R = (0, 0, 0), (0, 0, 2), 1.0

    def test_touching_and_one_ulp_apart(self):
        self.assertTrue(probe.cylinder_triangle_intersect(self.C0, self.C1, self.R, [(1, 0, -5), (1, 0, 5), (4, 0, 0)]))
        x = math.nextafter(1.0, 2.0)
        self.assertFalse(probe.cylinder_triangle_intersect(self.C0, self.C1, self.R, [(x, 0, -5), (x, 0, 5), (4, 0, 0)]))
        self.assertTrue(probe.cylinder_triangle_intersect(self.C0, self.C1, self.R, [(-3, -3, 0), (3, -3, 0), (0, 3, 0)]))
        z = math.nextafter(0.0, -1.0)
        self.assertFalse(probe.cylinder_triangle_intersect(self.C0, self.C1, self.R, [(-3, -3, z), (3, -3, z), (0, 3, z)]))

    def test_three_projection_counterexample(self):
        s = 1 / math.sqrt(2)
        t = [(3, -3, 2.1), (-3, 3, 2.1), (2, 2, 2.1 - 4 * s)]
        c1 = (0, 0, 1)
        self.assertTrue(probe.frame_projection_test(self.C0, c1, self.R, t))
        # The paper's own projections (along a triangle edge) separate this one.
        self.assertFalse(probe.three_projection_test(self.C0, c1, self.R, t))
        self.assertFalse(probe.cylinder_triangle_intersect(self.C0, c1, self.R, t))
        d, pc, pt = probe.cylinder_triangle_distance(self.C0, c1, self.R, t)
        self.assertAlmostEqual(d, 0.1 / math.sqrt(2), places=9)
        self.assertAlmostEqual(math.dist(pc, pt), d, places=9)


class PaperMachine31(unittest.TestCase):
    """Issue #28: the paper's §3.1 machine, its inverse kinematics and the paper's projections."""

    def test_rear_circle_formula_and_inverse(self):
        robot = probe.read_robot(os.path.join(os.path.dirname(ROBOT), "probe_paper_machine.json"))
        q = [12.5, -40.0, 250.0, 33.0, -21.0]
        tip, axis = probe.forward_kinematics(robot, q)
        a, b = math.radians(q[3]), math.radians(q[4])
        rear = (q[0] + 30 * math.cos(a) + 120 * math.sin(a) * math.cos(b),
                q[1] - 30 * math.sin(a) + 120 * math.cos(a) * math.cos(b), -q[2] + 120 * math.sin(b))
        for i in range(3):
            self.assertAlmostEqual(tip[i] - 40 * axis[i], rear[i], places=9)
        back = probe.inverse_kinematics(robot, tip, axis, previous=q)
        for i in range(5):
            self.assertAlmostEqual(back[i], q[i], places=9)
        with self.assertRaises(itf.InputError) as e:
            probe.inverse_kinematics(robot, (0, 0, -2500), (0, 1, 0))
        self.assertIn("joint z", str(e.exception))
        path = probe.pose_path_to_joints(probe.pose_path([(tip, axis)]), probe.paper_machine_31(30, 120, 40))
        self.assertEqual(len(path.joints), 1)

    def test_paper_projections_false_positive(self):
        t = [(-0.41762788177630833, -0.8210775298506976, 2.0431113483579426),
             (-0.5255325554798489, -0.11186297107474368, 3.2267138360446035),
             (-1.0452788651563281, -2.71650785719231, 1.850198368577664)]
        self.assertEqual(probe.paper_projections((0, 0, 0), (0, 0, 2), 1.0, t), (True, True, True))
        self.assertFalse(probe.cylinder_triangle_intersect((0, 0, 0), (0, 0, 2), 1.0, t))


class HolderBox(unittest.TestCase):
    # Probe down from tip z = 100, length 40; box 40 wide (along ref), 20 deep, 30 long behind it.
    WALL = itf.TriMesh([[18, -100, -100], [18, 100, -100], [18, 100, 300], [18, -100, 300]], [[0, 1, 2], [0, 2, 3]])

    def test_forward_pose_reference(self):
        tip, axis, ref = probe.forward_pose(probe.paper_machine(), [1, 2, 3, 90, 30])  # x5 = (0, cos b, -sin b)
        for a, b in zip(ref, (0.0, math.sqrt(0.75), -0.5)):
            self.assertAlmostEqual(a, b, places=14)
        self.assertAlmostEqual(sum(a * b for a, b in zip(ref, axis)), 0.0, places=14)

    def test_exact_box_triangle(self):
        box = ((0, 0, 0), ((1, 0, 0), (0, 1, 0), (0, 0, 1)), (1, 2, 3))
        self.assertTrue(probe.box_triangle_intersect(*box, [(1, 0.5, 0.5), (4, 0, 0), (4, 1, 1)]))
        x = math.nextafter(1.0, 2.0)
        self.assertFalse(probe.box_triangle_intersect(*box, [(x, 0.5, 0.5), (4, 0, 0), (4, 1, 1)]))
        d, on_box, on_tri = probe.box_triangle_distance(*box, [(3, 0, 0), (4, 0, 0), (4, 1, 1)])
        self.assertAlmostEqual(d, 2.0, places=12)
        self.assertAlmostEqual(on_box[0], 1.0, places=12)
        corners = probe.holder_box((0, 0, 100), (0, 0, -1), (1, 0, 0), 40, 40, 20, 30)
        self.assertEqual(len(corners), 8)
        self.assertAlmostEqual(max(c[0] for c in corners), 20.0, places=12)
        self.assertAlmostEqual(max(c[2] for c in corners), 170.0, places=12)

    def test_sweep_box_holder(self):
        path = probe.pose_path([((0, 0, 100), (0, 0, -1), (1, 0, 0)), ((0, 0, 100), (0, 0, -1), (0, 1, 0))])
        self.assertEqual(path.refs, [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])
        r = probe.sweep(self.WALL, path, probe_radius=5, probe_length=40, holder_box_width=40, holder_box_depth=20,
                        holder_box_length=30, continuous=False)
        self.assertEqual([p["collides"] for p in r["points"]], [True, False])
        self.assertTrue(r["points"][0]["holder"])
        self.assertAlmostEqual(r["points"][1]["clearance"], 8.0, places=9)
        with self.assertRaises(ValueError):  # no reference directions
            probe.sweep(self.WALL, probe.pose_path([((0, 0, 100), (0, 0, -1))]), holder_box_width=40,
                        holder_box_depth=20, holder_box_length=30)
        with self.assertRaises(ValueError):  # partly given
            probe.sweep(self.WALL, path, holder_box_width=40)


class Sweep(unittest.TestCase):
    def test_small_sweep_hierarchies_agree(self):
        mesh = probe.make_panel("saddle", 20, 12)
        path = probe.make_panel_path("saddle", lines=3, points_per_line=30, collide_every=11)
        robot = probe.paper_machine()
        ref = probe.sweep(mesh, path, robot, hierarchy="brute", clearance=False, continuous=False)
        self.assertGreater(ref["colliding_points"], 0)
        for h in ("bvh", "patches", "grid", "distance_field"):
            r = probe.sweep(mesh, path, robot, hierarchy=h, clearance=False, continuous=False, threads=1)
            self.assertEqual([p["hits"] for p in r["points"]], [p["hits"] for p in ref["points"]], h)
        full = probe.sweep(mesh, path, robot)
        clear = [p["clearance"] for p in full["points"] if not p["collides"]]
        self.assertTrue(all(7.0 < c < 10.5 for c in clear), min(clear))  # stand-off 10 minus facet sag

    def test_collision_between_samples(self):
        mesh = itf.make_box((-500, -500, 70), (500, 500, 80), 1)
        path = probe.read_path(self._swing(), probe.paper_machine())
        r = probe.sweep(mesh, path, probe.paper_machine())
        self.assertEqual(r["colliding_points"], 0)
        self.assertEqual(r["between_samples_segments"], 1)
        lo, hi = r["segments"][0]["intervals"][0]
        self.assertTrue(0.1 < lo < 0.5 < hi < 0.9)

    def test_probe_inside_a_closed_workpiece_is_a_clash(self):
        # Issue #23, item 3 through Python: the probe wholly inside a closed cube collides.
        cube = itf.make_box((0, 0, 0), (100, 100, 100), 1)
        r = probe.sweep(cube, probe.pose_path([((50, 50, 50), (0, 0, -1))]), probe_radius=5, probe_length=40)
        self.assertTrue(r["points"][0]["collides"])
        self.assertTrue(r["points"][0]["inside"])
        self.assertEqual(r["points"][0]["verdict"], "clash")
        self.assertEqual(r["verdict"], "clash")
        # The same pose 50 mm above the cube is clear, and says so.
        r = probe.sweep(cube, probe.pose_path([((50, 50, 150), (0, 0, -1))]), probe_radius=5, probe_length=40)
        self.assertEqual(r["verdict"], "clear")
        self.assertEqual(r["points"][0]["verdict"], "clear")

    def _swing(self):
        d = tempfile.mkdtemp()
        f = os.path.join(d, "swing.csv")
        with open(f, "w") as out:
            out.write("x,y,z,a,b\n0,0,200,0,-60\n0,0,200,0,60\n")
        return f


if __name__ == "__main__":
    unittest.main()
