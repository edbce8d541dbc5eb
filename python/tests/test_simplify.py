"""Python bindings of the simplification module and the CAD pipeline (issue #6).

Run: PYTHONPATH=build/python python3 -m unittest discover -s python/tests -p 'test_simplify.py'
"""
import json
import os
import shutil
import subprocess
import tempfile
import unittest

import interfere as itf

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "cli", "data")
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def cli_path():
    """The `interfere` CLI: $INTERFERE_CLI, the build tree's (beside the module's build directory), or PATH."""
    env = os.environ.get("INTERFERE_CLI")
    if env:
        return env
    built = os.path.join(os.path.dirname(os.path.abspath(itf.__file__)), "..", "..", "apps", "cli", "interfere")
    return built if os.access(built, os.X_OK) else shutil.which("interfere")


def cap_faces(mesh):
    pos = [tuple(p) for p in mesh.positions]
    return [1 if sum(pos[i][2] for i in t) / 3 > 0.9 else 0 for t in (tuple(int(x) for x in tri) for tri in mesh.triangles)]


def plate_2_screw_process(d):
    """A process file in d: step P1 screws instance plate_2 of the test assembly."""
    proc = os.path.join(d, "p.json")
    with open(proc, "w") as out:
        json.dump({"steps": [{"id": "P1", "parts": ["plate_2"], "constraint": "screw"}]}, out)
    return proc


