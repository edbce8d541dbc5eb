#!/usr/bin/env python3
"""Generated scenes for the interfere-mpi tests (issue #31, item 5): binary STL bodies and scene
files, deterministic (seeded).

  tiny/    many tiny bodies (UV spheres and boxes, ~100-300 triangles) in clusters, some
           overlapping, some touching, some within the clearance; a hard and a clearance test;
           tiny/motion.csv moves a few bodies over 6 frames (the time series).
  huge/    one huge body pair (two overlapping 40,000-triangle spheres) that dominates the cost,
           and a handful of tiny bodies around it.
  fe/      an FE model (CalculiX .frd, 5 bodies of 2 x 2 x 2 HEX8, 4 displacement steps: a designed
           contact, a body pushed into another, a body moving away) beside 3 STL boxes (two that
           overlap each other, no body of theirs deformed; one touching an FE body).
  repeats/ 12 joints of one plate file and one pin file (every joint its own two entries), in two
           relative poses: one process decides 2 configurations (core_runs 2), and so must K ranks.
  broken/  a scene whose last body file is not a mesh (a rank cannot read it).
Usage: make_scenes.py OUT_DIR
"""
import math
import os
import random
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from hex_blocks import hex_box  # noqa: E402  (tests/cli/hex_blocks.py)


def sphere(c, r, nu, nv):
    """Closed UV sphere, outward triangles."""
    verts = [(c[0], c[1], c[2] + r)]
    for i in range(1, nv):
        th = math.pi * i / nv
        for j in range(nu):
            ph = 2 * math.pi * j / nu
            verts.append((c[0] + r * math.sin(th) * math.cos(ph), c[1] + r * math.sin(th) * math.sin(ph), c[2] + r * math.cos(th)))
    verts.append((c[0], c[1], c[2] - r))
    tris = []
    bottom = len(verts) - 1
    ring = lambda i, j: 1 + (i - 1) * nu + (j % nu)
    for j in range(nu):
        tris.append((0, ring(1, j), ring(1, j + 1)))
    for i in range(1, nv - 1):
        for j in range(nu):
            a, b, cc, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            tris.append((a, cc, d))
            tris.append((a, d, b))
    for j in range(nu):
        tris.append((bottom, ring(nv - 1, j + 1), ring(nv - 1, j)))
    return [(verts[a], verts[b], verts[cc]) for a, b, cc in tris]


