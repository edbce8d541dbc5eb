#!/usr/bin/env python3
"""Writes the small FEM test files of tests/data/fem/ (standard library only, deterministic).

    python3 tests/data/fem/make_fem_files.py

Every file is written by this script (hand-composed text, or packed with struct/base64/zlib for
the binary variants); see README.md. Public domain (CC0).
"""
import base64
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data)


# Unit cube corners (VTK / Abaqus / Nastran corner order) and its 12 edge midpoints in VTK order.
CUBE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
VTK_HEX20_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def mid(a, b):
    return tuple((x + y) / 2 for x, y in zip(CUBE[a], CUBE[b]))


HEX20 = CUBE + [mid(a, b) for a, b in VTK_HEX20_EDGES]  # VTK order == Abaqus C3D20 order

# ---------------------------------------------------------------- Nastran
write("small_field.bdf", """\
$ interfere test deck: small field, continuations, INCLUDE, shorthand reals (CC0)
SOL 101
CEND
TITLE = two cubes
BEGIN BULK
PSOLID  1       1
MAT1    1       2.1+5           .3                                      +M1
+M1     1.-5
$ grid 2 uses Nastran's implicit exponent: 1.+0 = 1.0, 2.5-1 = 0.25 on grid 3
GRID    1               0.      0.      0.
GRID    2               1.+0    0.      0.
GRID    3               1.      1.      0.
GRID    4               0.      1.      0.
INCLUDE 'small_field_top.bdf'
CHEXA   20      1       1       2       3       4       5       6       +H20
+H20    7       8
CHEXA   21      2       5       6       7       8       9       10
        11      12
CTETRA  30      2       9       10      11      13
ENDDATA
GRID    99              5.      5.      5.
""")
write("small_field_top.bdf", """\
$ included by small_field.bdf
GRID    5               0.      0.      1.
GRID    6               1.      0.      1.
GRID    7               1.      1.      1.
GRID    8               0.      1.      1.
GRID    9               0.      0.      2.
GRID    10              1.      0.      2.
GRID    11              1.      1.      2.
GRID    12              0.      1.      2.
GRID    13              2.5-1   2.5-1   -2.5+1
""")
# Large field (GRID* + '*' continuation) and free field, CPENTA15 with mid-side grids.
lines = ["$ large and free field (CC0)", "BEGIN BULK"]
def grid_large(gid, x, y, z):
    return ["GRID*   %-16d%-16s%-16s%-16s*G%d" % (gid, "", x, y, gid), "*G%-6d%-16s" % (gid, z)]
W = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
VTK_W15 = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
WP = W + [tuple((a + b) / 2 for a, b in zip(W[i], W[j])) for i, j in VTK_W15]
def fmt(v):
    s = repr(float(v))
    return s
for i, p in enumerate(WP):
    if i % 2 == 0:
        lines += grid_large(i + 1, fmt(p[0]), fmt(p[1]), fmt(p[2]))
    else:
        lines.append("GRID,%d,,%s,%s,%s" % (i + 1, fmt(p[0]), fmt(p[1]), fmt(p[2])))
# Nastran CPENTA15 order: corners, bottom edges (G7-G9), vertical (G10-G12), top (G13-G15).
nas_order = list(range(6)) + [6, 7, 8] + [12, 13, 14] + [9, 10, 11]
ids = [nas_order[k] + 1 for k in range(15)]
lines.append("CPENTA,40,5," + ",".join(str(g) for g in ids[:6]))
lines.append("," + ",".join(str(g) for g in ids[6:14]))
lines.append("," + str(ids[14]))
lines.append("CTRIA3,50,6,1,2,3")  # a shell next to a solid: dropped (lower dimension)
lines.append("ENDDATA")
write("large_free_field.bdf", "\n".join(lines) + "\n")