class Simplify(unittest.TestCase):
    def test_budget_error_bound_and_no_self_intersections(self):
        s = itf.make_sphere(4000)
        r = itf.simplify(s, target=400)
        self.assertEqual(len(r.mesh.triangles), 400)
        self.assertTrue(r.reached)
        self.assertGreater(r.hausdorff, 0)
        self.assertGreaterEqual(r.error_bound, r.hausdorff)
        self.assertEqual(itf.count_self_intersections(r.mesh), 0)
        names = [name for name, _ in r.phases]  # wall time per phase, in order
        self.assertEqual(names[0], "weld")
        self.assertIn("heap", names)
        self.assertTrue(all(sec >= 0 for _, sec in r.phases))
        self.assertFalse(r.guard_rerun)
        self.assertEqual(r.guard_reruns, 0)
        a_to_b, b_to_a = itf.hausdorff(s, r.mesh)
        self.assertAlmostEqual(max(a_to_b, b_to_a), r.hausdorff)
        self.assertFalse(r.one_below)
        odd = itf.simplify(s, target=401, measure_error=False)  # a closed mesh loses triangles in pairs
        self.assertEqual(len(odd.mesh.triangles), 400)
        self.assertTrue(odd.one_below)
        self.assertFalse(odd.reached)

    def test_the_inputs_own_contacts_are_inherited(self):
        # Two flat sheets tessellated apart, overlapping by 1e-6 along x = 1 (a crack).
        def sheet(n, x0):
            pos = [(x0 + i / n, j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
            tri = []
            for j in range(n):
                for i in range(n):
                    a = j * (n + 1) + i
                    tri += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
            return pos, tri
        p0, t0 = sheet(8, 0.0)
        p1, t1 = sheet(13, 1.0 - 1e-6)
        m = itf.TriMesh(p0 + p1, t0 + [(a + len(p0), b + len(p0), c + len(p0)) for a, b, c in t1])
        own = itf.count_self_intersections(m)
        self.assertGreater(own, 0)
        strict = itf.simplify(m, target=20, measure_error=False, inherit_input_contacts=False)
        self.assertFalse(strict.reached)
        self.assertEqual(strict.input_contact_pairs, own)
        r = itf.simplify(m, target=20, measure_error=False)
        self.assertTrue(r.reached)
        self.assertEqual(r.input_contact_pairs, own)
        self.assertEqual(r.inherited_pairs, itf.count_self_intersections(r.mesh))

    def test_seams_modes(self):
        s = itf.make_sphere(4000)
        faces = cap_faces(s)
        for seams in ("all", "features", "none", "auto"):
            r = itf.simplify(s, target=400, face_ids=faces, feature_faces=[1], seams=seams, measure_error=False)
            self.assertEqual(len(r.mesh.triangles), 400)
            self.assertTrue(set(r.face_ids) <= set(faces))
        with self.assertRaises(ValueError):
            itf.simplify(s, target=400, seams="some")

    def test_no_face_vanishes(self):
        # Single-triangle faces scattered over a sphere: each keeps a triangle; rejected_face counts
        # the collapses refused for that.
        s = itf.make_sphere(4000)
        faces = [0 if t % 97 else 1 + t // 97 for t in range(len(s.triangles))]
        r = itf.simplify(s, target=200, face_ids=faces, measure_error=False, prevent_self_intersections=False,
                         seams="all")  # (the default, auto, lets them go where every seam cannot meet the budget)
        self.assertEqual(set(r.face_ids), set(faces))
        self.assertGreater(r.rejected_face, 0)

    def test_max_error(self):
        s = itf.make_sphere(4000)
        plain = itf.simplify(s, target=200)
        r = itf.simplify(s, target=200, max_error=plain.error_bound / 2)
        self.assertLessEqual(r.error_bound, plain.error_bound / 2)
        self.assertGreater(len(r.mesh.triangles), 200)
        self.assertGreater(r.max_error_runs, 1)
        self.assertGreaterEqual(r.error_limited_budget, len(r.mesh.triangles))
        with self.assertRaises(ValueError):
            itf.simplify(s, target=200, max_error=-1.0)

    def test_locked_features_keep_their_triangles(self):
        s = itf.make_sphere(4000)
        faces = cap_faces(s)
        r = itf.simplify(s, target=1500, face_ids=faces, feature_faces=[1], lock=True)
        self.assertEqual(r.feature_triangles_in, r.feature_triangles_out)
        self.assertLessEqual(r.hausdorff_features, 1e-12)
        self.assertEqual(len(r.face_ids), len(r.mesh.triangles))

    def test_bad_budgets_raise(self):
        s = itf.make_sphere(200)
        with self.assertRaises(ValueError):
            itf.simplify(s, target=10**6)
        with self.assertRaises(ValueError):
            itf.simplify(s)
        with self.assertRaises(ValueError):
            itf.simplify(s, ratio=2.0)

    def test_error_bound_round_trip_and_distance_bound(self):
        s = itf.make_sphere(4000)
        r = itf.simplify(s, target=400)
        a_to_b, _ = itf.hausdorff(s, r.mesh)
        self.assertGreaterEqual(itf.distance_bound(s, r.mesh), a_to_b)
        self.assertGreaterEqual(r.error_bound, r.hausdorff)
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "s.ply")
            itf.write_tagged_mesh(out, r.mesh, error_bound=r.error_bound)
            self.assertEqual(itf.read_error_bound(out), r.error_bound)
            plain = os.path.join(d, "p.obj")
            itf.write_tagged_mesh(plain, r.mesh)
            self.assertEqual(itf.read_error_bound(plain), -1.0)
            with open(plain, "w") as f:
                f.write("# error_bound nan\nv 0 0 0\n")
            with self.assertRaises(ValueError):
                itf.read_error_bound(plain)

    def test_write_glb_instances_a_part(self):
        s = itf.make_sphere(2000)
        r = itf.simplify(s, target=200)
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "b.glb")
            moved = itf.Transform("1 0 0 5 0 1 0 0 0 0 1 0")
            itf.write_glb(out, [("ball", r.mesh, [], [], r.error_bound)],
                          [("left", 0, itf.Transform("1 0 0 0 0 1 0 0 0 0 1 0")), ("right", 0, moved)], units="m")
            with open(out, "rb") as f:
                data = f.read()
            self.assertEqual(data[:4], b"glTF")
            n = int.from_bytes(data[12:16], "little")
            doc = json.loads(data[20:20 + n])
            self.assertEqual(len(doc["meshes"]), 1)
            self.assertEqual(len(doc["nodes"]), 3)  # root + 2 instances
            back, info = itf.read_mesh(out, return_info=True)  # both instances, placed
            self.assertEqual(info["format"], "glb")
            self.assertEqual(len(back.triangles), 400)
            xs = [p[0] for p in back.positions]
            self.assertGreater(max(xs), 5.5)
            self.assertAlmostEqual(itf.read_error_bound(out), r.error_bound)  # metres: unscaled
            # .gltf: the same scene as JSON, read back alike.
            out_json = os.path.join(d, "b.gltf")
            itf.write_glb(out_json, [("ball", r.mesh, [], [], r.error_bound)],
                          [("left", 0, itf.Transform("1 0 0 0 0 1 0 0 0 0 1 0")), ("right", 0, moved)], units="m")
            with open(out_json) as f:
                self.assertEqual(len(json.load(f)["meshes"]), 1)
            again, info = itf.read_mesh(out_json, return_info=True)
            self.assertEqual(info["format"], "gltf")
            self.assertEqual([tuple(p) for p in again.positions], [tuple(p) for p in back.positions])
            self.assertAlmostEqual(itf.read_error_bound(out_json), r.error_bound)
            with self.assertRaises(ValueError):
                itf.write_glb(out, [("ball", r.mesh, [], [], -1)], [("x", 4, moved)])

    def test_triangle_budgets(self):
        b = itf.triangle_budgets([(35548, 4000), (10000, 0)], 12000)
        self.assertEqual(sum(b), 12000)
        self.assertGreaterEqual(b[0], 4000)
        with self.assertRaises(ValueError):
            itf.triangle_budgets([(10, 20)], 5)


@unittest.skipUnless(getattr(itf, "HAVE_CAD", False), "built without OpenCASCADE")
class Cad(unittest.TestCase):

    def test_rebalanced_budgets(self):
        parts = [(35548, 4000), (10000, 0), (2000, 500)]
        self.assertEqual(itf.rebalanced_budgets(parts, 12000, [None] * 3), itf.triangle_budgets(parts, 12000))
        b = itf.rebalanced_budgets(parts, 12000, [9000, None, None])
        self.assertEqual(b, [9000] + itf.triangle_budgets(parts[1:], 3000))
        self.assertEqual(sum(b), 12000)
        with self.assertRaises(ValueError):
            itf.rebalanced_budgets(parts, 12000, [None])
    def test_import_and_features(self):
        step = os.path.join(DATA, "counterbored_plate.step")
        m = itf.import_step(step)
        self.assertEqual(len(m["parts"]), 1)
        part = m["parts"][0]
        self.assertEqual(len(part["face_ids"]), len(part["mesh"].triangles))
        self.assertEqual(len(part["aag_nodes"]), 9)
        self.assertEqual(m["units"], "mm")
        self.assertEqual(len(m["file_length_units"]), 1)  # written by OCCT in millimetres
        bare = itf.import_step(step, linear_deflection=0.005, aag=False)  # triangles only
        self.assertEqual(bare["parts"][0]["aag_nodes"], [])
        self.assertEqual(bare["parts"][0]["linear_deflection"], 0.005)
        self.assertEqual(bare["parts"][0]["tessellation_deviation"], -1)  # not asked for
        measured = itf.import_step(step, linear_deflection=0.005, aag=False, measure_deviation=True)
        self.assertGreater(measured["parts"][0]["tessellation_deviation"], 0)
        self.assertGreater(len(bare["parts"][0]["mesh"].triangles), len(part["mesh"].triangles))
        f = itf.step_features(step)
        self.assertEqual([x["type"] for x in f[0]["features"]], ["counterbored_hole"])
        with tempfile.TemporaryDirectory() as d:
            proc = os.path.join(d, "p.json")
            with open(proc, "w") as out:
                json.dump({"steps": [{"id": "P1", "constraint": "screw"}]}, out)
            f = itf.step_features(step, process=proc, step="P1")
            self.assertEqual(len(f[0]["assembly_feature_faces"]), 3)
            dot = f[0]["dot"]  # the AAG as DOT: 9 faces, the step's 3 outlined, the feature's 5 filled
            # (issue #29: the hole's exit face is its `bottom` role, data/features/library.json)
            self.assertTrue(dot.startswith("graph aag {"))
            self.assertEqual(dot.count('[label="F'), 9)
            self.assertEqual(dot.count("color=red"), 3)
            self.assertEqual(dot.count("fillcolor=\"#"), 5 + 1)  # and the legend
            # The user's rules instead of the installed ones; a constraint they lack is an error.
            with open(os.path.join(ROOT, "data", "features", "semantics.json")) as src:
                rules = json.load(src)
            for rule in rules["rules"]:
                if rule["constraint"] == "screw":
                    rule["constraint"] = "cap_screw"
            own = os.path.join(d, "rules.json")
            with open(own, "w") as out:
                json.dump(rules, out)
            with open(proc, "w") as out:
                json.dump({"steps": [{"id": "P1", "constraint": "cap_screw"}]}, out)
            g = itf.step_features(step, process=proc, step="P1", rules=own)
            self.assertEqual(g[0]["assembly_feature_faces"], f[0]["assembly_feature_faces"])
            with self.assertRaisesRegex(ValueError, "cap_screw"):
                itf.step_features(step, process=proc, step="P1")
        with self.assertRaises(ValueError):
            itf.import_step(os.path.join(DATA, "missing.step"))

    def test_step_features_of_an_instance_named_in_the_step(self):
        asm = os.path.join(DATA, "assembly.step")
        with tempfile.TemporaryDirectory() as d:
            proc = plate_2_screw_process(d)
            f = {x["part"]: x for x in itf.step_features(asm, process=proc, step="P1")}
            self.assertEqual(len(f["plate"]["assembly_feature_faces"]), 3)  # via its instance plate_2
            self.assertEqual(f["shaft"]["assembly_feature_faces"], [])

    def test_prepare_step_with_mates_and_delabella(self):
        # Issue #29: without a process, mates=True (the default, as the CLI's --mates auto) keeps what the
        # mates inferred from the assembly pick (the CLI test data's bolted joint: every part mates);
        # mates=False keeps none; mesher='delabella' tessellates alike.
        joint = os.path.join(ROOT, "tests", "cli", "data", "bolted_joint.step")
        prep = itf.prepare_step(joint, mates=True)
        self.assertEqual(prep["report"]["features_from"], "mates")
        self.assertEqual(len(prep["report"]["mates"]), 11)
        self.assertTrue(all(p["feature_faces"] for p in prep["parts"]))
        self.assertTrue(all(not p["feature_faces"] for p in itf.prepare_step(joint, mates=False)["parts"]))
        self.assertEqual([p["feature_faces"] for p in itf.prepare_step(joint)["parts"]], [p["feature_faces"] for p in prep["parts"]])
        fast = itf.prepare_step(joint, mates=True, mesher="delabella")
        self.assertEqual([p["feature_faces"] for p in fast["parts"]], [p["feature_faces"] for p in prep["parts"]])
        with self.assertRaises(ValueError):
            itf.prepare_step(joint, mesher="fast")

    def test_prepare_step_then_simplify_each_part(self):
        asm = os.path.join(DATA, "assembly.step")
        with tempfile.TemporaryDirectory() as d:
            proc = plate_2_screw_process(d)
            with self.assertRaises(ValueError):  # a step without its process
                itf.prepare_step(asm, step="P1")
            prep = itf.prepare_step(asm, process=proc, step="P1")
            parts = {p["name"]: p for p in prep["parts"]}
            self.assertEqual(sorted(parts), ["plate", "plate [P1]", "shaft"])
            self.assertEqual(len(parts["plate [P1]"]["feature_faces"]), 3)  # bore, counterbore, seat
            self.assertEqual(parts["plate"]["feature_faces"], [])
            self.assertTrue(all(p["tessellation_error"] > 0 for p in prep["parts"]))  # curved faces: chordal
            self.assertEqual(parts["plate"]["tessellation_error"], parts["plate [P1]"]["tessellation_error"])
            self.assertEqual(len(prep["instances"]), 3)
            by_name = {i["name"]: i for i in prep["instances"]}
            self.assertEqual(prep["parts"][by_name["plate_2"]["part"]]["name"], "plate [P1]")
            self.assertAlmostEqual(by_name["plate_2"]["placement"].t[2], 20.0)
            self.assertIn("instances", prep["report"])
            # Each part to half its triangles, the step's features locked: their triangles stay (on the
            # plate they are 183 of 260 and the rest lies on seams: the budget cannot be met, a warning).
            glb_parts = []
            for p in prep["parts"]:
                r = itf.simplify(p["mesh"], ratio=0.5, face_ids=p["face_ids"], feature_faces=p["feature_faces"],
                                 lock=True)
                feat_in = sum(1 for f in p["face_ids"] if f in p["feature_faces"])
                self.assertEqual(r.feature_triangles_out, feat_in)
                if p["feature_faces"]:
                    self.assertFalse(r.reached)
                    self.assertTrue(any("not reached" in w for w in r.warnings))
                else:
                    self.assertTrue(r.reached)
                    self.assertEqual(len(r.mesh.triangles), len(p["mesh"].triangles) // 2)
                glb_parts.append((p["name"], r.mesh, r.face_ids, p["feature_faces"], r.error_bound))
            glb = os.path.join(d, "asm.glb")
            itf.write_glb(glb, glb_parts, [(i["name"], i["part"], i["placement"]) for i in prep["instances"]])
            with open(glb, "rb") as f:
                self.assertEqual(f.read(4), b"glTF")
        m = itf.import_step(asm)
        self.assertTrue(all(hasattr(i["placement"], "t") for i in m["instances"]))

    def test_assembly_clash(self):
        asm = os.path.join(DATA, "assembly.step")
        r = itf.assembly_clash(asm, clearance=15)
        self.assertEqual((r["clashes"], r["contacts"], r["within_clearance"]), (0, 0, 1))
        self.assertEqual(r["pairs"][0]["meeting"], "clearance")
        self.assertAlmostEqual(r["pairs"][0]["min_clearance"], 10.0)
        self.assertEqual(itf.assembly_clash(asm)["pairs"], [])
        with self.assertRaises(ValueError):
            itf.assembly_clash(asm, clearance=-1)
        # plate_2 moved into plate_1: a clash, with its geometry on request.
        with open(asm) as f:
            text = f.read()
        with tempfile.TemporaryDirectory() as d:
            moved = os.path.join(d, "moved.step")
            with open(moved, "w") as f:
                f.write(text.replace("(0.,0.,20.)", "(10.,0.,5.)"))
            g = itf.assembly_clash(moved, geometry=True)
            self.assertEqual(g["clashes"], 1)
            p = g["pairs"][0]
            self.assertGreater(len(p["curves"]), 0)
            self.assertAlmostEqual(sum(c.length for c in p["curves"]), p["curve_length"])
            self.assertGreater(len(p["region_triangles_a"]), 0)
            self.assertGreater(len(p["region_triangles_b"]), 0)
            self.assertNotIn("curves", itf.assembly_clash(moved)["pairs"][0])

    def test_simplify_step_to_one_total(self):
        # The CLI's STEP simplification: parts to their shares of one total, the step's features
        # locked on the instance it names, instances placed.
        asm = os.path.join(DATA, "assembly.step")
        with tempfile.TemporaryDirectory() as d:
            proc = plate_2_screw_process(d)
            s = itf.simplify_step(asm, target=400, process=proc, step="P1", lock=True)
            r = s["result"]
            self.assertEqual(len(r.mesh.triangles), 400)
            self.assertTrue(r.reached)
            self.assertEqual(r.target_triangles, 400)
            self.assertEqual(len(r.face_ids), 400)
            parts = s["parts"]
            self.assertEqual(sorted(p["name"] for p in parts), ["plate", "plate [P1]", "shaft"])
            self.assertEqual(sum(p["instances"] * len(p["result"].mesh.triangles) for p in parts), 400)
            self.assertEqual(r.feature_triangles_out, r.feature_triangles_in)
            self.assertGreater(r.feature_triangles_in, 0)
            self.assertEqual(r.error_bound, max(p["result"].error_bound for p in parts))
            for p in parts:  # each part's result is simplify() of it to its budget
                prep = {q["name"]: q for q in itf.prepare_step(asm, process=proc, step="P1")["parts"]}[p["name"]]
                own = itf.simplify(prep["mesh"], target=p["budget"], face_ids=prep["face_ids"],
                                   feature_faces=prep["feature_faces"], lock=True)
                self.assertEqual([tuple(t) for t in own.mesh.triangles], [tuple(t) for t in p["result"].mesh.triangles])
            # renderer_max: the total is the renderer's maximum, or the whole model when it is below it.
            self.assertEqual(len(itf.simplify_step(asm, renderer_max=300)["result"].mesh.triangles), 300)
            whole = itf.simplify_step(asm, renderer_max=10 ** 6)["result"]
            self.assertEqual(len(whole.mesh.triangles), whole.input_triangles)
            for bad in ({"target": 10 ** 6}, {"target": 10, "ratio": 0.5}, {}, {"ratio": 0.5, "step": "P1"},
                        {"ratio": 0.5, "seams": "some"}, {"ratio": 0.5, "feature_mode": "x"}):
                with self.assertRaises(ValueError, msg=str(bad)):
                    itf.simplify_step(asm, **bad)

    def cli_simplify(self, d, path, *args):
        """`interfere simplify PATH out.ply ARGS --json`: its report."""
        cli = cli_path()
        if not cli:
            self.skipTest("no interfere CLI (set INTERFERE_CLI)")
        report = os.path.join(d, "r.json")
        p = subprocess.run([cli, "simplify", path, os.path.join(d, "out.ply"), *args, "--json", report],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        with open(report) as f:
            return json.load(f)

    def assert_same_as_cli(self, s, cli):
        r = s["result"]
        self.assertEqual(s["report"]["features_from"], cli["cad"]["features_from"])
        self.assertEqual(s["feature_faces"], cli["feature_faces"])
        kept = [(p["name"], p.get("assembly_feature_faces", [])) for p in s["report"]["parts"]]
        self.assertEqual(kept, [(p["name"], p.get("assembly_feature_faces", [])) for p in cli["cad"]["parts"]])
        self.assertEqual((r.feature_triangles_in, r.feature_triangles_out),
                         (cli["feature_triangles"]["input"], cli["feature_triangles"]["output"]))
        self.assertEqual((r.input_triangles, len(r.mesh.triangles)), (cli["input_triangles"], cli["output_triangles"]))

    def test_simplify_step_mates_by_default_as_the_cli(self):
        # Issue #29, item 4: without a process both keep what the inferred mates pick by default
        # (the CLI's --mates auto); mates=False is --mates off and keeps nothing.
        joint = os.path.join(DATA, "bolted_joint.step")
        with tempfile.TemporaryDirectory() as d:
            s = itf.simplify_step(joint, ratio=0.5)
            self.assertEqual(s["report"]["features_from"], "mates")
            self.assertEqual(len(s["report"]["mates"]), 11)
            self.assertTrue(all(p["feature_faces"] for p in s["parts"]))  # every part of the joint mates
            self.assertGreater(s["result"].feature_triangles_in, 0)
            self.assert_same_as_cli(s, self.cli_simplify(d, joint, "--ratio", "0.5"))
            off = itf.simplify_step(joint, ratio=0.5, mates=False)
            self.assertEqual(off["report"]["features_from"], "none")
            self.assertEqual(off["feature_faces"], [])
            self.assertEqual(off["result"].feature_triangles_in, 0)
            self.assertNotEqual(off["feature_faces"], s["feature_faces"])
            self.assert_same_as_cli(off, self.cli_simplify(d, joint, "--ratio", "0.5", "--mates", "off"))
            # mesher: the same features on Delabella's triangles, as --mesher delabella.
            fast = itf.simplify_step(joint, ratio=0.5, mesher="delabella")
            self.assertEqual(fast["feature_faces"], s["feature_faces"])
            self.assert_same_as_cli(fast, self.cli_simplify(d, joint, "--ratio", "0.5", "--mesher", "delabella"))
            with self.assertRaisesRegex(ValueError, "mesher"):
                itf.simplify_step(joint, ratio=0.5, mesher="fast")

    def test_simplify_step_with_a_process_ignores_mates_as_the_cli(self):
        # With a process the step's features are kept whatever mates says (the CLI ignores --mates).
        asm = os.path.join(DATA, "assembly.step")
        with tempfile.TemporaryDirectory() as d:
            proc = plate_2_screw_process(d)
            s = itf.simplify_step(asm, target=400, process=proc, step="P1")
            self.assertEqual(s["report"]["features_from"], "process")
            self.assertGreater(len(s["feature_faces"]), 0)
            off = itf.simplify_step(asm, target=400, process=proc, step="P1", mates=False)
            self.assertEqual(off["feature_faces"], s["feature_faces"])
            self.assertEqual(off["result"].feature_triangles_out, s["result"].feature_triangles_out)
            self.assert_same_as_cli(s, self.cli_simplify(d, asm, "--target", "400", "--process", proc, "--step", "P1"))


if __name__ == "__main__":
    unittest.main()