def box(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
    return [(v[a], v[b], v[c]) for a, b, c in f]


def write_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"interfere mpi test".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def scene(path, bodies, tests, motion=None):
    import json
    s = {"units": "mm", "bodies": bodies, "tests": tests}
    if motion:
        s["motion"] = motion
    with open(path, "w") as f:
        json.dump(s, f, indent=1)


def tiny(out):
    os.makedirs(out, exist_ok=True)
    rnd = random.Random(31)
    bodies = []
    n = 0
    for cl in range(12):  # clusters 10 mm apart, 6 bodies each, 1.5 mm cells: some overlap, some near
        cx, cy = 10.0 * (cl % 4), 10.0 * (cl // 4)
        for k in range(6):
            c = (cx + rnd.uniform(0, 3), cy + rnd.uniform(0, 3), rnd.uniform(0, 2))
            name = "t%03d" % n
            if k % 2:
                tris = sphere(c, rnd.uniform(0.5, 1.0), 12, 8)
            else:
                h = rnd.uniform(0.3, 0.8)
                tris = box((c[0] - h, c[1] - h, c[2] - h), (c[0] + h, c[1] + h, c[2] + h))
            write_stl(os.path.join(out, name + ".stl"), tris)
            bodies.append({"file": name + ".stl", "id": name, "tags": ["sphere" if k % 2 else "box"]})
            n += 1
    # two touching boxes (a contact) and a far body alone
    write_stl(os.path.join(out, "touch_a.stl"), box((100, 0, 0), (101, 1, 1)))
    write_stl(os.path.join(out, "touch_b.stl"), box((101, 0, 0), (102, 1, 1)))
    write_stl(os.path.join(out, "alone.stl"), box((200, 200, 200), (201, 201, 201)))
    for name in ("touch_a", "touch_b", "alone"):
        bodies.append({"file": name + ".stl", "id": name, "tags": ["box"]})
    tests = [{"name": "hard", "a": ["all"], "mode": "hard"},
             {"name": "gap", "a": ["tag:sphere"], "b": ["tag:box"], "mode": "clearance", "clearance": 0.5}]
    scene(os.path.join(out, "scene.json"), bodies, tests)
    # the time series: 6 frames, bodies t001, t007 and touch_a moving
    with open(os.path.join(out, "motion.csv"), "w") as f:
        f.write("frame,time,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz\n")
        for fr in range(6):
            for b, (dx, dy) in (("t001", (0.4, 0.0)), ("t007", (0.0, 0.5)), ("touch_a", (-0.3, 0.0))):
                f.write("%d,%g,%s,1,0,0,%g,0,1,0,%g,0,0,1,0\n" % (fr, 0.1 * fr, b, dx * fr, dy * fr))


def huge(out):
    os.makedirs(out, exist_ok=True)
    bodies = []
    write_stl(os.path.join(out, "big_a.stl"), sphere((0, 0, 0), 10.0, 200, 101))
    write_stl(os.path.join(out, "big_b.stl"), sphere((12.0, 1.0, 0.5), 8.0, 200, 101))
    bodies += [{"file": "big_a.stl", "id": "big_a"}, {"file": "big_b.stl", "id": "big_b"}]
    rnd = random.Random(7)
    for k in range(8):
        name = "small%d" % k
        c = (rnd.uniform(-15, 25), rnd.uniform(-12, 12), rnd.uniform(-12, 12))
        write_stl(os.path.join(out, name + ".stl"), sphere(c, 1.5, 10, 6))
        bodies.append({"file": name + ".stl", "id": name})
    scene(os.path.join(out, "scene.json"), bodies, [{"name": "hard", "a": ["all"], "mode": "hard"}])


def fe(out, steps=4):
    """CalculiX .frd, ASCII long format (tests/cli/test_fem_inputs.py write_frd): 1UMAT names, node
    block 2C, element block 3C (he8, material g), one DISP block per step."""
    os.makedirs(out, exist_ok=True)
    boxes = [((0, 1), (0, 1), (0, 1)),          # B1 fixed
             ((1, 2), (0, 1), (0, 1)),          # B2 touches B1 (designed contact), moves +x: apart
             ((0, 1), (3, 4), (0, 1)),          # B3 moves +x into B4
             ((1.2, 2.2), (3.2, 3.8), (0.2, 0.8)),  # B4 fixed
             ((0, 1), (6, 7), (0, 1))]          # B5 fixed, near the STL box
    vel = [(0, 0, 0), (0.1, 0, 0), (0.15, 0, 0), (0, 0, 0), (0, 0, 0)]
    bodies = [hex_box(b, 2, 1 + 1000 * g, 1 + 100 * g) for g, b in enumerate(boxes)]
    nodes = [nd for ns, _ in bodies for nd in ns]
    body_of = {nid: g for g, (ns, _) in enumerate(bodies) for nid, _ in ns}
    L = ["    1C"] + ["    1UMAT%5dB%d" % (g + 1, g + 1) for g in range(len(boxes))]
    L.append("    2C" + " " * 18 + "%12d" % len(nodes) + " " * 37 + "1")
    L += [" -1%10d%12.5E%12.5E%12.5E" % (nid, *x) for nid, x in nodes]
    L.append(" -3")
    nel = sum(len(e) for _, e in bodies)
    L.append("    3C" + " " * 18 + "%12d" % nel + " " * 37 + "1")
    for g, (_, elems) in enumerate(bodies):
        for eid, v in elems:
            L.append(" -1%10d%5d%5d%5d" % (eid, 1, 0, g + 1))
            L.append(" -2" + "".join("%10d" % nn for nn in v))
    L.append(" -3")
    for st in range(steps):
        L.append("    1PSTEP" + " " * 14 + "%12d%12d%12d" % (st + 1, st + 1, 1))
        L.append("  100CL%5d%12.5E%12d%20s%2d%5d%10s%2s" % (101 + st, float(st), len(nodes), "", 0, st + 1, "", " 1"))
        L += [" -4  DISP        4    1", " -5  D1          1    2    1    0", " -5  D2          1    2    2    0",
              " -5  D3          1    2    3    0", " -5  ALL         1    2    0    0    1ALL"]
        L += [" -1%10d%12.5E%12.5E%12.5E" % (nid, *(v * st for v in vel[body_of[nid]])) for nid, _ in nodes]
        L.append(" -3")
    L.append("9999")
    with open(os.path.join(out, "model.frd"), "w") as f:
        f.write("\n".join(L) + "\n")
    write_stl(os.path.join(out, "m1.stl"), box((5, 0, 0), (6, 1, 1)))
    write_stl(os.path.join(out, "m2.stl"), box((5.5, 0.5, 0.5), (6.5, 1.5, 1.5)))
    write_stl(os.path.join(out, "m3.stl"), box((1, 6, 0), (2, 7, 1)))
    scene(os.path.join(out, "scene.json"),
          [{"file": "model.frd", "id": "fe"}, {"file": "m1.stl", "id": "m1"}, {"file": "m2.stl", "id": "m2"},
           {"file": "m3.stl", "id": "m3"}],
          [{"name": "hard", "a": ["all"], "mode": "hard"}])


def repeats(out):
    os.makedirs(out, exist_ok=True)
    write_stl(os.path.join(out, "plate.stl"), box((0, 0, 0), (2, 2, 0.5)))
    write_stl(os.path.join(out, "pin.stl"), sphere((1, 1, 0.25), 0.5, 12, 7))
    bodies = []
    for i in range(12):
        x = 4.0 * i  # (binary-exact offsets: the relative poses are equal bit for bit)
        dx = 0.25 if i % 2 else 0.0
        bodies.append({"file": "plate.stl", "id": "plate%02d" % i, "transform": [1, 0, 0, x, 0, 1, 0, 0, 0, 0, 1, 0]})
        bodies.append({"file": "pin.stl", "id": "pin%02d" % i, "transform": [1, 0, 0, x + dx, 0, 1, 0, 0, 0, 0, 1, 0]})
    scene(os.path.join(out, "scene.json"), bodies, [{"name": "hard", "a": ["all"], "mode": "hard"}])


def broken(out):
    os.makedirs(out, exist_ok=True)
    write_stl(os.path.join(out, "ok1.stl"), box((0, 0, 0), (1, 1, 1)))
    write_stl(os.path.join(out, "ok2.stl"), box((0.5, 0, 0), (1.5, 1, 1)))
    with open(os.path.join(out, "bad.stl"), "w") as f:
        f.write("solid bad\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 nonsense\n")
    scene(os.path.join(out, "scene.json"),
          [{"file": "ok1.stl", "id": "ok1"}, {"file": "ok2.stl", "id": "ok2"}, {"file": "bad.stl", "id": "bad"}], [])


if __name__ == "__main__":
    out = sys.argv[1]
    tiny(os.path.join(out, "tiny"))
    huge(os.path.join(out, "huge"))
    fe(os.path.join(out, "fe"))
    repeats(os.path.join(out, "repeats"))
    broken(os.path.join(out, "broken"))
