#!/usr/bin/env python3
"""`interfere distance` and `interfere check` on FE files (issue #26, item 5), and the bad input of
issue #26 ("Bad input": exit status 2, a message naming the file, the line or block, the step, the
node).

Usage: test_fem_inputs.py PATH_TO_INTERFERE WORK_DIR   (run by ctest). Standard library only, but
for the Exodus files (meshio / netCDF4 / numpy, Debian python3-meshio python3-netcdf4; skipped
without them or without the Exodus reader in the build).

One model in every FE format, written here by the test's own writers (fixed-column CalculiX .frd,
Gmsh MSH 2.2, Abaqus .inp, Nastran free field .bdf, legacy VTK, VTU ascii; Exodus by meshio): two
bodies of 2 x 2 x 2 HEX8,
  A = [0, 1]^3                      (node ids 1..27,      element ids 1..8),
  B = [1.5, 2.5] x [1.3, 1.9] x [0.2, 0.8]  (node ids 1001..1027, element ids 101..108),
B moved by (-V s, 0, 0) at step s (s = 0 .. STEPS-1) where the format holds displacements. The
expected values are analytic: the distance of two axis-aligned boxes (the per-axis gaps' norm), the
boxes' volumes, the 48 triangles of a 2 x 2 x 2 box's surface.
"""
import math
import os
import struct
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_common  # noqa: E402
from cli_common import assert_input_error, load_json, path, run  # noqa: E402
from hex_blocks import CORNERS, hex_box  # noqa: E402

try:
    import meshio
    import netCDF4
    import numpy as np
    HAVE_EXODUS_WRITER = True
except ImportError:  # tools/deps.sh installs python3-meshio and python3-netcdf4
    HAVE_EXODUS_WRITER = False

A_BOX = ((0.0, 1.0), (0.0, 1.0), (0.0, 1.0))
B_BOX = ((1.5, 2.5), (1.3, 1.9), (0.2, 0.8))
STEPS, V = 4, 0.125

A = hex_box(A_BOX, 2, 1, 1)
B = hex_box(B_BOX, 2, 1001, 101)
NODES = A[0] + B[0]
BODIES = [(1, A[1]), (2, B[1])]  # (group number, elements)


def disp(nid, s):
    return (-V * s if nid >= 1001 else 0.0, 0.0, 0.0)


def box_distance(p, q):
    """The distance of two axis-aligned boxes: the norm of the per-axis gaps."""
    return math.sqrt(sum(max(0.0, q[a][0] - p[a][1], p[a][0] - q[a][1]) ** 2 for a in range(3)))


def moved(box, dx):
    return ((box[0][0] + dx, box[0][1] + dx), box[1], box[2])


def box_volume(box):
    return (box[0][1] - box[0][0]) * (box[1][1] - box[1][0]) * (box[2][1] - box[2][0])


def write(name, text):
    with open(path(name), "w") as f:
        f.write(text)
    return path(name)


# ---- writers (the test's own, from the formats' documentation) ----

def write_msh(name, steps=STEPS, nodes=NODES):
    """Gmsh MSH 2.2 ASCII, physical volumes "left" (1) and "right" (2), $NodeData "disp" per step."""
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "2", '3 1 "left"', '3 2 "right"',
           "$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += ["%d %r %r %r" % (nid, *x) for nid, x in nodes]
    out += ["$EndNodes", "$Elements", str(sum(len(e) for _, e in BODIES))]
    for g, elems in BODIES:
        out += ["%d 5 2 %d %d %s" % (eid, g, g, " ".join(map(str, v))) for eid, v in elems]
    out.append("$EndElements")
    for s in range(steps):
        out += ["$NodeData", "1", '"disp"', "1", repr(float(s)), "3", str(s), "3", str(len(nodes))]
        out += ["%d %r %r %r" % (nid, *disp(nid, s)) for nid, _ in nodes]
        out.append("$EndNodeData")
    return write(name, "\n".join(out) + "\n")


