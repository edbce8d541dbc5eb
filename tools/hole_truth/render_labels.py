#!/usr/bin/python3
"""Renders a part with its truth labels highlighted, to check the labels by eye (issue #29, item 2:
the truth set's holes "labelled ... from the B-Rep ..., checked by rendering").

The mesh comes from tools/hole_truth/tessellate_faces.cpp (OCCT, the labellers' solid and face numbering),
the image from a small orthographic z-buffer rasterizer in numpy (no X server, no GPU: this machine's VTK and
ParaView need one), composed with matplotlib: one sheet per part, 2 x 2 views from the corners
(+x+y+z, -x-y+z, +x-y-z, -x+y-z; every face direction seen twice), flat shading, face boundaries drawn.

Holes (--holes, tests/data/hole_truth/*.json): a face belongs to a labelled hole when its surface is one of
the hole's elements: a cylinder or cone coaxial with the hole (axis parallel, on the axis line), of the
element's radius (at the element's ends for a cone), its axial extent within the element's. Those faces are
coloured by the hole's type and the hole's index ("solid.index" for multi-solid files) is written at its
visible open end (nothing when that end is hidden). Cylinder and cone faces in no label are yellow when
concave (the wall seen from the inside: unlabelled hole walls, but also fillets, corner rounds and slot
ends) and light blue-grey when convex (bosses, shafts, outer rounds): so a hole left grey-yellow is a
missed label, a coloured face that is not a hole a false one.
Floors (--floors, tests/data/floor_truth/*.json): the features' floors in the type's colour, their other
faces (walls, fillets) in a lighter shade, the index at the first floor point.

Also prints (and with --summary writes as JSON) per label the faces matched, and the unlabelled concave
cylinder/cone surfaces with the angle their faces cover around the axis (a full 360 is hole-like).

Looking inside and at details: --solids (an assembly's parts one set at a time: the bolts fill the holes),
--zoom X,Y,Z,R (the views show that sphere), --cut (with --zoom: a cutaway, nothing nearer the eye than X,Y,Z),
--highlight S:F,... (faces in bright green), --views 0,2 (some of the four views). B-spline faces are purple
(the labellers skip them: a B-spline hole wall would show purple, not coloured).

usage: render_labels.py MESH.txt OUT.png [--holes H.json] [--floors F.json] [--title T] [--size PX]
                        [--summary S.json] [--solids ...] [--zoom ...] [--cut] [--highlight ...] [--views ...]
   or: render_labels.py --step FILE.stp --tessellator BIN OUT.png ...   (tessellates into a temp file; BIN is
       build/tests/interfere_tessellate_faces)
The ctest render_labels_generated (tests/cad/check_render_labels.py) runs it on a generated part.
Exit status 0, 1 on unreadable input (named), 2 on usage.
"""
import argparse, json, math, os, subprocess, sys, tempfile

import numpy as np

HOLE_COLOURS = {
    "through_hole": (0.85, 0.10, 0.10),
    "blind_hole": (0.10, 0.30, 0.95),
    "counterbored_hole": (1.00, 0.55, 0.00),
    "countersunk_hole": (0.80, 0.10, 0.80),
    "counterdrilled_hole": (0.00, 0.75, 0.80),
    "stepped_hole": (0.10, 0.70, 0.10),
}
FLOOR_COLOURS = {
    "pocket": (0.10, 0.65, 0.15),
    "slot": (0.85, 0.10, 0.10),
    "blind_slot": (0.10, 0.30, 0.95),
    "through_step": (0.85, 0.45, 0.00),
    "step": (0.85, 0.45, 0.00),
}
BASE = (0.72, 0.72, 0.72)
CONCAVE = (0.95, 0.90, 0.35)
CONVEX = (0.62, 0.70, 0.80)
BSPLINE = (0.80, 0.62, 0.85)
VIEWS = [(1, 1, 1), (-1, -1, 1), (1, -1, -1), (-1, 1, -1)]


def read_mesh(path):
    faces = {}  # (solid, face) -> dict(type, params)
    tris, keys = [], []
    nsolids = 0
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "s":
                nsolids = max(nsolids, int(w[1]) + 1)
            elif w[0] == "f":
                faces[(int(w[1]), int(w[2]))] = {"type": w[3], "params": [float(x) for x in w[4:]]}
            elif w[0] == "t":
                keys.append((int(w[1]), int(w[2])))
                tris.append([float(x) for x in w[3:12]])
    if not tris:
        raise ValueError("%s: no triangles" % path)
    return nsolids, faces, np.array(tris).reshape(-1, 3, 3), np.array(keys, dtype=np.int64)


