#!/usr/bin/env python3
"""Generates the example inspection cell of examples/probe (issue #28, deliverable 6).

Everything here is made by this script (numpy only; run with /usr/bin/python3 make_cell.py in this
directory); nothing is copied from elsewhere except paper_machine.json (data/examples/
probe_paper_machine.json, the paper's §3.1 machine as a DH file).

  arm6r.urdf          a UR5-type 6R arm: the UR5's published kinematic lengths (d1 0.089159, a2 0.425,
                      a3 0.39225, d4 0.10915, d5 0.09465, d6 0.0823 m) in URDF form; link shapes are
                      simple cylinders (not Universal Robots' meshes), metres, in meshes/*.obj
  workpiece.obj       a 600 x 400 x 20 mm plate (top face z = 0) with a 40 mm rib across it (mm)
  clamp.obj           a clamp block beside the scan line (mm)
  path.csv            a joint path (degrees) found by damped least squares so that the probe tip runs
                      along y = 0, 10 mm above the plate, pointing down, x = 350 ... 700 mm
  paper_path.csv      the same line as a pose path for `interfere sweep` (the probe alone)
  industrial_6r.urdf  an industrial 6R arm in the ROS-Industrial layout (joint 1 about z, 2-3 about y,
                      4 about x, 5 about y, 6 about x; lengths of a small 6-axis arm: 0.29, 0.27, 0.07,
                      0.302, 0.072 m), cylinder link shapes in meshes/ind_*.obj, tool flange tool0
                      (z along link_6's x); used by cell_industrial.json (forward kinematics test)
The joint path is checked here with this script's own forward kinematics (tip within 1e-6 mm).
"""
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

# ---- the arm: (name, parent, child, origin xyz (m), origin rpy, axis) ----
PI2 = math.pi / 2
JOINTS = [
    ("shoulder_pan", "base_link", "shoulder_link", (0, 0, 0.089159), (0, 0, 0), (0, 0, 1)),
    ("shoulder_lift", "shoulder_link", "upper_arm_link", (0, 0.13585, 0), (0, PI2, 0), (0, 1, 0)),
    ("elbow", "upper_arm_link", "forearm_link", (0, -0.1197, 0.425), (0, 0, 0), (0, 1, 0)),
    ("wrist_1", "forearm_link", "wrist_1_link", (0, 0, 0.39225), (0, PI2, 0), (0, 1, 0)),
    ("wrist_2", "wrist_1_link", "wrist_2_link", (0, 0.093, 0), (0, 0, 0), (0, 0, 1)),
    ("wrist_3", "wrist_2_link", "wrist_3_link", (0, 0, 0.09465), (0, 0, 0), (0, 1, 0)),
    ("flange", "wrist_3_link", "tool0", (0, 0.0823, 0), (-PI2, 0, 0), None),
]
# link shape: cylinder (axis 'x'|'y'|'z', from, to, radius), metres, in the link frame
SHAPES = {
    "base_link": ("z", 0.0, 0.08, 0.075),
    "shoulder_link": ("y", -0.03, 0.10, 0.06),
    "upper_arm_link": ("z", 0.06, 0.40, 0.05),
    "forearm_link": ("z", 0.05, 0.37, 0.04),
    "wrist_1_link": ("y", 0.0, 0.07, 0.035),
    "wrist_2_link": ("z", 0.0, 0.07, 0.035),
    "wrist_3_link": ("y", 0.0, 0.07, 0.035),
}
LIMIT = 2 * math.pi


def cylinder_obj(axis, a, b, r, sides=16):
    k = "xyz".index(axis)
    u, v = [i for i in range(3) if i != k]
    verts = []
    for h in (a, b):
        for s in range(sides):
            p = [0.0, 0.0, 0.0]
            p[k] = h
            p[u] = r * math.cos(2 * math.pi * s / sides)
            p[v] = r * math.sin(2 * math.pi * s / sides)
            verts.append(p)
    c0 = [0.0] * 3
    c0[k] = a
    c1 = [0.0] * 3
    c1[k] = b
    verts += [c0, c1]
    faces = []
    n = sides
    flip = (k == 1)  # keep the triangles outward for the y axis (u = x, v = z is left-handed)
    for s in range(n):
        t = (s + 1) % n
        quads = [(s, t, n + t), (s, n + t, n + s), (2 * n, t, s), (2 * n + 1, n + s, n + t)]
        for f in quads:
            faces.append((f[0], f[2], f[1]) if flip else f)
    return verts, faces


def box(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6),
             (3, 0, 4), (3, 4, 7)]
    return verts, faces