def write_inp(name):
    """Abaqus .inp: *NODE, one *ELEMENT block per body (C3D8, ELSET=LEFT / RIGHT)."""
    out = ["*HEADING", "two boxes", "*NODE"]
    out += ["%d, %r, %r, %r" % (nid, *x) for nid, x in NODES]
    for (g, elems), set_name in zip(BODIES, ("LEFT", "RIGHT")):
        out.append("*ELEMENT, TYPE=C3D8, ELSET=%s" % set_name)
        out += ["%d, %s" % (eid, ", ".join(map(str, v))) for eid, v in elems]
    return write(name, "\n".join(out) + "\n")


def write_bdf(name):
    """Nastran free field: GRID, CHEXA with property ids 1 and 2 (Nastran's corner order is VTK's)."""
    out = ["BEGIN BULK", "PSOLID,1,1", "PSOLID,2,1", "MAT1,1,2.1e5,,0.3"]
    out += ["GRID,%d,,%r,%r,%r" % (nid, *x) for nid, x in NODES]
    for g, elems in BODIES:
        out += ["CHEXA,%d,%d,%s" % (eid, g, ",".join(map(str, v[:6]))) + "\n,%s" % ",".join(map(str, v[6:]))
                for eid, v in elems]
    out.append("ENDDATA")
    return write(name, "\n".join(out) + "\n")


def vtk_index():
    return {nid: i for i, (nid, _) in enumerate(NODES)}


def write_vtk(name):
    """Legacy VTK 4.2 ASCII UNSTRUCTURED_GRID, cell type 12, cell data mat_id (1, 2)."""
    ix = vtk_index()
    cells = [(g, v) for g, elems in BODIES for _, v in elems]
    out = ["# vtk DataFile Version 4.2", "two boxes", "ASCII", "DATASET UNSTRUCTURED_GRID",
           "POINTS %d double" % len(NODES)]
    out += ["%r %r %r" % x for _, x in NODES]
    out.append("CELLS %d %d" % (len(cells), 9 * len(cells)))
    out += ["8 " + " ".join(str(ix[n]) for n in v) for _, v in cells]
    out.append("CELL_TYPES %d" % len(cells))
    out += ["12"] * len(cells)
    out += ["CELL_DATA %d" % len(cells), "SCALARS mat_id int 1", "LOOKUP_TABLE default"]
    out += [str(g) for g, _ in cells]
    return write(name, "\n".join(out) + "\n")


def write_vtu(name):
    """VTK XML .vtu, ascii arrays, cell data MaterialIds (1, 2)."""
    ix = vtk_index()
    cells = [(g, v) for g, elems in BODIES for _, v in elems]
    pts = " ".join("%r %r %r" % x for _, x in NODES)
    conn = " ".join(str(ix[n]) for _, v in cells for n in v)
    offs = " ".join(str(8 * (i + 1)) for i in range(len(cells)))
    out = ['<?xml version="1.0"?>',
           '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">',
           "<UnstructuredGrid>",
           '<Piece NumberOfPoints="%d" NumberOfCells="%d">' % (len(NODES), len(cells)),
           '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">%s</DataArray></Points>' % pts,
           "<Cells>",
           '<DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>' % conn,
           '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray>' % offs,
           '<DataArray type="UInt8" Name="types" format="ascii">%s</DataArray>' % " ".join(["12"] * len(cells)),
           "</Cells>",
           '<CellData><DataArray type="Int32" Name="MaterialIds" format="ascii">%s</DataArray></CellData>'
           % " ".join(str(g) for g, _ in cells),
           "</Piece>", "</UnstructuredGrid>", "</VTKFile>"]
    return write(name, "\n".join(out) + "\n")


