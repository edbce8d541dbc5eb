#!/usr/bin/env python3
"""Issue #23 on FEM input (items 1, 10, 13): a part buried in a wall of warped hexahedra (whose
opposite-corner orientation votes tie) is a clash, not clear; bonded bodies of one conforming mesh
are a contact, overlapping ones a clash; gmsh's Abaqus, Nastran, VTK and MSH exports of one geometry
(with their line and boundary elements) read as the same closed body of the right volume.

Usage: test_fem_verdicts.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only; the
gmsh test is skipped when the gmsh binary is absent. Oracles: the analytic volume of the gmsh box, a
winding-number test of the buried part's corners against every triangulation of the hexahedron's
faces, the gmsh files' own element counts.
"""
import itertools
import math
import os
import shutil
import struct
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run, load_json, write_text  # noqa: E402

# Two hexahedra (Abaqus/VTK node order, integer coordinates, positive Jacobian at every corner)
# with one face so warped that the opposite-corner vote of the surface extraction ties: four of the
# other corners lie on each side of the face's two triangle planes (the faces of the can).
TIED_HEXES = [
    [(-167, 284, -91), (770, -194, -95), (854, 1034, 295), (110, 746, -183),
     (204, -230, 193), (741, 221, 93), (803, 1218, 333), (56, 1209, 44)],
    [(-280, 43, -6), (1023, 152, 109), (1207, 777, 175), (-19, 1207, -56),
     (-133, -194, 47), (749, -233, 478), (849, 1198, 342), (22, 1182, 468)],
]
HEX_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def det3(u, v, w):
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])


def norm(u):
    return math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])


def solid_angle(p, a, b, c):
    """Signed solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983)."""
    u, v, w = sub(a, p), sub(b, p), sub(c, p)
    lu, lv, lw = norm(u), norm(v), norm(w)
    dot = lambda x, y: x[0] * y[0] + x[1] * y[1] + x[2] * y[2]  # noqa: E731
    return 2 * math.atan2(det3(u, v, w), lu * lv * lw + dot(u, v) * lw + dot(u, w) * lv + dot(v, w) * lu)


def inside_every_triangulation(hexa, p):
    """p is inside the hexahedron whichever diagonal splits each of its (warped) faces: the winding
    number of every one of the 2^6 triangulated surfaces is 1 (either orientation)."""
    for choice in itertools.product((0, 1), repeat=6):
        total = 0.0
        for (a, b, c, d), ch in zip(HEX_FACES, choice):
            tris = [(a, b, c), (a, c, d)] if ch == 0 else [(b, c, d), (b, d, a)]
            for t in tris:
                total += solid_angle(p, hexa[t[0]], hexa[t[1]], hexa[t[2]])
        if abs(abs(total / (4 * math.pi)) - 1) > 1e-6:
            return False
    return True


def write_inp(name, hexes):
    lines = ["*NODE"]
    for k, h in enumerate(hexes):
        for i, (x, y, z) in enumerate(h):
            lines.append("%d, %r, %r, %r" % (8 * k + i + 1, float(x), float(y), float(z)))
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=wall")
    for k in range(len(hexes)):
        lines.append("%d, %s" % (k + 1, ", ".join(str(8 * k + i + 1) for i in range(8))))
    return write_text(name, "\n".join(lines) + "\n")