def face_geometry(faces, tris, keys):
    """Per face: triangle indices, and for cylinders/cones the axis frame and concavity."""
    order = np.lexsort((keys[:, 1], keys[:, 0]))
    out = {}
    ks = keys[order]
    bounds = np.flatnonzero(np.any(np.diff(ks, axis=0) != 0, axis=1)) + 1
    for grp in np.split(order, bounds):
        k = tuple(keys[grp[0]])
        info = dict(faces.get(k, {"type": "other", "params": []}))
        info["tris"] = grp
        if info["type"] in ("cylinder", "cone"):
            p = np.array(info["params"][0:3])
            a = np.array(info["params"][3:6])
            a = a / np.linalg.norm(a)
            pts = tris[grp].reshape(-1, 3)
            h = (pts - p) @ a
            radial = pts - p - np.outer(h, a)
            info["h"] = (h.min(), h.max())
            # concave: the outward normals point to the axis (a hole's wall)
            n = np.cross(tris[grp, 1] - tris[grp, 0], tris[grp, 2] - tris[grp, 0])
            c = tris[grp].mean(axis=1)
            rc = c - p - np.outer((c - p) @ a, a)
            info["concave"] = float(np.sum(np.einsum("ij,ij->i", n, rc))) < 0
            # angle covered around the axis (5-degree bins)
            e1 = np.cross(a, [1.0, 0, 0] if abs(a[0]) < 0.9 else [0, 1.0, 0])
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(a, e1)
            ang = np.arctan2(radial @ e2, radial @ e1).reshape(-1, 3)
            bins = set()
            for j in range(3):  # each triangle edge covers the short arc between its ends' angles
                a0, a1 = ang[:, j], ang[:, (j + 1) % 3]
                da = np.remainder(a1 - a0 + math.pi, 2 * math.pi) - math.pi
                for f in np.linspace(0, 1, 9):
                    bins |= set((((a0 + f * da) + math.pi) / (2 * math.pi) * 72).astype(int) % 72)
            info["bins"] = bins
            info["p"], info["a"] = p, a
        out[k] = info
    return out


def radius_at(info, q):
    """Radius of a face's cylinder/cone at the axis point nearest q (q on its axis)."""
    r = info["params"][6]
    if info["type"] == "cylinder":
        return r
    return r + ((q - info["p"]) @ info["a"]) * math.tan(info["params"][7])


def match_holes(holes, geo, tol):
    """For each labelled hole (solid, index, hole) the faces that are its elements."""
    matched = []
    for s, idx, hole in holes:
        p = np.array(hole["axis_point"], float)
        a = np.array(hole["axis"], float)
        a /= np.linalg.norm(a)
        fs = []
        for k, info in geo.items():
            if k[0] != s or info["type"] not in ("cylinder", "cone") or "a" not in info:
                continue
            if np.linalg.norm(np.cross(info["a"], a)) > 1e-6:
                continue
            d = info["p"] - p
            if np.linalg.norm(d - (d @ a) * a) > tol:
                continue
            # the face's axial extent in the hole's frame
            sign = 1.0 if info["a"] @ a > 0 else -1.0
            base = (info["p"] - p) @ a
            h0, h1 = sorted((base + sign * info["h"][0], base + sign * info["h"][1]))
            for e in hole["elements"]:
                if e["kind"] != info["type"]:
                    continue
                if h0 < e["h0"] - tol or h1 > e["h1"] + tol:
                    continue
                ok = all(abs(radius_at(info, p + a * hh) - rr) <= tol for hh, rr in ((e["h0"], e["r0"]), (e["h1"], e["r1"])))
                if ok:
                    fs.append(k)
                    break
        matched.append(fs)
    return matched