def write_frd(name, steps=STEPS, disp_nodes=None, truncate_at=None):
    """CalculiX .frd, ASCII long format as ccx writes it (the CalculiX GraphiX manual's fixed
    columns: ids in 10 columns, reals %12.5E): 1UMAT names, node block 2C, element block 3C (type 1
    he8, material 1 / 2), one DISP result block (100C) per step after its 1PSTEP record.
    `disp_nodes`: the node ids of each DISP block (default every node)."""
    out = ["    1C", "    1UMAT    1LEFT", "    1UMAT    2RIGHT",
           "    2C" + " " * 18 + "%12d" % len(NODES) + " " * 37 + "1"]
    out += [" -1%10d%12.5E%12.5E%12.5E" % (nid, *x) for nid, x in NODES]
    out.append(" -3")
    nel = sum(len(e) for _, e in BODIES)
    out.append("    3C" + " " * 18 + "%12d" % nel + " " * 37 + "1")
    for g, elems in BODIES:
        for eid, v in elems:
            out.append(" -1%10d%5d%5d%5d" % (eid, 1, 0, g))
            out.append(" -2" + "".join("%10d" % n for n in v))
    out.append(" -3")
    ids = disp_nodes if disp_nodes is not None else [nid for nid, _ in NODES]
    for s in range(steps):
        out.append("    1PSTEP" + " " * 14 + "%12d%12d%12d" % (s + 1, s + 1, 1))
        out.append("  100CL%5d%12.5E%12d%20s%2d%5d%10s%2s" % (101 + s, float(s), len(ids), "", 0, s + 1, "", " 1"))
        out += [" -4  DISP        4    1", " -5  D1          1    2    1    0", " -5  D2          1    2    2    0",
                " -5  D3          1    2    3    0", " -5  ALL         1    2    0    0    1ALL"]
        out += [" -1%10d%12.5E%12.5E%12.5E" % (nid, *disp(nid, s)) for nid in ids]
        out.append(" -3")
    out.append("9999")
    return write(name, "\n".join(out) + "\n")


def write_csv(name, steps, nodes=None, extra=None):
    """step,node_id,ux,uy,uz for B's nodes (or `nodes`), `extra` rows appended (text)."""
    rows = ["step,node_id,ux,uy,uz"]
    for s in range(steps):
        rows += ["%d,%d,%r,%r,%r" % (s, nid, *disp(nid, s)) for nid in (nodes or [n for n, _ in B[0]])]
    rows += extra or []
    return write(name, "\n".join(rows) + "\n")


def write_exodus(name, variables=("DISPL_X", "DISPL_Y", "DISPL_Z"), steps=STEPS):
    """Exodus II by meshio (two HEX8 blocks), the time steps and number maps added with netCDF4 as
    tests/cli/test_exodus.py does (file_size = 1 and coordx/y/z make meshio's layout consistent)."""
    ix = vtk_index()
    points = np.array([x for _, x in NODES], dtype=np.float64)
    cells = [("hexahedron", np.array([[ix[n] for n in v] for _, v in elems], dtype=np.int32)) for _, elems in BODIES]
    times = [float(s) for s in range(steps)]

    def value(var, s):
        if var.upper().startswith("DISP") and var.upper().endswith("_X"):
            return np.array([disp(nid, s)[0] for nid, _ in NODES])
        return np.zeros(len(NODES))

    f = path(name)
    pd = {v: value(v, 0) for v in variables}
    meshio.write_points_cells(f, points, cells, point_data=pd, file_format="exodus")
    with netCDF4.Dataset(f, "a") as nc:
        if variables:
            for s, t in enumerate(times):
                nc.variables["time_whole"][s] = t
                for k, v in enumerate(variables):
                    nc.variables["vals_nod_var%d" % (k + 1)][s, :] = value(v, s)
        nm = nc.createVariable("node_num_map", "i4", ("num_nodes",))
        nm[:] = np.array([nid for nid, _ in NODES])
        em = nc.createVariable("elem_num_map", "i4", ("num_elem",))
        em[:] = np.array([eid for _, elems in BODIES for eid, _ in elems])
        nc.file_size = np.int32(1)
        for d, cname in enumerate(("coordx", "coordy", "coordz")):
            cv = nc.createVariable(cname, "f8", ("num_nodes",))
            cv[:] = points[:, d]
    return f


