"""Truncated CalculiX .frd files on the command line (issue #26, "Bad input": a truncated .frd block
is a clear error naming the file, the block, the line or byte and the step; exit status 2; never a
crash or a hang).

The test writes its own .frd files with the record layouts of the CalculiX GraphiX manual ("Result
Format"; the fixed columns ccx 2.20 writes): two hex8 boxes of two materials, 3 DISP steps (each
after a 1PSTEP record naming step s + 1), in ASCII (long format) and in binary (as *NODE OUTPUT
writes it: nodes int32 id + 3 float64, elements int32 id, type, group, material, nodes, results
int32 node + 3 float32, the header records as text, no -3 after binary data). Two sizes: a small
model and one of more than 1 MB with DISP blocks of more than 4,096 nodes (the reader maps such a
file and reads its DISP blocks in parallel chunks; its errors must be the same). Each file is cut
inside the node block, inside the element block and inside the DISP block of step 2, once at a
record boundary and once inside a record; `clash`, `check` and the two-part `clash` must all exit
with status 2, write no report, and print the file, the block, the position (file:line for ASCII,
"byte N" for binary data, computed here from the cut) and "truncated"; for the DISP block also
"step 2". The uncut files are read (exit status 0 or 1) by the same commands.
"""
import os
import struct
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_common import main, path, run  # noqa: E402

STEPS = 3


def model(n):
    """Two boxes of n x n x n hex8 cells (A at the origin, B 0.2 beyond it in x); node ids from 1."""
    nodes, elems = [], []
    p = n + 1
    for body, x0 in ((1, 0.0), (2, 1.2)):
        base = len(nodes)
        for k in range(p):
            for j in range(p):
                for i in range(p):
                    nodes.append((base + (k * p + j) * p + i + 1, (x0 + i / n, j / n, k / n)))

        def nid(i, j, k, base=base):
            return base + (k * p + j) * p + i + 1
        for k in range(n):
            for j in range(n):
                for i in range(n):
                    v = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                         nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                    elems.append((len(elems) + 1, body, v))
    return nodes, elems


def disp(x, s):
    return (-0.05 * (s + 1) if x[0] > 1.1 else 0.0, 0.001 * s * x[1], 0.0)


def write_frd(name, n, binary):
    """Writes the model; returns (path, bytes, marks) with marks: block -> (begin, data begin, end)
    byte offsets (begin: the header record; data: the first record; end: after the last datum)."""
    nodes, elems = model(n)
    out = bytearray()
    marks = {}

    def text(line):
        out.extend((line + "\n").encode())

    text("    1C")
    text("    1UUSER")
    text("    1UMAT    1STEEL")
    text("    1UMAT    2ALU")
    begin = len(out)
    text("    2C" + " " * 18 + "%12d" % len(nodes) + " " * 37 + ("3" if binary else "1"))
    data = len(out)
    for i, x in nodes:
        if binary:
            out.extend(struct.pack("<i3d", i, *x))
        else:
            text(" -1%10d%12.5E%12.5E%12.5E" % (i, *x))
    marks["node"] = (begin, data, len(out))
    if not binary:
        text(" -3")
    begin = len(out)
    text("    3C" + " " * 18 + "%12d" % len(elems) + " " * 37 + ("2" if binary else "1"))
    data = len(out)
    for e, mat, v in elems:
        if binary:
            out.extend(struct.pack("<4i", e, 1, 0, mat) + struct.pack("<8i", *v))
        else:
            text(" -1%10d%5d%5d%5d" % (e, 1, 0, mat))
            text(" -2" + "".join("%10d" % q for q in v))
    marks["element"] = (begin, data, len(out))
    if not binary:
        text(" -3")
    for s in range(STEPS):
        text("    1PSTEP" + " " * 14 + "%12d%12d%12d" % (s + 1, 1, s + 1))
        begin = len(out)
        text("  100CL%5d%12.5E%12d%20s%2d%5d%10s%2d" % (101 + s, 0.5 * (s + 1), len(nodes), "", 0, s + 1, "",
                                                       2 if binary else 1))
        for line in (" -4  DISP        4    1", " -5  D1          1    2    1    0", " -5  D2          1    2    2    0",
                     " -5  D3          1    2    3    0", " -5  ALL         1    2    0    0    1ALL"):
            text(line)
        data = len(out)
        for i, x in nodes:
            u = disp(x, s)
            if binary:
                out.extend(struct.pack("<i3f", i, *u))
            else:
                text(" -1%10d%12.5E%12.5E%12.5E" % (i, *u))
        marks["disp%d" % (s + 1)] = (begin, data, len(out))
        if not binary:
            text(" -3")
    text(" 9999")
    p = path(name)
    with open(p, "wb") as f:
        f.write(out)
    return p, bytes(out), marks