def write_cube_stl(name, c, h):
    """Closed outward cube of half-size h around c (ASCII STL)."""
    v = [(c[0] + sx * h, c[1] + sy * h, c[2] + sz * h) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    out = ["solid cube"]
    for a, b, cc, d in quads:
        for t in ((a, b, cc), (a, cc, d)):
            out.append("facet normal 0 0 0\nouter loop")
            out += ["vertex %r %r %r" % v[i] for i in t]
            out.append("endloop\nendfacet")
    out.append("endsolid cube")
    return write_text(name, "\n".join(out) + "\n"), v


def read_binary_stl(p):
    with open(p, "rb") as f:
        data = f.read()
    (n,) = struct.unpack_from("<I", data, 80)
    return [[struct.unpack_from("<3f", data, 84 + 50 * i + 12 + 12 * k) for k in range(3)] for i in range(n)]


def stl_volume(tris):
    return sum(det3(a, b, c) for a, b, c in tris) / 6


class FemVerdicts(unittest.TestCase):
    def test_part_buried_in_a_warped_hex_wall_is_a_clash(self):
        hexa = TIED_HEXES[1]  # its face S2 ties
        wall = write_inp("wall.inp", [hexa])
        # Above the centroid (427.25, 516.5, 194.6), where the hexahedron is thick enough for every
        # triangulation of its warped faces to hold the cube.
        cube, corners = write_cube_stl("buried.stl", (427.25, 516.5, 150.0), 20.0)
        # The oracle: every corner of the cube lies inside the hexahedron, whatever the face splits.
        for q in corners:
            self.assertTrue(inside_every_triangulation(hexa, q), q)
        # The wall's surface is closed (the tied face is oriented like its neighbours).
        rc, out, err = run("surface", wall, path("wall.stl"), "--json", path("wall_surface.json"))
        self.assertEqual(rc, 0, err)
        self.assertTrue(load_json("wall_surface.json")["parts"][0]["closed"])
        self.assertGreater(stl_volume(read_binary_stl(path("wall.stl"))), 0)
        rc, out, err = run("check", path("wall.stl"), "--json", path("wall_check.json"))
        self.assertTrue(load_json("wall_check.json")["closed"], out + err)
        # The buried part: containment decides, a clash (exit 1), never clear.
        rc, out, err = run("clash", wall, cube, "--json", path("buried.json"))
        self.assertEqual(rc, 1, out + err)
        rep = load_json("buried.json")
        self.assertEqual(rep["verdict"], "clash")
        self.assertEqual(rep["result"]["containment"], "b_inside_a")

    def test_bonded_bodies_are_a_contact_and_overlapping_ones_a_clash(self):
        # One conforming hex mesh of [0,2]x[0,1]x[0,1] (2 cells in x): materials "left" and "right"
        # share the face x = 1 (its nodes). Then "right" as its own mesh moved 0.25 into "left".
        def grid_model(name, shift):
            nodes, elems = [], []
            idx = {}
            for k in range(2):
                for j in range(2):
                    for i in range(3):
                        idx[(i, j, k)] = len(nodes) + 1
                        nodes.append((i, j, k))
            cor = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
            for i in range(2):
                elems.append((i + 1, i + 1, [idx[(i + a, b, c)] for a, b, c in cor]))
            if shift:  # right body on its own nodes, moved by -shift
                base = len(nodes)
                for n in range(len(nodes)):
                    x, y, z = nodes[n]
                    nodes.append((x - shift, y, z))
                elems[1] = (2, 2, [v + base for v in elems[1][2]])
            lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "2", '3 1 "left"', '3 2 "right"',
                     "$EndPhysicalNames", "$Nodes", str(len(nodes))]
            lines += ["%d %r %r %r" % (n + 1, float(x), float(y), float(z)) for n, (x, y, z) in enumerate(nodes)]
            lines += ["$EndNodes", "$Elements", str(len(elems))]
            lines += ["%d 5 2 %d %d %s" % (e, g, g, " ".join(map(str, v))) for e, g, v in elems]
            lines.append("$EndElements")
            return write_text(name, "\n".join(lines) + "\n")

        bonded = grid_model("bonded.msh", 0)
        args = ["clash", bonded, bonded, "--part-a", "left", "--part-b", "right"]
        rc, out, err = run(*args, "--json", path("bonded.json"))
        self.assertEqual(rc, 0, out + err)
        rep = load_json("bonded.json")
        self.assertEqual(rep["verdict"], "contact")
        self.assertGreater(rep["result"]["touch_pairs"], 0)
        self.assertEqual(rep["result"]["cross_pairs"], 0)
        rc, out, err = run(*args, "--fail-on", "contact")
        self.assertEqual(rc, 1, out + err)
        overlap = grid_model("overlap.msh", 0.25)
        rc, out, err = run("clash", overlap, overlap, "--part-a", "left", "--part-b", "right", "--json",
                           path("overlap.json"))
        self.assertEqual(rc, 1, out + err)
        self.assertEqual(load_json("overlap.json")["verdict"], "clash")

    @unittest.skipUnless(shutil.which("gmsh"), "gmsh not installed")
    def test_gmsh_exports_read_as_one_closed_body(self):
        # A 2 x 1 x 1.5 box meshed by gmsh (tets with the boundary triangles, edge lines and corner
        # points gmsh writes beside them), exported to every FEM format it writes.
        geo = write_text("part.geo", 'SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 2, 1, 1.5};\n'
                         "Mesh.MeshSizeMax = 0.5;\n")
        volume = 2 * 1 * 1.5
        for order in (1, 2):
            for ext in ("inp", "bdf", "vtk", "msh"):
                with self.subTest(order=order, ext=ext):
                    out = path("part%d.%s" % (order, ext))
                    p = subprocess.run(["gmsh", geo, "-3", "-order", str(order), "-o", out], capture_output=True,
                                       text=True, timeout=300)
                    self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
                    js = path("part%d_%s.json" % (order, ext))
                    rc, o, err = run("surface", out, path("part%d_%s.stl" % (order, ext)), "--json", js)
                    self.assertEqual(rc, 0, err)
                    rep = load_json(js)
                    self.assertEqual(rep["input"]["bodies"], [rep["parts"][0]["name"]])  # one body
                    self.assertTrue(rep["parts"][0]["closed"])
                    self.assertAlmostEqual(rep["input"]["enclosed_volume"], volume, delta=1e-9 * volume)
                    # The lines (and points) gmsh wrote are skipped with a counted warning.
                    self.assertIn("skipped", err)
                    if ext == "inp":
                        with open(out) as f:
                            text = f.read().upper()
                        self.assertIn("TYPE=T3D", text)
                        self.assertIn("TYPE=CPS", text)
                    rc, o, err = run("clash", out, out, "--json", path("self_%d_%s.json" % (order, ext)))
                    self.assertEqual(rc, 1, o + err)  # a body against itself: a clash


if __name__ == "__main__":
    cli_common.main()
