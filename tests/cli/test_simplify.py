#!/usr/bin/env python3
"""End-to-end tests of `interfere simplify` and `interfere features` (issue #6): budgets, tagged
outputs, feature locks, JSON reports, bad input (exit 2, no output written).

Usage: test_simplify.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import json
import math
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run, write_obj, load_json  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import make_examples  # noqa: E402


def uv_sphere(lon=40, lat=21, bump=0.05):
    v = [(0.0, 0.0, 1.0)]
    for i in range(1, lat):
        th = math.pi * i / lat
        for j in range(lon):
            ph = 2 * math.pi * j / lon
            r = 1 + bump * math.sin(5 * th) * math.sin(5 * ph)
            v.append((r * math.sin(th) * math.cos(ph), r * math.sin(th) * math.sin(ph), r * math.cos(th)))
    v.append((0.0, 0.0, -1.0))
    idx = lambda i, j: 1 + (i - 1) * lon + (j % lon)
    f = []
    for j in range(lon):
        f.append((0, idx(1, j), idx(1, j + 1)))
        f.append((len(v) - 1, idx(lat - 1, j + 1), idx(lat - 1, j)))
    for i in range(1, lat - 1):
        for j in range(lon):
            a, b, c, d = idx(i, j), idx(i, j + 1), idx(i + 1, j), idx(i + 1, j + 1)
            f.append((a, c, b))
            f.append((b, c, d))
    return v, f


def box_mesh(n):
    """A closed cube [0, n]^3, each side an n x n grid (integer corners: exact), outward; sides in
    order -x, +x, -y, +y, -z, +z (the bundled examples' generator)."""
    return make_examples.box((0.0, 0.0, 0.0), (float(n), float(n), float(n)), n)


def write_region_sheet(name, region_of, n=32):
    """A bumpy n x n sheet as NAME.obj, each grid square's two triangles in region region_of(i, j),
    written one per line to NAME.txt; returns the per-triangle regions."""
    pos = [(i / n, j / n, 0.2 * math.sin(3 * i / n) * math.cos(2 * j / n)) for j in range(n + 1) for i in range(n + 1)]
    tri, faces = [], []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            tri += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
            faces += [region_of(i, j)] * 2
    write_obj(name + ".obj", (pos, tri))
    with open(path(name + ".txt"), "w") as out:
        out.write("\n".join(map(str, faces)) + "\n")
    return faces


def write_process(name, steps):
    """Writes a process description {"steps": steps} to the work file `name`; returns its path."""
    with open(path(name), "w") as out:
        json.dump({"steps": steps}, out)
    return path(name)


def read_glb(file_name):
    """GLB (binary glTF 2.0) checked for structure: header, two chunks, aligned views inside the BIN
    chunk, accessor counts; returns (json, bin bytes, reader(accessor) -> list of numbers)."""
    import struct
    with open(file_name, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2 and length == len(data), (magic, version, length, len(data))
    jlen, jtype = struct.unpack_from("<II", data, 12)
    assert jtype == 0x4E4F534A and jlen % 4 == 0
    doc = json.loads(data[20:20 + jlen].decode("utf-8"))
    blen, btype = struct.unpack_from("<II", data, 20 + jlen)
    assert btype == 0x004E4942 and blen % 4 == 0
    bin_ = data[28 + jlen:28 + jlen + blen]
    assert len(bin_) == blen == doc["buffers"][0]["byteLength"]
    for v in doc["bufferViews"]:
        assert v["byteOffset"] % 4 == 0 and v["byteOffset"] + v["byteLength"] <= blen

    def read(i):
        a = doc["accessors"][i]
        v = doc["bufferViews"][a["bufferView"]]
        width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        fmt = {5126: "f", 5125: "I"}[a["componentType"]]
        assert a["count"] * width * 4 == v["byteLength"]
        return list(struct.unpack_from("<%d%s" % (a["count"] * width, fmt), bin_, v["byteOffset"]))
    return doc, bin_, read


def read_ply_ascii(name):
    with open(path(name)) as f:
        lines = f.read().split("\n")
    header_end = lines.index("end_header")
    header = lines[:header_end]
    nv = int([l for l in header if l.startswith("element vertex")][0].split()[2])
    nf = int([l for l in header if l.startswith("element face")][0].split()[2])
    body = lines[header_end + 1:]
    verts = [tuple(float(x) for x in body[i].split()) for i in range(nv)]
    faces = [tuple(int(x) for x in body[nv + i].split()) for i in range(nf)]
    return header, verts, faces


class Simplify(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.mesh = uv_sphere()
        write_obj("sphere.obj", cls.mesh)
        cls.n = len(cls.mesh[1])

    def test_target_exact_report_and_output(self):
        code, out, err = run("simplify", path("sphere.obj"), path("s.ply"), "--target", "400", "--json", path("s.json"),
                             "--check-self-intersections")
        self.assertEqual(code, 0, err)
        r = load_json("s.json")
        self.assertEqual(r["input_triangles"], self.n)
        self.assertEqual(r["output_triangles"], 400)
        self.assertTrue(r["reached"])
        self.assertEqual(r["self_intersections"], 0)
        self.assertGreater(r["hausdorff"], 0)
        self.assertGreaterEqual(r["error_bound"], r["hausdorff"])
        self.assertIn("400 triangles", out)

    def test_max_error_stops_above_the_budget(self):
        code, _, err = run("simplify", path("sphere.obj"), path("me0.ply"), "--target", "100", "--json", path("me0.json"))
        self.assertEqual(code, 0, err)
        plain = load_json("me0.json")
        self.assertIsNone(plain["max_error"])
        self.assertEqual(plain["max_error_runs"], 0)
        limit = plain["error_bound"] / 3
        code, _, err = run("simplify", path("sphere.obj"), path("me.ply"), "--target", "100", "--max-error", repr(limit),
                           "--json", path("me.json"))
        self.assertEqual(code, 0, err)
        r = load_json("me.json")
        self.assertEqual(r["max_error"], limit)
        self.assertLessEqual(r["error_bound"], limit)
        self.assertGreater(r["output_triangles"], 100)
        self.assertFalse(r["reached"])
        self.assertGreater(r["max_error_runs"], 1)
        self.assertGreaterEqual(r["error_limited_budget"], r["output_triangles"])
        self.assertIn("exceeds max_error", err)
        # The same limit relative to the bounding-box diagonal.
        code, _, err = run("simplify", path("sphere.obj"), path("me_rel.ply"), "--target", "100", "--max-error-rel",
                           repr(limit / r["bbox_diagonal"]), "--json", path("me_rel.json"))
        self.assertEqual(code, 0, err)
        rel = load_json("me_rel.json")
        self.assertAlmostEqual(rel["max_error"], limit, delta=1e-12 * limit)
        self.assertLessEqual(rel["error_bound"], rel["max_error"])
        for bad, message in ((("--max-error", "-1"), "--max-error must be a length > 0"),
                             (("--max-error-rel", "2"), "--max-error-rel must be a fraction"),
                             (("--max-error", "0.1", "--no-error"), "excludes"),
                             (("--max-error", "0.1", "--max-error-rel", "0.1"), "excludes")):
            self.assert_input_error("simplify", path("sphere.obj"), path("me_bad.ply"), "--target", "100", *bad,
                                    output=path("me_bad.ply"), message=message)

    def test_plain_mesh_as_glb(self):
        code, _, err = run("simplify", path("sphere.obj"), path("s.glb"), "--ratio", "0.5", "--json", path("s_glb.json"))
        self.assertEqual(code, 0, err)
        r = load_json("s_glb.json")
        doc, _, read = read_glb(path("s.glb"))
        self.assertEqual(len(doc["meshes"]), 1)
        # A mesh file is in mm unless --units says otherwise: glTF is in metres, so the root scales.
        self.assertEqual(doc["nodes"][0]["scale"], [0.001, 0.001, 0.001])
        self.assertEqual(r["units"], "mm")
        prim = doc["meshes"][0]["primitives"][0]
        self.assertEqual(len(read(prim["indices"])) // 3, r["output_triangles"])
        self.assertNotIn("_FACE_ID", prim["attributes"])  # no regions given
        normals = read(prim["attributes"]["NORMAL"])
        self.assertEqual(len(normals), len(read(prim["attributes"]["POSITION"])))
        for i in range(0, len(normals), 3):
            self.assertAlmostEqual(math.sqrt(sum(x * x for x in normals[i:i + 3])), 1.0, places=5)
        code, _, err = run("simplify", path("sphere.obj"), path("s_m.glb"), "--ratio", "0.5", "--units", "m")
        self.assertEqual(code, 0, err)
        self.assertNotIn("scale", read_glb(path("s_m.glb"))[0]["nodes"][0])  # already metres
        # --format glb whatever the name says.
        code, _, err = run("simplify", path("sphere.obj"), path("s_glb.bin"), "--ratio", "0.5", "--format", "glb")
        self.assertEqual(code, 0, err)
        doc, _, _ = read_glb(path("s_glb.bin"))
        self.assertEqual(len(doc["meshes"]), 1)

    def test_plain_mesh_as_gltf_clashes_conservatively(self):
        # OUT.gltf: the same glTF as JSON, its buffer a base64 data: URI; it reads back (clash, check)
        # as the GLB does, and --conservative takes its stored bound.
        code, _, err = run("simplify", path("sphere.obj"), path("s.gltf"), "--ratio", "0.5", "--json", path("s_gltf.json"))
        self.assertEqual(code, 0, err)
        code, _, err = run("simplify", path("sphere.obj"), path("s2.glb"), "--ratio", "0.5")
        self.assertEqual(code, 0, err)
        with open(path("s.gltf")) as f:
            doc = json.load(f)
        self.assertTrue(doc["buffers"][0]["uri"].startswith("data:application/octet-stream;base64,"))
        bound = load_json("s_gltf.json")["error_bound"]
        self.assertAlmostEqual(doc["scenes"][0]["extras"]["error_bound"], bound)
        checks = []
        for f in ("s.gltf", "s2.glb"):
            code, out, err = run("check", path(f))
            self.assertEqual(code, 0, err)
            checks.append(json.loads(out))
        self.assertEqual(checks[0]["format"], "gltf")
        for k in ("triangles", "vertices", "closed", "bbox"):
            self.assertEqual(checks[0][k], checks[1][k], k)
        code, out, err = run("clash", path("s.gltf"), path("s2.glb"), "--conservative", "--transform-b",
                             "1 0 0 5 0 1 0 0 0 0 1 0", "--json", path("sg.json"))
        self.assertEqual(code, 0, out + err)
        self.assertAlmostEqual(load_json("sg.json")["conservative"]["error_bound_a"], bound)
        # --format gltf whatever the name says; a file of the other container is read by content.
        code, _, err = run("simplify", path("sphere.obj"), path("s_gltf.bin"), "--ratio", "0.5", "--format", "gltf")
        self.assertEqual(code, 0, err)
        with open(path("s_gltf.bin")) as f:
            self.assertEqual(json.load(f)["asset"]["version"], "2.0")
        code, out, err = run("check", path("s_gltf.bin"))
        self.assertEqual((code, json.loads(out)["format"]), (0, "gltf"), err)

    def test_glb_crease_angle(self):
        # A cube without regions (kept whole: without regions its edges are not protected): its
        # 90-degree edges are creases at the default 40 (every normal along an axis), smooth at
        # --crease-angle 100 (corner normals between the sides).
        write_obj("gcube.obj", box_mesh(6))

        def normals(*extra):
            code, _, err = run("simplify", path("gcube.obj"), path("gcube.glb"), "--ratio", "1", *extra)
            self.assertEqual(code, 0, err)
            doc, _, read = read_glb(path("gcube.glb"))
            n = read(doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"])
            return [n[i:i + 3] for i in range(0, len(n), 3)]
        self.assertTrue(all(sorted(abs(x) for x in n)[:2] == [0, 0] for n in normals()))
        smooth = normals("--crease-angle", "100")
        self.assertTrue(any(sorted(abs(x) for x in n)[1] > 0.1 for n in smooth))
        for v in smooth:
            self.assertAlmostEqual(math.sqrt(sum(x * x for x in v)), 1.0, places=5)
        # Where it means nothing, or out of range: errors, nothing written.
        for extra, message in ((["--crease-angle", "100", "--format", "ply"], "not .glb"),
                               (["--crease-angle", "100", "--sharp-angle", "30"], "follow the faces"),
                               (["--crease-angle", "0"], "(0, 180)"), (["--crease-angle", "180"], "(0, 180)")):
            code, _, err = run("simplify", path("gcube.obj"), path("gcube2.glb"), "--target", "100", *extra)
            self.assertEqual(code, 2, extra)
            self.assertIn(message, err)
            self.assertFalse(os.path.exists(path("gcube2.glb")))

    def test_warnings_are_printed_with_quiet(self):
        # --quiet (every test runs with it) silences progress lines, not warnings: an odd budget on a
        # closed mesh ends one below, which a warning says on stderr and in the report.
        write_obj("odd.obj", uv_sphere())
        code, _, err = run("simplify", path("odd.obj"), path("odd.ply"), "--target", "301", "--json", path("odd.json"))
        self.assertEqual(code, 0, err)
        r = load_json("odd.json")
        self.assertEqual(r["output_triangles"], 300)
        self.assertTrue(r["one_below"])
        self.assertFalse(r["reached"])
        self.assertIn("[interfere] warning: budget 301 not reached exactly", err)
        self.assertTrue(any("one below" in w for w in r["warnings"]))
        self.assertNotIn("simplifying", err)  # no progress lines

    def test_cracked_input_strict_guard_and_inherited_contacts(self):
        # Two flat sheets tessellated apart, overlapping by 1e-6 along x = 1 (a crack, as in CAD exports).
        def sheet(n, x0):
            pos = [(x0 + i / n, j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
            tri = [t for j in range(n) for i in range(n) for a in [j * (n + 1) + i]
                   for t in ((a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1))]
            return pos, tri
        p0, t0 = sheet(8, 0.0)
        p1, t1 = sheet(13, 1.0 - 1e-6)
        write_obj("crack.obj", (p0 + p1, t0 + [(a + len(p0), b + len(p0), c + len(p0)) for a, b, c in t1]))
        code, _, err = run("simplify", path("crack.obj"), path("crack_strict.obj"), "--target", "20",
                           "--strict-intersection-guard", "--json", path("crack_strict.json"))
        self.assertEqual(code, 0, err)
        strict = load_json("crack_strict.json")
        self.assertFalse(strict["reached"])
        self.assertGreater(strict["input_contact_pairs"], 0)
        self.assertEqual(strict["inherited_pairs"], 0)
        self.assertIn("--strict-intersection-guard", err)  # the warning says how to lift it
        code, _, err = run("simplify", path("crack.obj"), path("crack_out.obj"), "--target", "20",
                           "--check-self-intersections", "--json", path("crack.json"))
        self.assertEqual(code, 0, err)
        r = load_json("crack.json")
        self.assertTrue(r["reached"])
        self.assertEqual(r["output_triangles"], 20)
        self.assertEqual(r["input_contact_pairs"], strict["input_contact_pairs"])
        self.assertEqual(r["inherited_pairs"], r["self_intersections"])

    def test_ratio(self):
        code, _, err = run("simplify", path("sphere.obj"), path("r.obj"), "--ratio", "0.25", "--json", path("r.json"))
        self.assertEqual(code, 0, err)
        r = load_json("r.json")
        self.assertEqual(r["target_triangles"], round(0.25 * self.n))

    def test_renderer_max_budget(self):
        code, _, err = run("simplify", path("sphere.obj"), path("rm.obj"), "--renderer-max", "500", "--json", path("rm.json"))
        self.assertEqual(code, 0, err)
        r = load_json("rm.json")
        self.assertEqual(r["target_triangles"], 500)
        self.assertEqual(r["output_triangles"], 500)
        with open(path("rm.obj")) as f:
            self.assertTrue(any(l.startswith("# error_bound ") for l in f))
        code, _, err = run("simplify", path("sphere.obj"), path("rm2.obj"), "--renderer-max", str(10 * self.n))
        self.assertEqual(code, 0, err)  # budget above the mesh: nothing to simplify, the mesh is kept

    def test_regions_locked_features_are_bit_identical_in_tagged_ply(self):
        v, f = self.mesh
        regions = [1 if sum(v[i][2] for i in t) / 3 > 0.8 else 0 for t in f]
        with open(path("regions.txt"), "w") as out:
            out.write("# region per triangle\n" + "\n".join(map(str, regions)) + "\n")
        code, _, err = run("simplify", path("sphere.obj"), path("lock.ply"), "--target", "600", "--regions",
                           path("regions.txt"), "--features", "1", "--lock", "--format", "ply-ascii", "--json",
                           path("lock.json"))
        self.assertEqual(code, 0, err)
        header, verts, faces = read_ply_ascii("lock.ply")
        self.assertIn("property uint face_id", header)
        self.assertIn("property uchar feature", header)
        bound = [l for l in header if l.startswith("comment error_bound ")]
        self.assertEqual(len(bound), 1)
        out_cap = sorted(tuple(sorted(verts[i] for i in face[1:4])) for face in faces if face[4] == 1)
        in_cap = sorted(tuple(sorted(v[i] for i in t)) for t, reg in zip(f, regions) if reg == 1)
        self.assertEqual(out_cap, in_cap)
        self.assertTrue(all(face[5] == (1 if face[4] == 1 else 0) for face in faces))
        r = load_json("lock.json")
        self.assertEqual(r["feature_faces"], [1])
        self.assertEqual(r["feature_mode"], "lock")
        # A region id no triangle has, or region ids without regions, would keep nothing: errors.
        code, _, err = run("simplify", path("sphere.obj"), path("lock2.ply"), "--target", "600", "--regions",
                           path("regions.txt"), "--features", "1,7")
        self.assertEqual(code, 2)
        self.assertIn("region id 7", err)
        code, _, err = run("simplify", path("sphere.obj"), path("lock2.ply"), "--target", "600", "--features", "1")
        self.assertEqual(code, 2)
        self.assertIn("--regions", err)
        self.assertFalse(os.path.exists(path("lock2.ply")))
        self.assertLessEqual(r["hausdorff_features"], 1e-12)
        self.assertEqual(float(bound[0].split()[2]), r["error_bound"])

    def test_sharp_angle_regions_are_face_ids_of_the_output(self):
        # A cube's sides are the regions of --sharp-angle (numbered in order of first triangle: the
        # sides as generated); the output carries them as face ids, --features names them.
        n = 8
        v, f = box_mesh(n)
        write_obj("cube.obj", (v, f))
        code, _, err = run("simplify", path("cube.obj"), path("cube.ply"), "--target", "200", "--sharp-angle", "30",
                           "--features", "2", "--lock", "--format", "ply-ascii", "--json", path("cube.json"))
        self.assertEqual(code, 0, err)
        r = load_json("cube.json")
        self.assertEqual(r["regions"], 6)
        self.assertEqual(r["sharp_angle"], 30)
        self.assertEqual(r["output_triangles"], 200)
        header, verts, faces = read_ply_ascii("cube.ply")
        self.assertEqual(sorted(set(face[4] for face in faces)), list(range(6)))
        per_side = 2 * n * n
        for face in faces:  # each output triangle lies in the side its face id names
            a, side = face[4] // 2, (face[4] % 2) * n
            self.assertTrue(all(verts[i][a] == side for i in face[1:4]), face)
        locked = sorted(tuple(sorted(verts[i] for i in face[1:4])) for face in faces if face[4] == 2)
        side2 = sorted(tuple(sorted(v[i] for i in t)) for t in f[2 * per_side:3 * per_side])
        self.assertEqual(locked, side2)  # bit-identical
        self.assertTrue(all(face[5] == (1 if face[4] == 2 else 0) for face in faces))
        # A region id the angle does not make is an error naming the ids there are; nothing written.
        code, _, err = run("simplify", path("cube.obj"), path("cube2.ply"), "--target", "200", "--sharp-angle", "30",
                           "--features", "2,6")
        self.assertEqual(code, 2)
        self.assertIn("region id 6 (ids 0 to 5)", err)
        for bad in ("180", "-5", "nan"):
            code, _, err = run("simplify", path("cube.obj"), path("cube2.ply"), "--target", "200", "--sharp-angle", bad)
            self.assertEqual(code, 2, bad)
            self.assertIn("--sharp-angle", err)
        self.assertFalse(os.path.exists(path("cube2.ply")))
        # The renderer's budget counts the feature regions' triangles: here they alone exceed it. The
        # cap holds (issue #29), the features are simplified too, and a warning says so.
        code, _, err = run("simplify", path("cube.obj"), path("cube3.ply"), "--renderer-max", "100", "--sharp-angle",
                           "30", "--features", "0,1", "--json", path("cube3.json"))
        self.assertEqual(code, 0, err)
        r3 = load_json("cube3.json")
        self.assertEqual(r3["feature_triangles"]["input"], 2 * per_side)
        self.assertEqual(r3["target_triangles"], 100)
        self.assertLessEqual(r3["output_triangles"], 100)
        self.assertIn("--renderer-max 100 is below the 256 triangles", err)

    def test_seams_of_non_feature_faces(self):
        # 8 x 8 square faces on a bumpy sheet: their corners hold the budget unless the seams of the
        # faces that are not features may go.
        write_region_sheet("tiles", lambda i, j: i // 4 + 8 * (j // 4))
        reports = {}
        for seams in ("all", "features", "auto"):
            code, _, err = run("simplify", path("tiles.obj"), path("tiles_%s.ply" % seams), "--target", "100",
                               "--regions", path("tiles.txt"), "--features", "27", "--seams", seams, "--json",
                               path("tiles_%s.json" % seams))
            self.assertEqual(code, 0, err)
            reports[seams] = load_json("tiles_%s.json" % seams)
            self.assertEqual(reports[seams]["seams"], seams)
        self.assertFalse(reports["all"]["reached"])
        self.assertTrue(any("--seams auto or features" in w for w in reports["all"]["warnings"]))
        self.assertTrue(reports["features"]["reached"])
        self.assertEqual(reports["features"]["output_triangles"], 100)
        self.assertTrue(reports["auto"]["reached"])  # every seam until they held, then the features' only
        self.assertEqual(reports["auto"]["seams_relaxed_at"], reports["all"]["output_triangles"])
        self.assertEqual(reports["features"]["seams_relaxed_at"], 0)
        self.assert_input_error("simplify", path("tiles.obj"), path("tiles_bad.ply"), "--target", "100", "--seams",
                                "some", output=path("tiles_bad.ply"), message="--seams must be all, auto, features or none")

    def test_no_face_vanishes_with_its_seams_kept(self):
        # 2 x 2 tiles of a bumpy sheet with 12 one-square faces (2 triangles each) inside them: QEM
        # would flatten those away; with their seams kept each keeps a triangle at least.
        small = {(3 + 8 * (k % 4), 5 + 10 * (k // 4)): 10 + k for k in range(12)}
        faces = write_region_sheet("dots", lambda i, j: small.get((i, j), i // 16 + 2 * (j // 16)))
        code, _, err = run("simplify", path("dots.obj"), path("dots.ply"), "--target", "60", "--regions",
                           path("dots.txt"), "--seams", "all", "--format", "ply-ascii", "--json", path("dots.json"))
        self.assertEqual(code, 0, err)
        _, _, out_faces = read_ply_ascii("dots.ply")
        self.assertEqual(sorted(set(face[4] for face in out_faces)), sorted(set(faces)))
        r = load_json("dots.json")
        self.assertGreater(r["rejected"]["last_face_triangle"], 0)
        self.assertEqual(r["rejected"]["last_face_triangle"] > 0, "face's last triangle" in " ".join(r["warnings"]))

    def assert_input_error(self, *args, output=None, message=None):
        if output and os.path.exists(output):
            os.remove(output)
        code, _, err = run(*args)
        self.assertEqual(code, 2, err)
        if output:
            self.assertFalse(os.path.exists(output), "an output was written on bad input")
        if message:
            self.assertIn(message, err)

    def test_bad_budgets_and_inputs(self):
        o = path("bad.ply")
        s = path("sphere.obj")
        self.assert_input_error("simplify", s, o, "--target", str(self.n + 1), output=o, message="larger than the mesh")
        self.assert_input_error("simplify", s, o, "--target", "0", output=o)
        self.assert_input_error("simplify", s, o, output=o, message="--target")
        self.assert_input_error("simplify", s, o, "--ratio", "1.5", output=o)
        self.assert_input_error("simplify", s, o, "--ratio", "0", output=o)
        self.assert_input_error("simplify", s, o, "--target", "10", "--ratio", "0.5", output=o)
        with open(path("short.txt"), "w") as out:
            out.write("0\n1\n")
        self.assert_input_error("simplify", s, o, "--target", "10", "--regions", path("short.txt"), output=o,
                                message="region ids for")
        with open(path("junk.txt"), "w") as out:
            out.write("0\nx1\n")
        self.assert_input_error("simplify", s, o, "--target", "10", "--regions", path("junk.txt"), output=o,
                                message=":2:")
        self.assert_input_error("simplify", s, o, "--target", "10", "--step", "P1", output=o)
        with open(path("empty.obj"), "w") as out:
            out.write("# nothing\n")
        self.assert_input_error("simplify", path("empty.obj"), o, "--target", "10", output=o)
        xyz = path("bad.xyz")
        self.assert_input_error("simplify", s, xyz, "--target", "10", output=xyz, message="unsupported extension")
        self.assert_input_error("simplify", s, path("no_such_dir/o.ply"), "--target", "10",
                                output=path("no_such_dir/o.ply"), message="directory does not exist")
        self.assert_input_error("simplify", s, o, "--target", "10", "--process", path("p.json"), output=o,
                                message="--step")
        # Tessellation options on a mesh would be ignored: an error.
        self.assert_input_error("simplify", s, o, "--target", "10", "--angular-deflection", "0.2", output=o,
                                message="STEP input")
        # Options are checked before the input is read: the option's error, not the file's.
        for extra, message in ((["--sharp-angle", "200"], "--sharp-angle"), (["--max-error", "-1"], "--max-error"),
                               (["--seams", "some"], "--seams"), (["--features", "1,x", "--sharp-angle", "30"], "not a face/region id"),
                               (["--max-error-rel", "2"], "--max-error-rel")):
            self.assert_input_error("simplify", path("empty.obj"), o, "--target", "10", *extra, output=o,
                                    message=message)
        # --parts-dir is not created when the run fails its checks.
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), o, "--target", "10", "--seams", "x",
                           "--parts-dir", path("never_made"))
        self.assertEqual(code, 2)
        self.assertFalse(os.path.exists(path("never_made")))
        # --lock without feature faces keeps nothing: a warning (stderr and report).
        code, _, err = run("simplify", s, path("nolock.ply"), "--target", "100", "--lock", "--json",
                           path("nolock.json"))
        self.assertEqual(code, 0, err)
        self.assertIn("no feature faces to keep", err)
        self.assertTrue(any("no feature faces" in w for w in load_json("nolock.json")["warnings"]))

    def test_existing_output_untouched_on_error(self):
        with open(path("keep.ply"), "w") as out:
            out.write("precious")
        code, _, _ = run("simplify", path("sphere.obj"), path("keep.ply"), "--target", str(self.n + 5))
        self.assertEqual(code, 2)
        with open(path("keep.ply")) as f:
            self.assertEqual(f.read(), "precious")


HAVE_CAD = None


class ConservativeClash(unittest.TestCase):
    """`interfere clash --conservative` on simplified parts (issue #6, item 6): the error bounds stored
    in the outputs widen the clearance, so touching originals are never reported clear."""

    def simplify(self, name, mesh):
        write_obj(name + ".obj", mesh)
        code, _, err = run("simplify", path(name + ".obj"), path(name + "_s.ply"), "--target", "120", "--json",
                           path(name + "_s.json"))
        self.assertEqual(code, 0, err)
        return load_json(name + "_s.json")["error_bound"]

    def test_touching_originals_are_a_possible_clash_of_their_simplified_versions(self):
        a = uv_sphere(lon=120, lat=60, bump=0.0)
        for shift, touching in ((1.999, True), (2.5, False)):
            b = ([(x + shift, y, z) for (x, y, z) in a[0]], a[1])
            ea, eb = self.simplify("ca", a), self.simplify("cb", b)
            self.assertGreater(ea, 0)
            code, _, err = run("clash", path("ca.obj"), path("cb.obj"))
            self.assertEqual(code, 1 if touching else 0, err)  # the originals
            code, out, err = run("clash", path("ca_s.ply"), path("cb_s.ply"), "--conservative", "--json",
                                 path("cons.json"))
            # A possible clash of the originals is undecided (exit 3) unless the simplified parts
            # themselves clash (exit 1); never clear (issue #23, item 13).
            rep = load_json("cons.json")
            expected = ("clash" if rep["result"]["cross_pairs"] > 0 else "undecided") if touching else "clear"
            self.assertEqual(rep["verdict"], expected)
            self.assertEqual(code, {"clash": 1, "undecided": 3, "clear": 0}[expected], err)
            c = load_json("cons.json")["conservative"]
            self.assertEqual(c["error_bound_a"], ea)  # read back from the PLY exactly
            self.assertEqual(c["error_bound_b"], eb)
            self.assertAlmostEqual(c["margin"], ea + eb)
            self.assertEqual(c["possible_clash"], touching)
            self.assertIn("possible clash" if touching else "do not clash", out)
        # A pose that scales the part scales its bound (the largest stretch of the pose).
        code, _, err = run("clash", path("ca_s.ply"), path("cb_s.ply"), "--conservative", "--transform-a",
                           "2 0 0 0 0 2 0 0 0 0 2 0", "--json", path("cons2.json"))
        self.assertIn(code, (0, 1, 3), err)
        self.assertAlmostEqual(load_json("cons2.json")["conservative"]["error_bound_a"], 2 * ea, places=9)
        # An original (no stored bound) counts as exact; a malformed bound is an input error.
        code, _, err = run("clash", path("ca.obj"), path("cb_s.ply"), "--conservative")
        self.assertIn(code, (0, 1, 3), err)
        self.assertIn("no error bound", err)
        with open(path("bad.obj"), "w") as out:
            out.write("# error_bound -3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        code, _, err = run("clash", path("bad.obj"), path("cb_s.ply"), "--conservative")
        self.assertEqual(code, 2)
        self.assertIn("bad.obj:1", err)

    def test_glb_outputs_clash_conservatively_as_they_are_placed(self):
        # A GLB written by simplify is read back (the clash reads glTF) with its bound: the mesh is
        # in mm (the default), written in metres as glTF says and read back into mm, so the bound is
        # the PLY's up to the rounding of the two scalings.
        a = uv_sphere(lon=120, lat=60, bump=0.0)
        b = ([(x + 1.999, y, z) for (x, y, z) in a[0]], a[1])
        for name, mesh in (("ga", a), ("gb", b)):
            write_obj(name + ".obj", mesh)
            for ext in ("ply", "glb"):
                code, _, err = run("simplify", path(name + ".obj"), path(name + "_s." + ext), "--target", "120")
                self.assertEqual(code, 0, err)
        code, _, err = run("clash", path("ga_s.glb"), path("gb_s.glb"), "--conservative", "--json", path("g.json"))
        self.assertIn(code, (1, 3), err)  # a clash of the simplified parts, or a possible one
        g = load_json("g.json")["conservative"]
        code, _, err = run("clash", path("ga_s.ply"), path("gb_s.ply"), "--conservative", "--json", path("p.json"))
        p = load_json("p.json")["conservative"]
        self.assertTrue(g["possible_clash"])
        self.assertAlmostEqual(g["error_bound_a"], p["error_bound_a"], delta=1e-12 * p["error_bound_a"])
        self.assertAlmostEqual(g["error_bound_b"], p["error_bound_b"], delta=1e-12 * p["error_bound_b"])
        # The same triangles (as floats) wherever they are read.
        code, out_g, err = run("check", path("ga_s.glb"))
        self.assertEqual(code, 0, err)
        self.assertEqual(json.loads(out_g)["triangles"], 120)
        # A truncated GLB is an input error naming the file; nothing is reported as clear.
        with open(path("ga_s.glb"), "rb") as f:
            data = f.read()
        with open(path("cut.glb"), "wb") as f:
            f.write(data[:-10])
        code, _, err = run("clash", path("cut.glb"), path("gb_s.glb"))
        self.assertEqual(code, 2)
        self.assertIn("cut.glb", err)
        self.assertIn("truncated", err)


def have_cad():
    global HAVE_CAD
    if HAVE_CAD is None:
        code, _, err = run("features", os.path.join(DATA, "counterbored_plate.step"))
        HAVE_CAD = code == 0
        # Skip only for a build without OpenCASCADE: any other failure of the probe (a regression in
        # `features`) would otherwise skip every test below and pass (issue #23, item 14).
        if not HAVE_CAD and "built with OpenCASCADE" not in err:
            raise AssertionError("features failed on counterbored_plate.step (exit %d): %s" % (code, err))
    return HAVE_CAD


class Features(unittest.TestCase):
    def setUp(self):
        if not have_cad():
            self.skipTest("built without OpenCASCADE")

    def test_features_lists_the_counterbore(self):
        code, out, err = run("features", os.path.join(DATA, "counterbored_plate.step"), "--json", path("f.json"), "--aag")
        self.assertEqual(code, 0, err)
        self.assertIn("counterbored_hole", out)
        # The listing gives face ids, radii and the axis (point, direction): since the hole
        # recognition of issue #29 the axis starts at the opening (the plate's top, z = 10) and points
        # into the part.
        self.assertIn("radii 6,3 axis (20, 15, 10) dir (0, 0, -1)", out)
        r = load_json("f.json")
        feats = r["parts"][0]["features"]
        self.assertEqual([f["type"] for f in feats], ["counterbored_hole"])
        self.assertEqual(sorted(round(x, 9) for x in feats[0]["radii"]), [3.0, 6.0])
        self.assertEqual(len(r["parts"][0]["aag"]["nodes"]), 9)
        self.assertEqual(r["units"], "mm")
        self.assertEqual(r["file_length_units"], ["millimetre"])
        self.assertIn("lengths in mm", out)
        self.assertAlmostEqual(feats[0]["axis"]["point"][0], 20.0)

    def test_step_parts_are_clashed_and_checked_as_tessellated(self):
        # clash/distance/check take a STEP file (every instance placed, welded): a pin in the plate's
        # r = 3 bore is clear at r = 2.8 and interferes at r = 3.2; the tessellated plate is closed.
        plate = os.path.join(DATA, "counterbored_plate.step")
        code, out, err = run("check", plate)
        self.assertEqual(code, 0, err)
        c = json.loads(out)
        self.assertEqual((c["format"], c["closed"], c["open_edges"]), ("step", True, 0))
        for r, expected in ((2.8, 0), (3.2, 1)):
            write_obj("pin.obj", make_examples.cylinder(r, 30, 64))
            code, out, err = run("clash", plate, path("pin.obj"), "--transform-b", "1 0 0 20 0 1 0 15 0 0 1 5",
                                 "--json", path("sc.json"))
            self.assertEqual(code, expected, err)
            self.assertEqual(load_json("sc.json")["inputs"]["a"]["format"], "step")
        code, out, err = run("distance", plate, path("pin.obj"), "--transform-b", "1 0 0 100 0 1 0 15 0 0 1 5")
        self.assertEqual(code, 0, err)
        # An assembly reads as all its instances; a malformed STEP is an error naming the file.
        code, out, err = run("check", os.path.join(DATA, "assembly.step"))
        self.assertEqual(json.loads(out)["components"], 3)
        with open(path("broken.step"), "w") as f:
            f.write("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=FOO(;\nENDSEC;\n")
        code, _, err = run("clash", path("broken.step"), path("pin.obj"))
        self.assertEqual(code, 2)
        self.assertIn("broken.step", err)

    def test_step_file_in_metres_is_read_in_mm(self):
        # Issue #23, item 6: a STEP file's own length unit. The counterbored plate's file with its
        # length unit declared as the metre, the numbers kept: a 40 x 30 x 10 m plate, read as
        # 40000 x 30000 x 10000 mm by every command. (tests/cad/test_step_units.cpp: files OCCT writes
        # in inches and metres.)
        with open(os.path.join(DATA, "counterbored_plate.step")) as f:
            text = f.read()
        mm_unit = "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )"
        self.assertEqual(text.count(mm_unit), 1)
        plate = path("plate_40m.step")
        with open(plate, "w") as f:
            f.write(text.replace(mm_unit, "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )"))
        code, out, err = run("features", plate, "--json", path("fm.json"))
        self.assertEqual(code, 0, err)
        r = load_json("fm.json")
        self.assertEqual((r["units"], r["file_length_units"]), ("mm", ["metre"]))
        feats = r["parts"][0]["features"]
        self.assertEqual([f["type"] for f in feats], ["counterbored_hole"])
        self.assertEqual(sorted(round(x, 6) for x in feats[0]["radii"]), [3000.0, 6000.0])
        self.assertAlmostEqual(feats[0]["axis"]["point"][0], 20000.0, places=6)
        code, out, err = run("check", plate)
        self.assertEqual(code, 0, err)
        bbox = json.loads(out)["bbox"]
        for got, want in zip(bbox["min"] + bbox["max"], [0, 0, 0, 40000, 30000, 10000]):
            self.assertAlmostEqual(got, want, places=6)
        # Against parts in mm: a pin through the bore (r = 3000 mm at (20000, 15000)) is clear at
        # r = 2800 mm and a clash at 3200 mm, as the mm plate's pins of 2.8 and 3.2 mm are; a 1 m cube
        # inside the plate's solid is a clash. Read as mm numbers, the plate would be 40 mm wide, and
        # all three clear of it.
        for name, mesh, transform, expected in (
                ("pin_2800.obj", make_examples.cylinder(2800, 30000, 64), "1 0 0 20000 0 1 0 15000 0 0 1 5000", "clear"),
                ("pin_3200.obj", make_examples.cylinder(3200, 30000, 64), "1 0 0 20000 0 1 0 15000 0 0 1 5000", "clash"),
                ("cube_1m.obj", make_examples.box((30000, 20000, 2000), (31000, 21000, 3000), 1), "", "clash")):
            write_obj(name, mesh)
            args = ["clash", plate, path(name), "--json", path("sm.json")]
            if transform:
                args += ["--transform-b", transform]
            code, out, err = run(*args)
            self.assertEqual(code, 1 if expected == "clash" else 0, out + err)
            rep = load_json("sm.json")
            self.assertEqual(rep["verdict"], expected, name)
            self.assertEqual(rep["units"], "mm")
            a, b = rep["inputs"]["a"], rep["inputs"]["b"]
            self.assertEqual((a["format"], a["units"], a["scale_to_working_unit"]), ("step", "mm", 1))
            self.assertEqual((b["units"], b["scale_to_working_unit"]), ("mm", 1))
            self.assertEqual(rep["input_warnings"], [])  # sizes within 100x of each other
        # Simplified to glTF (metres): the plate is 40 m there, and it clashes with its STEP file.
        glb = path("plate_40m.glb")
        code, _, err = run("simplify", plate, glb, "--ratio", "0.5")
        self.assertEqual(code, 0, err)
        doc, _, read = read_glb(glb)
        scale = doc["nodes"][0].get("scale", [1, 1, 1])
        xs = read(doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"])[0::3]
        self.assertAlmostEqual(max(xs) * scale[0], 40.0, places=4)  # metres (float32 positions)
        code, out, err = run("clash", glb, plate, "--json", path("sgm.json"))
        self.assertEqual(code, 1, out + err)
        rep = load_json("sgm.json")
        self.assertEqual((rep["verdict"], rep["inputs"]["a"]["units"]), ("clash", "m"))
        self.assertEqual(rep["input_warnings"], [])

    def test_simplified_step_as_glb_clashes_with_the_step(self):
        # Issue #23, item 6, as reported: `simplify part.step part.glb` then `clash part.glb part.step`
        # printed "clear: 0 pairs" (the glTF's metres taken as mm: a 0.04 mm plate in the 40 mm one's
        # corner; forced so with --units-a mm it now touches there, 0 crossing pairs, and a size
        # warning). Each input is converted from its own unit to the working unit: the simplified
        # plate lies on the original, their surfaces cross, a clash (exit 1), in mm or in metres.
        plate = os.path.join(DATA, "counterbored_plate.step")
        glb = path("plate_simplified.glb")
        code, _, err = run("simplify", plate, glb, "--ratio", "0.5")
        self.assertEqual(code, 0, err)
        for units, scale_a, scale_b in (("mm", 1000, 1), ("m", 1, 0.001)):
            code, out, err = run("clash", glb, plate, "--units", units, "--json", path("sg.json"))
            self.assertEqual(code, 1, out + err)
            rep = load_json("sg.json")
            self.assertEqual(rep["verdict"], "clash")
            self.assertEqual(rep["units"], units)
            a, b = rep["inputs"]["a"], rep["inputs"]["b"]
            self.assertEqual((a["format"], a["units"], b["format"], b["units"]), ("glb", "m", "step", "mm"))
            self.assertAlmostEqual(a["scale_to_working_unit"], scale_a, places=12)
            self.assertAlmostEqual(b["scale_to_working_unit"], scale_b, places=12)
            self.assertGreater(rep["result"]["cross_pairs"], 0)
            self.assertEqual(rep["input_warnings"], [])
        # The other order too.
        code, out, err = run("clash", plate, glb)
        self.assertEqual(code, 1, out + err)

    def test_step_tessellation_options_and_conservative_clash(self):
        # --linear-deflection sets the STEP tessellation (reported); --conservative takes a STEP part's
        # deflection as its error bound: a pin of r = 2.95 in the plate's r = 3 bore (a 0.05 gap) is
        # clear, a possible clash when the bore may be 0.1 off, and clear again at 0.01.
        plate = os.path.join(DATA, "counterbored_plate.step")
        counts = []
        for d in ("0.5", "0.01"):
            code, out, err = run("check", plate, "--linear-deflection", d)
            self.assertEqual(code, 0, err)
            c = json.loads(out)
            self.assertEqual(c["linear_deflection"], float(d))
            self.assertGreater(c["tessellation_deviation"], 0)  # measured: the bores are curved
            self.assertEqual(bool(c["warnings"]), c["tessellation_deviation"] > float(d))
            self.assertTrue(c["closed"])
            counts.append(c["triangles"])
        self.assertLess(counts[0], counts[1])
        write_obj("pin295.obj", make_examples.cylinder(2.95, 30, 64))
        pose = ("--transform-b", "1 0 0 20 0 1 0 15 0 0 1 5")
        for d, expected in (("0.1", 3), ("0.01", 0)):  # possible clash: undecided (exit 3)
            code, out, err = run("clash", plate, path("pin295.obj"), *pose, "--linear-deflection", d, "--conservative",
                                 "--json", path("cons.json"))
            self.assertEqual(code, expected, out + err)
            r = load_json("cons.json")
            a = r["inputs"]["a"]
            self.assertEqual(a["linear_deflection"], float(d))
            self.assertEqual(r["conservative"]["error_bound_a"], max(float(d), a["tessellation_deviation"]))
            self.assertEqual(r["conservative"]["error_bound_b"], 0)
            self.assertEqual(r["result"]["pairs"], 0)
        code, _, err = run("clash", plate, path("pin295.obj"), *pose, "--linear-deflection", "0.1")
        self.assertEqual(code, 0, err)
        # Misused flags are input errors naming the reason: deflection flags without a STEP input, a
        # STEP input with other units, a bad deflection.
        write_obj("pin2.obj", make_examples.cylinder(2.8, 30, 64))
        for args, message in ((["clash", path("pin2.obj"), path("pin295.obj"), "--linear-deflection", "0.1"], "STEP"),
                              (["check", path("pin2.obj"), "--angular-deflection", "0.2"], "STEP"),
                              (["clash", plate, path("pin295.obj"), "--units-a", "m"], "carries its own length unit"),
                              (["distance", plate, path("pin295.obj"), "--linear-deflection", "-1"], "deflection"),
                              (["check", plate, "--angular-deflection", "7"], "angular deflection")):
            code, _, err = run(*args)
            self.assertEqual(code, 2, args)
            self.assertIn(message, err)

    def test_assembly_clash_pairs_of_instances(self):
        # The test assembly as written: no pair meets (plate_2 lies 10 mm above plate_1); with a 15 mm
        # clearance that pair is listed. plate_2 moved onto plate_1: a contact; moved into it: a clash
        # 5 mm deep (exit status 1).
        asm = os.path.join(DATA, "assembly.step")
        code, out, err = run("assembly-clash", asm, "--clearance", "15", "--json", path("ac.json"))
        self.assertEqual(code, 0, err)
        r = load_json("ac.json")
        self.assertEqual((r["clashes"], r["contacts"], r["within_clearance"]), (0, 0, 1))
        self.assertEqual(len(r["instances"]), 3)
        p = r["pairs"][0]
        self.assertEqual((p["meeting"], p["b_name"]), ("clearance", "plate_2"))
        self.assertAlmostEqual(p["min_clearance"], 10.0)
        with open(asm) as f:
            text = f.read()
        self.assertIn("#20 = CARTESIAN_POINT('',(0.,0.,20.));", text)  # plate_2's placement
        for lift, meeting, status in (("(0.,0.,10.)", "contact", 0), ("(10.,0.,5.)", "clash", 1)):
            with open(path("moved.step"), "w") as f:
                f.write(text.replace("(0.,0.,20.)", lift))
            for f in ("reg.obj", "cur.obj"):
                if os.path.exists(path(f)):
                    os.remove(path(f))
            code, out, err = run("assembly-clash", path("moved.step"), "--json", path("ac2.json"), "--regions",
                                 path("reg.obj"), "--curves", path("cur.obj"))
            self.assertEqual(code, status, err)
            r = load_json("ac2.json")
            self.assertEqual([q["meeting"] for q in r["pairs"]], [meeting])
            self.assertIn(meeting, out)
            if meeting == "contact":  # nothing clashes: no region, no curve, a note each
                self.assertFalse(os.path.exists(path("reg.obj")))
                self.assertFalse(os.path.exists(path("cur.obj")))
                self.assertIn("not written", err)
            if meeting == "clash":
                self.assertAlmostEqual(r["pairs"][0]["depth"], 5.0, places=6)
                # The upper bound: at least the depth, within the 10 % its branch and bound aims at.
                self.assertTrue(5.0 <= r["pairs"][0]["depth_bound"] <= 5.5 * (1 + 1e-9), r["pairs"][0]["depth_bound"])
                self.assertIn("at most", out)
                code0, _, err0 = run("assembly-clash", path("moved.step"), "--depth-bound-splits", "0", "--json",
                                     path("ac0.json"))
                self.assertEqual(code0, 1, err0)
                self.assertIsNone(load_json("ac0.json")["pairs"][0]["depth_bound"])
                self.assertGreater(r["pairs"][0]["cross_pairs"], 0)
                self.assertGreater(r["pairs"][0]["tessellation_error"], 0)
                self.assertEqual(r["clashes_within_tessellation_error"], 0)
                # The clash regions: triangles of both plates (instances 0 and 1, world coordinates),
                # and the intersection curves inside the plates' common box x in [0, 10], y in [0, 30],
                # z in [5, 10] (plate_2 turned about z and moved by (10, 0, 5)).
                groups, verts, group = {}, [], None
                with open(path("reg.obj")) as f:
                    for line in f:
                        w = line.split()
                        if w and w[0] == "v":
                            verts.append(tuple(map(float, w[1:4])))
                        elif w and w[0] == "g":
                            group = w[1]
                        elif w and w[0] == "f":
                            groups[group] = groups.get(group, 0) + 1
                self.assertEqual(sorted(groups), ["face_0", "face_1"])
                self.assertTrue(all(-20 - 1e-9 <= v[0] <= 40 + 1e-9 and 0 <= v[2] <= 15 + 1e-9 for v in verts))
                points = []
                with open(path("cur.obj")) as f:
                    for line in f:
                        w = line.split()
                        if w and w[0] == "v":
                            points.append(tuple(map(float, w[1:4])))
                self.assertGreater(len(points), 2)
                for x, y, z in points:
                    self.assertTrue(-1e-9 <= x <= 10 + 1e-9 and -1e-9 <= y <= 30 + 1e-9 and 5 - 1e-9 <= z <= 10 + 1e-9,
                                    (x, y, z))
        # Not a STEP file, or a bad clearance: input errors; nothing written.
        write_obj("m.obj", uv_sphere())
        for args, message in (([path("m.obj")], "STEP"), ([asm, "--clearance", "-1"], "--clearance"),
                              ([asm, "--regions", path("r.step")], "--regions"), ([asm, "--curves", path("c.stl")], "--curves")):
            code, _, err = run("assembly-clash", *args, "--json", path("ac3.json"))
            self.assertEqual(code, 2)
            self.assertIn(message, err)
        self.assertFalse(os.path.exists(path("ac3.json")))

    def test_features_dot_is_the_aag(self):
        # --dot draws the graph of --aag: a node per face, an arc per edge with its convexity as the
        # line style, the feature's faces filled, the step's assembly-feature faces in red.
        import re
        import shutil
        import subprocess
        write_process("dot_process.json", [{"id": "P1", "parts": ["*"], "constraint": "screw"}])
        code, _, err = run("features", os.path.join(DATA, "counterbored_plate.step"), "--json", path("fd.json"),
                           "--aag", "--dot", path("fd.dot"), "--process", path("dot_process.json"), "--step", "P1")
        self.assertEqual(code, 0, err)
        part = load_json("fd.json")["parts"][0]
        with open(path("fd.dot")) as f:
            dot = f.read()
        self.assertTrue(dot.startswith("graph aag {") and dot.rstrip().endswith("}"))
        nodes = dict(re.findall(r'^    p0_(\d+) \[(.*)\];$', dot, re.M))
        self.assertEqual(sorted(int(n) for n in nodes), [n["face"] for n in part["aag"]["nodes"]])
        style = {"convex": "solid", "concave": "dashed", "smooth": "dotted"}
        arcs = re.findall(r'^    p0_(\d+) -- p0_(\d+) \[style=(\w+), label="(\w+)"', dot, re.M)
        self.assertEqual(sorted((int(a), int(b), st, c) for a, b, st, c in arcs),
                         sorted((a["faces"][0], a["faces"][1], style[a["convexity"]], a["curve"])
                                for a in part["aag"]["arcs"]))
        feature_faces = set(part["features"][0]["faces"])
        for face, attrs in nodes.items():
            self.assertEqual("fillcolor" in attrs, int(face) in feature_faces, attrs)
            self.assertEqual("color=red" in attrs, int(face) in part["assembly_feature_faces"], attrs)
        self.assertEqual(len(part["assembly_feature_faces"]), 3)  # bore, counterbore, seat
        self.assertIn('label="F6\\ncylinder\\nr 6 hole"', dot)
        if shutil.which("dot"):  # Graphviz, where installed, reads it
            subprocess.run(["dot", "-Tsvg", path("fd.dot"), "-o", path("fd.svg")], check=True)
        code, _, err = run("features", os.path.join(DATA, "counterbored_plate.step"), "--dot",
                           os.path.join(DATA, "counterbored_plate.step"))
        self.assertEqual(code, 2)
        self.assertIn("--dot", err)

    def test_simplify_step_with_process_keeps_the_step_features(self):
        write_process("process.json", [{"id": "P1", "parts": ["*"], "constraint": "screw"},
                                       {"id": "P2", "parts": ["*"], "constraint": "bolt"}])
        code, out, err = run("simplify", os.path.join(DATA, "counterbored_plate.step"), path("cb.ply"), "--ratio",
                             "0.6", "--step", "P1", "--process", path("process.json"), "--lock", "--json",
                             path("cb.json"), "--check-self-intersections")
        self.assertEqual(code, 0, err)
        r = load_json("cb.json")
        self.assertEqual(len(r["feature_faces"]), 3)  # bore, counterbore, seat
        self.assertEqual(r["feature_triangles"]["input"], r["feature_triangles"]["output"])
        self.assertLessEqual(r["hausdorff_features"], 1e-12)
        self.assertEqual(r["self_intersections"], 0)
        # A step naming a part the model does not have keeps nothing of it: a warning, not silence.
        write_process("typo.json", [{"id": "P1", "parts": ["plaet"], "constraint": "screw"}])
        code, _, err = run("simplify", os.path.join(DATA, "counterbored_plate.step"), path("typo.ply"), "--ratio",
                           "0.6", "--step", "P1", "--process", path("typo.json"), "--json", path("typo_r.json"))
        self.assertEqual(code, 0, err)
        self.assertTrue(any("'plaet'" in w for w in load_json("typo_r.json")["cad"]["warnings"]))
        self.assertEqual(load_json("typo_r.json")["feature_faces"], [])
        code, _, err = run("simplify", os.path.join(DATA, "counterbored_plate.step"), path("cb9.ply"), "--ratio",
                           "0.6", "--step", "P9", "--process", path("process.json"))
        self.assertEqual(code, 2)
        self.assertIn("P9", err)
        self.assertFalse(os.path.exists(path("cb9.ply")))

    def test_assembly_parts_are_written_once_each_with_their_placements(self):
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("asm.ply"), "--ratio", "0.5",
                           "--parts-dir", path("parts"), "--json", path("asm.json"))
        self.assertEqual(code, 0, err)
        r = load_json("asm.json")
        parts = r["parts_simplified"]
        self.assertEqual(sorted(p["name"] for p in parts), ["plate", "shaft"])
        out_tris = {}
        for p in parts:
            with open(p["file"], "rb") as f:
                header = []
                while not header or header[-1] != "end_header":
                    header.append(f.readline().decode("ascii").strip())
            faces = int([h for h in header if h.startswith("element face")][0].split()[2])
            self.assertEqual(faces, p["output_triangles"])
            bound = [h for h in header if h.startswith("comment error_bound ")]
            self.assertEqual(float(bound[0].split()[2]), p["error_bound"])
            self.assertLessEqual(p["error_bound"], r["error_bound"])
            self.assertGreater(p["tessellation_error"], 0)  # the B-Rep's curved faces: a chordal error
            self.assertLessEqual(p["tessellation_error"], r["tessellation_error"])
            out_tris[p["part"]] = p["output_triangles"]
        instances = r["cad"]["instances"]
        self.assertEqual(len(instances), 3)  # the plate twice, the shaft once
        for i in instances:
            self.assertEqual(len(i["placement"]), 3)
            self.assertEqual(len(i["placement"][0]), 4)
        self.assertEqual(sum(out_tris[i["part"]] for i in instances), r["output_triangles"])
        shaft = [i for i in instances if i["name"] == "shaft_1"][0]
        self.assertEqual(shaft["placement"][0][3], 100.0)  # moved by (100, 0, 0)
        with open(path("not_a_dir"), "w") as f:
            f.write("x")
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("asm2.ply"), "--ratio", "0.5",
                           "--parts-dir", path("not_a_dir"))
        self.assertEqual(code, 2)
        self.assertIn("not_a_dir", err)
        self.assertFalse(os.path.exists(path("asm2.ply")))  # nothing written
        write_obj("m.obj", uv_sphere())
        code, _, err = run("simplify", path("m.obj"), path("m.ply"), "--ratio", "0.5", "--parts-dir", path("p2"))
        self.assertEqual(code, 2)
        self.assertIn("--parts-dir", err)
        self.assertFalse(os.path.exists(path("m.ply")))

    def test_parts_that_stop_early_leave_their_excess_to_the_others(self):
        # 15 %: the plate (two instances) stops above its share (its seams and corners), the shaft takes
        # the difference and the total budget is met; 10 %: the plate alone fills it, nothing is cut
        # further (the formula's shares, a warning).
        # (--seams all: the default, auto, lets the plate's seams go instead of stopping.)
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("rb.ply"), "--ratio", "0.15",
                           "--seams", "all", "--json", path("rb.json"))
        self.assertEqual(code, 0, err)
        r = load_json("rb.json")
        parts = {p["name"]: p for p in r["parts_simplified"]}
        self.assertGreater(parts["plate"]["output_triangles"], parts["plate"]["target_triangles"])
        self.assertGreaterEqual(r["budget_rounds"], 2)
        self.assertEqual(r["output_triangles"], r["target_triangles"])
        self.assertTrue(r["reached"])
        self.assertEqual(sum(p["instances"] * p["output_triangles"] for p in parts.values()), r["output_triangles"])
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("rb2.ply"), "--ratio", "0.1",
                           "--seams", "all", "--json", path("rb2.json"))
        self.assertEqual(code, 0, err)
        r2 = load_json("rb2.json")
        self.assertEqual(r2["budget_rounds"], 1)
        self.assertFalse(r2["reached"])
        self.assertTrue(any("total budget" in w for w in r2["warnings"]), r2["warnings"])
        shaft = [p for p in r2["parts_simplified"] if p["name"] == "shaft"][0]
        self.assertEqual(shaft["output_triangles"], shaft["target_triangles"])

    def test_default_seams_meet_the_ratio_on_cad_parts_or_say_why(self):
        # Issue #29, item 7: by default (--seams auto) a requested ratio is met on a CAD assembly whose
        # plate's corners hold it above its share with every seam kept (800 -> 112 for 80 before); a
        # warning says the seams were relaxed and what every seam allowed. --seams all keeps the old
        # result and says what holds it.
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("sd.ply"), "--ratio", "0.1",
                           "--json", path("sd.json"))
        self.assertEqual(code, 0, err)
        r = load_json("sd.json")
        self.assertEqual(r["seams"], "auto")
        self.assertEqual(r["output_triangles"], r["target_triangles"])
        self.assertGreater(r["seams_relaxed_at"], 0)
        self.assertIn("with every face seam kept the budget", err)
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("sa.ply"), "--ratio", "0.1",
                           "--seams", "all", "--json", path("sa.json"))
        self.assertEqual(code, 0, err)
        a = load_json("sa.json")
        self.assertGreater(a["output_triangles"], a["target_triangles"])
        self.assertIn("corner vertices", err)

    def test_gltf_is_twin_ready_hierarchy_and_feature_material(self):
        # Issue #29, item 6: the glTF of a STEP assembly keeps its product tree (a group node per path
        # level, the instance's node under it with extras.path) and shows the step's assembly features
        # with their own material, on the mesh's second primitive; read back by this file's reader and,
        # where Node and three.js are found, by three.js's GLTFLoader (an independent reader).
        write_process("twin.json", [{"id": "P1", "parts": ["plate_2"], "constraint": "screw"}])
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("twin.glb"), "--ratio", "0.5",
                           "--step", "P1", "--process", path("twin.json"), "--json", path("twin_r.json"))
        self.assertEqual(code, 0, err)
        r = load_json("twin_r.json")
        doc, _, _ = read_glb(path("twin.glb"))
        nodes = doc["nodes"]
        parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
        self.assertEqual([m["name"] for m in doc["materials"]], ["part", "assembly feature"])
        leaves = {n["extras"]["path"]: i for i, n in enumerate(nodes) if "mesh" in n and "extras" in n}
        for inst in r["cad"]["instances"]:
            self.assertIn(inst["path"], leaves)
            levels = [x for x in inst["path"].split("/") if x]
            i, chain = leaves[inst["path"]], []
            while i in parent:
                chain.append(nodes[i]["name"])
                i = parent[i]
            self.assertEqual(chain[::-1], levels)  # root, then one node per level
        feature_tris = {}
        for m in doc["meshes"]:
            for p in m["primitives"]:
                if p["material"] == 1:
                    feature_tris[m["name"]] = doc["accessors"][p["indices"]]["count"] // 3
        expect = {p["name"]: p["feature_triangles"]["output"] for p in r["parts_simplified"] if p["feature_triangles"]["output"]}
        self.assertEqual(feature_tris, expect)
        self.assertTrue(expect)
        modules = [os.environ.get("INTERFERE_NODE_MODULES"),
                   os.path.join(os.path.dirname(os.path.abspath(cli_common.EXE)), "..", "..", "viewer", "node_modules")]
        modules = [m for m in modules if m and os.path.isfile(os.path.join(m, "three", "examples", "jsm", "loaders",
                                                                          "GLTFLoader.js"))]
        import shutil
        import subprocess
        if not modules or not shutil.which("node"):
            self.skipTest("three.js or Node not found (INTERFERE_NODE_MODULES)")
        script = os.path.join(ROOT, "tests", "view", "twin_summary.mjs")
        out = subprocess.run(["node", script, path("twin.glb"), modules[0]], capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        objects = json.loads(out.stdout)["objects"]
        by_path = {o["path"]: o for o in objects if o["path"]}
        for inst in r["cad"]["instances"]:
            levels = [x for x in inst["path"].split("/") if x]
            self.assertEqual(by_path[inst["path"]]["name"], levels[-1])
            self.assertEqual(by_path[inst["path"]]["parent"], levels[-2] if len(levels) > 1 else "interfere_root")
        shown = {}
        for o in objects:
            if o["mesh"] and o["material"] == "assembly feature":
                shown[o["triangles"]] = shown.get(o["triangles"], 0) + 1
        self.assertEqual(sorted(shown), sorted(set(expect.values())))

    def test_gltf_lod_chain_in_one_run(self):
        # Issue #29, item 6: --lod writes coarser levels (fractions of the budget) as MSFT_lod: every
        # instance node lists one node per level (outside the scene tree, same placement, a mesh of its
        # part's level) and its screen coverages; the report's lods give each level's triangles.
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("lod.glb"), "--ratio", "0.5",
                           "--lod", "0.5,0.25", "--json", path("lod.json"))
        self.assertEqual(code, 0, err)
        r = load_json("lod.json")
        self.assertEqual([l["fraction"] for l in r["lods"]], [0.5, 0.25])
        self.assertEqual([l["target_triangles"] for l in r["lods"]], [200, 100])
        self.assertTrue(all(l["output_triangles"] <= r["output_triangles"] for l in r["lods"]))
        doc, _, _ = read_glb(path("lod.glb"))
        self.assertEqual(doc["extensionsUsed"], ["MSFT_lod"])
        nodes = doc["nodes"]
        in_tree = {c for n in nodes for c in n.get("children", [])}
        leaves = [n for n in nodes if "mesh" in n and "extensions" in n]
        self.assertEqual(len(leaves), len(r["cad"]["instances"]))
        level_tris = [0, 0]
        for n in leaves:
            ids = n["extensions"]["MSFT_lod"]["ids"]
            self.assertEqual(len(ids), 2)
            self.assertEqual(len(n["extras"]["MSFT_screencoverage"]), 3)
            for k, i in enumerate(ids):
                self.assertNotIn(i, in_tree)
                self.assertEqual(nodes[i].get("matrix"), n.get("matrix"))
                mesh = doc["meshes"][nodes[i]["mesh"]]
                self.assertEqual(mesh["name"], doc["meshes"][n["mesh"]]["name"] + " LOD%d" % (k + 1))
                level_tris[k] += sum(doc["accessors"][p["indices"]]["count"] // 3 for p in mesh["primitives"])
        self.assertEqual(level_tris, [l["output_triangles"] for l in r["lods"]])
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("lod.ply"), "--ratio", "0.5",
                           "--lod", "0.5")
        self.assertEqual(code, 2)
        self.assertIn("--lod", err)
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("lod2.glb"), "--ratio", "0.5",
                           "--lod", "0.2,0.5")
        self.assertEqual(code, 2)
        self.assertIn("decreasing", err)

    def test_assembly_clash_pairs_print_by_full_instance_path(self):
        # Issue #29, item 5: pairs print by full instance path (on AS1 six different bolt x bracket
        # pairs all read "bolt_1 x l-bracket_1"), the JSON gives a_path/b_path; distinct pairs never
        # print alike.
        code, out, err = run("assembly-clash", os.path.join(DATA, "assembly.step"), "--clearance", "100",
                             "--json", path("names.json"))
        self.assertIn(code, (0, 1), err)
        r = load_json("names.json")
        paths = [i["path"] for i in r["instances"]]
        self.assertEqual(len(set(paths)), len(paths))
        lines = [l for l in out.splitlines() if " x " in l]
        self.assertEqual(len(lines), len(r["pairs"]))
        self.assertEqual(len(set(l.split(":")[0] for l in lines)), len(lines))
        for p, line in zip(r["pairs"], lines):
            self.assertEqual((p["a_path"], p["b_path"]), (paths[p["a"]], paths[p["b"]]))
            self.assertIn("%s x %s:" % (p["a_path"], p["b_path"]), line)

    def test_mates_pick_the_features_without_a_process(self):
        # Issue #29, item 4: a STEP assembly without --process keeps the features its mates pick (the
        # generated bolted joint: each bolt through the cover, the plate and its nut; head, nut and
        # cover seated); --mates off keeps none; assembly-clash finds its 9 fits, all contacts.
        joint = os.path.join(DATA, "bolted_joint.step")
        code, _, err = run("simplify", joint, path("mates.ply"), "--ratio", "0.3", "--lock", "--json",
                           path("mates.json"))
        self.assertEqual(code, 0, err)
        r = load_json("mates.json")
        self.assertEqual(r["cad"]["features_from"], "mates")
        mates = r["cad"]["mates"]
        self.assertEqual(sum(m["kind"] == "insertion" for m in mates), 6)
        self.assertEqual(sum(m["kind"] == "planar_contact" for m in mates), 5)
        self.assertTrue(all(m["constraint"] == "bolt" for m in mates if m["kind"] == "insertion"))
        self.assertTrue(all(m["a_path"].startswith("/joint/") and m["b_path"].startswith("/joint/") for m in mates))
        self.assertGreater(r["feature_triangles"]["input"], 0)
        self.assertEqual(r["feature_triangles"]["input"], r["feature_triangles"]["output"])  # locked
        for part in r["cad"]["parts"]:
            self.assertTrue(part["assembly_feature_faces"], part["name"])  # every part mates
        code, _, err = run("simplify", joint, path("nomates.ply"), "--ratio", "0.3", "--mates", "off", "--json",
                           path("nomates.json"))
        self.assertEqual(code, 0, err)
        r = load_json("nomates.json")
        self.assertEqual(r["cad"]["features_from"], "none")
        self.assertEqual(r["feature_faces"], [])
        code, _, err = run("simplify", joint, path("badmates.ply"), "--ratio", "0.3", "--mates", "on")
        self.assertEqual(code, 2)
        self.assertIn("--mates must be auto or off", err)
        self.assertFalse(os.path.exists(path("badmates.ply")))
        code, out, err = run("assembly-clash", joint, "--json", path("joint_clash.json"))
        self.assertEqual(code, 0, err)
        c = load_json("joint_clash.json")
        self.assertEqual((c["contacts"], c["clashes"], len(c["pairs"])), (9, 0, 9))
        self.assertEqual(len(set((p["a_path"], p["b_path"]) for p in c["pairs"])), 9)

    def test_mesher_delabella(self):
        # --mesher delabella (issue #29): OCCT's Delabella triangulation of a STEP input, the same
        # features; an unknown name, or a mesh input, is an option error.
        plate = os.path.join(DATA, "counterbored_plate.step")
        write_process("mesher.process.json", [{"id": "P1", "parts": ["*"], "constraint": "screw"}])
        for mesher in ("default", "delabella"):
            code, _, err = run("simplify", plate, path("mesher_%s.ply" % mesher), "--ratio", "0.5", "--step", "P1",
                               "--process", path("mesher.process.json"), "--mesher", mesher, "--json",
                               path("mesher_%s.json" % mesher))
            self.assertEqual(code, 0, err)
        a, b = load_json("mesher_default.json"), load_json("mesher_delabella.json")
        self.assertEqual(len(a["feature_faces"]), len(b["feature_faces"]))
        self.assertGreater(b["input_triangles"], 0)
        code, _, err = run("simplify", plate, path("mesher_x.ply"), "--ratio", "0.5", "--mesher", "fast")
        self.assertEqual(code, 2)
        self.assertIn("--mesher must be default or delabella", err)
        write_obj("mesher_sphere.obj", uv_sphere())
        code, _, err = run("simplify", path("mesher_sphere.obj"), path("mesher_s.ply"), "--ratio", "0.5", "--mesher",
                           "delabella")
        self.assertEqual(code, 2)
        self.assertIn("--mesher tessellates a STEP input", err)

    def test_assembly_budget_is_met_exactly_when_the_parts_allow(self):
        # Every part of the test assembly is closed (an even triangle count): an even total is met
        # exactly, whatever the shares' rounding and odd per-part budgets; an odd one ends one below.
        for target in (300, 301, 304, 307):
            code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path("t.ply"), "--target", str(target),
                               "--json", path("t.json"))
            self.assertEqual(code, 0, err)
            r = load_json("t.json")
            self.assertEqual(r["output_triangles"], target - target % 2, target)
            self.assertEqual(sum(p["instances"] * p["output_triangles"] for p in r["parts_simplified"]),
                             r["output_triangles"])
            self.assertEqual(r["reached"], target % 2 == 0)
            if target % 2:
                self.assertTrue(any("one triangle below" in w for w in r["warnings"]), r["warnings"])
            # Parts one below are counted in one warning (when the total falls short), not each with its own.
            below = [p for p in r["parts_simplified"] if p["one_below"]]
            for p in r["parts_simplified"]:
                self.assertEqual(p["one_below"], p["output_triangles"] + 1 == p["target_triangles"], p)
            self.assertFalse(any("not reached exactly" in w for w in r["warnings"]), r["warnings"])
            if below and not r["reached"]:
                n = len(below)
                self.assertTrue(any(w.startswith("%d part%s ended one triangle below" % (n, "" if n == 1 else "s"))
                                    for w in r["warnings"]), r["warnings"])

    def simplify_assembly_step(self, step, out, ratio):
        """Simplifies the test assembly to `ratio` with the process step `step` (id P1); the report."""
        write_process(out + ".process.json", [step])
        code, _, err = run("simplify", os.path.join(DATA, "assembly.step"), path(out), "--ratio", ratio, "--step",
                           "P1", "--process", path(out + ".process.json"), "--json", path(out + ".json"))
        self.assertEqual(code, 0, err)
        return load_json(out + ".json")

    def test_step_all_simplifies_every_step_like_single_runs(self):
        # --step all: one import, one output and report per step, each identical to its own run.
        steps = [{"id": "P1", "parts": ["plate_2"], "constraint": "screw"},
                 {"id": "P2", "parts": ["shaft"], "constraint": "gear_shaft"}]
        write_process("all.process.json", steps)
        asm = os.path.join(DATA, "assembly.step")
        code, out, err = run("simplify", asm, path("all.ply"), "--ratio", "0.6", "--step", "all", "--process",
                             path("all.process.json"), "--json", path("all.json"), "--parts-dir", path("all_parts"))
        self.assertEqual(code, 0, err)
        self.assertIn("step P1:", out)
        self.assertIn("step P2:", out)
        for step in ("P1", "P2"):
            r = load_json("all_%s.json" % step)
            self.assertEqual(r["cad"]["step"], step)
            self.assertTrue(os.path.isdir(path(os.path.join("all_parts", step))))
            code, _, err = run("simplify", asm, path("one_%s.ply" % step), "--ratio", "0.6", "--step", step,
                               "--process", path("all.process.json"))
            self.assertEqual(code, 0, err)
            with open(path("all_%s.ply" % step), "rb") as a, open(path("one_%s.ply" % step), "rb") as b:
                self.assertEqual(a.read(), b.read())
        self.assertNotEqual(load_json("all_P1.json")["feature_faces"], load_json("all_P2.json")["feature_faces"])
        code, _, err = run("simplify", asm, path("bad.ply"), "--ratio", "0.6", "--step", "all")
        self.assertEqual(code, 2)
        self.assertIn("--process", err)
        # Step ids that map to one file name ("P 1", "P_1": OUT_P_1.ply) would overwrite each other.
        write_process("clash.process.json", [{"id": "P 1", "parts": ["*"], "constraint": "screw"},
                                             {"id": "P_1", "parts": ["*"], "constraint": "gear_shaft"}])
        code, _, err = run("simplify", asm, path("clash.ply"), "--ratio", "0.6", "--step", "all", "--process",
                           path("clash.process.json"))
        self.assertEqual(code, 2)
        self.assertIn("'P 1' and 'P_1'", err)
        self.assertFalse(os.path.exists(path("clash_P_1.ply")))

    def test_features_of_a_step_input_are_kept(self):
        # --features on a STEP input names faces by the output's face ids (one part: the ids
        # `interfere features` lists): locked, they come out bit-identical, like the step's.
        plate = os.path.join(DATA, "counterbored_plate.step")
        code, out, err = run("features", plate, "--json", path("fx_features.json"))
        self.assertEqual(code, 0, err)
        bore = load_json("fx_features.json")["parts"][0]["features"][0]["faces"]  # the counterbored hole
        code, _, err = run("simplify", plate, path("fx.ply"), "--ratio", "0.3", "--features",
                           ",".join(str(f) for f in bore), "--lock", "--json", path("fx.json"))
        self.assertEqual(code, 0, err)
        r = load_json("fx.json")
        self.assertEqual(r["feature_faces"], sorted(bore))
        self.assertGreater(r["feature_triangles"]["input"], 0)
        self.assertEqual(r["feature_triangles"]["input"], r["feature_triangles"]["output"])
        self.assertLessEqual(r["hausdorff_features"], 1e-12)
        code, _, err = run("simplify", plate, path("fx_bad.ply"), "--ratio", "0.3", "--features", "9999")
        self.assertEqual(code, 2)
        self.assertIn("face id 9999 is on no part", err)
        self.assertFalse(os.path.exists(path("fx_bad.ply")))
        # A STEP input's regions are its faces: --regions and --sharp-angle would be ignored, so errors.
        with open(path("fx_regions.txt"), "w") as f:
            f.write("0\n")
        for extra in (["--regions", path("fx_regions.txt")], ["--sharp-angle", "30"]):
            code, _, err = run("simplify", plate, path("fx_bad.ply"), "--ratio", "0.3", *extra)
            self.assertEqual(code, 2, extra)
            self.assertIn("plain meshes", err)

    def test_a_constraint_no_rule_knows_is_an_error_before_anything_is_written(self):
        # A misspelt constraint would leave the step's features unprotected: an error naming the
        # step, the constraint and the constraints the rules know; with --step all no step's output
        # is written, also where an earlier step is fine.
        steps = [{"id": "P1", "parts": ["*"], "constraint": "screw"},
                 {"id": "P2", "parts": ["*"], "constraint": "gear_on_shaft"}]
        write_process("misspelt.process.json", steps)
        plate = os.path.join(DATA, "counterbored_plate.step")
        for step in ("P2", "all"):
            code, out, err = run("simplify", plate, path("misspelt.ply"), "--ratio", "0.6", "--step", step,
                                 "--process", path("misspelt.process.json"), "--json", path("misspelt.json"))
            self.assertEqual(code, 2, err)
            self.assertIn("'gear_on_shaft'", err)
            self.assertIn("'P2'", err)
            self.assertIn("'gear_shaft'", err)  # the known constraints are listed
            self.assertEqual(out, "")
            for name in ("misspelt.ply", "misspelt_P1.ply", "misspelt_P2.ply", "misspelt.json", "misspelt_P1.json"):
                self.assertFalse(os.path.exists(path(name)), name)
        code, out, err = run("features", plate, "--step", "all", "--process", path("misspelt.process.json"))
        self.assertEqual(code, 2)
        self.assertIn("'gear_on_shaft'", err)
        self.assertEqual(out, "")  # checked before the import: no part listed

    def test_simplify_reads_its_own_rules_and_library(self):
        # --rules/--library: the user's JSON instead of the installed files, as for `features`. A rule
        # set naming the screw rule's constraint "cap_screw" selects the same faces as the default
        # rules do for "screw".
        with open(os.path.join(ROOT, "data", "features", "semantics.json")) as f:
            rules = json.load(f)
        for rule in rules["rules"]:
            if rule["constraint"] == "screw":
                rule["constraint"] = "cap_screw"
        with open(path("own_rules.json"), "w") as f:
            json.dump(rules, f)
        write_process("own.process.json", [{"id": "P1", "parts": ["*"], "constraint": "cap_screw"}])
        write_process("default.process.json", [{"id": "P1", "parts": ["*"], "constraint": "screw"}])
        plate = os.path.join(DATA, "counterbored_plate.step")
        library = os.path.join(ROOT, "data", "features", "library.json")
        code, _, err = run("simplify", plate, path("own.ply"), "--ratio", "0.6", "--step", "P1", "--process",
                           path("own.process.json"), "--rules", path("own_rules.json"), "--library", library,
                           "--json", path("own.json"))
        self.assertEqual(code, 0, err)
        code, _, err = run("simplify", plate, path("default.ply"), "--ratio", "0.6", "--step", "P1", "--process",
                           path("default.process.json"), "--json", path("default.json"))
        self.assertEqual(code, 0, err)
        self.assertEqual(len(load_json("own.json")["feature_faces"]), 3)  # bore, counterbore, seat
        self.assertEqual(load_json("own.json")["feature_faces"], load_json("default.json")["feature_faces"])
        # The installed rules do not know "cap_screw".
        code, _, err = run("simplify", plate, path("own2.ply"), "--ratio", "0.6", "--step", "P1", "--process",
                           path("own.process.json"))
        self.assertEqual(code, 2)
        self.assertIn("'cap_screw'", err)
        # Rules without a process apply to the mates inferred from an assembly (--mates auto, the
        # default, issue #29); with --mates off, or on a plain mesh, they are option errors.
        code, _, err = run("simplify", plate, path("own3.ply"), "--ratio", "0.6", "--rules", path("own_rules.json"))
        self.assertEqual(code, 0, err)
        code, _, err = run("simplify", plate, path("own3.ply"), "--ratio", "0.6", "--rules", path("own_rules.json"),
                           "--mates", "off")
        self.assertEqual(code, 2)
        self.assertIn("process", err)
        write_obj("own_sphere.obj", uv_sphere())
        code, _, err = run("simplify", path("own_sphere.obj"), path("own4.ply"), "--ratio", "0.6",
                           "--rules", path("own_rules.json"))
        self.assertEqual(code, 2)
        self.assertIn("STEP input", err)

    def test_features_step_all_lists_every_step(self):
        steps = [{"id": "P1", "parts": ["plate_2"], "constraint": "screw"},
                 {"id": "P2", "parts": ["shaft"], "constraint": "gear_shaft"}]
        write_process("fall.process.json", steps)
        asm = os.path.join(DATA, "assembly.step")
        code, out, err = run("features", asm, "--process", path("fall.process.json"), "--step", "all", "--json",
                             path("fall.json"))
        self.assertEqual(code, 0, err)
        parts = {p["name"]: p for p in load_json("fall.json")["parts"]}
        for step in ("P1", "P2"):
            code, _, err = run("features", asm, "--process", path("fall.process.json"), "--step", step, "--json",
                               path("f_%s.json" % step))
            self.assertEqual(code, 0, err)
            for p in load_json("f_%s.json" % step)["parts"]:
                self.assertEqual(parts[p["name"]]["steps"][step]["assembly_feature_faces"], p["assembly_feature_faces"])
        self.assertEqual(len(parts["plate"]["steps"]["P1"]["assembly_feature_faces"]), 3)
        self.assertEqual(parts["plate"]["steps"]["P2"]["assembly_feature_faces"], [])
        self.assertGreater(len(parts["shaft"]["steps"]["P2"]["assembly_feature_faces"]), 0)
        self.assertIn("step P2:", out)

    def test_a_step_naming_one_instance_keeps_the_features_of_that_instance_only(self):
        # The plate is used twice; the step names the instance plate_2: the plate is simplified once
        # with the screw features (for plate_2) and once without (for the other instance).
        r = self.simplify_assembly_step({"id": "P1", "parts": ["plate_2"], "constraint": "screw"}, "inst.ply", "0.6")
        parts = {p["name"]: p for p in r["parts_simplified"]}
        self.assertEqual(sorted(parts), ["plate", "plate [P1]", "shaft"])
        self.assertEqual(parts["plate"]["model_part"], parts["plate [P1]"]["model_part"])
        self.assertGreater(parts["plate [P1]"]["feature_triangles"]["input"], 0)
        self.assertEqual(parts["plate"]["feature_triangles"]["input"], 0)
        inst = {i["name"]: i for i in r["cad"]["instances"]}
        self.assertTrue(inst["plate_2"]["in_step"])
        self.assertFalse(inst["shaft_1"]["in_step"])
        by_index = {p["part"]: p["name"] for p in r["parts_simplified"]}
        self.assertEqual(by_index[inst["plate_2"]["simplified_part"]], "plate [P1]")
        self.assertEqual(len(r["feature_faces"]), 3)  # bore, counterbore, seat of one plate
        self.assertEqual(r["cad"]["warnings"], [])  # plate_2 is a known name
        # `features` lists the plate's step features too (its instance plate_2 is in the step).
        code, _, err = run("features", os.path.join(DATA, "assembly.step"), "--process", path("inst.ply.process.json"),
                           "--step", "P1", "--json", path("inst_features.json"))
        self.assertEqual(code, 0, err)
        f = {p["name"]: p for p in load_json("inst_features.json")["parts"]}
        self.assertEqual(len(f["plate"]["assembly_feature_faces"]), 3)
        self.assertEqual(f["shaft"]["assembly_feature_faces"], [])
        self.assertEqual(load_json("inst_features.json")["warnings"], [])

    def test_assembly_as_glb_stores_each_part_once_with_instances(self):
        r = self.simplify_assembly_step({"id": "P1", "parts": ["*"], "constraint": "screw"}, "asm.glb", "0.5")
        doc, _, read = read_glb(path("asm.glb"))
        parts = {p["name"]: p for p in r["parts_simplified"]}
        self.assertEqual(sorted(m["name"] for m in doc["meshes"]), sorted(parts))
        root = doc["nodes"][0]
        self.assertEqual(root["scale"], [0.001, 0.001, 0.001])  # mm -> metres
        # The product tree (issue #29): the root holds the assembly's group node, whose children are
        # the three instances (plate twice, shaft once).
        self.assertEqual([doc["nodes"][c]["name"] for c in root["children"]], ["assembly"])
        leaves = [n for n in doc["nodes"] if "mesh" in n]
        self.assertEqual(len(leaves), 3)
        self.assertEqual(sorted(doc["nodes"][root["children"][0]]["children"]),
                         sorted(i for i, n in enumerate(doc["nodes"]) if "mesh" in n))
        triangles = 0
        for node in leaves:
            mesh = doc["meshes"][node["mesh"]]
            prim = mesh["primitives"][0]  # (the part's triangles; its assembly features: a second one)
            for p in mesh["primitives"][1:]:
                self.assertEqual(p["attributes"], prim["attributes"])  # the same vertices
            idx = [i for p in mesh["primitives"] for i in read(p["indices"])]
            pos = read(prim["attributes"]["POSITION"])
            face = read(prim["attributes"]["_FACE_ID"])
            feature = read(prim["attributes"]["_FEATURE"])
            nv = len(pos) // 3
            self.assertEqual(len(face), nv)
            self.assertTrue(all(0 <= i < nv for i in idx))
            self.assertEqual(len(idx) // 3, parts[mesh["name"]]["output_triangles"])
            self.assertEqual(mesh["extras"]["error_bound"], parts[mesh["name"]]["error_bound"])
            a = doc["accessors"][prim["attributes"]["POSITION"]]
            for k in range(3):
                self.assertAlmostEqual(a["min"][k], min(pos[k::3]))
                self.assertAlmostEqual(a["max"][k], max(pos[k::3]))
            if mesh["name"] == "plate":  # the counterbore's faces are the screw step's features
                self.assertEqual(sum(1 for x in feature if x == 1.0) > 0, True)
            triangles += len(idx) // 3
            if node["name"] == "shaft_1":
                self.assertEqual(node["matrix"][12:15], [100.0, 0.0, 0.0])  # column-major translation
        self.assertEqual(triangles, r["output_triangles"])
        self.assertEqual(doc["scenes"][0]["extras"]["error_bound"], r["error_bound"])

    def test_bad_step_files(self):
        with open(path("empty.step"), "w"):
            pass
        code, _, err = run("features", path("empty.step"))
        self.assertEqual(code, 2)
        self.assertIn("empty", err)
        with open(path("junk.step"), "w") as out:
            out.write("not a step file\n")
        code, _, err = run("features", path("junk.step"))
        self.assertEqual(code, 2)
        with open(path("rules.json"), "w") as out:
            json.dump({"rules": [{"name": "weld", "constraint": "w", "features": [{"type": "weld_seam"}]}]}, out)
        write_process("p.json", [{"id": "P1", "constraint": "w"}])
        code, _, err = run("features", os.path.join(DATA, "counterbored_plate.step"), "--rules", path("rules.json"),
                           "--process", path("p.json"), "--step", "P1")
        self.assertEqual(code, 2)
        self.assertIn("weld_seam", err)

    def test_malformed_step_is_an_error_naming_the_line_with_nothing_on_stdout(self):
        # OCCT prints its parser's failures to stdout; they belong in the error, stdout stays clean,
        # and an existing output is left alone.
        with open(os.path.join(DATA, "counterbored_plate.step")) as f:
            text = f.read()
        with open(path("truncated.step"), "w") as out:
            out.write(text[: len(text) * 3 // 5])
        code, out_text, err = run("features", path("truncated.step"))
        self.assertEqual(code, 2)
        self.assertIn("truncated.step", err)
        self.assertIn("Line", err)
        self.assertEqual(out_text.strip(), "")
        with open(path("keep.ply"), "w") as out:
            out.write("previous result")
        code, out_text, err = run("simplify", path("truncated.step"), path("keep.ply"), "--ratio", "0.5")
        self.assertEqual(code, 2)
        self.assertNotIn("ERR", out_text)
        with open(path("keep.ply")) as f:
            self.assertEqual(f.read(), "previous result")


if __name__ == "__main__":
    cli_common.main()