def cut_file(name, data, at):
    p = path(name)
    with open(p, "wb") as f:
        f.write(data[:at])
    return p


def line_of(data, at):
    """1-based line of byte `at`."""
    return data[:at].count(b"\n") + 1


class TruncatedFrd(unittest.TestCase):
    def commands(self, f):
        return [["clash", f, "--json", path("never.json")], ["check", f, "--json", path("never.json")],
                ["clash", f, f, "--part-a", "STEEL", "--part-b", "ALU", "--field", "DISP", "--json", path("never.json")]]

    def assert_bad(self, f, needles):
        for args in self.commands(f):
            code, out, err = run(*args)
            self.assertEqual(code, 2, "%s: %s%s" % (args[0], out, err))
            for needle in needles:
                self.assertIn(needle, err, args)
            self.assertNotIn("Traceback", err)
            self.assertFalse(os.path.exists(path("never.json")), args)

    def check_model(self, n, binary):
        kind = ("bin" if binary else "ascii") + str(n)
        f, data, marks = write_frd("good_%s.frd" % kind, n, binary)
        if n > 10:
            self.assertGreater(len(data), 1 << 20)  # mapped by the reader
        for args in self.commands(f):
            code, out, err = run(*args)
            self.assertIn(code, (0, 1), "%s: %s%s" % (args[0], out, err))
        os.remove(path("never.json"))
        rec = {"node": 28 if binary else 50, "element": 48 if binary else 113, "disp2": 16 if binary else 50}
        block = {"node": "node block (2C)", "element": "element block (3C)",
                 "disp2": "DISP result block 2 (step 2, increment 1)"}
        for what in ("node", "element", "disp2"):
            begin, first, end = marks[what]
            count = (end - first) // rec[what]
            for where, at in (("boundary", first + rec[what] * (count // 2)),
                              ("inside", first + rec[what] * (count // 2) + rec[what] // 2)):
                with self.subTest(kind=kind, block=what, cut=where):
                    bad = cut_file("cut_%s_%s_%s.frd" % (kind, what, where), data, at)
                    needles = [bad, block[what], "truncated"]
                    if what == "disp2":
                        needles.append("step 2")
                    if binary:
                        # The record the file ends in starts at the cut (boundary) or half a record before.
                        start = at if where == "boundary" else at - rec[what] // 2
                        needles.append("byte %d:" % start)
                    else:
                        # The last line read: the one before the cut (boundary) or the one cut.
                        needles.append("%s:%d:" % (bad, line_of(data, at) - (1 if where == "boundary" else 0)))
                    self.assert_bad(bad, needles)

    def test_small_ascii(self):
        self.check_model(3, False)

    def test_small_binary(self):
        self.check_model(3, True)

    def test_large_ascii(self):
        self.check_model(17, False)

    def test_large_binary(self):
        self.check_model(17, True)

    def test_cut_header_records(self):
        """Cut inside the header record of a block: the block and its step are named."""
        f, data, marks = write_frd("hdr.frd", 3, False)
        begin = marks["disp2"][0]
        bad = cut_file("cut_hdr_disp.frd", data, begin + 30)  # inside the 100C record (in its time field)
        self.assert_bad(bad, [bad, "result block 2 (step 2, increment 1)", "truncated", "%s:%d:" % (bad, line_of(data, begin))])
        begin = marks["element"][0]
        bad = cut_file("cut_hdr_elem.frd", data, begin + 20)  # before its count
        self.assert_bad(bad, [bad, "element block (3C)", "truncated", "%s:%d:" % (bad, line_of(data, begin))])


if __name__ == "__main__":
    main()
