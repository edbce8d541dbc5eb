"""Tests of the scene bindings (issue #24, item 7): Body, Scene, ClashTest, Scene.clash, ClashReport,
to_records(), baselines, Scene.from_file.

Run:  PYTHONPATH=<build>/python python3 -m unittest python.tests.test_scene -v
The expectations are computed here from the boxes' coordinates (axis-aligned boxes: which overlap,
touch or lie within a distance is interval arithmetic; the intersection curve of two crossing boxes
is a rectangle on a face), not by the engine.
"""

import base64
import itertools
import json
import math
import os
import struct
import sys
import tempfile
import unittest

import interfere as itf

import numpy as np  # required by the module (issue #30)


def box(lo, hi):
    """A closed, outward box: vertices (8, 3) float64 and triangles (12, 3) int64."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
         (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    return np.array(v, dtype=np.float64), np.array(f, dtype=np.int64)


def signed_volume(v, f):
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


# Bodies (mm). A and B cross (B's x range [8, 18] enters A's [0, 10] by 2, B's y and z ranges inside
# A's), A and D share the face y = 10 (contact), B and D are 2 apart (in y), B and C 3 apart (in x),
# E is far from everything.
BOXES = {
    "A": ((0, 0, 0), (10, 10, 10), ["plate"]),
    "B": ((8, 2, 2), (18, 8, 8), ["pin"]),
    "C": ((21, 0, 0), (31, 10, 10), ["pin"]),
    "D": ((0, 10, 0), (10, 20, 10), ["plate"]),
    "E": ((100, 100, 100), (110, 110, 110), ["spare"]),
}


def gap(p, q):
    """(distance between boxes p and q, whether their interiors overlap)."""
    (plo, phi), (qlo, qhi) = p, q
    d2, overlap = 0.0, True
    for k in range(3):
        g = max(qlo[k] - phi[k], plo[k] - qhi[k], 0.0)
        d2 += g * g
        overlap = overlap and qlo[k] < phi[k] and plo[k] < qhi[k]
    return math.sqrt(d2), overlap


def expected_verdicts(boxes, clearance=0.0, overrides=None):
    """{(id, id): verdict} for every pair that is not clear, by interval arithmetic."""
    out = {}
    for i, j in itertools.combinations(sorted(boxes), 2):
        d, overlap = gap(boxes[i][:2], boxes[j][:2])
        c = (overrides or {}).get((i, j), clearance)
        if overlap:
            out[(i, j)] = "clash"
        elif d == 0:
            out[(i, j)] = "contact"
        elif d < c:
            out[(i, j)] = "clearance"
    return out


def make_scene(boxes=BOXES, units="mm"):
    s = itf.Scene(units=units)
    for k, (lo, hi, tags) in boxes.items():
        v, f = box(lo, hi)
        s.add(itf.Body(k, (v, f), name="body " + k, tags=tags))
    return s


def found(report):
    return {(c.body_a, c.body_b): c.verdict for c in report.clashes}


def ascii_stl(path, v, f):
    with open(path, "w") as out:
        out.write("solid t\n")
        for t in f:
            out.write(" facet normal 0 0 0\n  outer loop\n")
            for i in t:
                out.write("   vertex %r %r %r\n" % tuple(float(x) for x in v[i]))
            out.write("  endloop\n endfacet\n")
        out.write("endsolid t\n")


def gltf_boxes(path, nodes, children, size=2.0**-7):
    """A .gltf (metres) whose nodes all instance one box [0, size]^3: nodes [(name, translation)],
    children {name: [node indices]}. Powers of two: exact in float32 and once scaled to mm."""
    v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
         (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    data = b"".join(struct.pack("<3f", *[c * size for c in p]) for p in v)
    data += b"".join(struct.pack("<3H", *t) for t in f)
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    child = {i for c in children.values() for i in c}
    doc = {"asset": {"version": "2.0"}, "scene": 0,
           "buffers": [{"byteLength": len(data), "uri": uri}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                           {"buffer": 0, "byteOffset": 96, "byteLength": 72}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                          "min": [0, 0, 0], "max": [size] * 3},
                         {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "nodes": [dict(name=n, mesh=0, translation=t, **({"children": children[n]} if n in children else {}))
                     for n, t in nodes],
           "scenes": [{"nodes": [i for i in range(len(nodes)) if i not in child]}]}
    with open(path, "w") as out:
        json.dump(doc, out)


class ScenePython(unittest.TestCase):
    def test_boxes_are_closed_and_outward(self):
        for lo, hi, _ in BOXES.values():
            v, f = box(lo, hi)
            self.assertAlmostEqual(signed_volume(v, f), math.prod(h - l for l, h in zip(lo, hi)))

    def test_body_and_scene_basics(self):
        s = make_scene()
        self.assertEqual(len(s), 5)
        self.assertEqual([b.id for b in s.bodies], list(BOXES))
        self.assertIn("B", s)
        b = s["B"]
        self.assertEqual((b.name, b.path, b.tags, b.num_triangles), ("body B", "/body B", ["pin"], 12))
        self.assertEqual(b.source_kind, "memory")
        self.assertEqual(list(b.source_ids), list(range(12)))
        self.assertTrue(b.pose.is_identity())
        with self.assertRaises(ValueError):
            s.add(itf.Body("A", box((0, 0, 0), (1, 1, 1))))  # duplicate id
        with self.assertRaises(ValueError):
            itf.Scene(units="furlong")
        with self.assertRaises(ValueError):
            itf.Body("x", box((0, 0, 0), (1, 1, 1)), unit="parsec")

    def test_hard_all_pairs_against_interval_arithmetic(self):
        r = make_scene().clash()
        self.assertEqual(found(r), expected_verdicts(BOXES))
        self.assertEqual(r.verdict, "clash")
        self.assertEqual(r.summary["clashes"], 1)
        self.assertEqual(r.summary["contacts"], 1)
        self.assertEqual(r.summary["bodies"], 5)
        ab = next(c for c in r.clashes if c.verdict == "clash")
        self.assertEqual((ab.body_a, ab.body_b, ab.kind, ab.status, ab.run_status), ("A", "B", "crossing", "new", "new"))
        # The curve is B's cross-section [2, 8]^2 on A's face x = 10: length 4 x 6, box of that square.
        self.assertAlmostEqual(ab.curve_length, 24.0, places=9)
        (lo, hi) = ab.box
        for got, want in zip(lo + hi, (10, 2, 2, 10, 8, 8)):
            self.assertAlmostEqual(got, want, places=9)
        self.assertEqual(ab.point.shape, (3,))
        self.assertAlmostEqual(float(ab.point[0]), 10.0, places=9)
        self.assertTrue(2 - 1e-9 <= ab.point[1] <= 8 + 1e-9 and 2 - 1e-9 <= ab.point[2] <= 8 + 1e-9)
        # Depth: the deepest point of either surface inside the other solid is 2 from its surface
        # (B's face x = 8 in A, A's face x = 10 in B); depth is a sampled lower bound, depth_bound an
        # upper bound.
        self.assertGreater(ab.depth, 0)
        self.assertLessEqual(ab.depth, 2 + 1e-9)
        self.assertGreaterEqual(ab.depth_bound, 2 - 1e-9)
        self.assertGreater(ab.cross_pairs, 0)
        self.assertEqual(ab.source_ids_a.dtype, np.int64)
        self.assertTrue(set(ab.source_ids_a.tolist()) <= set(range(12)))
        ad = next(c for c in r.clashes if c.verdict == "contact")
        self.assertEqual((ad.body_a, ad.body_b), ("A", "D"))
        self.assertGreater(ad.touch_pairs, 0)
        self.assertEqual(ad.cross_pairs, 0)
        (lo, hi) = ad.box  # the common face y = 10
        self.assertAlmostEqual(lo[1], 10.0, places=9)
        self.assertAlmostEqual(hi[1], 10.0, places=9)
        self.assertEqual([(p["body_a"], p["body_b"], p["verdict"]) for p in r.pairs],
                         [("A", "B", "clash"), ("A", "D", "contact")])
        self.assertEqual(len(r.groups), 2)  # group_by="pair"
        self.assertEqual(len(r), 2)

    def test_clearance_with_override(self):
        s = make_scene()
        r = s.clash(itf.ClashTest("clr", mode="clearance", clearance=2.5))
        self.assertEqual(found(r), expected_verdicts(BOXES, 2.5))
        bd = next(c for c in r.clashes if c.verdict == "clearance")
        self.assertEqual((bd.body_a, bd.body_b, bd.kind), ("B", "D", "clearance"))
        self.assertAlmostEqual(bd.distance, 2.0, places=9)
        self.assertAlmostEqual(float(bd.witness_b[1] - bd.witness_a[1]), 2.0, places=9)
        t = itf.ClashTest("clr", mode="clearance", clearance=2.5, clearance_overrides=[("id:B", "id:C", 3.5)])
        self.assertEqual(t.clearance_overrides, [(["id:B"], ["id:C"], 3.5)])
        r = s.clash([t])
        self.assertEqual(found(r), expected_verdicts(BOXES, 2.5, {("B", "C"): 3.5}))
        self.assertAlmostEqual(next(c for c in r.clashes if c.body_b == "C").distance, 3.0, places=9)
        self.assertEqual(r.summary["clearances"], 2)

    def test_selections_suppression_and_tolerance(self):
        s = make_scene()
        across = s.clash(itf.ClashTest("x", a="tag:plate", b=["tag:pin"]))
        self.assertEqual(found(across), {("A", "B"): "clash"})  # A-D: both plates, not tested
        sup = s.clash(itf.ClashTest(suppress=[("id:A", "id:B", "designed press fit")]))
        self.assertEqual(found(sup), {("A", "D"): "contact"})
        self.assertEqual(sup.summary["suppressed"], 1)
        shallow = s.clash(itf.ClashTest(tolerance=1.0))  # depth 2 > 1: still a clash
        self.assertEqual(found(shallow)[("A", "B")], "clash")
        tol = s.clash(itf.ClashTest(tolerance=10.0))  # depth 2 (bound within 10 %) <= 10: a contact
        ab = next(c for c in tol.clashes if c.body_b == "B")
        self.assertEqual((ab.verdict, ab.kind), ("contact", "within_tolerance"))
        self.assertEqual(tol.verdict, "contact")
        parsed = itf.ClashTest.parse("pins: tag:pin vs tag:plate clearance 2.5")
        self.assertEqual((parsed.name, parsed.a, parsed.b, parsed.mode, parsed.clearance),
                         ("pins", ["tag:pin"], ["tag:plate"], "clearance", 2.5))
        r = s.clash(parsed)
        self.assertEqual(found(r), {k: v for k, v in expected_verdicts(BOXES, 2.5).items()
                                    if {BOXES[k[0]][2][0], BOXES[k[1]][2][0]} == {"pin", "plate"}})
        with self.assertRaises(ValueError):
            itf.ClashTest(mode="sideways")
        with self.assertRaises(ValueError):
            itf.ClashTest(mode="clearance")  # no clearance given
        with self.assertRaises(ValueError):
            itf.ClashTest(tolerance=-1)
        with self.assertRaises(ValueError):
            s.clash([itf.ClashTest("t"), itf.ClashTest("t")])  # duplicate test names

    def test_records_are_plain_and_match_the_clashes(self):
        r = make_scene().clash(itf.ClashTest("clr", mode="clearance", clearance=2.5))
        records = r.to_records()
        self.assertEqual(len(records), len(r.clashes))
        plain = (str, int, float, bool, type(None))
        for rec, c in zip(records, r.clashes):
            self.assertTrue(all(type(v) in plain for v in rec.values()), rec)
            self.assertEqual((rec["id"], rec["verdict"], rec["body_a"], rec["body_b"], rec["kind"]),
                             (c.id, c.verdict, c.body_a, c.body_b, c.kind))
            self.assertEqual((rec["x"], rec["y"], rec["z"]), tuple(float(v) for v in c.point))
            self.assertEqual(rec["depth_bound"], c.depth_bound)
            self.assertEqual(rec["name_a"], "body " + c.body_a)
        self.assertEqual(json.loads(json.dumps(records)), records)
        csv = r.to_csv().splitlines()
        self.assertTrue(csv[0].startswith("id,test,status,verdict,kind,body_a"))
        self.assertEqual(len(csv), 1 + len(records))
        try:
            import pandas as pd
        except ImportError:
            return  # pandas is optional: the plain dicts above are what it would take
        df = pd.DataFrame(records)
        self.assertEqual(list(df["verdict"]), [c.verdict for c in r.clashes])

    def test_json_report_and_thread_independence(self):
        s = make_scene()
        one = s.clash(threads=1)
        two = s.clash(threads=2)
        self.assertEqual(one.to_records(), two.to_records())
        j = json.loads(one.to_json())
        self.assertEqual(j["schema"], "interfere.scene-clash")
        self.assertEqual(j["verdict"], "clash")
        self.assertEqual([c["id"] for c in j["clashes"]], [c.id for c in one.clashes])
        self.assertEqual(one.exit_status(), 1)
        self.assertEqual(s.clash(itf.ClashTest(a="id:C,id:E")).exit_status(), 0)

    def test_json_report_validates_against_the_schema(self):
        # The CLI's clash report (issue #30, item 4): docs/schema/report.schema.json and
        # clash.schema.json (tests/cli/report_schema.py; skipped without python3-jsonschema).
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli"))
        import report_schema
        if not report_schema.AVAILABLE:
            self.skipTest("python3-jsonschema is not installed")
        for r in (make_scene().clash(), make_scene().clash(itf.ClashTest(a="id:C,id:E"))):
            j = json.loads(r.to_json())
            self.assertEqual(j["command"], "clash")
            self.assertTrue(report_schema.is_report(j))
            self.assertEqual(report_schema.errors(j), [])

    def test_grouping(self):
        # The A-B clash box (x = 10, y, z in [2, 8]) and the A-D contact face (y = 10) are 2 apart.
        s = make_scene()
        self.assertEqual(s.clash(group_by=None).groups, [])
        apart = s.clash(group_by="location")
        self.assertEqual(sorted(len(g["clashes"]) for g in apart.groups), [1, 1])
        near = s.clash(group_by="location", group_distance=3)
        self.assertEqual([sorted(g["clashes"]) for g in near.groups], [sorted(c.id for c in near.clashes)])
        with self.assertRaises(ValueError):
            s.clash(group_by="colour")

    def test_ids_survive_reordering(self):
        shuffled = make_scene(dict(reversed(list(BOXES.items()))))
        self.assertEqual([c.id for c in make_scene().clash().clashes], [c.id for c in shuffled.clash().clashes])

    def test_baseline_round_trip(self):
        s = make_scene()
        first = s.clash()
        report = json.loads(first.to_json())
        ab = next(c for c in report["clashes"] if c["verdict"] == "clash")
        ab["status"] = "approved"
        ab["assignee"] = "kim"
        second = s.clash(baseline=report)  # a dict
        c = next(c for c in second.clashes if c.id == ab["id"])
        self.assertEqual((c.status, c.run_status), ("approved", "active"))
        self.assertEqual(c.user_fields, {"status": "approved", "assignee": "kim"})
        rec = next(x for x in second.to_records() if x["id"] == ab["id"])
        self.assertEqual((rec["status"], rec["run_status"], rec["assignee"]), ("approved", "active", "kim"))
        self.assertTrue(all(x.run_status == "active" for x in second.clashes))
        # Without D the contact is resolved (listed once), a new body's clash is new; text and path work.
        t = dict(BOXES)
        del t["D"]
        t["F"] = ((1, 1, 1), (3, 3, 3), ["pin"])  # inside A: a clash (kind "inside")
        third = make_scene(t).clash(baseline=second.to_json())
        self.assertEqual([(x.body_a, x.body_b, x.run_status, x.verdict) for x in third.resolved],
                         [("A", "D", "resolved", "contact")])
        self.assertEqual({(x.body_a, x.body_b): x.run_status for x in third.clashes},
                         {("A", "B"): "active", ("A", "F"): "new"})
        self.assertEqual(next(x for x in third.clashes if x.body_b == "B").status, "approved")
        last = third.to_records()[-1]  # resolved clashes follow, from the baseline's fields
        self.assertEqual((last["run_status"], last["status"], last["body_a"], last["body_b"], last["verdict"]),
                         ("resolved", "resolved", "A", "D", "contact"))
        self.assertEqual(len(third.to_records(resolved=False)), 2)
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "third.json")
            with open(p, "w") as out:
                out.write(third.to_json())
            fourth = make_scene(t).clash(baseline=p)
        self.assertEqual(fourth.resolved, [])
        with self.assertRaises(itf.InputError):
            s.clash(baseline={"schema": "something else"})

    def test_motion_frames(self):
        s = make_scene()
        s.add_frame("start", 0.0)
        s.add_frame("B lifted", 1.0, poses={"B": itf.Transform.translation((0, 0, 50))})
        self.assertEqual(s.num_frames, 2)
        r = s.clash()
        self.assertEqual([(f["clashes"], f["contacts"]) for f in r.frames], [(1, 1), (0, 1)])
        ab = next(c for c in r.clashes if c.body_b == "B")
        self.assertEqual(ab.frames, [0])
        with self.assertRaises(ValueError):
            s.add_frame("bad", poses={"nobody": itf.Transform()})

    def test_scene_file_with_two_stl_files(self):
        with tempfile.TemporaryDirectory() as d:
            va, fa = box((0, 0, 0), (10, 10, 10))
            vb, fb = box((0.8, 0.2, 0.2), (1.8, 0.8, 0.8))  # B of BOXES, in cm
            ascii_stl(os.path.join(d, "plate.stl"), va, fa)
            ascii_stl(os.path.join(d, "pin.stl"), vb, fb)
            with open(os.path.join(d, "scene.json"), "w") as out:
                json.dump({"units": "mm",
                           "bodies": [{"file": "plate.stl", "id": "A", "tags": ["plate"]},
                                      {"file": "pin.stl", "id": "B", "units": "cm", "tags": ["pin"],
                                       "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0]}],
                           "tests": [{"name": "fit", "a": ["tag:plate"], "b": ["tag:pin"], "mode": "hard"}]},
                          out)
            s = itf.Scene.from_file(os.path.join(d, "scene.json"))
            self.assertEqual([b.id for b in s.bodies], ["A", "B"])
            self.assertEqual([t.name for t in s.tests], ["fit"])
            pin = s["B"]
            self.assertEqual((pin.unit, pin.mesh_unit, pin.source_kind), ("cm", "mm", "mesh_file"))
            lo, hi = pin.mesh.bounds()
            for got, want in zip(lo + hi, (8, 2, 2, 18, 8, 8)):
                self.assertAlmostEqual(got, want, places=9)
            r = s.clash()
            self.assertEqual([(c.test, c.body_a, c.body_b, c.verdict) for c in r.clashes], [("fit", "A", "B", "clash")])
            self.assertAlmostEqual(r.clashes[0].curve_length, 24.0, places=9)
            # The same body read directly, converted when added.
            body = itf.Body.from_file(os.path.join(d, "pin.stl"), units="cm")
            self.assertEqual((body.id, body.mesh_unit), ("pin", "cm"))
            s2 = itf.Scene()
            s2.add(body)
            self.assertAlmostEqual(s2["pin"].mesh.bounds()[1][0], 18.0, places=9)
            # Bad input: an unknown key names the JSON path; a missing file is an input error too.
            with open(os.path.join(d, "bad.json"), "w") as out:
                json.dump({"bodies": [{"file": "plate.stl", "colour": "red"}]}, out)
            with self.assertRaises(itf.InputError) as e:
                itf.Scene.from_file(os.path.join(d, "bad.json"))
            self.assertIn("colour", str(e.exception))
            with self.assertRaises(itf.InputError):
                itf.Scene.from_file(os.path.join(d, "missing.json"))

    def test_gltf_scene_nodes(self):
        # Boxes of 2^-7 m = 7.8125 mm: "right" 2^-9 m = 1.953125 mm right of "left"; "up", a child of
        # "right", 7.8125 mm above it (its world pose composes both): a face contact with "right",
        # and 1.953125 mm from "left" (diagonally: x gap 1.953125, y ranges touch).
        e, g = 2.0 ** -7, 2.0 ** -9
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "cell.gltf")
            gltf_boxes(p, [("left", [0, 0, 0]), ("right", [e + g, 0, 0]), ("up", [0, e, 0])], {"right": [2]})
            s = itf.Scene.from_gltf(p)
            self.assertEqual([(b.name, b.path, b.source_kind) for b in s.bodies],
                             [("left", "/left", "gltf_node"), ("right", "/right", "gltf_node"),
                              ("up", "/right/up", "gltf_node")])
            self.assertEqual(s.bodies[2].pose.t, (1000 * (e + g), 1000 * e, 0.0))
            boxes = {"/left": ((0, 0, 0), (1000 * e,) * 3, []),
                     "/right": ((1000 * (e + g), 0, 0), (1000 * (2 * e + g), 1000 * e, 1000 * e), []),
                     "/right/up": ((1000 * (e + g), 1000 * e, 0), (1000 * (2 * e + g), 2000 * e, 1000 * e), [])}
            self.assertEqual([b.id for b in s.bodies], list(boxes))
            r = s.clash(itf.ClashTest(mode="clearance", clearance=3))
            self.assertEqual(found(r), expected_verdicts(boxes, 3))
            for c in r.clashes:
                want, _ = gap(boxes[c.body_a][:2], boxes[c.body_b][:2])
                self.assertAlmostEqual(c.distance, want, places=9)

    def test_fe_model_in_a_scene_file(self):
        # An Abaqus deck with two hex8 elements in two element sets: two bodies, 2 mm apart in x,
        # whose triangles carry the solver's element ids (101, 102).
        boxes = {"LEFT": ((0, 0, 0), (10, 10, 10)), "RIGHT": ((12, 0, 0), (22, 10, 10))}
        corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
        lines, n = ["*NODE"], 0
        for lo, hi in boxes.values():
            for c in corners:
                n += 1
                lines.append("%d, %s" % (n, ", ".join(repr(float(lo[k] + (hi[k] - lo[k]) * c[k])) for k in range(3))))
        for e, name in enumerate(boxes):
            lines += ["*ELEMENT, TYPE=C3D8, ELSET=%s" % name,
                      "%d, %s" % (101 + e, ", ".join(str(8 * e + k + 1) for k in range(8)))]
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "model.inp"), "w") as out:
                out.write("\n".join(lines) + "\n")
            with open(os.path.join(d, "scene.json"), "w") as out:
                json.dump({"bodies": [{"file": "model.inp", "id": "fe", "tags": ["fe"]}]}, out)
            s = itf.Scene.from_file(os.path.join(d, "scene.json"))
        self.assertEqual(len(s), 2)
        self.assertTrue(all(b.source_kind == "fe_body" and b.tags == ["fe"] for b in s.bodies))
        self.assertEqual([sorted(set(b.source_ids.tolist())) for b in s.bodies], [[101], [102]])
        r = s.clash(itf.ClashTest(mode="clearance", clearance=3))
        self.assertEqual([(c.verdict, c.distance) for c in r.clashes], [("clearance", 2.0)])
        self.assertEqual((r.clashes[0].source_ids_a.tolist(), r.clashes[0].source_ids_b.tolist()), ([101], [102]))

    @unittest.skipUnless(itf.HAVE_CAD, "built without OpenCASCADE")
    def test_step_assembly_in_a_scene_file(self):
        # tests/cli/data/assembly.step: two 10 mm plates, plate_2 placed at z = 20 (10 mm above
        # plate's top face), and a shaft clear of both (test_simplify.py's assembly-clash test).
        step = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "cli", "data", "assembly.step")
        with open(step) as f:
            text = f.read()
        self.assertIn("#20 = CARTESIAN_POINT('',(0.,0.,20.));", text)
        with tempfile.TemporaryDirectory() as d:
            for lift, verdict, distance in (("(0.,0.,20.)", "clearance", 1.0), ("(0.,0.,10.)", "contact", 0.0)):
                with open(os.path.join(d, "asm.step"), "w") as out:
                    out.write(text.replace("(0.,0.,20.)", lift))
                with open(os.path.join(d, "scene.json"), "w") as out:
                    json.dump({"units": "cm", "bodies": [{"file": "asm.step", "id": "asm", "tags": ["cad"]}]}, out)
                s = itf.Scene.from_file(os.path.join(d, "scene.json"))
                self.assertEqual([b.name for b in s.bodies], ["plate", "plate_2", "shaft_1"])
                self.assertTrue(all(b.source_kind == "step_instance" and b.id.startswith("asm/") for b in s.bodies))
                self.assertEqual(s.bodies[0].source_id_kind, "brep_face")
                r = s.clash(itf.ClashTest(mode="clearance", clearance=1.5))  # 15 mm in cm
                self.assertEqual([(s[c.body_a].name, s[c.body_b].name, c.verdict) for c in r.clashes],
                                 [("plate", "plate_2", verdict)])
                self.assertAlmostEqual(r.clashes[0].distance, distance, places=9)


if __name__ == "__main__":
    unittest.main()