# ---------------------------------------------------------------- Abaqus
write("assembly.inp", """\
*HEADING
two instances of one part, the second translated then rotated (CC0)
** comment line
*PART, NAME=Block
*NODE, NSET=all
1, 0., 0., 0.
2, 1., 0., 0.
3, 1., 1., 0.
4, 0., 1., 0.
5, 0., 0., 1.
6, 1., 0., 1.
7, 1., 1., 1.
8, 0., 1., 1.
*ELEMENT, TYPE=C3D8R, ELSET=body
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=bottom, GENERATE
1, 4, 1
*END PART
*ASSEMBLY, NAME=Assembly
*INSTANCE, NAME=B1, PART=Block
*END INSTANCE
*Instance, name=B2, part=BLOCK
10., 0., 0.
10., 0., 0., 10., 0., 1., 90.
*End Instance
*NSET, NSET=corner, INSTANCE=B2
2
*END ASSEMBLY
*MATERIAL, NAME=steel
*ELASTIC
210000., 0.3
""")
nodes = "\n".join("%d, %r, %r, %r" % ((i + 1,) + tuple(float(c) for c in p)) for i, p in enumerate(HEX20))
write("hex20_nodes.inp", "** nodes of hex20.inp (CC0)\n*NODE\n" + nodes + "\n")
write("hex20.inp", """\
** C3D20 over two data lines, *INCLUDE, ELSET GENERATE (CC0)
*INCLUDE, INPUT=hex20_nodes.inp
*ELEMENT, TYPE=C3D20R, ELSET=cube
7, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,
16, 17, 18, 19, 20
*ELEMENT, TYPE=C3D4, ELSET=spike
8, 5, 6, 7, 1
*ELSET, ELSET=everything, GENERATE
7, 8
""")

# ---------------------------------------------------------------- Gmsh MSH
write("two_bodies_v22.msh", """\
$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
2 7 "contact"
3 1 "steel"
3 2 "rubber"
$EndPhysicalNames
$Nodes
5
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 1 1 1
$EndNodes
$Elements
4
1 2 2 7 3 1 2 3
2 4 2 1 1 1 2 3 4
3 4 2 2 2 2 3 4 5
4 4 2 1 2 2 3 4 5
$EndElements
""")
write("two_bodies_v41.msh", """\
$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
2 7 "contact"
3 1 "steel"
3 2 "rubber"
$EndPhysicalNames
$Entities
0 0 1 2
3 0 0 0 1 1 0 1 7 0
1 0 0 0 1 1 1 1 1 0
2 0 0 0 1 1 1 2 2 1 0
$EndEntities
$Nodes
1 5 1 5
3 1 0 5
1
2
3
4
5
0 0 0
1 0 0
0 1 0
0 0 1
1 1 1
$EndNodes
$Elements
3 3 1 3
2 3 2 1
1 1 2 3
3 1 4 1
2 1 2 3 4
3 2 4 1
3 2 3 4 5
$EndElements
""")

# ---------------------------------------------------------------- legacy VTK
write("wedge_v51.vtk", """\
# vtk DataFile Version 5.1
one wedge and one pyramid, 5.1 layout (CC0)
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 7 float
0 0 0 1 0 0 0 1 0
0 0 1 1 0 1 0 1 1
0.5 0.5 2
CELLS 3 11
OFFSETS vtktypeint64
0 6 11
CONNECTIVITY vtktypeint64
0 1 2 3 4 5
3 4 5 5 6
CELL_TYPES 2
13
14
CELL_DATA 2
SCALARS mat_id int 1
LOOKUP_TABLE default
4
9
POINT_DATA 7
VECTORS displacement double
0 0 0 0 0 0 0 0 0
0 0 0.5 0 0 0.5 0 0 0.5
0 0 1
METADATA
INFORMATION 0

""")
def vtk_binary():
    pts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    out = b"# vtk DataFile Version 3.0\nbinary tetra (CC0)\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
    out += b"POINTS 4 float\n" + b"".join(struct.pack(">3f", *p) for p in pts) + b"\n"
    out += b"CELLS 1 5\n" + struct.pack(">5i", 4, 0, 1, 2, 3) + b"\n"
    out += b"CELL_TYPES 1\n" + struct.pack(">i", 10) + b"\n"
    out += b"CELL_DATA 1\nFIELD FieldData 1\nGlobalElementId 1 1 int\n" + struct.pack(">i", 77) + b"\n"
    out += b"POINT_DATA 4\nSCALARS GlobalNodeId int\nLOOKUP_TABLE default\n" + struct.pack(">4i", 11, 12, 13, 14) + b"\n"
    return out
