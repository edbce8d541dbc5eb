#!/usr/bin/env python3
"""glTF scene export (issue #25, item 2), read back by independent readers.

Runs interfere_view_samples (tests/view/write_view_samples.cpp) into WORKDIR, then checks each
.glb against the document facts it wrote to expect.json:
  1. the GLB container (glTF 2.0 spec 4.4): magic, version, length, chunk types, 4-byte padding;
  2. the JSON against a schema of the glTF 2.0 rules written here (python3-jsonschema), and the
     rules a schema cannot say: indices in range, a node tree, buffer views and accessors inside
     their buffers and 4-byte aligned, POSITION min/max equal to the data, index values below the
     vertex count, animation samplers (increasing key times, output counts, unit quaternions);
  3. the content: node names, body and clash extras, clash region materials red / contact orange,
     curves and witnesses as LINES primitives, units to metres on the root; every body's world box
     computed here from the node matrices and the buffer (numpy), in the static view and at every
     animation key, against the box expect.json gives for that step;
  4. three.js's GLTFLoader in Node (tests/view/gltf_summary.mjs): the objects it builds (names,
     userData from extras, LineSegments, material colours) and the world boxes after playing the
     animation with an AnimationMixer.
Exit status 0: all passed; 1: a check failed; 77: a reader (jsonschema, Node.js with three) is
missing and every check that could run passed.

Usage: check_gltf.py SAMPLES_EXE WORKDIR [--node-modules DIR]...
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys

import numpy as np

FLOAT, UINT, USHORT, UBYTE = 5126, 5125, 5123, 5121
COMPONENT_SIZE = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
NUMPY_TYPE = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}

# ---- the glTF 2.0 rules as a JSON schema (written from the specification's property tables) ----
ID = {"type": "integer", "minimum": 0}
NAMED = {"name": {"type": "string"}, "extensions": {"type": "object"}, "extras": {}}


def obj(required, props, **more):
    return {"type": "object", "required": required, "properties": {**NAMED, **props}, "additionalProperties": False, **more}


def num_array(n, lo=None, hi=None):
    item = {"type": "number"}
    if lo is not None:
        item["minimum"] = lo
    if hi is not None:
        item["maximum"] = hi
    return {"type": "array", "items": item, "minItems": n, "maxItems": n}


def array_of(schema):
    return {"type": "array", "items": schema, "minItems": 1}


GLTF_SCHEMA = obj(["asset"], {
    "asset": obj(["version"], {"version": {"type": "string", "pattern": r"^[0-9]+\.[0-9]+$"},
                               "minVersion": {"type": "string"}, "generator": {"type": "string"},
                               "copyright": {"type": "string"}}),
    "extensionsUsed": {"type": "array", "items": {"type": "string"}, "uniqueItems": True, "minItems": 1},
    "extensionsRequired": {"type": "array", "items": {"type": "string"}, "uniqueItems": True, "minItems": 1},
    "scene": ID,
    "scenes": array_of(obj([], {"nodes": {"type": "array", "items": ID, "uniqueItems": True, "minItems": 1}})),
    "nodes": array_of(obj([], {
        "children": {"type": "array", "items": ID, "uniqueItems": True, "minItems": 1},
        "mesh": ID, "camera": ID, "skin": ID,
        "matrix": num_array(16), "rotation": num_array(4, -1, 1), "scale": num_array(3), "translation": num_array(3),
        "weights": {"type": "array", "items": {"type": "number"}, "minItems": 1}},
        **{"not": {"anyOf": [{"required": ["matrix", p]} for p in ("translation", "rotation", "scale")]}})),
    "meshes": array_of(obj(["primitives"], {
        "primitives": array_of(obj(["attributes"], {
            "attributes": {"type": "object", "minProperties": 1, "additionalProperties": ID},
            "indices": ID, "material": ID, "mode": {"enum": [0, 1, 2, 3, 4, 5, 6]},
            "targets": {"type": "array", "minItems": 1}})),
        "weights": {"type": "array", "items": {"type": "number"}, "minItems": 1}})),
    "materials": array_of(obj([], {
        "pbrMetallicRoughness": obj([], {
            "baseColorFactor": num_array(4, 0, 1), "metallicFactor": {"type": "number", "minimum": 0, "maximum": 1},
            "roughnessFactor": {"type": "number", "minimum": 0, "maximum": 1},
            "baseColorTexture": {"type": "object"}, "metallicRoughnessTexture": {"type": "object"}}),
        "emissiveFactor": num_array(3, 0, 1), "alphaMode": {"enum": ["OPAQUE", "MASK", "BLEND"]},
        "alphaCutoff": {"type": "number", "minimum": 0}, "doubleSided": {"type": "boolean"},
        "normalTexture": {"type": "object"}, "occlusionTexture": {"type": "object"}, "emissiveTexture": {"type": "object"}})),
    "accessors": array_of(obj(["componentType", "count", "type"], {
        "bufferView": ID, "byteOffset": {"type": "integer", "minimum": 0},
        "componentType": {"enum": sorted(COMPONENT_SIZE)}, "normalized": {"type": "boolean"},
        "count": {"type": "integer", "minimum": 1}, "type": {"enum": sorted(WIDTH)},
        "max": {"type": "array", "items": {"type": "number"}, "minItems": 1, "maxItems": 16},
        "min": {"type": "array", "items": {"type": "number"}, "minItems": 1, "maxItems": 16},
        "sparse": {"type": "object"}})),
    "bufferViews": array_of(obj(["buffer", "byteLength"], {
        "buffer": ID, "byteOffset": {"type": "integer", "minimum": 0}, "byteLength": {"type": "integer", "minimum": 1},
        "byteStride": {"type": "integer", "minimum": 4, "maximum": 252, "multipleOf": 4},
        "target": {"enum": [34962, 34963]}})),
    "buffers": array_of(obj(["byteLength"], {"uri": {"type": "string"}, "byteLength": {"type": "integer", "minimum": 1}})),
    "animations": array_of(obj(["channels", "samplers"], {
        "channels": array_of(obj(["sampler", "target"], {
            "sampler": ID,
            "target": obj(["path"], {"node": ID, "path": {"enum": ["translation", "rotation", "scale", "weights"]}})})),
        "samplers": array_of(obj(["input", "output"], {
            "input": ID, "output": ID, "interpolation": {"enum": ["LINEAR", "STEP", "CUBICSPLINE"]}}))})),
    "cameras": array_of({"type": "object"}), "images": array_of({"type": "object"}), "samplers": array_of({"type": "object"}),
    "skins": array_of({"type": "object"}), "textures": array_of({"type": "object"}),
})


class Checker:
    def __init__(self, name):
        self.name = name
        self.problems = []

    def check(self, ok, what):
        if not ok:
            self.problems.append(f"{self.name}: {what}")
        return ok


def read_glb(path, c):
    data = open(path, "rb").read()
    c.check(len(data) >= 20, "shorter than a GLB header")
    magic, version, length = struct.unpack_from("<III", data, 0)
    c.check(magic == 0x46546C67, "magic is not glTF")
    c.check(version == 2, f"GLB version {version}")
    c.check(length == len(data), f"header length {length} != file size {len(data)}")
    json_len, json_type = struct.unpack_from("<II", data, 12)
    c.check(json_type == 0x4E4F534A, "first chunk is not JSON")
    c.check(json_len % 4 == 0, "JSON chunk length not a multiple of 4")
    text = data[20:20 + json_len]
    c.check(text.rstrip(b" ") + b" " * (len(text) - len(text.rstrip(b" "))) == text, "JSON chunk padding")
    doc = json.loads(text.decode("utf-8"))
    binary = b""
    at = 20 + json_len
    if at < len(data):
        bin_len, bin_type = struct.unpack_from("<II", data, at)
        c.check(bin_type == 0x004E4942, "second chunk is not BIN")
        c.check(bin_len % 4 == 0, "BIN chunk length not a multiple of 4")
        c.check(at + 8 + bin_len == len(data), "data after the BIN chunk")
        binary = data[at + 8:at + 8 + bin_len]
    return doc, binary


def accessor_data(doc, binary, index):
    a = doc["accessors"][index]
    v = doc["bufferViews"][a["bufferView"]]
    width = WIDTH[a["type"]]
    start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    values = np.frombuffer(binary, dtype=NUMPY_TYPE[a["componentType"]], count=a["count"] * width, offset=start)
    return values.reshape(a["count"], width)


def structure(doc, binary, c):
    """The rules a schema cannot express (glTF 2.0 spec 3.5-3.11)."""
    n = {k: len(doc.get(k, [])) for k in ("nodes", "meshes", "materials", "accessors", "bufferViews", "buffers", "scenes")}
    c.check("scene" not in doc or doc["scene"] < n["scenes"], "scene index out of range")
    parent = {}
    for i, node in enumerate(doc.get("nodes", [])):
        for ch in node.get("children", []):
            if c.check(ch < n["nodes"], f"node {i}: child {ch} out of range"):
                c.check(ch not in parent, f"node {ch} has two parents")
                parent[ch] = i
        c.check(node.get("mesh", 0) < n["meshes"], f"node {i}: mesh out of range")
    for i in range(n["nodes"]):  # no cycles
        seen, at = set(), i
        while at in parent:
            if not c.check(at not in seen, f"node {i}: a cycle"):
                break
            seen.add(at)
            at = parent[at]
    for s in doc.get("scenes", []):
        for root in s.get("nodes", []):
            c.check(root < n["nodes"] and root not in parent, f"scene root {root} is not a root node")
    for b in doc.get("buffers", []):
        c.check("uri" not in b and len(binary) >= b["byteLength"] and len(binary) - b["byteLength"] < 4,
                "the GLB buffer's byteLength does not match the BIN chunk")
    for i, v in enumerate(doc.get("bufferViews", [])):
        c.check(v["buffer"] < n["buffers"], f"bufferView {i}: buffer out of range")
        c.check(v.get("byteOffset", 0) % 4 == 0, f"bufferView {i}: byteOffset not 4-byte aligned")
        c.check(v.get("byteOffset", 0) + v["byteLength"] <= doc["buffers"][0]["byteLength"], f"bufferView {i}: beyond the buffer")
    used_as = {}
    for mi, mesh in enumerate(doc.get("meshes", [])):
        for pi, prim in enumerate(mesh["primitives"]):
            where = f"mesh {mi} primitive {pi}"
            attrs = prim["attributes"]
            for name, ai in attrs.items():
                used_as.setdefault(ai, set()).add("attribute")
            c.check("POSITION" in attrs, f"{where}: no POSITION")
            c.check(prim.get("material", 0) < n["materials"] or "material" not in prim, f"{where}: material out of range")
            if "POSITION" not in attrs:
                continue
            pa = doc["accessors"][attrs["POSITION"]]
            c.check(pa["type"] == "VEC3" and pa["componentType"] == FLOAT, f"{where}: POSITION is not float VEC3")
            if c.check("min" in pa and "max" in pa, f"{where}: POSITION without min/max"):
                pos = accessor_data(doc, binary, attrs["POSITION"])
                c.check(list(pos.min(axis=0)) == [np.float32(x) for x in pa["min"]], f"{where}: POSITION min {pa['min']} is not the data's")
                c.check(list(pos.max(axis=0)) == [np.float32(x) for x in pa["max"]], f"{where}: POSITION max {pa['max']} is not the data's")
            for name, ai in attrs.items():
                c.check(doc["accessors"][ai]["count"] == pa["count"], f"{where}: {name} count differs from POSITION")
            if "COLOR_0" in attrs:
                col = accessor_data(doc, binary, attrs["COLOR_0"])
                c.check(doc["accessors"][attrs["COLOR_0"]]["type"] in ("VEC3", "VEC4"), f"{where}: COLOR_0 type")
                c.check(col.min() >= 0 and col.max() <= 1, f"{where}: COLOR_0 outside [0, 1]")
            mode = prim.get("mode", 4)
            if "indices" in prim:
                used_as.setdefault(prim["indices"], set()).add("indices")
                ia = doc["accessors"][prim["indices"]]
                c.check(ia["type"] == "SCALAR" and ia["componentType"] in (UBYTE, USHORT, UINT), f"{where}: indices type")
                idx = accessor_data(doc, binary, prim["indices"])
                c.check(int(idx.max()) < pa["count"], f"{where}: an index beyond the vertices")
                count = ia["count"]
            else:
                count = pa["count"]
            c.check({1: count % 2 == 0 and count >= 2, 3: count >= 2, 4: count % 3 == 0 and count >= 3}.get(mode, True),
                    f"{where}: {count} vertices for mode {mode}")
    for i, a in enumerate(doc.get("accessors", [])):
        if not c.check(a.get("bufferView", 0) < n["bufferViews"], f"accessor {i}: bufferView out of range"):
            continue
        v = doc["bufferViews"][a["bufferView"]]
        size = COMPONENT_SIZE[a["componentType"]]
        element = size * WIDTH[a["type"]]
        stride = v.get("byteStride", element)
        c.check(a.get("byteOffset", 0) % size == 0 and (v.get("byteOffset", 0) + a.get("byteOffset", 0)) % size == 0,
                f"accessor {i}: not aligned to its component size")
        c.check(a.get("byteOffset", 0) + stride * (a["count"] - 1) + element <= v["byteLength"], f"accessor {i}: beyond its bufferView")
        for role in used_as.get(i, ()):
            want = 34963 if role == "indices" else 34962
            c.check(v.get("target", want) == want, f"accessor {i}: used as {role} in a bufferView of target {v.get('target')}")
        for key in ("min", "max"):
            if key in a:
                c.check(len(a[key]) == WIDTH[a["type"]], f"accessor {i}: {key} has the wrong length")
    animated = set()
    for ai, anim in enumerate(doc.get("animations", [])):
        targets = set()
        for ch in anim["channels"]:
            s = anim["samplers"][ch["sampler"]] if c.check(ch["sampler"] < len(anim["samplers"]), "channel sampler out of range") else None
            node, path = ch["target"].get("node"), ch["target"]["path"]
            c.check((node, path) not in targets, f"animation {ai}: two channels on node {node} {path}")
            targets.add((node, path))
            animated.add(node)
            c.check(node is not None and node < n["nodes"], f"animation {ai}: channel node out of range")
            if s is None:
                continue
            ia, oa = doc["accessors"][s["input"]], doc["accessors"][s["output"]]
            c.check(ia["type"] == "SCALAR" and ia["componentType"] == FLOAT and "min" in ia and "max" in ia,
                    f"animation {ai}: input accessor is not float SCALAR with min/max")
            times = accessor_data(doc, binary, s["input"])[:, 0]
            c.check(times[0] >= 0 and all(np.diff(times) > 0), f"animation {ai}: key times not >= 0 and increasing")
            want = {"translation": "VEC3", "scale": "VEC3", "rotation": "VEC4"}.get(path)
            c.check(oa["type"] == want, f"animation {ai}: {path} output is {oa['type']}")
            c.check(oa["count"] == ia["count"] * (3 if s.get("interpolation") == "CUBICSPLINE" else 1),
                    f"animation {ai}: output count {oa['count']} for {ia['count']} keys")
            if path == "rotation":
                q = accessor_data(doc, binary, s["output"])
                c.check(np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-5), f"animation {ai}: rotations not unit quaternions")
    for node in animated:
        c.check("matrix" not in doc["nodes"][node], f"node {node} is animated and has a matrix")
    used_ext = set()
    for m in doc.get("materials", []):
        used_ext |= set(m.get("extensions", {}))
    c.check(used_ext <= set(doc.get("extensionsUsed", [])), f"extensions {used_ext} not all in extensionsUsed")


# ---- world boxes from the node matrices (column-major) and TRS, computed here ----
def quat_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def local_matrix(node, trs):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=float).reshape(4, 4).T  # column-major
    t = trs.get("translation", node.get("translation", [0, 0, 0]))
    r = trs.get("rotation", node.get("rotation", [0, 0, 0, 1]))
    s = trs.get("scale", node.get("scale", [1, 1, 1]))
    m = np.eye(4)
    m[:3, :3] = quat_matrix(r) @ np.diag(s)
    m[:3, 3] = t
    return m


def world_boxes(doc, binary, key=None):
    """Per body node (child of "bodies"): its world box over meshes with a non-degenerate matrix;
    `key`: the animation key whose STEP values replace the nodes' TRS."""
    trs = {}
    if key is not None:
        anim = doc["animations"][0]
        for ch in anim["channels"]:
            s = anim["samplers"][ch["sampler"]]
            trs.setdefault(ch["target"]["node"], {})[ch["target"]["path"]] = list(accessor_data(doc, binary, s["output"])[key])
    nodes = doc["nodes"]
    world = {}

    def walk(i, m):
        world[i] = m @ local_matrix(nodes[i], trs.get(i, {}))
        for ch in nodes[i].get("children", []):
            walk(ch, world[i])
    for root in doc["scenes"][doc.get("scene", 0)]["nodes"]:
        walk(root, np.eye(4))
    group = next(i for i, nd in enumerate(nodes) if nd.get("name") == "bodies")
    boxes = {}
    for b in nodes[group].get("children", []):
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        stack = [b]
        while stack:
            i = stack.pop()
            stack += nodes[i].get("children", [])
            if "mesh" not in nodes[i] or abs(np.linalg.det(world[i][:3, :3])) < 1e-30:
                continue
            for prim in doc["meshes"][nodes[i]["mesh"]]["primitives"]:
                p = accessor_data(doc, binary, prim["attributes"]["POSITION"]).astype(float)
                w = (world[i] @ np.c_[p, np.ones(len(p))].T).T[:, :3]
                lo, hi = np.minimum(lo, w.min(axis=0)), np.maximum(hi, w.max(axis=0))
        boxes[nodes[b]["extras"]["id"]] = [lo.tolist(), hi.tolist()]
    return boxes