def write_box_stl(name, box):
    """The box as a binary STL (outward triangles)."""
    (x0, x1), (y0, y1), (z0, z1) = box
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7),
         (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    with open(path(name), "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(f)))
        for t in f:
            out.write(struct.pack("<12fH", 0, 0, 0, *v[t[0]], *v[t[1]], *v[t[2]], 0))
    return path(name)


def exodus_reader_in_build():
    f = write_exodus("probe.e")
    rc, out, err = run("check", f)
    return "no Exodus II reader" not in err


# format -> (writer, file name, body names as the reader names them, displacement field or None)
FORMATS = {
    "msh": (write_msh, "boxes.msh", ("left", "right"), "disp"),
    "inp": (write_inp, "boxes.inp", ("left", "right"), None),  # (Abaqus names are case-insensitive: lower case)
    "bdf": (write_bdf, "boxes.bdf", ("PID 1", "PID 2"), None),
    "nas": (write_bdf, "boxes.nas", ("PID 1", "PID 2"), None),
    "vtk": (write_vtk, "boxes.vtk", ("mat_id 1", "mat_id 2"), None),
    "vtu": (write_vtu, "boxes.vtu", ("MaterialIds 1", "MaterialIds 2"), None),
    "frd": (write_frd, "boxes.frd", ("LEFT", "RIGHT"), "DISP"),
    "e": (write_exodus, "boxes.e", ("block 0", "block 1"), "DISPL"),
    "exo": (write_exodus, "boxes.exo", ("block 0", "block 1"), "DISPL"),
}


class FemInputs(unittest.TestCase):
    files = {}

    @classmethod
    def setUpClass(cls):
        exodus = HAVE_EXODUS_WRITER and exodus_reader_in_build()
        for fmt, (writer, name, _, _) in FORMATS.items():
            if writer is write_exodus and not exodus:
                continue
            cls.files[fmt] = writer(name)

    def formats(self):
        for fmt, (_, _, bodies, field) in FORMATS.items():
            if fmt not in self.files:
                print("  (%s skipped: no meshio/netCDF4 or no Exodus reader in this build)" % fmt, file=sys.stderr)
                continue
            with self.subTest(format=fmt):
                yield fmt, self.files[fmt], bodies, field

    def assert_bad(self, args, needles, outputs=()):
        return assert_input_error(self, args, needles, outputs)

    # ---- distance ----

    def test_distance_between_two_bodies_of_each_format(self):
        expected = box_distance(A_BOX, B_BOX)  # gaps 0.5 (x) and 0.3 (y)
        self.assertAlmostEqual(expected, math.sqrt(0.34), places=15)
        for fmt, f, bodies, _ in self.formats():
            js = path("dist_%s.json" % fmt)
            rc, out, err = run("distance", f, f, "--part-a", bodies[0], "--part-b", bodies[1], "--json", js)
            self.assertEqual(rc, 0, out + err)
            r = load_json(js)
            self.assertAlmostEqual(r["result"]["distance"], expected, places=5 if fmt == "frd" else 12)
            self.assertEqual(r["verdict"], "clear")
            for side, body, box in (("a", bodies[0], A_BOX), ("b", bodies[1], B_BOX)):
                inp = r["inputs"][side]
                self.assertEqual(inp["format"], {"bdf": "nastran", "nas": "nastran", "e": "exodus", "exo": "exodus",
                                                 "inp": "inp", "vtk": "vtk"}.get(fmt, fmt))
                self.assertEqual(inp["fem"]["part"], body)
                self.assertEqual(inp["fem"]["bodies"], list(bodies))
                self.assertEqual(inp["triangles"], 48)
                self.assertTrue(inp["closed"])
            # The witness points lie on the facing edges: A's at x = 1, y = 1; B's at x = 1.5, y = 1.3.
            pa, pb = r["result"]["point_a"], r["result"]["point_b"]
            self.assertAlmostEqual(pa[0], 1.0, places=5)
            self.assertAlmostEqual(pa[1], 1.0, places=5)
            self.assertAlmostEqual(pb[0], 1.5, places=5)
            self.assertAlmostEqual(pb[1], 1.3, places=5)
            self.assertIn("A: body '%s'" % bodies[0], out)

    def test_distance_at_a_deformed_step(self):
        for fmt, f, bodies, field in self.formats():
            if field is None:
                continue
            for step, scale in ((2, 1.0), (3, 0.5)):
                js = path("dstep_%s.json" % fmt)
                rc, out, err = run("distance", f, f, "--part-a", bodies[0], "--part-b", bodies[1], "--field", field,
                                   "--step", str(step), "--scale", str(scale), "--json", js)
                self.assertEqual(rc, 0, out + err)
                r = load_json(js)
                exp = box_distance(A_BOX, moved(B_BOX, -V * step * scale))
                self.assertAlmostEqual(r["result"]["distance"], exp, places=5 if fmt == "frd" else 12)
                self.assertEqual(r["inputs"]["b"]["fem"]["step"], step)
                self.assertEqual(r["inputs"]["b"]["fem"]["displacement"]["steps"], STEPS)
                self.assertIn("at step %d of %d" % (step, STEPS), out)
            # Default: the last step.
            rc, out, err = run("distance", f, f, "--part-a", bodies[0], "--part-b", bodies[1], "--field", field,
                               "--json", path("dlast.json"))
            self.assertEqual(rc, 0, out + err)
            r = load_json(path("dlast.json"))
            self.assertEqual(r["inputs"]["b"]["fem"]["step"], STEPS - 1)
            self.assertAlmostEqual(r["result"]["distance"], box_distance(A_BOX, moved(B_BOX, -V * (STEPS - 1))),
                                   places=5)

    def test_distance_with_a_displacement_csv(self):
        f = self.files["inp"]
        csv = write_csv("b_disp.csv", STEPS)
        rc, out, err = run("distance", f, f, "--part-a", "left", "--part-b", "right", "--disp-b", csv, "--step", "3",
                           "--json", path("dcsv.json"))
        self.assertEqual(rc, 0, out + err)
        r = load_json(path("dcsv.json"))
        self.assertAlmostEqual(r["result"]["distance"], box_distance(A_BOX, moved(B_BOX, -3 * V)), places=12)
        self.assertEqual(r["inputs"]["b"]["fem"]["displacement"]["source"], "csv")
        self.assertIsNone(r["inputs"]["a"]["fem"]["displacement"])

    def test_distance_fe_body_against_a_mesh_with_units(self):
        # Issue #23, item 6, as clash does it: A's file in cm (body LEFT = [0, 10] mm), B an STL box in mm.
        stl = write_box_stl("bar_mm.stl", ((12.0, 13.0), (0.0, 1.0), (0.0, 1.0)))
        f = self.files["inp"]
        rc, out, err = run("distance", f, stl, "--part-a", "left", "--units-a", "cm", "--json", path("dunits.json"))
        self.assertEqual(rc, 0, out + err)
        r = load_json(path("dunits.json"))
        self.assertAlmostEqual(r["result"]["distance"], 2.0, places=5)
        self.assertEqual(r["inputs"]["a"]["units"], "cm")
        self.assertEqual(r["inputs"]["a"]["scale_to_working_unit"], 10)
        self.assertNotIn("fem", r["inputs"]["b"])
        # Without the unit: taken as mm, the box [0, 1] mm is 11 mm away.
        rc, out, err = run("distance", f, stl, "--part-a", "left", "--json", path("dmm.json"))
        self.assertEqual(rc, 0, out + err)
        self.assertAlmostEqual(load_json(path("dmm.json"))["result"]["distance"], 11.0, places=5)

    def test_distance_flag_errors(self):
        f = self.files["msh"]
        stl = write_box_stl("far.stl", ((5.0, 6.0), (0.0, 1.0), (0.0, 1.0)))
        # Several bodies and no --part: the bodies are listed.
        self.assert_bad(["distance", f, stl], ["2 bodies", "'left'", "'right'", "--part-a"])
        self.assert_bad(["distance", f, stl, "--part-a", "middle"], ["no body 'middle'"])
        # FE flags for files that are no FE models: an error, not ignored.
        self.assert_bad(["distance", stl, stl, "--part", "left"], ["--part", "neither A nor B is an FE file"])
        self.assert_bad(["distance", f, stl, "--part-a", "left", "--part-b", "x"], ["--part-b", "far.stl is not an FE file"])
        # A step out of range names the displacements and their file.
        self.assert_bad(["distance", f, f, "--part-a", "left", "--part-b", "right", "--field", "disp", "--step", "9"],
                        ["--step 9: out of range", "field 'disp' of %s" % f, "4 steps"])
        self.assert_bad(["distance", f, f, "--part-a", "left", "--part-b", "right", "--step", "2"],
                        ["--step 2", "no displacements"])

    # ---- check ----

    def test_check_reports_each_body(self):
        for fmt, f, bodies, _ in self.formats():
            js = path("check_%s.json" % fmt)
            rc, out, err = run("check", f, "--json", js)
            self.assertEqual(rc, 0, out + err)
            r = load_json(js)
            self.assertEqual(r["command"], "check")
            self.assertEqual(r["fem"]["nodes"], len(NODES))
            self.assertEqual(r["fem"]["elements"], 16)
            self.assertEqual([b["name"] for b in r["bodies"]], list(bodies))
            for b, box in zip(r["bodies"], (A_BOX, B_BOX)):
                self.assertTrue(b["closed"], b)
                self.assertTrue(b["outward"], b)
                self.assertEqual(b["triangles"], 48)
                self.assertEqual(b["volume_elements"], 8)
                self.assertEqual(b["open_edges"], 0)
                self.assertEqual(b["warnings"], [])
                self.assertAlmostEqual(b["volume"], box_volume(box), places=5 if fmt == "frd" else 12)
                self.assertAlmostEqual(b["bbox"]["min"][1], box[1][0], places=5)
                self.assertAlmostEqual(b["bbox"]["max"][1], box[1][1], places=5)
            self.assertEqual(r["warnings"], [])
            self.assertEqual(json_of_stdout(out), r)

    def test_check_one_body_at_a_step(self):
        f = self.files["frd"]
        rc, out, err = run("check", f, "--part", "RIGHT", "--field", "DISP", "--step", "2", "--json", path("c2.json"))
        self.assertEqual(rc, 0, out + err)
        r = load_json(path("c2.json"))
        self.assertEqual([b["name"] for b in r["bodies"]], ["RIGHT"])
        b = r["bodies"][0]
        self.assertAlmostEqual(b["bbox"]["min"][0], B_BOX[0][0] - 2 * V, places=5)
        self.assertAlmostEqual(b["volume"], box_volume(B_BOX), places=5)  # a translation keeps it
        self.assertEqual(r["fem"]["step"], 2)

    def test_check_open_and_inward_bodies(self):
        # One hexahedron's faces as quad shells: closed, outward as written; the same with every
        # quad reversed: closed, inward (negative volume); five faces: open, no volume.
        nodes = [(i + 1, tuple(float(c) for c in CORNERS[i])) for i in range(8)]
        faces = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]
        def inp(name, quads):
            out = ["*NODE"] + ["%d, %r, %r, %r" % (n, *x) for n, x in nodes] + ["*ELEMENT, TYPE=S4, ELSET=SKIN"]
            out += ["%d, %s" % (k + 1, ", ".join(map(str, q))) for k, q in enumerate(quads)]
            return write(name, "\n".join(out) + "\n")
        for name, quads, closed, outward, volume in (
                ("skin_out.inp", faces, True, True, 1.0),
                ("skin_in.inp", [tuple(reversed(q)) for q in faces], True, False, -1.0),
                ("skin_open.inp", faces[:5], False, False, None)):
            rc, out, err = run("check", inp(name, quads), "--json", path("c.json"))
            self.assertEqual(rc, 0, out + err)
            b = load_json(path("c.json"))["bodies"][0]
            self.assertEqual((b["closed"], b["outward"], b["shell_elements"]), (closed, outward, len(quads)), name)
            if volume is None:
                self.assertIsNone(b["volume"])
                self.assertGreater(b["open_edges"], 0)
            else:
                self.assertAlmostEqual(b["volume"], volume, places=12)

    def test_check_flags_need_an_fe_file(self):
        stl = write_box_stl("c.stl", A_BOX)
        self.assert_bad(["check", stl, "--part", "x"], ["--part", "c.stl is not an FE file"])
        self.assert_bad(["check", self.files["msh"], "--part", "nobody"], ["no body 'nobody'", "'left'"])

    def test_sweep_names_an_fe_workpiece(self):
        # sweep takes meshes: an FE model is named as such (it was "cannot tell the mesh format ...
        # set ReadOptions::format").
        csv = write("probe_path.csv", "px,py,pz,ax,ay,az\n5,5,5,0,0,1\n")
        err = self.assert_bad(["sweep", "--workpiece", self.files["msh"], "--path", csv, "--probe-radius", "1",
                               "--probe-length", "2"], ["boxes.msh: an FE model", "interfere surface"])
        self.assertNotIn("ReadOptions", err)

    def test_surface_help_lists_every_format(self):
        for cmd in ("surface", "check", "distance"):
            rc, out, err = run(cmd, "--help")
            self.assertEqual(rc, 0, err)
            for ext in (".msh", ".inp", ".bdf", ".nas", ".vtk", ".vtu", ".frd", ".e", ".exo"):
                self.assertIn(ext, out, cmd)

    # ---- bad input (issue #26): exit 2, file, block or line, step, node ----

    def test_step_counts_that_disagree(self):
        a = write_msh("a10.msh", steps=STEPS)
        b = write_frd("b3.frd", steps=3)
        js = path("never.json")
        for cmd in ("clash", "distance"):
            self.assert_bad([cmd, a, b, "--part-a", "left", "--part-b", "RIGHT", "--field-a", "disp", "--field-b",
                             "DISP", "--json", js],
                            ["mismatched step counts", "(field 'disp' of %s) have %d steps" % (a, STEPS),
                             "(field 'DISP' of %s) 3" % b], [js])
            # The same with CSVs of 2 and 3 steps.
            c2, c3 = write_csv("two.csv", 2), write_csv("three.csv", 3)
            f = self.files["inp"]
            self.assert_bad([cmd, f, f, "--part-a", "right", "--part-b", "right", "--disp-a", c2, "--disp-b", c3,
                             "--json", js],
                            ["mismatched step counts", "(CSV %s for %s) have 2 steps" % (c2, f), "(CSV %s for %s) 3" % (c3, f)],
                            [js])

    def test_csv_displacement_of_an_unknown_node(self):
        f = self.files["msh"]
        bad = write_csv("unknown.csv", 2, extra=["1,424242,0,0,0"])
        line = 2 + 2 * len(B[0])  # the header, 2 steps x 27 rows, then the bad row
        for cmd in ("clash", "distance"):
            self.assert_bad([cmd, f, f, "--part-a", "left", "--part-b", "right", "--disp-b", bad, "--json",
                             path("never.json")],
                            ["%s:%d" % (bad, line), "step 1", "node 424242", "is not in the mesh", f],
                            [path("never.json")])
        self.assert_bad(["check", f, "--disp", bad], ["%s:%d" % (bad, line), "node 424242"])

    def test_frd_displacement_of_an_unknown_node(self):
        ids = [nid for nid, _ in NODES] + [99999]
        f = write_frd("unknown_node.frd", steps=2, disp_nodes=ids)
        with open(f) as fh:
            lines = fh.read().split("\n")
        line = next(i + 1 for i, t in enumerate(lines) if t.startswith(" -1     99999"))
        for args in (["check", f], ["distance", f, f, "--part-a", "LEFT", "--part-b", "RIGHT"],
                     ["clash", f, f, "--part-a", "LEFT", "--part-b", "RIGHT", "--field", "DISP"], ["clash", f]):
            self.assert_bad(args, ["%s:%d" % (f, line), "DISP result block 1", "(step 1, increment 1)",
                                   "node 99999 is not defined in the node block"])

    def test_exodus_without_displacements(self):
        if "e" not in self.files:
            self.skipTest("no meshio/netCDF4 or no Exodus reader in this build")
        # A mesh-only file: distance and check read it; a displacement asked for is an error naming
        # the file and the fields it has (none).
        mesh_only = write_exodus("mesh_only.e", variables=())
        rc, out, err = run("check", mesh_only, "--json", path("mo.json"))
        self.assertEqual(rc, 0, out + err)
        for b, box in zip(load_json(path("mo.json"))["bodies"], (A_BOX, B_BOX)):
            self.assertAlmostEqual(b["volume"], box_volume(box), places=12)
        for cmd in ("clash", "distance"):
            self.assert_bad([cmd, mesh_only, mesh_only, "--part-a", "block 0", "--part-b", "block 1", "--field", "DISPL"],
                            [mesh_only, "no nodal field 'DISPL'", "fields: none"])
        # Nodal variables and time steps but no displacement: the reader's error, naming the file.
        temp = write_exodus("temp_only.e", variables=("TEMP",))
        for args in (["clash", temp, temp, "--part-a", "block 0", "--part-b", "block 1", "--field", "DISPL"],
                     ["distance", temp, temp, "--part-a", "block 0", "--part-b", "block 1"], ["check", temp]):
            self.assert_bad(args, [temp, "no displacement among the nodal variables (TEMP)"])


def json_of_stdout(out):
    import json
    return json.loads(out)


if __name__ == "__main__":
    cli_common.main()