def extrusion():
    """The plate-with-rib profile (counter-clockwise in x-z) extruded from y = -200 to 200, caps as
    three convex pieces fanned from their centres; outward triangles (checked by the volume)."""
    prof = [(250, -20), (480, -20), (520, -20), (850, -20), (850, 0), (520, 0), (520, 40), (480, 40), (480, 0), (250, 0)]
    pieces = [[0, 1, 8, 9], [1, 2, 5, 6, 7, 8], [2, 3, 4, 5]]
    n = len(prof)
    verts = [(x, -200, z) for x, z in prof] + [(x, 200, z) for x, z in prof]
    faces = []
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, j, n + j), (i, n + j, n + i)]
    for piece in pieces:
        cx = sum(prof[k][0] for k in piece) / len(piece)
        cz = sum(prof[k][1] for k in piece) / len(piece)
        c0 = len(verts)
        verts += [(cx, -200, cz), (cx, 200, cz)]
        for a, b in zip(piece, piece[1:] + piece[:1]):
            faces += [(c0, b, a), (c0 + 1, n + a, n + b)]
    vol = 0.0
    for a, b, c in faces:
        vol += np.dot(np.array(verts[a]), np.cross(np.array(verts[b]), np.array(verts[c])))
    if vol < 0:
        faces = [(a, c, b) for a, b, c in faces]
    return verts, faces