def unlabelled_surfaces(geo, labelled, tol):
    """Concave cylinder/cone faces in no label, grouped by surface: radius, axis, angle covered."""
    groups = []
    for k, info in sorted(geo.items()):
        if k in labelled or "a" not in info or not info["concave"]:
            continue
        for g in groups:
            o = geo[g["faces"][0]]
            d = info["p"] - o["p"]
            if (g["solid"] == k[0] and o["type"] == info["type"] and np.linalg.norm(np.cross(o["a"], info["a"])) < 1e-6
                    and np.linalg.norm(d - (d @ o["a"]) * o["a"]) < tol and abs(o["params"][6] - info["params"][6]) < tol
                    and (info["type"] == "cylinder" or abs(abs(o["params"][7]) - abs(info["params"][7])) < 1e-6)):
                g["faces"].append(k)
                g["bins"] |= info["bins"]
                break
        else:
            groups.append({"solid": k[0], "faces": [k], "bins": set(info["bins"]), "type": info["type"]})
    out = []
    for g in groups:
        info = geo[g["faces"][0]]
        out.append({"solid": int(g["solid"]), "faces": [int(k[1]) for k in g["faces"]], "type": g["type"],
                    "radius": round(info["params"][6], 4), "axis": [round(float(x), 4) for x in info["a"]],
                    "point": [round(float(x), 3) for x in info["p"]], "degrees": 5 * len(g["bins"])})
    return out


def camera(view):
    d = np.array(view, float)
    d /= np.linalg.norm(d)  # from the part towards the eye
    up0 = np.array([0, 0, 1.0]) if abs(d[2]) < 0.99 else np.array([0, 1.0, 0])
    right = np.cross(up0, d)
    right /= np.linalg.norm(right)
    up = np.cross(d, right)
    return d, right, up


