#!/usr/bin/env python3
"""End-to-end tests of the supported coordinate range (issue #23, item 7; docs/robustness.md,
'Coordinate range'): 0, or 2^-250 <= |x| <= 2^100.

Just inside the range the answers are exact: the intersecting triangle pairs of a scene placed at
the top (2^100) and at the bottom (2^-250) of the range are compared with an independent exact
oracle (rational arithmetic, Python's fractions), and a part wholly inside another is found
inside. Just outside it every command rejects the input (exit 2, the file, the line and the vertex
named, no output written): before, 1e110 gave wrong pairs and 'contact' for a contained part, 1e200
'degenerate' triangles, 1e300 'max_error -nan' from simplify.

Usage: test_coordinate_range.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only.
"""
import math
import os
import sys
import unittest
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import path, run, load_json, write_obj  # noqa: E402

TOP = 2.0 ** 100
BOTTOM = 2.0 ** -250
TET_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]  # outward for the corners below


def tet(size, offset=(0.0, 0.0, 0.0)):
    """The corner tetrahedron (0, e1, e2, e3) * size + offset, outward faces."""
    corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    v = [tuple(c[k] * size + offset[k] for k in range(3)) for c in corners]
    return v, TET_FACES


# --- the oracle: exact closed triangle-triangle intersection in rationals ------------------------

def sub(a, b):
    return tuple(a[k] - b[k] for k in range(3))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(a[k] * b[k] for k in range(3))


def sgn(x):
    return (x > 0) - (x < 0)


