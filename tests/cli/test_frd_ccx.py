"""`interfere clash model.frd` on a result file of the real CalculiX solver (issue #26, item 1).

The test writes a small model, runs `ccx` (Debian calculix-ccx; tools/deps.sh installs it) in its
work directory, and reads the .frd it wrote, in ASCII (*NODE FILE) and binary (*NODE OUTPUT):

  block A: x in [0, 1], y, z in [0, 1], 4 x 4 x 4 C3D8, held at its face x = 0;
  block B: x in [1 + g, 2 + g], y, z in [0.2, 0.8], 4 x 4 x 4 C3D8; its face x = 2 + g moved by
           u = (-D t, 0, 0) (its y and z held), t = 0.1 ... 1 in N = 10 fixed increments
           (*STATIC, DIRECT, NLGEOM). No contact is defined: the blocks are independent bodies.

Analytic solution: B's only boundary condition is a uniform displacement of one face, so the
stress-free rigid translation u = (-D t, 0, 0) satisfies every condition and is the solution
(uniqueness of elasticity; also exact under NLGEOM): B's near face is at x = 1 + g - D t. With
g = 0.23, D = 0.5 it enters A between increment 4 (t = 0.4, gap 0.03) and 5 (t = 0.5, 0.02 deep),
so the first clashing frame is 4 (0-based; time 0.5). A has no load: it stays put. The test checks
the translation in the solver's own output with a parser of its own (fixed columns), then that
interfere's first clashing frame is 4, frames 0-3 have no clash, and the clashing elements at that
frame are, computed from the generated mesh: A's elements of the layer at x = 1 whose face x = 1
meets the outline of B's cross-section (the 12 of 16 cells around the middle 2 x 2), and B's
elements of its first layer on its sides (12 of 16): B's side faces cross A's face x = 1; B's near
face lies inside A and crosses nothing. Bad input: a truncated .frd is exit status 2 with the
file, the line and the block named.
"""
import os
import shutil
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_common import load_json, main, path, run, write_text  # noqa: E402

N_CELLS = 4
GAP, PUSH, INCREMENTS = 0.23, 0.5, 10
A_BOX = ((0.0, 1.0), (0.0, 1.0), (0.0, 1.0))
B_BOX = ((1.0 + GAP, 2.0 + GAP), (0.2, 0.8), (0.2, 0.8))


def node_id(base, i, j, k):
    n = N_CELLS + 1
    return base + 1 + i + n * (j + n * k)


def elem_id(base, i, j, k):
    return base + 1 + i + N_CELLS * (j + N_CELLS * k)


def grid(box, t):
    (x0, x1), (y0, y1), (z0, z1) = box
    return [x0 + (x1 - x0) * t[0] / N_CELLS, y0 + (y1 - y0) * t[1] / N_CELLS, z0 + (z1 - z0) * t[2] / N_CELLS]


def model_inp(binary):
    lines = ["*HEADING", "two blocks, B pushed into A (interfere issue #26 test)", "*NODE"]
    r = range(N_CELLS + 1)
    for base, box in ((0, A_BOX), (1000, B_BOX)):
        for k in r:
            for j in r:
                for i in r:
                    lines.append("%d, %r, %r, %r" % ((node_id(base, i, j, k),) + tuple(grid(box, (i, j, k)))))
    for base, name in ((0, "A"), (1000, "B")):
        lines.append("*ELEMENT, TYPE=C3D8, ELSET=%s" % name)
        for k in range(N_CELLS):
            for j in range(N_CELLS):
                for i in range(N_CELLS):
                    c = [(i, j, k), (i + 1, j, k), (i + 1, j + 1, k), (i, j + 1, k),
                         (i, j, k + 1), (i + 1, j, k + 1), (i + 1, j + 1, k + 1), (i, j + 1, k + 1)]
                    lines.append("%d, %s" % (elem_id(base, i, j, k), ", ".join(str(node_id(base, *p)) for p in c)))
    lines.append("*NSET, NSET=HOLD")
    lines += ["%d," % node_id(0, 0, j, k) for j in r for k in r]
    lines.append("*NSET, NSET=PUSH")
    lines += ["%d," % node_id(1000, N_CELLS, j, k) for j in r for k in r]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
              "*SOLID SECTION, ELSET=A, MATERIAL=STEEL", "*SOLID SECTION, ELSET=B, MATERIAL=STEEL",
              "*STEP, NLGEOM", "*STATIC, DIRECT", "%r, 1." % (1.0 / INCREMENTS),
              "*BOUNDARY", "HOLD, 1, 3, 0.", "PUSH, 1, 1, %r" % -PUSH, "PUSH, 2, 3, 0.",
              "*NODE OUTPUT" if binary else "*NODE FILE", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def run_ccx(job, binary):
    d = path(job)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, job + ".inp"), "w") as f:
        f.write(model_inp(binary))
    p = subprocess.run(["ccx", "-i", job], cwd=d, capture_output=True, text=True, timeout=300)
    frd = os.path.join(d, job + ".frd")
    if p.returncode != 0 or not os.path.exists(frd):
        raise AssertionError("ccx failed:\n" + p.stdout[-2000:] + p.stderr[-2000:])
    return frd