write("tet_binary.vtk", vtk_binary())

# ---------------------------------------------------------------- VTU variants
TET_PTS = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.]
TET_CONN = [0, 1, 2, 3, 1, 2, 3, 4]
TET_OFFS = [4, 8]
TET_TYPES = [10, 10]
DISP = [0.1 * i for i in range(15)]
ARRAYS = [  # (section, name, vtk type, struct code, components, values)
    ("PointData", "DISPL", "Float32", "f", 3, DISP),
    ("PointData", "GlobalNodeId", "Int32", "i", 1, [101, 102, 103, 104, 105]),
    ("CellData", "element_id", "UInt16", "H", 1, [7, 9]),
    ("CellData", "MaterialIds", "Int8", "b", 1, [3, -2]),
    ("Points", "", "Float64", "d", 3, TET_PTS),
    ("Cells", "connectivity", "Int64", "q", 1, TET_CONN),
    ("Cells", "offsets", "UInt32", "I", 1, TET_OFFS),
    ("Cells", "types", "UInt8", "B", 1, TET_TYPES),
]


def vtu(encoding, header="UInt32", order="<", compress=False, block=7):
    hcode = "I" if header == "UInt32" else "Q"
    appended = b""
    sections = {}
    for sec, name, vt, code, comps, vals in ARRAYS:
        raw = struct.pack(order + str(len(vals)) + code, *vals)
        attrs = 'type="%s"%s NumberOfComponents="%d"' % (vt, ' Name="%s"' % name if name else "", comps)
        if compress:
            blocks = [raw[i:i + block] for i in range(0, len(raw), block)] or [b""]
            comp = [zlib.compress(b) for b in blocks]
            head = struct.pack(order + str(3 + len(blocks)) + hcode, len(blocks), block, len(blocks[-1]), *[len(c) for c in comp])
            body = b"".join(comp)
        else:
            head = struct.pack(order + hcode, len(raw))
            body = raw
        if encoding == "ascii":
            text = " ".join(repr(v) for v in vals)
            el = '<DataArray %s format="ascii">\n%s\n</DataArray>' % (attrs, text)
        elif encoding == "binary":
            b64 = (base64.b64encode(head) + base64.b64encode(body)) if compress else base64.b64encode(head + body)
            el = '<DataArray %s format="binary">\n%s\n</DataArray>' % (attrs, b64.decode())
        else:
            el = '<DataArray %s format="appended" offset="%d"/>' % (attrs, len(appended))
            if encoding == "appended_raw":
                appended += head + body
            else:
                appended += base64.b64encode(head) + base64.b64encode(body)
        sections.setdefault(sec, []).append(el)
    comp_attr = ' compressor="vtkZLibDataCompressor"' if compress else ""
    bo = "LittleEndian" if order == "<" else "BigEndian"
    xml = '<?xml version="1.0"?>\n<!-- interfere test file (CC0) -->\n'
    xml += '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="%s" header_type="%s"%s>\n' % (bo, header, comp_attr)
    xml += "<UnstructuredGrid>\n<Piece NumberOfPoints=\"5\" NumberOfCells=\"2\">\n"
    for sec in ["PointData", "CellData", "Points", "Cells"]:
        xml += "<%s>\n%s\n</%s>\n" % (sec, "\n".join(sections[sec]), sec)
    xml += "</Piece>\n</UnstructuredGrid>\n"
    out = xml.encode()
    if encoding.startswith("appended"):
        enc = "raw" if encoding == "appended_raw" else "base64"
        out += b'<AppendedData encoding="%s">\n   _' % enc.encode() + appended + b"\n</AppendedData>\n"
    out += b"</VTKFile>\n"
    return out


