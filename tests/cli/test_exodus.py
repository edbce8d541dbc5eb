"""`interfere clash file.e` on Exodus II files from an independent writer (issue #26, item 1).

meshio (Debian python3-meshio, on python3-netcdf4) writes two element blocks of 4 x 4 x 4 HEX8 with
the nodal variables DISPL_X, DISPL_Y, DISPL_Z; meshio writes one time step, so the test adds the
others, and the node and element number maps, with netCDF4 itself (the Exodus II names time_whole,
vals_nod_var<k>, node_num_map, elem_num_map; and file_size = 1 with coordx/y/z, see write_model). `ncdump -h` (Debian netcdf-bin) checks the file's
layout before interfere reads it through the Exodus II library.

  block A: x in [0, 1], y, z in [0, 1], held;
  block B: x in [1 + g, 2 + g], y, z in [0.2, 0.8], moved by (-D t, 0, 0), t = 0.1 ... 1 (10 steps).

With g = 0.23, D = 0.5, B enters A between steps 3 (t = 0.4) and 4 (t = 0.5): the first clashing
frame is 4, and the clashing elements at that frame are A's elements of its layer at x = 1 whose
face meets the outline of B's cross-section and B's first-layer elements on its sides (computed from
the mesh, by the solver ids of the number maps). Bad input: displacements missing, or incomplete,
are exit status 2 naming the file.
"""
import os
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_common import load_json, main, path, run  # noqa: E402

try:
    import meshio
    import netCDF4
    import numpy as np
    HAVE_WRITER = True
except ImportError:  # tools/deps.sh installs python3-meshio and python3-netcdf4
    HAVE_WRITER = False

N = 4
GAP, PUSH, STEPS = 0.23, 0.5, 10
A_BOX = ((0.0, 1.0), (0.0, 1.0), (0.0, 1.0))
B_BOX = ((1.0 + GAP, 2.0 + GAP), (0.2, 0.8), (0.2, 0.8))
NODE_BASE = (500, 9000)    # solver node ids: base + local index
ELEM_BASE = (100, 7000)    # solver element ids: base + 1 + i + N (j + N k)
FIRST = next(k for k in range(1, STEPS + 1) if PUSH * k / STEPS > GAP) - 1  # 0-based frame


def block(box):
    (x0, x1), (y0, y1), (z0, z1) = box
    n = N + 1
    pts = [(x0 + (x1 - x0) * i / N, y0 + (y1 - y0) * j / N, z0 + (z1 - z0) * k / N)
           for k in range(n) for j in range(n) for i in range(n)]
    v = lambda i, j, k: i + n * (j + n * k)  # noqa: E731
    cells = [[v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
              v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1), v(i, j + 1, k + 1)]
             for k in range(N) for j in range(N) for i in range(N)]
    return pts, cells


def write_model(name, variables=("DISPL_X", "DISPL_Y", "DISPL_Z"), steps=STEPS, repair=True):
    """Two HEX8 blocks; `variables` nodal variables (DISPL_* hold B's motion, others zero)."""
    pa, ca = block(A_BOX)
    pb, cb = block(B_BOX)
    points = np.array(pa + pb, dtype=np.float64)
    nb = len(pa)
    cells = [("hexahedron", np.array(ca, dtype=np.int32)), ("hexahedron", np.array(cb, dtype=np.int32) + nb)]
    moving = np.arange(len(points)) >= nb
    times = [(s + 1) / STEPS for s in range(steps)]

    def value(var, t):
        if var.upper().endswith("_X") and var.upper().startswith("DISP"):
            return np.where(moving, -PUSH * t, 0.0)
        return np.zeros(len(points))

    f = path(name)
    meshio.write_points_cells(f, points, cells, point_data={v: value(v, times[0]) for v in variables},
                              file_format="exodus")
    with netCDF4.Dataset(f, "a") as nc:
        for s, t in enumerate(times):
            nc.variables["time_whole"][s] = t
            for k, v in enumerate(variables):
                nc.variables["vals_nod_var%d" % (k + 1)][s, :] = value(v, t)
        nm = nc.createVariable("node_num_map", "i4", ("num_nodes",))
        nm[:] = np.array([NODE_BASE[0] + i for i in range(nb)] + [NODE_BASE[1] + i for i in range(len(pb))])
        em = nc.createVariable("elem_num_map", "i4", ("num_elem",))
        em[:] = np.array([ELEM_BASE[0] + 1 + e for e in range(len(ca))] + [ELEM_BASE[1] + 1 + e for e in range(len(cb))])
        # meshio 5.0 stores one array per nodal variable (vals_nod_var<k>, the "large model"
        # layout) but the coordinates as one array (coord) and no file_size attribute, which tells
        # the Exodus library the other layout: it would find no variable values. Made consistent
        # the Exodus II way: file_size = 1 and coordx/coordy/coordz.
        if repair:
            nc.file_size = np.int32(1)
            for d, cname in enumerate(("coordx", "coordy", "coordz")):
                cv = nc.createVariable(cname, "f8", ("num_nodes",))
                cv[:] = points[:, d]
    return f