def ascii_disp_blocks(frd):
    """[(time, {node: (ux, uy, uz)})] of the DISP blocks, read by fixed columns (the cgx manual's
    long format): independent of interfere's reader."""
    out, cur, time = [], None, None
    with open(frd) as f:
        for line in f:
            if line.startswith("  100C"):
                time = float(line[12:24])
            elif line.startswith(" -4  DISP"):
                cur = {}
            elif cur is not None and line.startswith(" -1"):
                cur[int(line[3:13])] = tuple(float(line[13 + 12 * c:25 + 12 * c]) for c in range(3))
            elif cur is not None and line.startswith(" -3"):
                out.append((time, cur))
                cur = None
    return out


def node_position(nid, shift):
    """The node's position with B moved by -shift in x (A's nodes ids 1..125, B's 1001..)."""
    base, box = (1000, B_BOX) if nid > 1000 else (0, A_BOX)
    n = N_CELLS + 1
    i, rest = (nid - base - 1) % n, (nid - base - 1) // n
    j, k = rest % n, rest // n
    p = grid(box, (i, j, k))
    if base:
        p[0] -= shift
    return p, base


def box_depth(p, box):
    """Distance of p to the surface of the box when strictly inside it, else 0."""
    if not all(lo < c < hi for c, (lo, hi) in zip(p, box)):
        return 0.0
    return min(min(c - lo, hi - c) for c, (lo, hi) in zip(p, box))


def node_depth(nid, shift):
    p, base = node_position(nid, shift)
    if base:
        return box_depth(p, A_BOX)
    (x0, x1), yb, zb = B_BOX
    return box_depth(p, ((x0 - shift, x1 - shift), yb, zb))