def rasterize(tris, d, right, up, size, centre, scale):
    """Orthographic z-buffer: per pixel the nearest triangle (-1: background) and its depth."""
    P = tris - centre
    u = (P @ right) * scale + size / 2
    v = size / 2 - (P @ up) * scale
    z = P @ d  # larger is nearer
    x0 = np.floor(u.min(axis=1)).astype(int)
    x1 = np.ceil(u.max(axis=1)).astype(int)
    y0 = np.floor(v.min(axis=1)).astype(int)
    y1 = np.ceil(v.max(axis=1)).astype(int)
    ext = np.maximum(x1 - x0, y1 - y0) + 1
    frag_pix, frag_z, frag_t = [], [], []
    S = 2
    remaining = np.arange(len(tris))
    while remaining.size:
        cls = remaining[ext[remaining] <= S]
        remaining = remaining[ext[remaining] > S]
        chunk = max(1, 2000000 // (S * S))
        for c0 in range(0, cls.size, chunk):
            t = cls[c0:c0 + chunk]
            ox, oy = np.meshgrid(np.arange(S), np.arange(S))
            px = x0[t, None] + ox.ravel()[None, :]
            py = y0[t, None] + oy.ravel()[None, :]
            cx, cy = px + 0.5, py + 0.5
            ax, ay, bx, by, qx, qy = (u[t, 0, None], v[t, 0, None], u[t, 1, None], v[t, 1, None], u[t, 2, None],
                                      v[t, 2, None])
            den = (by - qy) * (ax - qx) + (qx - bx) * (ay - qy)
            den = np.where(np.abs(den) < 1e-12, 1e-12, den)
            l0 = ((by - qy) * (cx - qx) + (qx - bx) * (cy - qy)) / den
            l1 = ((qy - ay) * (cx - qx) + (ax - qx) * (cy - qy)) / den
            l2 = 1 - l0 - l1
            eps = -1e-6
            inside = (l0 >= eps) & (l1 >= eps) & (l2 >= eps) & (px >= 0) & (py >= 0) & (px < size) & (py < size)
            zz = l0 * z[t, 0, None] + l1 * z[t, 1, None] + l2 * z[t, 2, None]
            frag_pix.append((py * size + px)[inside])
            frag_z.append(zz[inside])
            frag_t.append(np.broadcast_to(t[:, None], px.shape)[inside])
        S *= 2
    pix = np.concatenate(frag_pix)
    zz = np.concatenate(frag_z)
    tt = np.concatenate(frag_t)
    order = np.lexsort((-zz, pix))
    pix, zz, tt = pix[order], zz[order], tt[order]
    first = np.ones(pix.size, bool)
    first[1:] = pix[1:] != pix[:-1]
    tri_buf = np.full(size * size, -1, np.int64)
    z_buf = np.full(size * size, -np.inf)
    tri_buf[pix[first]] = tt[first]
    z_buf[pix[first]] = zz[first]
    return tri_buf.reshape(size, size), z_buf.reshape(size, size)


def shade(tris, tri_buf, face_id, colours, d, size):
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-30)[:, None]
    light = d + 0.4 * np.cross(d, [0.3, 0.5, 0.8])
    light /= np.linalg.norm(light)
    lam = 0.35 + 0.65 * np.abs(n @ light)
    img = np.ones((size, size, 3))
    m = tri_buf >= 0
    t = tri_buf[m]
    img[m] = colours[t] * lam[t, None]
    # face boundaries and silhouettes: a pixel whose right or lower neighbour shows another face
    fid = np.where(m, face_id[np.maximum(tri_buf, 0)], -1)
    edge = np.zeros((size, size), bool)
    edge[:, :-1] |= fid[:, :-1] != fid[:, 1:]
    edge[:-1, :] |= fid[:-1, :] != fid[1:, :]
    img[edge] *= 0.35
    return img


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh", nargs="?", help="tessellate_faces output (or use --step)")
    ap.add_argument("out", help="output PNG (the 2 x 2 sheet)")
    ap.add_argument("--step", help="STEP file, tessellated with --tessellator")
    ap.add_argument("--tessellator", help="tessellate_faces binary")
    ap.add_argument("--holes", help="hole truth JSON")
    ap.add_argument("--floors", help="floor truth JSON")
    ap.add_argument("--title", default=None)
    ap.add_argument("--size", type=int, default=640, help="pixels per view (default 640)")
    ap.add_argument("--summary", help="write the matching summary as JSON")
    ap.add_argument("--views", default="0,1,2,3",
                    help="which of the views from (+1,+1,+1), (-1,-1,+1), (+1,-1,-1), (-1,+1,-1) (default all: 0,1,2,3), "
                         "or directions X:Y:Z (towards the eye)")
    ap.add_argument("--solids", help="S,...: only these solids (an assembly's parts hide each other's holes)")
    ap.add_argument("--zoom", help="X,Y,Z,R: the views show the sphere of radius R (mm) about X,Y,Z")
    ap.add_argument("--cut", action="store_true", help="with --zoom: a cutaway, no triangle nearer the eye than X,Y,Z")
    ap.add_argument("--highlight", help="SOLID:FACE,...: faces painted bright green (to find a face)")
    ap.add_argument("--no-image", action="store_true", help="only the matching summary (OUT is not written)")
    ap.add_argument("--no-index", action="store_true", help="no label indices on the image")
    args = ap.parse_args()
    if bool(args.mesh) == bool(args.step) or (args.step and not args.tessellator):
        ap.error("give MESH.txt, or --step FILE with --tessellator BIN")
    mesh = args.mesh
    tmp = None
    if args.step:
        tmp = tempfile.NamedTemporaryFile(suffix=".txt", delete=False)
        tmp.close()
        r = subprocess.run([args.tessellator, args.step, tmp.name])
        if r.returncode != 0:
            print("render_labels: %s: tessellation failed (exit %d)" % (args.step, r.returncode), file=sys.stderr)
            return 1
        mesh = tmp.name
    try:
        nsolids, faces, tris, keys = read_mesh(mesh)
    except (OSError, ValueError) as e:
        print("render_labels: %s" % e, file=sys.stderr)
        return 1
    finally:
        if tmp:
            os.unlink(tmp.name)
    if args.solids:  # an assembly's parts one at a time: the others hide their holes
        keep = np.isin(keys[:, 0], [int(x) for x in args.solids.split(",")])
        if not keep.any():
            print("render_labels: --solids %s: no such solid (the file has %d)" % (args.solids, nsolids), file=sys.stderr)
            return 1
        tris, keys = tris[keep], keys[keep]
        faces = {k: v for k, v in faces.items() if k[0] in set(keys[:, 0].tolist())}
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    diag = float(np.linalg.norm(hi - lo))
    tol = 1e-4 * diag + 1e-6
    geo = face_geometry(faces, tris, keys)

    colours = np.tile(np.array(BASE), (len(tris), 1))
    for k, info in geo.items():
        if "a" in info:
            colours[info["tris"]] = CONCAVE if info["concave"] else CONVEX
        elif info["type"] == "bspline":
            colours[info["tris"]] = BSPLINE
    marks = []  # (point, text, colour, kind) kind: hole end / floor
    summary = {"triangles": int(len(tris)), "solids": nsolids}
    legend = []
    labelled = set()
    if args.holes:
        try:
            truth = json.load(open(args.holes))
        except (OSError, ValueError) as e:
            print("render_labels: %s: %s" % (args.holes, e), file=sys.stderr)
            return 1
        shown = set(keys[:, 0].tolist())
        holes = [(s["index"], i, h) for s in truth["solids"] if s["index"] in shown for i, h in enumerate(s["holes"])]
        matched = match_holes(holes, geo, tol)
        summary["holes"] = []
        multi = len(truth["solids"]) > 1
        for (s, i, h), fs in zip(holes, matched):
            col = HOLE_COLOURS.get(h["type"], (0, 0, 0))
            for k in fs:
                colours[geo[k]["tris"]] = col
                labelled.add(k)
            p = np.array(h["axis_point"], float)
            a = np.array(h["axis"], float)
            a /= np.linalg.norm(a)
            name = "%d.%d" % (s, i) if multi else "%d" % i
            ends = [p + a * h["extent"][j] for j in (0, 1) if h["ends"][j] == "open"] or [p + a * h["extent"][0]]
            marks.append((ends, name, col, h.get("max_radius", 0)))
            nlab = sum(e.get("faces", 0) for e in h["elements"])
            summary["holes"].append({"solid": s, "index": i, "type": h["type"], "faces_labelled": nlab,
                                     "faces_matched": [int(k[1]) for k in fs]})
        used = sorted({h["type"] for _, _, h in holes})
        legend += [(t, HOLE_COLOURS.get(t, (0, 0, 0))) for t in used]
        summary["unlabelled_concave"] = unlabelled_surfaces(geo, labelled, tol)
    if args.floors:
        try:
            truth = json.load(open(args.floors))
        except (OSError, ValueError) as e:
            print("render_labels: %s: %s" % (args.floors, e), file=sys.stderr)
            return 1
        summary["floors"] = []
        multi = len(truth["solids"]) > 1
        used = set()
        for s in truth["solids"]:
            if s["index"] not in set(keys[:, 0].tolist()):
                continue
            for i, f in enumerate(s["features"]):
                col = np.array(FLOOR_COLOURS.get(f["type"], (0, 0, 0)))
                used.add(f["type"])
                for fi in f["faces"]:
                    if (s["index"], fi) in geo:
                        colours[geo[(s["index"], fi)]["tris"]] = 0.45 * col + 0.55
                for fi in f["floors"]:
                    if (s["index"], fi) in geo:
                        colours[geo[(s["index"], fi)]["tris"]] = col
                name = "%d.%d" % (s["index"], i) if multi else "%d" % i
                marks.append(([np.array(q, float) for q in f["floor_points"][:1]], name, tuple(col), 0))
                summary["floors"].append({"solid": s["index"], "index": i, "type": f["type"], "floors": f["floors"],
                                          "faces": len(f["faces"])})
        legend += [(t, FLOOR_COLOURS.get(t, (0, 0, 0))) for t in sorted(used)]
        legend.append(("(lighter: walls, fillets)", (0.8, 0.8, 0.8)))
    if args.holes:
        legend += [("unlabelled concave cyl/cone", CONCAVE), ("unlabelled convex cyl/cone", CONVEX), ("B-spline", BSPLINE)]

    if args.highlight:
        for w in args.highlight.split(","):
            k = tuple(int(x) for x in w.split(":"))
            if k in geo:
                colours[geo[k]["tris"]] = (0.0, 1.0, 0.2)
        legend.append(("--highlight", (0.0, 1.0, 0.2)))
    zoom = np.array([float(x) for x in args.zoom.split(",")]) if args.zoom else None
    if args.no_image:
        return report(summary, args)
    face_id = np.zeros(len(tris), np.int64)
    for n, (k, info) in enumerate(sorted(geo.items())):
        face_id[info["tris"]] = n
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    size = args.size
    views = [tuple(float(x) for x in v.split(":")) if ":" in v else VIEWS[int(v)] for v in args.views.split(",")]
    nx = 1 if len(views) == 1 else 2
    ny = (len(views) + 1) // 2 if len(views) > 1 else 1
    fig, axs = plt.subplots(ny, nx, figsize=(nx * size / 100, ny * size / 100 + 0.6), dpi=100, squeeze=False)
    pts_all = tris.reshape(-1, 3)
    for ax in axs.ravel()[len(views):]:
        ax.set_axis_off()
    for ax, view in zip(axs.ravel(), views):
        d, right, up = camera(view)
        if zoom is not None:  # a sphere's region fills the view
            centre = zoom[:3] - d * (zoom[:3] @ d)
            scale = 0.5 * size / zoom[3]
        else:  # fit the part's projection into the view
            pu, pv = pts_all @ right, pts_all @ up
            centre = right * (pu.min() + pu.max()) / 2 + up * (pv.min() + pv.max()) / 2
            scale = 0.94 * size / max(pu.max() - pu.min(), pv.max() - pv.min(), 1e-9)
        vt = np.arange(len(tris))
        if zoom is not None and args.cut:  # a cutaway: what lies nearer the eye than the zoom centre is gone
            vt = vt[tris.mean(axis=1) @ d <= zoom[:3] @ d]
        tri_buf, z_buf = rasterize(tris[vt], d, right, up, size, centre, scale)
        tri_buf = np.where(tri_buf >= 0, vt[np.maximum(tri_buf, 0)], -1)
        ax.imshow(shade(tris, tri_buf, face_id, colours, d, size), interpolation="nearest")
        ax.set_axis_off()
        ax.set_title("view from (%+g,%+g,%+g)" % view, fontsize=8)
        if args.no_index:
            continue
        for pts, name, col, rad in marks:
            # the nearest visible end: its pixel (or one within the hole's radius) shows a depth at or in front of it
            best = None
            for q in pts:
                P = q - centre
                x, y, zq = P @ right * scale + size / 2, size / 2 - P @ up * scale, P @ d
                xi, yi = int(x), int(y)
                if not (0 <= xi < size and 0 <= yi < size):
                    continue
                r = max(2, int(rad * scale))
                win = z_buf[max(0, yi - r):yi + r + 1, max(0, xi - r):xi + r + 1]
                vis = np.isfinite(win) & (win <= zq + max(rad, tol * 10))
                if vis.mean() > 0.3 and (best is None or zq > best[2]):
                    best = (x, y, zq)
            if best:
                # beside the end, not over it (the hole's colour stays visible), with a leader line
                off = max(6, rad * scale) + 4
                ax.annotate(name, (best[0], best[1]), (best[0] + off, best[1] - off), color=col, fontsize=6,
                            ha="left", va="bottom", fontweight="bold",
                            arrowprops=dict(arrowstyle="-", color=col, lw=0.5, shrinkA=0, shrinkB=0),
                            bbox=dict(boxstyle="round,pad=0.1", fc="white", ec=col, lw=0.5, alpha=0.75))
    fig.legend(handles=[Patch(color=c, label=t) for t, c in legend], loc="lower center", ncol=min(4, len(legend)),
               fontsize=7, frameon=False)
    title = args.title or os.path.basename(args.step or mesh)
    nh = len(summary.get("holes", []))
    nf = len(summary.get("floors", []))
    fig.suptitle("%s: %s" % (title, ", ".join(x for x in (("%d holes" % nh) if args.holes else "",
                                                             ("%d floor features" % nf) if args.floors else "") if x)),
                 fontsize=9)
    fig_h = ny * size / 100 + 0.6  # inches: room for the title above and the legend below
    fig.subplots_adjust(left=0.005, right=0.995, top=1 - 0.4 / fig_h, bottom=0.55 / fig_h, wspace=0.01, hspace=0.06)
    fig.savefig(args.out)
    return report(summary, args)


def report(summary, args):
    nh = len(summary.get("holes", []))
    nf = len(summary.get("floors", []))
    for h in summary.get("holes", []):
        if not h["faces_matched"]:
            print("render_labels: hole %d.%d (%s) matched no face" % (h["solid"], h["index"], h["type"]))
    if args.summary:
        with open(args.summary, "w") as f:
            json.dump(summary, f, indent=1)
    print(json.dumps({"triangles": summary["triangles"], "holes": nh, "floors": nf,
                      "holes_unmatched": sum(1 for h in summary.get("holes", []) if not h["faces_matched"]),
                      "unlabelled_concave_full_circle": sum(1 for g in summary.get("unlabelled_concave", [])
                                                            if g["degrees"] >= 355)}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