def seg_seg_2d(p, q, r, s):
    """Closed 2D segments intersect (exact)."""
    def o(a, b, c):
        return sgn((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))

    def on(a, b, c):  # c on segment ab, given collinear
        return min(a[0], b[0]) <= c[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= c[1] <= max(a[1], b[1])
    d1, d2, d3, d4 = o(p, q, r), o(p, q, s), o(r, s, p), o(r, s, q)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return (d1 == 0 and on(p, q, r)) or (d2 == 0 and on(p, q, s)) or (d3 == 0 and on(r, s, p)) or \
        (d4 == 0 and on(r, s, q))


def point_in_tri_2d(x, a, b, c):
    def o(p, q, r):
        return sgn((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
    s = [o(a, b, x), o(b, c, x), o(c, a, x)]
    return not (min(s) < 0 < max(s))


def seg_tri(p, q, t):
    """Closed segment pq meets the closed (non-degenerate) triangle t, exactly."""
    a, b, c = t
    n = cross(sub(b, a), sub(c, a))
    drop = max(range(3), key=lambda k: abs(n[k]))
    keep = [k for k in range(3) if k != drop]

    def pr(x):
        return (x[keep[0]], x[keep[1]])
    den = dot(n, sub(q, p))
    num = dot(n, sub(a, p))
    if den == 0:
        if num != 0:
            return False  # parallel, off the plane
        if point_in_tri_2d(pr(p), pr(a), pr(b), pr(c)) or point_in_tri_2d(pr(q), pr(a), pr(b), pr(c)):
            return True
        return any(seg_seg_2d(pr(p), pr(q), pr(u), pr(v)) for u, v in ((a, b), (b, c), (c, a)))
    tt = num / den
    if tt < 0 or tt > 1:
        return False
    x = tuple(p[k] + tt * (q[k] - p[k]) for k in range(3))
    return point_in_tri_2d(pr(x), pr(a), pr(b), pr(c))


def tri_tri(t, u):
    """Closed triangles meet iff an edge of one meets the other (the intersection is convex; its
    extreme points lie on edges)."""
    return any(seg_tri(t[i], t[(i + 1) % 3], u) for i in range(3)) or \
        any(seg_tri(u[i], u[(i + 1) % 3], t) for i in range(3))


def oracle_pairs(ma, mb):
    def tris(m):
        v, f = m
        fv = [tuple(Fraction(x) for x in p) for p in v]
        return [(fv[i], fv[j], fv[k]) for i, j, k in f]
    ta, tb = tris(ma), tris(mb)
    return sorted((i, j) for i in range(len(ta)) for j in range(len(tb)) if tri_tri(ta[i], tb[j]))


def engine_pairs(name):
    with open(path(name)) as f:
        return sorted(tuple(int(x) for x in line.split()[:2]) for line in f if line.strip())


class InsideTheRange(unittest.TestCase):
    def check_scene(self, tag, small, big):
        a = write_obj(tag + "_a.obj", small)
        b = write_obj(tag + "_b.obj", big)
        code, out, err = run(a, b, "--pairs", path(tag + ".pairs"), "--json", path(tag + ".json"),
                             command=("clash",))
        self.assertIn(code, (0, 1), err)
        got = engine_pairs(tag + ".pairs")
        self.assertEqual(got, oracle_pairs(small, big), tag)
        return load_json(tag + ".json"), got

    def test_pairs_at_the_top_match_the_exact_oracle(self):
        # A unit tetrahedron on a face of one 2^100 across, shifted down by 2^97: the faces in
        # the planes x = 0 and y = 0 touch, the far faces are 2^96 and more away.
        report, got = self.check_scene("top", tet(1.0), tet(TOP, (0.0, 0.0, -TOP / 8)))
        self.assertTrue(got)
        self.assertEqual(report["result"]["cross_pairs"], 0)

    def test_pairs_at_the_bottom_match_the_exact_oracle(self):
        report, got = self.check_scene("bottom", tet(BOTTOM * 2 ** 20),
                                       tet(BOTTOM * 2 ** 60, (0.0, 0.0, -BOTTOM * 2 ** 57)))
        self.assertTrue(got)

    def test_mixed_magnitudes_match_the_exact_oracle(self):
        # A tetrahedron of size 2^-200 resting, from inside, on the face z = 0 of one 2^100
        # across: coordinates 2^-201 beside 2^98 in the same determinants.
        self.check_scene("mixed", tet(2.0 ** -200, (2.0 ** -201, 2.0 ** -201, 0.0)),
                         tet(TOP, (-TOP / 4, -TOP / 4, 0.0)))

    def test_contained_part_is_a_clash_at_the_top(self):
        # The unit tetrahedron strictly inside one 2^100 across: containment, no pair.
        a = write_obj("in_a.obj", tet(1.0))
        b = write_obj("in_b.obj", tet(TOP, (-TOP / 8,) * 3))
        code, out, err = run(a, b, "--json", path("in.json"), command=("clash",))
        self.assertEqual(code, 1, err)
        r = load_json("in.json")["result"]
        self.assertEqual(r["containment"], "a_inside_b")
        self.assertEqual(r["pairs"], 0)

    def test_check_at_the_top_finds_no_degenerate_triangle(self):
        m = write_obj("top_check.obj", tet(TOP))
        code, out, err = run(m, "--json", path("top_check.json"), command=("check",))
        self.assertEqual(code, 0, err)
        self.assertEqual(load_json("top_check.json")["degenerate_triangles"], 0)

    def test_simplify_at_the_top_reports_finite_errors(self):
        m = write_obj("sphere_top.obj", uv_sphere(TOP))
        code, out, err = run("--ratio", "0.5", "--json", path("sphere_top.json"), m, path("sphere_top_out.obj"),
                             command=("simplify",))
        self.assertEqual(code, 0, err)
        self.assertNotIn("nan", (out + err).lower())
        with open(path("sphere_top.json")) as f:
            self.assertNotIn("nan", f.read().lower())


def uv_sphere(radius, n=8):
    v, f = [], []
    v.append((0.0, 0.0, radius))
    for i in range(1, n):
        th = math.pi * i / n
        for j in range(2 * n):
            ph = math.pi * j / n
            v.append((radius * math.sin(th) * math.cos(ph), radius * math.sin(th) * math.sin(ph),
                      radius * math.cos(th)))
    v.append((0.0, 0.0, -radius))
    ring = lambda i, j: 1 + (i - 1) * 2 * n + j % (2 * n)  # noqa: E731
    for j in range(2 * n):
        f.append((0, ring(1, j), ring(1, j + 1)))
        f.append((len(v) - 1, ring(n - 1, j + 1), ring(n - 1, j)))
    for i in range(1, n - 1):
        for j in range(2 * n):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            f.append((a, c, b))
            f.append((b, c, d))
    return v, f


class OutsideTheRange(unittest.TestCase):
    def expect_rejected(self, code, err, file, *words):
        self.assertEqual(code, 2, err)
        self.assertIn(os.path.basename(file), err)
        self.assertIn("outside the supported coordinate range", err)
        for w in words:
            self.assertIn(w, err)
        self.assertNotIn("nan", err.lower())

    def test_clash_at_1e110_is_rejected_not_answered(self):
        # Before: 'contact', 2 pairs, exit 0 for a part wholly inside the other.
        a = write_obj("o_a.obj", tet(1.0))
        b = write_obj("o_b.obj", tet(1e110, (-1e109,) * 3))
        code, out, err = run(a, b, "--json", path("o.json"), command=("clash",))
        self.expect_rejected(code, err, b, "o_b.obj:1: vertex 1: x = -1e+109")
        self.assertFalse(os.path.exists(path("o.json")))

    def test_just_above_the_top_is_rejected(self):
        over = math.nextafter(TOP, math.inf)
        b = write_obj("over.obj", tet(over))
        code, out, err = run(write_obj("u.obj", tet(1.0)), b, command=("clash",))
        self.expect_rejected(code, err, b, "over.obj:2: vertex 2: x = 1.2676506002282297e+30")

    def test_just_below_the_bottom_is_rejected(self):
        under = math.nextafter(BOTTOM, 0.0)
        m = write_obj("under.obj", tet(1.0, (0.0, under, 0.0)))
        code, out, err = run(m, command=("check",))
        self.expect_rejected(code, err, m, "under.obj:1: vertex 1: y = 5.527147875260444e-76")

    def test_check_at_1e200_is_rejected(self):
        m = write_obj("c200.obj", tet(1e200))
        code, out, err = run(m, "--json", path("c200.json"), command=("check",))
        self.expect_rejected(code, err, m, "vertex 2: x = 1e+200")
        self.assertFalse(os.path.exists(path("c200.json")))

    def test_simplify_at_1e300_is_rejected_without_nan(self):
        m = write_obj("s300.obj", uv_sphere(1e300))
        out_file = path("s300_out.obj")
        code, out, err = run("--ratio", "0.5", m, out_file, command=("simplify",))
        self.expect_rejected(code, err, m, "s300.obj:1: vertex 1: z = 1e+300")
        self.assertFalse(os.path.exists(out_file))

    def test_unit_conversion_out_of_the_range_is_rejected(self):
        # 1e28 m is inside the range, 1e31 mm is not.
        b = write_obj("metres.obj", tet(1e28))
        code, out, err = run(write_obj("u2.obj", tet(1.0)), b, "--units-b", "m", command=("clash",))
        self.expect_rejected(code, err, b, "once converted to mm")

    def test_fem_node_out_of_the_range_is_rejected(self):
        vtk = ("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
               "0 0 0\n1 0 0\n0 1 0\n0 0 1e110\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n")
        f = cli_common.write_text("node.vtk", vtk)
        code, out, err = run(f, f, command=("clash",))
        self.expect_rejected(code, err, f, "node ", "z = 1e+110")


if __name__ == "__main__":
    cli_common.main()
