#!/usr/bin/env python3
"""Regenerates the bundled example parts in data/examples/ (public domain, CC0).

plate.stl  - binary STL, a 100 x 60 x 10 mm plate with its top face subdivided (closed, outward)
pin.obj    - OBJ, a closed cylinder r = 6 mm, h = 40 mm, 48 sides, axis z, centred at the origin
scene.json - the pin posed through the plate, slightly tilted, so the parts clash along two curves
"""
import math
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "examples")


def box(lo, hi, n):
    pos, tris, index = [], [], {}

    def vid(p):
        if p not in index:
            index[p] = len(pos)
            pos.append(p)
        return index[p]

    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, 1):
            def pt(i, j):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = lo[u] + (hi[u] - lo[u]) * i / n
                p[v] = lo[v] + (hi[v] - lo[v]) * j / n
                return tuple(p)
            for i in range(n):
                for j in range(n):
                    a, b, c, d = vid(pt(i, j)), vid(pt(i + 1, j)), vid(pt(i + 1, j + 1)), vid(pt(i, j + 1))
                    if side:
                        tris += [(a, b, c), (a, c, d)]
                    else:
                        tris += [(a, c, b), (a, d, c)]
    return pos, tris


def cylinder(r, h, sides):
    pos = [(0.0, 0.0, -h / 2), (0.0, 0.0, h / 2)]
    for k in range(sides):
        t = 2 * math.pi * k / sides
        pos.append((r * math.cos(t), r * math.sin(t), -h / 2))
        pos.append((r * math.cos(t), r * math.sin(t), h / 2))
    tris = []
    for k in range(sides):
        b0, t0 = 2 + 2 * k, 3 + 2 * k
        b1, t1 = 2 + 2 * ((k + 1) % sides), 3 + 2 * ((k + 1) % sides)
        tris += [(b0, b1, t1), (b0, t1, t0), (0, b1, b0), (1, t0, t1)]
    return pos, tris


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return [x / length for x in n]


def write_stl(path, pos, tris):
    with open(path, "wb") as f:
        f.write(b"interfere example plate (CC0)".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            a, b, c = (pos[i] for i in t)
            f.write(struct.pack("<12fH", *normal(a, b, c), *a, *b, *c, 0))


def write_obj(path, pos, tris):
    with open(path, "w") as f:
        f.write("# interfere example pin (CC0)\n")
        for p in pos:
            f.write("v %.17g %.17g %.17g\n" % p)
        for t in tris:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


if __name__ == "__main__":
    os.makedirs(HERE, exist_ok=True)
    write_stl(os.path.join(HERE, "plate.stl"), *box((0.0, 0.0, 0.0), (100.0, 60.0, 10.0), 12))
    write_obj(os.path.join(HERE, "pin.obj"), *cylinder(6.0, 40.0, 48))
    tilt = math.radians(5.0)
    c, s = math.cos(tilt), math.sin(tilt)
    scene = ('{\n  "units": "mm",\n  "a": {"file": "plate.stl"},\n'
             '  "b": {"file": "pin.obj",\n        "transform": [1, 0, 0, 30,  0, %.17g, %.17g, 30,  0, %.17g, %.17g, 5]}\n}\n'
             % (c, -s, s, c))
    with open(os.path.join(HERE, "scene.json"), "w") as f:
        f.write(scene)