def expected_elements():
    lo, hi = B_BOX[1]
    a = set()
    for j in range(N):
        for k in range(N):
            y0, y1, z0, z1 = j / N, (j + 1) / N, k / N, (k + 1) / N
            if (y0 <= hi and y1 >= lo and z0 <= hi and z1 >= lo) and not (y0 > lo and y1 < hi and z0 > lo and z1 < hi):
                a.add(ELEM_BASE[0] + 1 + (N - 1) + N * (j + N * k))
    b = {ELEM_BASE[1] + 1 + 0 + N * (j + N * k) for j in range(N) for k in range(N) if j in (0, N - 1) or k in (0, N - 1)}
    return a, b


def has_reader():
    """False when this build has no Exodus II reader (configured without the Exodus library)."""
    f = write_model("probe.e", steps=1)
    code, out, err = run("surface", f, path("probe.stl"))
    return "no Exodus II reader" not in err


@unittest.skipUnless(HAVE_WRITER, "meshio / netCDF4 / numpy not importable (Debian python3-meshio python3-netcdf4)")
class ExodusFiles(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        if not has_reader():
            raise unittest.SkipTest("this interfere build has no Exodus II reader (libexodusii-dev not found at configure time)")

    def test_ncdump_sees_the_exodus_layout(self):
        if not shutil.which("ncdump"):
            self.skipTest("ncdump (Debian netcdf-bin) not installed")
        f = write_model("layout.e")
        h = subprocess.run(["ncdump", "-h", f], capture_output=True, text=True, check=True).stdout
        self.assertIn("num_el_blk = 2 ;", h)
        self.assertIn("num_nodes = %d ;" % (2 * (N + 1) ** 3), h)
        self.assertIn("num_elem = %d ;" % (2 * N ** 3), h)
        self.assertIn("time_step = UNLIMITED ; // (%d currently)" % STEPS, h)
        self.assertIn('connect1:elem_type = "HEX8"', h)
        self.assertIn('connect2:elem_type = "HEX8"', h)
        for k in (1, 2, 3):
            self.assertIn("vals_nod_var%d(time_step" % k, h)
        self.assertIn("elem_num_map(num_elem)", h)

    def test_first_clash_step_and_elements(self):
        f = write_model("blocks.e")
        code, out, err = run("clash", f, "--json", path("blocks.json"))
        self.assertEqual(code, 1, out + err)
        r = load_json("blocks.json")
        self.assertEqual(sorted(b["name"] for b in r["bodies"]), ["block 0", "block 1"])  # meshio's block ids 0, 1
        self.assertEqual(len(r["frames"]), STEPS)
        for s, fr in enumerate(r["frames"]):
            self.assertAlmostEqual(fr["time"], (s + 1) / STEPS, places=6)  # (meshio: time_whole is float32)
            self.assertEqual(fr["clashes"] > 0, s >= FIRST, fr)
        clash = [c for c in r["clashes"] if c["verdict"] == "clash"]
        self.assertEqual(len(clash), 1, r["clashes"])
        c = clash[0]
        self.assertEqual(FIRST, 4)
        self.assertEqual(c["first_frame"], FIRST)
        ids = {c["body_a"]["name"]: set(c["source_ids_a"]), c["body_b"]["name"]: set(c["source_ids_b"])}
        exp_a, exp_b = expected_elements()
        self.assertEqual((len(exp_a), len(exp_b)), (12, 12))
        self.assertEqual(ids, {"block 0": exp_a, "block 1": exp_b})
        # The two-part form with the block names and the field by name.
        code, out, err = run("clash", f, f, "--part-a", "block 0", "--part-b", "block 1", "--field", "DISPL")
        self.assertEqual(code, 1, out + err)
        self.assertIn("first clash at step %d (time 0.5) of %d" % (FIRST, STEPS), out + err)

    def test_without_displacements_is_bad_input(self):
        f = write_model("temp_only.e", variables=("TEMP",))
        code, out, err = run("clash", f)
        self.assertEqual(code, 2, out + err)
        self.assertIn("temp_only.e", err)
        self.assertIn("no displacement among the nodal variables (TEMP)", err)
        g = write_model("xy_only.e", variables=("DISPL_X", "DISPL_Y"))
        code, out, err = run("clash", g)
        self.assertEqual(code, 2, out + err)
        self.assertIn("xy_only.e", err)
        self.assertIn("component Z missing", err)

    def test_quadratic_blocks_in_exodus_node_order(self):
        # HEX20 in Exodus order (mid-side nodes 9-12 bottom, 13-16 vertical, 17-20 top) and TETRA10,
        # a skewed hexahedron so that a wrong order changes the surface: the surface is closed and
        # encloses the elements' volume only when the reader puts every mid-side node on its edge.
        c = [(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0), (0.5, 0, 1), (2.5, 0, 1), (2.5, 1, 1), (0.5, 1, 1)]
        edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6), (6, 7), (7, 4)]
        hexp = c + [tuple((a + b) / 2 for a, b in zip(c[i], c[j])) for i, j in edges]
        t = [(5, 0, 0), (6, 0, 0), (5, 1, 0), (5, 0, 1)]
        tet_edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
        tetp = t + [tuple((a + b) / 2 for a, b in zip(t[i], t[j])) for i, j in tet_edges]
        points = np.array(hexp + tetp, dtype=np.float64)
        cells = [("hexahedron20", np.array([list(range(20))], dtype=np.int32)),
                 ("tetra10", np.array([list(range(20, 30))], dtype=np.int32))]
        f = path("quadratic.e")
        meshio.write_points_cells(f, points, cells, file_format="exodus")
        h = subprocess.run(["ncdump", "-h", f], capture_output=True, text=True).stdout if shutil.which("ncdump") else ""
        if h:
            self.assertIn('connect1:elem_type = "HEX20"', h)
            self.assertIn('connect2:elem_type = "TETRA10"', h)
        code, out, err = run("surface", f, path("quadratic.stl"), "--json", path("quadratic.json"))
        self.assertEqual(code, 0, out + err)
        r = load_json("quadratic.json")
        self.assertEqual(r["input"]["bodies"], ["block 0", "block 1"])
        self.assertEqual(r["input"]["nonmanifold_faces"], 0)
        self.assertEqual([(p["closed"], p["triangles"]) for p in r["parts"]], [(True, 36), (True, 16)])  # quad8 / tri6 faces
        self.assertAlmostEqual(r["input"]["enclosed_volume"], 2.0, places=12)  # (of the first body: the hexahedron)

    def test_meshio_layout_without_file_size_is_a_clear_error(self):
        f = write_model("as_meshio_writes.e", repair=False)
        code, out, err = run("clash", f)
        self.assertEqual(code, 2, out + err)
        self.assertIn("as_meshio_writes.e", err)
        self.assertIn("file_size = 1", err)

    def test_not_an_exodus_file(self):
        with open(path("text.e"), "w") as f:
            f.write("not netCDF\n")
        code, out, err = run("clash", path("text.e"))
        self.assertEqual(code, 2, out + err)
        self.assertIn("text.e", err)
        self.assertIn("cannot open as an Exodus II file", err)


if __name__ == "__main__":
    main()
