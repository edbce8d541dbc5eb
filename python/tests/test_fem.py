"""Tests of the FEM bindings (read_fem, generators, extract_surface, clash_series).

Run:  PYTHONPATH=<build>/python python3 -m unittest discover -s python/tests -p 'test_fem.py' -v
Expected values are analytic (box volume and area, a block moving toward another by a known step).
"""

import os
import tempfile
import unittest

import interfere as itf


def rows(x):
    return [tuple(float(v) for v in r) for r in (x.tolist() if hasattr(x, "tolist") else x)]


def signed_volume(mesh):
    p = rows(mesh.positions)
    s = 0.0
    for t in (x.tolist() if hasattr(x := mesh.triangles, "tolist") else x):
        a, b, c = p[t[0]], p[t[1]], p[t[2]]
        s += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
    return s


class FemPython(unittest.TestCase):
    def test_box_surface_is_closed_with_the_box_volume(self):
        for t in ("tet4", "tet10", "hex8", "hex20", "hex27", "wedge6", "wedge15", "pyr5"):
            mesh, volume, area = itf.make_fem_box(t, (2, 3, 2), (0, 0, 0), (1, 2, 3))
            self.assertEqual(volume, 6.0)
            s = itf.extract_surface(mesh)
            self.assertEqual(len(s["parts"]), 1, t)
            part = s["parts"][0]
            self.assertTrue(itf.mesh_stats(part["mesh"]).closed, t)
            self.assertAlmostEqual(signed_volume(part["mesh"]), 6.0, places=9)
            ids = set(int(i) for i in part["tri_element_id"])
            self.assertTrue(ids <= set(int(i) for i in mesh.element_ids))
            self.assertEqual(len(part["tri_face"]), len(rows(part["mesh"].triangles)))

    def test_threads_give_identical_surfaces(self):
        mesh, _, _ = itf.make_fem_sphere("tet10", (6, 6, 6), 1.0)
        a = itf.extract_surface(mesh, threads=1)["parts"][0]
        b = itf.extract_surface(mesh, threads=2)["parts"][0]
        self.assertEqual(rows(a["mesh"].triangles), rows(b["mesh"].triangles))
        self.assertEqual(list(a["tri_element"]), list(b["tri_element"]))

    def test_clash_series_onset_step(self):
        a, _, _ = itf.make_fem_box("hex8", (4, 4, 4))
        b, _, _ = itf.make_fem_box("tet4", (3, 3, 3), (1.5, 0.3, 0.3), (2.5, 1.3, 1.3))
        n = b.num_nodes
        steps = [[(-0.125 * s, 0.0, 0.0)] * n for s in range(8)]
        r = itf.clash_series(a, "", None, b, "", steps)
        self.assertEqual(r["num_steps"], 8)
        # gap 0.5 closes at 4 x 0.125: touching is a contact, the clash starts at 5 (issue #23, item 13)
        self.assertEqual(r["first_contact_step"], 4)
        self.assertEqual(r["first_clash_step"], 5)
        self.assertEqual(r["verdict"], "clash")
        self.assertEqual([row["interference"] for row in r["steps"]], [s >= 4 for s in range(8)])
        self.assertEqual([row["verdict"] for row in r["steps"][:6]], ["clear"] * 4 + ["contact", "clash"])
        self.assertTrue(r["first_clash"].interference)
        self.assertGreater(len(r["first_clash_regions"]), 0)
        r2 = itf.clash_series(a, "", None, b, "", steps, scale=2.0, steps=[1, 2, 3])
        self.assertEqual(r2["first_contact_step"], 2)
        self.assertEqual(r2["first_clash_step"], 3)
        with self.assertRaises(ValueError):
            itf.clash_series(a, "", None, b, "", steps, steps=[9])
        with self.assertRaises(ValueError):
            itf.clash_series(a, "nobody", None, b, "", steps)

    def test_clash_series_depth_names_the_deepest_node(self):
        # Issue #26, item 3. A = [0,1]^3, B = [1.5,2.5] x [0.3,1.3]^2 moving -0.125 per step: the
        # deepest surface node of each clashing step against the boxes' geometry (a point strictly
        # inside a box lies min(p - lo, hi - p) over the axes from its surface).
        a, _, _ = itf.make_fem_box("hex8", (4, 4, 4))
        b, _, _ = itf.make_fem_box("tet4", (3, 3, 3), (1.5, 0.3, 0.3), (2.5, 1.3, 1.3))
        steps = [[(-0.125 * s, 0.0, 0.0)] * b.num_nodes for s in range(12)]
        r = itf.clash_series(a, "", None, b, "", steps)

        def inside(p, lo, hi):
            d = min(min(p[k] - lo[k], hi[k] - p[k]) for k in range(3))
            return max(d, 0.0)
        nodes = {"a": rows(a.nodes), "b": rows(b.nodes)}
        ids = {"a": [int(i) for i in a.node_ids], "b": [int(i) for i in b.node_ids]}
        surface = {"a": itf.extract_surface(a)["parts"][0], "b": itf.extract_surface(b)["parts"][0]}
        measured = 0
        for row in r["steps"]:
            k = row["step"]
            if row["verdict"] != "clash":
                self.assertIsNone(row["depth"], k)
                self.assertIsNone(row["deepest"], k)
                continue
            x0 = 1.5 - 0.125 * k
            boxes = {"a": ((x0, 0.3, 0.3), (x0 + 1, 1.3, 1.3)), "b": ((0, 0, 0), (1, 1, 1))}  # the other part's

            def depth_of(part, n):
                p = list(nodes[part][n])
                if part == "b":
                    p[0] -= 0.125 * k
                return inside(p, *boxes[part])
            best = max(depth_of(part, int(n)) for part in "ab" for n in surface[part]["vertex_node"])
            d = row["deepest"]
            self.assertAlmostEqual(d["depth"], best, places=12, msg=k)
            self.assertAlmostEqual(depth_of(d["part"], ids[d["part"]].index(d["node"])), best, places=12, msg=k)
            self.assertGreaterEqual(row["depth"], best - 1e-12)
            self.assertGreaterEqual(row["depth_bound"], row["depth"] - 1e-12)
            measured += 1
        self.assertEqual(measured, 7)  # steps 5..11
        self.assertIsNotNone(r["deepest_step"])
        off = itf.clash_series(a, "", None, b, "", steps, depth=False)
        self.assertTrue(all(row["depth"] is None for row in off["steps"]))

    def test_read_fem_fields_and_csv(self):
        # Two unit hexes 0.5 apart in one MSH 2.2 file (bodies "left", "right"); "right" moves by -0.25
        # per step (field "disp" and the same values as CSV): touching at step 2, overlapping at 3.
        nodes = []
        for b, x0 in ((0, 0.0), (1, 1.5)):
            for k in range(2):
                for j in range(2):
                    for i in range(2):
                        nodes.append((100 * b + 1 + i + 2 * j + 4 * k, (x0 + i, float(j), float(k))))
        hexes = [[1, 2, 4, 3, 5, 6, 8, 7], [101, 102, 104, 103, 105, 106, 108, 107]]
        lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "2", '3 1 "left"', '3 2 "right"',
                 "$EndPhysicalNames", "$Nodes", str(len(nodes))]
        lines += ["%d %r %r %r" % (n, *p) for n, p in nodes]
        lines += ["$EndNodes", "$Elements", "2"]
        lines += ["%d 5 2 %d %d %s" % (e + 1, e + 1, e + 1, " ".join(map(str, h))) for e, h in enumerate(hexes)]
        lines += ["$EndElements"]
        csv = ["step,node_id,ux,uy,uz"]
        for s in range(4):
            lines += ["$NodeData", "1", '"disp"', "1", repr(float(s)), "3", str(s), "3", str(len(nodes))]
            for n, _ in nodes:
                ux = -0.25 * s if n > 100 else 0.0
                lines.append("%d %r 0 0" % (n, ux))
                csv.append("%d,%d,%r,0,0" % (s, n, ux))
            lines.append("$EndNodeData")
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "two.msh")
            with open(p, "w") as f:
                f.write("\n".join(lines) + "\n")
            c = os.path.join(d, "disp.csv")
            with open(c, "w") as f:
                f.write("\n".join(csv) + "\n")
            mesh = itf.read_fem(p)
            self.assertEqual(mesh.num_elements, 2)
            self.assertEqual(mesh.fields, ["disp"])
            self.assertEqual(len(mesh.field("disp")["values"]), 4)
            parts = itf.extract_surface(mesh)["parts"]
            self.assertEqual([q["name"] for q in parts], ["left", "right"])
            self.assertEqual(sorted(set(int(i) for i in parts[1]["tri_element_id"])), [2])
            r = itf.clash_series(mesh, "left", None, mesh, "right", "disp")
            self.assertEqual(r["first_contact_step"], 2)  # touching: a contact
            self.assertEqual(r["first_clash_step"], 3)
            self.assertEqual([int(x) for x in r["first_clash_regions"][0]["elements_b"]], [2])
            u = itf.read_displacements_csv(c, mesh)
            self.assertEqual(len(u["values"]), 4)
            r = itf.clash_series(mesh, "left", None, mesh, "right", u)
            self.assertEqual(r["first_clash_step"], 3)

    def test_read_fem_and_errors(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "bad.msh")
            with open(p, "w") as f:
                f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n")
            with self.assertRaises(itf.InputError) as e:
                itf.read_fem(p)
            self.assertEqual(e.exception.file, p)
        with self.assertRaises(ValueError):
            itf.make_fem_box("tet7")


if __name__ == "__main__":
    unittest.main()