def close_box(got, want, scale, tol=1e-5):
    if got is None:
        return False
    return all(abs(g - w * scale) <= tol * max(1.0, abs(w * scale)) for gs, ws in zip(got, want) for g, w in zip(gs, ws))


def linear_to_srgb(c):
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def content(doc, binary, expect, c):
    extras = doc["scenes"][doc.get("scene", 0)].get("extras", {})
    for key in ("units", "command", "verdict", "title"):
        c.check(extras.get(key) == expect[key], f"scene extras {key} = {extras.get(key)!r}, expected {expect[key]!r}")
    c.check(extras.get("schema") == "interfere.viewer", "scene extras schema")
    root = doc["nodes"][doc["scenes"][0]["nodes"][0]]
    scale = expect["metres_per_unit"]
    c.check(abs(root.get("scale", [1, 1, 1])[0] - scale) < 1e-12, f"root scale {root.get('scale')} for {expect['units']}")
    nodes = doc["nodes"]
    by_name = {}
    for i, nd in enumerate(nodes):
        by_name.setdefault(nd.get("name"), []).append(i)
    for b in expect["bodies"]:
        hits = [i for i in by_name.get(b["name"], []) if nodes[i].get("extras", {}).get("id") == b["id"]]
        if not c.check(len(hits) == 1, f"body {b['name']!r}: {len(hits)} nodes with its name and id"):
            continue
        ex = nodes[hits[0]]["extras"]
        for key in ("path", "role", "tags", "visible"):
            c.check(ex.get(key) == b[key], f"body {b['name']!r}: extras {key} = {ex.get(key)!r}, expected {b[key]!r}")
    materials = doc.get("materials", [])
    for cl in expect["clashes"]:
        hits = [i for i in by_name.get(cl["id"], []) if nodes[i].get("extras", {}).get("clash_id") == cl["id"]]
        if not c.check(len(hits) == 1, f"clash {cl['id']}: {len(hits)} nodes"):
            continue
        node = nodes[hits[0]]
        ex = node["extras"]
        for key in ("verdict", "status", "kind", "depth", "distance", "bodies"):
            c.check(ex.get(key) == cl[key], f"clash {cl['id']}: extras {key} = {ex.get(key)!r}, expected {cl[key]!r}")
        kids = {nodes[k]["name"]: nodes[k] for k in node.get("children", [])}
        region = kids.get(cl["id"] + " region")
        if c.check((region is not None) == (cl["region_triangles"] > 0), f"clash {cl['id']}: region node"):
            if region is not None:
                prim = doc["meshes"][region["mesh"]]["primitives"][0]
                c.check(prim.get("mode", 4) == 4, f"clash {cl['id']}: region is not triangles")
                c.check(doc["accessors"][prim["indices"]]["count"] == 3 * cl["region_triangles"], f"clash {cl['id']}: region triangles")
                r, g, b, a = materials[prim["material"]]["pbrMetallicRoughness"]["baseColorFactor"]
                rgb = [round(255 * linear_to_srgb(x)) for x in (r, g, b)]
                want = {"clash": [0xe0, 0x20, 0x20], "contact": [0xf0, 0xa0, 0x20]}.get(cl["verdict"])
                if want:
                    c.check(all(abs(x - y) <= 1 for x, y in zip(rgb, want)), f"clash {cl['id']}: region colour {rgb}, expected {want}")
                    c.check(a == 1, f"clash {cl['id']}: region not opaque")
        curves = kids.get(cl["id"] + " curves")
        segments = sum(max(0, n - 1) for n in cl["curve_points"])
        if c.check((curves is not None) == (segments > 0), f"clash {cl['id']}: curves node"):
            if curves is not None:
                prim = doc["meshes"][curves["mesh"]]["primitives"][0]
                c.check(prim.get("mode") == 1, f"clash {cl['id']}: curves are not LINES")
                c.check(doc["accessors"][prim["indices"]]["count"] == 2 * segments, f"clash {cl['id']}: curve segments")
                r, g, b, _ = materials[prim["material"]]["pbrMetallicRoughness"]["baseColorFactor"]
                c.check(r > 0.9 and 0.3 < g < 0.8 and b < 0.05, f"clash {cl['id']}: curve colour is not yellow")
        witness = kids.get(cl["id"] + " witness")
        if c.check((witness is not None) == cl["witness"], f"clash {cl['id']}: witness node"):
            if witness is not None:
                prim = doc["meshes"][witness["mesh"]]["primitives"][0]
                c.check(prim.get("mode") == 1 and doc["accessors"][prim["indices"]]["count"] == 2, f"clash {cl['id']}: witness line")
    # Body meshes stored once: bodies drawing the same document mesh share their POSITION accessor.
    positions = [doc["meshes"][nd["mesh"]]["primitives"][0]["attributes"]["POSITION"] for nd in nodes if "mesh" in nd]
    c.check(len(positions) >= len(set(positions)), "mesh sharing")
    # World boxes: static view (a static document) or each animation key (a framed one).
    if expect["frame_count"] == 0:
        boxes = world_boxes(doc, binary)
        for b, step in zip(expect["bodies"], expect["steps"][0]["bodies"]):
            c.check(close_box(boxes.get(b["id"]), step["world_box"], scale), f"body {b['id']}: world box {boxes.get(b['id'])}")
    else:
        anim = doc.get("animations", [])
        if c.check(len(anim) == 1, "a framed document without its animation"):
            times = accessor_data(doc, binary, anim[0]["samplers"][0]["input"])[:, 0]
            c.check(np.allclose(times, expect["times"]), f"key times {times} != {expect['times']}")
            for k, step in enumerate(expect["steps"]):
                boxes = world_boxes(doc, binary, k)
                for b, sb in zip(expect["bodies"], step["bodies"]):
                    c.check(close_box(boxes.get(b["id"]), sb["world_box"], scale), f"frame {k}: body {b['id']}: world box {boxes.get(b['id'])}")


