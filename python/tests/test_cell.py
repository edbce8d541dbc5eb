"""Tests of `interfere.cell` (issue #28): the example cell of examples/probe along its joint path and
along the same line as a pose path (numerical inverse kinematics), per-point verdicts as numpy
arrays (the example's colliding points 5-7 and 12-14, as its README and `interfere cell` report
them), the conservative check between points, forward/inverse kinematics round trips on both
shipped arms, and bad input (InputError naming the file and line, ValueError for bad arrays).

Run:  PYTHONPATH=<build>/python python3 -m unittest discover -s python/tests -p 'test_cell.py'
"""

import os
import unittest

import numpy as np

import interfere as itf

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "probe")
START = [-18, -93, 141, -138, -90, 162]  # path.csv's first row, rounded: the elbow-up branch


@unittest.skipUnless(itf.cell.has_urdf_reader(), "built without urdfdom")
class CellRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cell = itf.cell.read_cell(os.path.join(EXAMPLE, "cell.json"))

    def test_properties(self):
        c = self.cell
        self.assertEqual(c.joint_names, ["shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"])
        self.assertEqual(c.dof, 6)
        self.assertEqual(c.limits.shape, (6, 2))
        self.assertTrue(np.all(c.limits[:, 0] < c.limits[:, 1]))
        self.assertEqual(c.tool_link, "tool0")
        self.assertTrue(c.path.endswith("path.csv"))

    def test_joint_path_per_point_arrays(self):
        r = self.cell.run()  # the cell's own path.csv
        self.assertEqual(r["verdict"], "clash")
        self.assertEqual(r["points"], 15)
        self.assertEqual(r["verdicts"].shape, (15,))
        self.assertEqual(r["collides"].dtype, np.bool_)
        self.assertEqual(r["tip"].shape, (15, 3))
        self.assertEqual(r["joints"].shape, (15, 6))
        self.assertEqual(list(r["colliding_points"]), [5, 6, 7, 12, 13, 14])
        self.assertEqual(list(np.nonzero(r["collides"])[0]), [5, 6, 7, 12, 13, 14])
        self.assertTrue(all(v == ("clash" if i in (5, 6, 7, 12, 13, 14) else "clear") for i, v in enumerate(r["verdicts"])))
        found = {(p["a"], p["b"]) for p in r["pairs"] if p["verdict"] == "clash"}
        self.assertEqual(found, {("probe", "workpiece"), ("fixture:clamp", "holder")})
        np.testing.assert_allclose(r["tip"][:, 2], 10.0, atol=1e-5)  # path.csv: 6 decimals
        np.testing.assert_allclose(r["tip"][:, 0], np.arange(350, 701, 25), atol=1e-4)
        # The same joints as an array: the same verdicts, lines 1..n.
        joints, lines = self.cell.read_joint_path(os.path.join(EXAMPLE, "path.csv"))
        r2 = self.cell.run(joints)
        self.assertEqual(list(r2["verdicts"]), list(r["verdicts"]))
        self.assertEqual(list(r2["lines"]), list(range(1, 16)))
        self.assertEqual(list(r["lines"]), list(lines))

    def test_pose_path_and_continuous(self):
        r = self.cell.run(poses=os.path.join(EXAMPLE, "paper_path.csv"), start=START, continuous=True)
        self.assertEqual(list(r["colliding_points"]), [5, 6, 7, 12, 13, 14])
        np.testing.assert_allclose(r["tip"][:, 2], 10.0, atol=1e-9)
        np.testing.assert_allclose(r["axis"], np.tile([0, 0, -1.0], (15, 1)), atol=1e-12)
        self.assertEqual(list(r["ik"]["seed"]), ["start"] + ["previous"] * 14)
        self.assertLess(r["ik"]["tip_error"].max(), 1e-9)
        self.assertEqual(r["segment_states"].shape, (14,))
        colliding = [k for k, s in enumerate(r["segment_states"]) if s == "collides"]
        self.assertEqual(colliding, [4, 5, 6, 7, 11, 12, 13])
        self.assertTrue(all(s == "clear" for k, s in enumerate(r["segment_states"]) if k not in colliding))
        self.assertTrue(np.all(np.isnan(r["segment_t"][[0, 1, 2, 3, 8, 9, 10]])))
        # The poses as an array give the same joints.
        arr = np.array([[x, 0, 10, 0, 0, -1] for x in range(350, 701, 25)], float)
        r2 = self.cell.pose_path_to_joints(arr, start=START)
        np.testing.assert_allclose(r2["joints"], r["joints"], atol=1e-9)

    def test_inverse_kinematics_round_trip_both_arms(self):
        rng = np.random.default_rng(28)
        for name in ("cell.json", "cell_industrial.json"):
            c = itf.cell.read_cell(os.path.join(EXAMPLE, name))
            lo, hi = np.maximum(c.limits[:, 0], -180), np.minimum(c.limits[:, 1], 180)
            for _ in range(10):
                q0 = rng.uniform(lo, hi)
                tip, axis = c.forward(q0)
                q = c.inverse_kinematics(tip, axis)
                self.assertTrue(np.all((q >= c.limits[:, 0]) & (q <= c.limits[:, 1])))
                tip2, axis2 = c.forward(q)
                self.assertLess(np.linalg.norm(tip2 - tip), 1e-9)
                self.assertLess(np.linalg.norm(np.cross(axis2, axis)), 1e-9)
                # the link poses carry the tool: tool0 * (0, 0, 130) is the tip
                t = c.link_poses(q)["tool0"]
                np.testing.assert_allclose(t[:, :3] @ [0, 0, 130.0] + t[:, 3], tip2, atol=1e-9)

    def test_errors(self):
        c = self.cell
        with self.assertRaises(itf.InputError) as cm:
            c.run(poses=np.array([[400, 0, 10, 0, 0, -1], [9000, 0, 10, 0, 0, -1]], float))
        self.assertEqual(cm.exception.line, 2)
        self.assertIn("unreachable", cm.exception.reason)
        with self.assertRaises(itf.InputError):
            c.inverse_kinematics([9000, 0, 0], [0, 0, -1])
        with self.assertRaises(ValueError):
            c.run(np.zeros((3, 5)))
        with self.assertRaises(ValueError):
            c.run(np.full((2, 6), 400.0))  # outside the limits
        with self.assertRaises(ValueError):
            c.run(np.zeros((2, 6)), poses=np.zeros((2, 6)))
        with self.assertRaises(itf.InputError) as cm:
            itf.cell.read_cell(os.path.join(EXAMPLE, "missing.json"))
        self.assertIn("missing.json", str(cm.exception))


if __name__ == "__main__":
    unittest.main()
