#!/usr/bin/env python3
"""Writes ccx_elements.inp and runs the CalculiX solver (Debian calculix-ccx, `ccx`) on it twice:
with *NODE FILE (an ASCII .frd: ccx_elements.frd) and with *NODE OUTPUT (ccx writes the data of
its blocks in binary: ccx_elements_bin.frd). Issue #26: the .frd reader is checked against files
the real solver wrote (tests/unit/fem/test_fem_io_frd.cpp compares them with the .inp).

    python3 tests/data/fem/make_frd_files.py

The model: one element of each solid type CalculiX writes to .frd (C3D8, C3D6, C3D4, C3D20,
C3D15, C3D10), each on its own nodes, unit sized, 2 apart in x; linear ones of material STEEL,
quadratic ones of material ALU (so the reader makes two groups). Nodes on z = 0 are held, nodes on
z = 1 pushed by (0.01, 0.02, 0) over two fixed increments (*STATIC, DIRECT). Node and element ids
are not consecutive (100 per element) so that id handling shows. Public domain (CC0).
"""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

HEX = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
WEDGE = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
TET = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
# Mid-edge nodes in Abaqus order (= VTK's, fem_mesh.h).
HEX20_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
WEDGE15_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
TET10_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]

ELEMENTS = [  # (type, corners, mid-edges, material)
    ("C3D8", HEX, [], "STEEL"),
    ("C3D6", WEDGE, [], "STEEL"),
    ("C3D4", TET, [], "STEEL"),
    ("C3D20", HEX, HEX20_EDGES, "ALU"),
    ("C3D15", WEDGE, WEDGE15_EDGES, "ALU"),
    ("C3D10", TET, TET10_EDGES, "ALU"),
]


def model(node_output):
    lines = ["*HEADING", "one element of each solid type (interfere test, CC0)", "*NODE"]
    blocks, bottom, top = [], [], []
    for k, (typ, corners, edges, mat) in enumerate(ELEMENTS):
        pts = list(corners) + [tuple((a + b) / 2 for a, b in zip(corners[i], corners[j])) for i, j in edges]
        base = 100 * (k + 1)
        ids = []
        for i, p in enumerate(pts):
            nid = base + 3 * i + 1
            x = (p[0] + 2 * k, p[1], p[2])
            lines.append("%d, %r, %r, %r" % ((nid,) + x))
            ids.append(nid)
            (bottom if p[2] == 0 else top if p[2] == 1 else []).append(nid)
        blocks.append((typ, 1000 + 7 * k, ids, mat))
    for typ, eid, ids, mat in blocks:
        lines.append("*ELEMENT, TYPE=%s, ELSET=E%s" % (typ, typ))
        rec = [str(eid)] + [str(n) for n in ids]
        # at most 16 entries per data line; a trailing comma continues the record
        while rec:
            chunk, rec = rec[:15], rec[15:]
            lines.append(", ".join(chunk) + ("," if rec else ""))
    lines.append("*ELSET, ELSET=LIN")
    lines.append(", ".join("E" + b[0] for b in blocks[:3]))
    lines.append("*ELSET, ELSET=QUAD")
    lines.append(", ".join("E" + b[0] for b in blocks[3:]))
    lines.append("*NSET, NSET=BOTTOM")
    lines += ["%d," % n for n in bottom]
    lines.append("*NSET, NSET=TOP")
    lines += ["%d," % n for n in top]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
              "*MATERIAL, NAME=ALU", "*ELASTIC", "70000., 0.33",
              "*SOLID SECTION, ELSET=LIN, MATERIAL=STEEL", "*SOLID SECTION, ELSET=QUAD, MATERIAL=ALU",
              "*STEP, NLGEOM", "*STATIC, DIRECT", "0.5, 1.0",
              "*BOUNDARY", "BOTTOM, 1, 3, 0.", "TOP, 1, 1, 0.01", "TOP, 2, 2, 0.02", "TOP, 3, 3, 0.",
              "*NODE OUTPUT" if node_output else "*NODE FILE", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def main():
    if not shutil.which("ccx"):
        sys.exit("ccx (Debian calculix-ccx) is not installed")
    with open(os.path.join(HERE, "ccx_elements.inp"), "w") as f:
        f.write(model(False))
    for node_output, out in ((False, "ccx_elements.frd"), (True, "ccx_elements_bin.frd")):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "job.inp"), "w") as f:
                f.write(model(node_output))
            subprocess.run(["ccx", "-i", "job"], cwd=d, check=True, stdout=subprocess.DEVNULL)
            shutil.copy(os.path.join(d, "job.frd"), os.path.join(HERE, out))


if __name__ == "__main__":
    main()