def three_js(glb, expect, modules, c):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gltf_summary.mjs")
    run = subprocess.run(["node", script, glb, modules], capture_output=True, text=True, timeout=120)
    if not c.check(run.returncode == 0, f"three.js GLTFLoader failed: {run.stderr.strip()[-2000:]}"):
        return
    s = json.loads(run.stdout)
    c.check(s["sceneExtras"].get("schema") == "interfere.viewer", "three.js: scene userData has no schema")
    objects = s["objects"]
    scale = expect["metres_per_unit"]
    for b in expect["bodies"]:
        hits = [o for o in objects if o["name"] == b["name"] and o["userData"].get("id") == b["id"] and o["parent"] == "bodies"]
        if c.check(len(hits) == 1, f"three.js: body {b['name']!r} found {len(hits)} times"):
            c.check(hits[0]["userData"].get("path") == b["path"], f"three.js: body {b['name']!r} path")
    for cl in expect["clashes"]:
        hits = [o for o in objects if o["name"] == cl["id"] and o["userData"].get("clash_id") == cl["id"]]
        if not c.check(len(hits) == 1, f"three.js: clash {cl['id']} found {len(hits)} times"):
            continue
        c.check(hits[0]["userData"].get("verdict") == cl["verdict"], f"three.js: clash {cl['id']} verdict")
        kids = {o["name"]: o for o in objects if o["parent"] == cl["id"]}
        region = kids.get(cl["id"] + " region")
        if cl["region_triangles"] and c.check(region is not None and region["type"] == "Mesh", f"three.js: clash {cl['id']} region mesh"):
            want = {"clash": "e02020", "contact": "f0a020"}.get(cl["verdict"])
            if want:
                c.check(region["material"]["color"] == want, f"three.js: clash {cl['id']} region colour {region['material']['color']}")
            c.check(region["indices"] == 3 * cl["region_triangles"], f"three.js: clash {cl['id']} region triangles")
        if any(n > 1 for n in cl["curve_points"]):
            curves = kids.get(cl["id"] + " curves")
            if c.check(curves is not None and curves["type"] == "LineSegments", f"three.js: clash {cl['id']} curves are not LineSegments"):
                c.check(curves["material"]["color"] == "ffd400", f"three.js: curve colour {curves['material']['color']}")
                c.check(curves["material"]["type"] == "LineBasicMaterial", "three.js: curve material")
        if cl["witness"]:
            w = kids.get(cl["id"] + " witness")
            c.check(w is not None and w["type"] == "LineSegments" and w["material"]["color"] == "2060e0", f"three.js: clash {cl['id']} witness")
    if expect["frame_count"] == 0:
        for b, step in zip(expect["bodies"], expect["steps"][0]["bodies"]):
            c.check(close_box(s["static"]["boxes"].get(b["id"]), step["world_box"], scale), f"three.js: body {b['id']} world box")
    else:
        if c.check(len(s["frames"]) == expect["frame_count"], f"three.js: {len(s['frames'])} animation keys"):
            for k, (frame, step) in enumerate(zip(s["frames"], expect["steps"])):
                for b, sb in zip(expect["bodies"], step["bodies"]):
                    c.check(close_box(frame["boxes"].get(b["id"]), sb["world_box"], scale, 1e-4),
                            f"three.js: frame {k}: body {b['id']} world box {frame['boxes'].get(b['id'])}")
                for cl in expect["clashes"]:
                    shown = frame["clashScale"].get(cl["id"], 0) > 0
                    c.check(shown == (cl["id"] in step["clashes"]), f"three.js: frame {k}: clash {cl['id']} shown = {shown}")


