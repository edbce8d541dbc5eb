"""Imported scars from Python (issue #27, deliverable 2; docs/bearing.md "Scars: raised and imported").

A CSV height map, a 16-bit PNG (written here with zlib, when the build reads PNG), a point cloud as
text and as a scanned ASCII STL, each generated from a function evaluated in the test, read through
interfere.bearing, resampled onto a roller's vertex grid and applied; the heights are checked against
the function itself (exactly for a bilinear map, within L x window for points), the meshed roller's
vertex radii against r + height, and a simulation carries the imported scar. Bad input raises
ValueError naming the file."""
import math
import os
import struct
import tempfile
import unittest
import zlib

import interfere as itf

B = itf.bearing


def bilinear(a_deg, z):
    """The map's function: bilinear in (angle, z), so that resampling is exact between nodes."""
    return 0.002 + 0.0004 * a_deg - 0.0003 * (z - 20) + 0.00002 * a_deg * (z - 20)


class ScarImportTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="itf_scar_")
        # 36 columns (10 degrees), 40 rows (1 mm): vertex (i, j) at angle 10 i, z = j
        self.params = B.RollerParams(radius=10, height=40, radial_segments=36, height_segments=40)

    def test_csv_map_resampled_exactly(self):
        angles = [-30 + 10 * k for k in range(7)]
        zs = [5 + 5 * k for k in range(7)]
        lines = ["z\\angle_deg," + ",".join(str(a) for a in angles)]
        for z in zs:
            lines.append(str(z) + "," + ",".join(repr(bilinear(a, z)) for a in angles))
        path = os.path.join(self.dir, "map.csv")
        with open(path, "w") as f:
            f.write("# a bilinear bump\n" + "\n".join(lines) + "\n")
        m = B.read_scar_csv(path)
        self.assertEqual((m.rows, m.cols), (7, 7))
        self.assertEqual(list(m.angle_deg), angles)
        h = B.resample_height_map(m, self.params)
        self.assertEqual((h.n, h.m), (36, 40))
        covered = 0
        for j in range(41):
            for i in range(36):
                v = j * 36 + i
                a = 10 * i if 10 * i <= 180 else 10 * i - 360
                inside = -30 <= a <= 30 and 5 <= j <= 35
                self.assertEqual(h.covered[v], inside, (i, j))
                if inside:
                    covered += 1
                    self.assertAlmostEqual(h.height[v], bilinear(a, j), delta=1e-12)
                else:
                    self.assertEqual(h.height[v], 0.0)
        self.assertEqual(h.covered_count, covered)
        self.assertEqual(covered, 7 * 31)
        # the meshed roller: displacement = -height, side vertex radius = r + height
        r = B.make_roller_with_scar(self.params, h)
        self.assertTrue(r.has_scar)
        self.assertAlmostEqual(r.max_raise, max(h.height), delta=1e-15)
        pos = r.mesh.positions if hasattr(r.mesh, "positions") else None
        for v in range(36 * 41):
            self.assertAlmostEqual(r.displacement[v], -h.height[v], delta=1e-15)
            if pos is not None:
                x, y, _ = pos[v]
                self.assertAlmostEqual(math.hypot(x, y), 10 + h.height[v], delta=1e-12)
        w = B.covered_window(h, self.params)
        self.assertAlmostEqual(w.z_min, 5)
        self.assertAlmostEqual(w.z_max, 35)
        # a simulation whose scarred rollers carry it
        res = B.simulate(pairs=2, frames=2, roller=self.params, gap=-0.05, scar_fraction=1.0, imported_scar=h)
        self.assertEqual(len(res.rows), 4)
        self.assertIn(res.verdict, ("clash", "contact", "clearance", "clear", "undecided"))
        self.assertTrue(all(math.isfinite(row.distance) for row in res.rows))

    def test_png_map(self):
        if not B.scar_png_supported():
            self.skipTest("this build has no PNG reader")
        width, height = 4, 3
        pixels = [[1000 * (y + 1) + 7 * x for x in range(width)] for y in range(height)]
        raw = b"".join(b"\x00" + b"".join(struct.pack(">H", p) for p in row) for row in pixels)

        def chunk(kind, data):
            return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

        png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 16, 0, 0, 0, 0))
        png += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
        path = os.path.join(self.dir, "map.png")
        with open(path, "wb") as f:
            f.write(png)
        m = B.read_scar_png(path, scale=1e-5, offset=-0.01, angle_min_deg=-15, angle_max_deg=15, z_min=10, z_max=30)
        self.assertEqual((m.rows, m.cols), (3, 4))
        for r in range(3):
            y = round((30 - m.z[r]) / 10)  # pixel rows from the top: z_max first
            for c in range(4):
                x = round((m.angle_deg[c] + 15) / 10)
                self.assertAlmostEqual(m.height[r * 4 + c], 1e-5 * pixels[y][x] - 0.01, delta=1e-15)
        with self.assertRaises(ValueError) as cm:
            B.read_scar_png(os.path.join(self.dir, "none.png"), scale=1e-5)
        self.assertIn("none.png", str(cm.exception))

    def write_points(self):
        """Points of a worn surface: deviation d(z) = 0.01 + 0.0005 (z - 20) over 40 degrees."""
        pts = []
        for ia in range(-20, 21):
            for iz in range(0, 41):
                a, z = math.radians(ia), 10 + 0.5 * iz
                rr = 10 + 0.01 + 0.0005 * (z - 20)
                pts.append((rr * math.cos(a), rr * math.sin(a), z))
        return pts

    def test_points_text_and_stl(self):
        pts = self.write_points()
        text = os.path.join(self.dir, "cloud.xyz")
        with open(text, "w") as f:
            f.write("# x y z\n" + "\n".join("%r %r %r" % p for p in pts) + "\n")
        got = B.read_scar_points(text)
        self.assertEqual(len(got), len(pts))
        window = 1.5
        h = B.scar_from_points(got, self.params, window=window, source=text)
        self.assertGreater(h.covered_count, 0)
        lipschitz = 0.0005  # |d(p) - d(q)| <= L |p - q| on the unrolled surface
        for j in range(41):
            for i in range(36):
                v = j * 36 + i
                if h.covered[v]:
                    self.assertLessEqual(abs(h.height[v] - (0.01 + 0.0005 * (j - 20))), lipschitz * window + 1e-12)
        # the same cloud as a scanned ASCII STL (its vertices, welded)
        stl = os.path.join(self.dir, "scan.stl")
        grid = lambda ia, iz: pts[(ia + 20) * 41 + iz]  # noqa: E731
        with open(stl, "w") as f:
            f.write("solid scan\n")
            for ia in range(-20, 20):
                for iz in range(40):
                    for tri in ((grid(ia, iz), grid(ia + 1, iz), grid(ia + 1, iz + 1)),
                                (grid(ia, iz), grid(ia + 1, iz + 1), grid(ia, iz + 1))):
                        f.write(" facet normal 0 0 0\n  outer loop\n")
                        for p in tri:
                            f.write("   vertex %r %r %r\n" % p)
                        f.write("  endloop\n endfacet\n")
            f.write("endsolid scan\n")
        scanned = B.read_scar_points(stl)
        self.assertEqual(len(scanned), len(pts))
        hs = B.scar_from_points(scanned, self.params, window=window, source=stl)
        self.assertEqual(hs.covered_count, h.covered_count)
        for a, b in zip(hs.height, h.height):
            self.assertAlmostEqual(a, b, delta=1e-6)

    def test_bad_input_names_the_file(self):
        with self.assertRaises(ValueError) as cm:
            B.parse_scar_csv("z,-10,10\n10,0,nan\n20,0,0\n", "worn.csv")
        self.assertIn("worn.csv", str(cm.exception))
        self.assertIn("worn.csv:2: field 3", str(cm.exception))  # the file, line and field
        with self.assertRaises(ValueError) as cm:
            B.parse_scar_csv("z,-10,10\n10,0\n20,0,0\n", "ragged.csv")
        self.assertIn("ragged.csv", str(cm.exception))
        with self.assertRaises(ValueError) as cm:
            B.read_scar_csv(os.path.join(self.dir, "missing.csv"))
        self.assertIn("missing.csv", str(cm.exception))
        # heights for another grid (a map of the wrong size for this roller)
        m = B.parse_scar_csv("z,-10,10\n10,0,0.01\n20,0,0.01\n", "small.csv")
        other = B.resample_height_map(m, B.RollerParams(radius=10, height=40, radial_segments=24, height_segments=40))
        with self.assertRaises(ValueError):
            B.make_roller_with_scar(self.params, other)
        with self.assertRaises(ValueError) as cm:
            B.read_scar_points(os.path.join(self.dir, "missing.xyz"))
        self.assertIn("missing.xyz", str(cm.exception))


if __name__ == "__main__":
    unittest.main()