def write_obj(path, verts, faces, comment):
    with open(path, "w") as f:
        f.write("# %s\n# generated by examples/probe/make_cell.py (issue #28)\n" % comment)
        for p in verts:
            f.write("v %.9g %.9g %.9g\n" % tuple(p))
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def rpy(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    ry = np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    return rz @ ry @ rx


def axis_angle(u, a):
    u = np.asarray(u, float)
    k = np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k


def fk(q_deg):
    """World <- tool0 (mm) of the arm at joint values q (degrees)."""
    T = np.eye(4)
    i = 0
    for name, _, _, xyz, r, axis in JOINTS:
        O = np.eye(4)
        O[:3, :3] = rpy(*r)
        O[:3, 3] = np.array(xyz) * 1000
        T = T @ O
        if axis is not None:
            M = np.eye(4)
            M[:3, :3] = axis_angle(axis, math.radians(q_deg[i]))
            T = T @ M
            i += 1
    return T


TIP = np.array([0, 0, 130.0])  # probe tip in tool0 (mm), probe along +z of tool0


def tool_error(q, target, down):
    T = fk(q)
    tip = T[:3, :3] @ TIP + T[:3, 3]
    z = T[:3, 2]
    x = T[:3, 0]
    return np.concatenate([tip - target, 100 * (z - down), 100 * (x - np.array([0, 1, 0]))])


def solve(q, target, down):
    q = np.array(q, float)
    for _ in range(200):
        e = tool_error(q, target, down)
        if np.linalg.norm(e) < 1e-9:
            break
        J = np.zeros((len(e), 6))
        for j in range(6):
            dq = np.zeros(6)
            dq[j] = 1e-6
            J[:, j] = (tool_error(q + dq, target, down) - e) / 1e-6
        q = q - np.linalg.solve(J.T @ J + 1e-8 * np.eye(6), J.T @ e)
    return q, np.linalg.norm(tool_error(q, target, down)[:3])


# the industrial arm: (name, parent, child, xyz, rpy, axis)
IND_JOINTS = [
    ("joint_1", "base_link", "link_1", (0, 0, 0), (0, 0, 0), (0, 0, 1)),
    ("joint_2", "link_1", "link_2", (0, 0, 0.29), (0, 0, 0), (0, 1, 0)),
    ("joint_3", "link_2", "link_3", (0, 0, 0.27), (0, 0, 0), (0, 1, 0)),
    ("joint_4", "link_3", "link_4", (0, 0, 0.07), (0, 0, 0), (1, 0, 0)),
    ("joint_5", "link_4", "link_5", (0.302, 0, 0), (0, 0, 0), (0, 1, 0)),
    ("joint_6", "link_5", "link_6", (0.072, 0, 0), (0, 0, 0), (1, 0, 0)),
    ("joint_6-tool0", "link_6", "tool0", (0, 0, 0), (0, PI2, 0), None),
]
IND_SHAPES = {
    "base_link": ("z", 0.0, 0.10, 0.09),
    "link_1": ("z", 0.12, 0.25, 0.06),
    "link_2": ("z", 0.04, 0.23, 0.045),
    "link_3": ("x", -0.04, 0.06, 0.045),
    "link_4": ("x", 0.08, 0.26, 0.035),
    "link_5": ("x", -0.02, 0.05, 0.03),
    "link_6": ("x", 0.0, 0.012, 0.03),
}
IND_LIMITS = {"joint_1": 2.87979, "joint_2": 1.91986, "joint_3": 1.22173, "joint_4": 2.79253, "joint_5": 2.094395,
              "joint_6": 6.98132}


def write_urdf(file, robot, comment, joints, shapes, prefix, limits):
    urdf = ['<?xml version="1.0"?>', "<!-- %s -->" % comment, '<robot name="%s">' % robot]
    links = [joints[0][1]] + [j[2] for j in joints]
    for link in links:
        if link in shapes:
            v, f = cylinder_obj(*shapes[link])
            write_obj(os.path.join(HERE, "meshes", prefix + link + ".obj"), v, f, link + " collision cylinder, metres")
            urdf.append('  <link name="%s"><collision><geometry><mesh filename="meshes/%s%s.obj"/></geometry></collision></link>'
                        % (link, prefix, link))
        else:
            urdf.append('  <link name="%s"/>' % link)
    names = []
    for name, parent, child, xyz, r, axis in joints:
        kind = "fixed" if axis is None else "revolute"
        s = '  <joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>' % (name, kind, parent, child)
        s += '<origin xyz="%.9g %.9g %.9g" rpy="%.17g %.17g %.17g"/>' % (xyz + r)
        if axis is not None:
            lim = limits(name)
            s += '<axis xyz="%g %g %g"/><limit lower="%.9f" upper="%.9f" effort="150" velocity="3.15"/>' % (
                axis + (-lim, lim))
            names.append(name)
        urdf.append(s + "</joint>")
    urdf.append("</robot>")
    with open(os.path.join(HERE, file), "w") as f:
        f.write("\n".join(urdf) + "\n")
    return names


def main():
    names = []
    urdf = ['<?xml version="1.0"?>', "<!-- UR5-type 6R arm for examples/probe (issue #28): the UR5's kinematic lengths,",
            "     cylinder link shapes generated by make_cell.py (metres). -->", '<robot name="ur5_type">']
    for link in ["base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link",
                 "wrist_3_link", "tool0"]:
        if link in SHAPES:
            v, f = cylinder_obj(*SHAPES[link])
            write_obj(os.path.join(HERE, "meshes", link + ".obj"), v, f, link + " collision cylinder, metres")
            urdf.append('  <link name="%s"><collision><geometry><mesh filename="meshes/%s.obj"/></geometry></collision></link>'
                        % (link, link))
        else:
            urdf.append('  <link name="%s"/>' % link)
    for name, parent, child, xyz, r, axis in JOINTS:
        kind = "fixed" if axis is None else "revolute"
        s = '  <joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>' % (name, kind, parent, child)
        s += '<origin xyz="%.9g %.9g %.9g" rpy="%.17g %.17g %.17g"/>' % (xyz + r)
        if axis is not None:
            s += '<axis xyz="%g %g %g"/><limit lower="%.9f" upper="%.9f" effort="150" velocity="3.15"/>' % (
                axis + (-LIMIT, LIMIT))
            names.append(name)
        urdf.append(s + "</joint>")
    urdf.append("</robot>")
    with open(os.path.join(HERE, "arm6r.urdf"), "w") as f:
        f.write("\n".join(urdf) + "\n")
    write_urdf("industrial_6r.urdf", "industrial_6r",
               "industrial 6R arm for examples/probe (issue #28), ROS-Industrial joint layout, cylinder link shapes "
               "generated by make_cell.py (metres)", IND_JOINTS, IND_SHAPES, "ind_", lambda n: IND_LIMITS[n])

    # workpiece: plate x 250..850, y -200..200, z -20..0 with a rib x 480..520 up to z 40: one closed
    # solid, the profile in the x-z plane extruded along y
    verts, faces = extrusion()
    write_obj(os.path.join(HERE, "workpiece.obj"), verts, faces,
              "plate 600 x 400 x 20 mm (top z = 0) with a 40 mm rib at x 480..520, one closed solid, mm")
    v, f = box((640, 15, 0), (700, 75, 150))
    write_obj(os.path.join(HERE, "clamp.obj"), v, f, "clamp block x 640..700, y 15..75, z 0..150, mm")

    # path: tip at (x, 0, 10), pointing down
    q = np.radians([0, -90, 90, -90, -90, 0]) * 180 / math.pi
    rows = []
    down = np.array([0, 0, -1.0])
    for x in range(350, 701, 25):
        q, err = solve(q, np.array([x, 0, 10.0]), down)
        assert err < 1e-6, (x, err)
        assert all(abs(a) < 360 for a in q)
        rows.append(q.copy())
    with open(os.path.join(HERE, "path.csv"), "w") as f:
        f.write("# joint path (degrees) of arm6r.urdf, generated by make_cell.py: the probe tip (130 mm along\n")
        f.write("# tool0's z) runs along y = 0, z = 10 mm, x = 350, 375, ..., 700 mm, pointing down\n")
        f.write(",".join(names) + "\n")
        for r in rows:
            f.write(",".join("%.6f" % a for a in r) + "\n")
    # check the rounded values
    for x, r in zip(range(350, 701, 25), rows):
        T = fk([float("%.6f" % a) for a in r])
        tip = T[:3, :3] @ TIP + T[:3, 3]
        assert np.linalg.norm(tip - [x, 0, 10]) < 1e-2, tip
    with open(os.path.join(HERE, "paper_path.csv"), "w") as f:
        f.write("# pose path for `interfere sweep` (the probe alone): the line of path.csv, tip 10 mm above the plate\n")
        f.write("px,py,pz,ax,ay,az\n")
        for x in range(350, 701, 25):
            f.write("%d,0,10,0,0,-1\n" % x)
    print("wrote arm6r.urdf, meshes/, workpiece.obj, clamp.obj, path.csv (%d points), paper_path.csv" % len(rows))


if __name__ == "__main__":
    main()