def find_three(candidates):
    for d in candidates:
        if d and os.path.isfile(os.path.join(d, "three", "examples", "jsm", "loaders", "GLTFLoader.js")):
            return d
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("samples")
    ap.add_argument("workdir")
    ap.add_argument("--node-modules", action="append", default=[])
    args = ap.parse_args()
    shutil.rmtree(args.workdir, ignore_errors=True)
    subprocess.run([args.samples, args.workdir], check=True)
    expect = json.load(open(os.path.join(args.workdir, "expect.json")))
    try:
        import jsonschema
    except ImportError:
        jsonschema = None
    modules = find_three(args.node_modules + [os.environ.get("INTERFERE_NODE_MODULES")])
    node = shutil.which("node")
    problems, missing = [], []
    if jsonschema is None:
        missing.append("python3-jsonschema")
    if node is None or modules is None:
        missing.append("Node.js with three (npm ci in viewer/)" if node else "Node.js")
    for name in ("static", "frames"):
        glb = os.path.join(args.workdir, name + ".glb")
        c = Checker(name + ".glb")
        doc, binary = read_glb(glb, c)
        if jsonschema is not None:
            for e in jsonschema.Draft7Validator(GLTF_SCHEMA).iter_errors(doc):
                c.check(False, f"schema: {'/'.join(map(str, e.absolute_path))}: {e.message}")
        structure(doc, binary, c)
        content(doc, binary, expect[name], c)
        if node and modules:
            three_js(glb, expect[name], modules, c)
        problems += c.problems
        print(f"{name}.glb: {len(c.problems)} problems")
    for p in problems:
        print("FAIL", p)
    if problems:
        return 1
    if missing:
        print("SKIPPED (reader missing):", ", ".join(missing), "- the other checks passed")
        return 77
    print("glTF checks passed (schema, structure, content, three.js GLTFLoader)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