write("tets_ascii.vtu", vtu("ascii"))
write("tets_binary_u32.vtu", vtu("binary", "UInt32"))
write("tets_binary_zlib_u64.vtu", vtu("binary", "UInt64", compress=True))
write("tets_appended_raw_zlib.vtu", vtu("appended_raw", "UInt32", compress=True))
write("tets_appended_base64_u64.vtu", vtu("appended_base64", "UInt64"))
write("tets_appended_raw_big_endian.vtu", vtu("appended_raw", "UInt64", order=">"))

# ---------------------------------------------------------------- displacements CSV
write("tets_disp.csv", "# step-wise displacements of tets_*.vtu (node ids 101-105)\nstep,node_id,ux,uy,uz\n"
      "2,105,0.5,0,0\n1,101,1e-3,0,0\n1,105,0.25,0,0\n2,101,2e-3,0,-1\n")


# ---------------------------------------------------------------- quadratic solids in the solvers'
# own mid-side orders (Nastran QRG: CTETRA G5-G10 on edges 1-2 2-3 3-1 1-4 2-4 3-4; CHEXA G9-G12
# bottom, G13-G16 vertical 1-5 .. 4-8, G17-G20 top; CPENTA G7-G9 bottom, G10-G12 vertical, G13-G15
# top; CPYRAM G6-G9 base, G10-G13 to the apex. Abaqus: C3D10 as CTETRA; C3D15 G7-G9 bottom,
# G10-G12 top, G13-G15 vertical; C3D20 9-12 bottom, 13-16 top, 17-20 vertical).
def quad_element(corners, edges, offset):
    pts = list(corners) + [tuple((a + b) / 2 for a, b in zip(corners[i], corners[j])) for i, j in edges]
    return pts, [offset + k + 1 for k in range(len(pts))]


TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
PYR = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
NAS = {
    "CTETRA": (TET, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]),
    "CHEXA": (CUBE, [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6), (6, 7), (7, 4)]),
    "CPENTA": (W, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (5, 3)]),
    "CPYRAM": (PYR, [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)]),
}
lines = ["$ quadratic solids, Nastran mid-side order (CC0)", "BEGIN BULK"]
elems = []
offset = 0
for k, (card, (corners, edges)) in enumerate(NAS.items()):
    shifted = [(x + 3 * k, y, z) for x, y, z in corners]
    pts, ids = quad_element(shifted, edges, offset)
    for gid, p in zip(ids, pts):
        lines.append("GRID,%d,,%r,%r,%r" % ((gid,) + tuple(float(c) for c in p)))
    fields = [str(100 + k), str(k + 1)] + [str(g) for g in ids]
    rec = card + "," + ",".join(fields[:8])
    rest = fields[8:]
    while rest:
        rec += "\n," + ",".join(rest[:8])
        rest = rest[8:]
    elems.append(rec)
    offset += len(pts)
write("quadratic.bdf", "\n".join(lines + elems + ["ENDDATA"]) + "\n")

ABQ = {
    "C3D10": (TET, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]),
    "C3D15": (W, [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]),
    "C3D20": (CUBE, VTK_HEX20_EDGES),
}
out = ["** quadratic solids, Abaqus node order (CC0)", "*NODE"]
blocks = []
offset = 0
for k, (ty, (corners, edges)) in enumerate(ABQ.items()):
    shifted = [(x + 3 * k, y, z) for x, y, z in corners]
    pts, ids = quad_element(shifted, edges, offset)
    out += ["%d, %r, %r, %r" % ((g,) + tuple(float(c) for c in p)) for g, p in zip(ids, pts)]
    rec = [str(100 + k)] + [str(g) for g in ids]
    text = ""
    while rec:
        text += ", ".join(rec[:16]) + (",\n" if len(rec) > 16 else "\n")
        rec = rec[16:]
    blocks.append("*ELEMENT, TYPE=%s, ELSET=%s\n%s" % (ty, ty.lower(), text))
    offset += len(pts)
write("quadratic.inp", "\n".join(out) + "\n" + "".join(blocks))
