#!/usr/bin/env python3
"""Generated scenes for the interfere-mpi tests (issue #31, item 5): binary STL bodies and scene
files, deterministic (seeded).

  tiny/    many tiny bodies (UV spheres and boxes, ~100-300 triangles) in clusters, some
           overlapping, some touching, some within the clearance; a hard and a clearance test;
           tiny/motion.csv moves a few bodies over 6 frames (the time series).
  huge/    one huge body pair (two overlapping 40,000-triangle spheres) that dominates the cost,
           and a handful of tiny bodies around it.
  broken/  a scene whose last body file is not a mesh (a rank cannot read it).
Usage: make_scenes.py OUT_DIR
"""
import math
import os
import random
import struct
import sys


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
    broken(os.path.join(out, "broken"))