def element_nodes(eid):
    base = 1000 if eid > 1000 else 0
    e = eid - base - 1
    i, j, k = e % N_CELLS, (e // N_CELLS) % N_CELLS, e // (N_CELLS * N_CELLS)
    return {node_id(base, i + a, j + b, k + c) for a in (0, 1) for b in (0, 1) for c in (0, 1)}


def expected_elements():
    """A's layer at x = 1 whose face meets the outline of B's cross-section [0.2, 0.8]^2, and B's
    first layer on its sides (the closed cell meets the outline: overlaps the square, not inside it)."""
    lo, hi = B_BOX[1]
    a = set()
    for j in range(N_CELLS):
        for k in range(N_CELLS):
            y0, y1 = j / N_CELLS, (j + 1) / N_CELLS
            z0, z1 = k / N_CELLS, (k + 1) / N_CELLS
            overlaps = y0 <= hi and y1 >= lo and z0 <= hi and z1 >= lo
            inside = y0 > lo and y1 < hi and z0 > lo and z1 < hi
            if overlaps and not inside:
                a.add(elem_id(0, N_CELLS - 1, j, k))
    b = {elem_id(1000, 0, j, k) for j in range(N_CELLS) for k in range(N_CELLS)
         if j in (0, N_CELLS - 1) or k in (0, N_CELLS - 1)}
    return a, b


FIRST = next(k for k in range(1, INCREMENTS + 1) if PUSH * k / INCREMENTS > GAP) - 1  # 0-based frame


@unittest.skipUnless(shutil.which("ccx"), "ccx (Debian calculix-ccx) is not installed: tools/deps.sh installs it")
class CalculixResults(unittest.TestCase):

    def test_solver_output_is_the_analytic_translation(self):
        blocks = ascii_disp_blocks(run_ccx("analytic", False))
        self.assertEqual(len(blocks), INCREMENTS)
        for s, (t, u) in enumerate(blocks):
            self.assertAlmostEqual(t, (s + 1) / INCREMENTS, places=6)
            for k in range(N_CELLS + 1):
                for j in range(N_CELLS + 1):
                    for i in range(N_CELLS + 1):
                        ua, ub = u[node_id(0, i, j, k)], u[node_id(1000, i, j, k)]
                        self.assertLessEqual(max(abs(c) for c in ua), 1e-9)
                        self.assertAlmostEqual(ub[0], -PUSH * t, places=6)
                        self.assertLessEqual(max(abs(ub[1]), abs(ub[2])), 1e-9)

    def check_scene(self, frd, name):
        code, out, err = run("clash", frd, "--json", path(name + ".json"))
        self.assertEqual(code, 1, out + err)
        r = load_json(name + ".json")
        self.assertEqual(sorted(b["name"] for b in r["bodies"]), ["body 1", "body 2"])  # by connectivity
        self.assertEqual(len(r["frames"]), INCREMENTS)
        for f, fr in enumerate(r["frames"]):
            self.assertAlmostEqual(fr["time"], (f + 1) / INCREMENTS, places=6)
            self.assertEqual(fr["clashes"] > 0, f >= FIRST, fr)
        clash = [c for c in r["clashes"] if c["verdict"] == "clash"]
        self.assertEqual(len(clash), 1, r["clashes"])
        c = clash[0]
        self.assertEqual(FIRST, 4)
        self.assertEqual(c["first_frame"], FIRST)
        self.assertEqual(c["frames"], list(range(FIRST, INCREMENTS)))
        ids = {c["body_a"]["name"]: set(c["source_ids_a"]), c["body_b"]["name"]: set(c["source_ids_b"])}
        exp_a, exp_b = expected_elements()
        self.assertEqual(len(exp_a), 12)
        self.assertEqual(len(exp_b), 12)
        self.assertEqual(ids, {"body 1": exp_a, "body 2": exp_b})

    def test_scene_clash_ascii_frd(self):
        self.check_scene(run_ccx("ascii", False), "ascii")

    def test_scene_clash_binary_frd(self):
        frd = run_ccx("binary", True)
        with open(frd, "rb") as f:
            head = f.read()
        self.assertIn(b"    2C", head)
        self.assertNotIn(b"\n -3\n", head)  # binary data blocks have no -3 record
        self.check_scene(frd, "binary")

    def test_frames_by_pairs_table(self):
        """Issue #26, items 2 and 4: the table frames x body pairs. With a clearance test of 0.5 every
        frame has a row for the pair; before the clash its min distance is the analytic gap
        g - D t (to the solver's 6 printed digits), from frame FIRST on it is a clash. The blocks are
        apart before the load: the clash is a new penetration, no contact is designed."""
        frd = run_ccx("table", False)
        csv_path = path("table_pairs.csv")
        code, out, err = run("clash", frd, "--clearance", "0.5", "--json", path("table.json"),
                             "--frame-pairs-csv", csv_path)
        self.assertEqual(code, 1, out + err)
        self.assertIn("0 designed contacts, 0 new contacts, 1 new penetrations", out)
        r = load_json("table.json")
        self.assertEqual(r["summary"]["new_penetrations"], 1)
        self.assertEqual(r["summary"]["designed_contacts"], 0)
        rows = r["frame_pairs"]
        self.assertEqual([x["frame"] for x in rows], list(range(INCREMENTS)))
        for x in rows:
            f = x["frame"]
            self.assertEqual(x["verdict"], "clash" if f >= FIRST else "clearance", x)
            if f < FIRST:
                self.assertAlmostEqual(x["min_distance"], GAP - PUSH * (f + 1) / INCREMENTS, delta=1e-5)
                self.assertEqual(x["max_depth"], 0)
            else:
                self.assertEqual(x["min_distance"], 0)
                depth = PUSH * (f + 1) / INCREMENTS - GAP  # B's near face sunk this far into A
                self.assertLessEqual(x["max_depth"], depth + 1e-5, x)
                self.assertGreaterEqual(x["max_depth_bound"], depth - 1e-5, x)
                # The deepest node (issue #26, item 3): its depth is the analytic one, recomputed
                # here from the node's id, the generated grid and B's translation, and its element
                # holds it.
                d = x["deepest"]
                self.assertAlmostEqual(d["depth"], depth, delta=1e-5)
                self.assertAlmostEqual(node_depth(d["node"], PUSH * (f + 1) / INCREMENTS), depth, delta=1e-5)
                self.assertIn(d["node"], element_nodes(d["element"]), d)
        (pair,) = r["pairs"]
        self.assertEqual(pair["first_frame"], 0)
        self.assertEqual(pair["first_clash_frame"], FIRST)
        self.assertEqual(pair["reference_verdict"], "clearance")
        with open(csv_path) as f:
            lines = f.read().splitlines()
        self.assertTrue(lines[0].startswith("frame,label,time,test,body_a,body_b,verdict,"))
        self.assertEqual(len(lines), INCREMENTS + 1)
        self.assertEqual(lines[FIRST + 1].split(",")[6], "clash")

    def test_two_part_series(self):
        frd = run_ccx("twopart", False)
        code, out, err = run("clash", frd, frd, "--part-a", "body 1", "--part-b", "body 2", "--field", "DISP")
        self.assertEqual(code, 1, out + err)
        self.assertIn("first clash at step %d (time 0.5) of %d" % (FIRST, INCREMENTS), out + err)

    def test_truncated_frd_is_bad_input(self):
        frd = run_ccx("trunc", False)
        with open(frd) as f:
            text = f.read()
        cut = text.find(" -1", text.find("100CL  103"))  # inside the third DISP block
        bad = write_text("trunc_cut.frd", text[:cut + 20])
        code, out, err = run("clash", bad)
        self.assertEqual(code, 2, out + err)
        self.assertIn("trunc_cut.frd", err)
        self.assertIn("DISP result block 3 (step 1, increment 3)", err)
        self.assertIn("trunc_cut.frd:%d:" % (text[:cut].count("\n") + 1), err)  # file:line


if __name__ == "__main__":
    main()
