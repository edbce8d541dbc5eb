#!/usr/bin/env python3
"""Writes the committed seed corpus of the fuzz targets (standard library only, deterministic).

    python3 tests/fuzz/make_corpus.py            # rewrites tests/fuzz/corpus/{read_mesh,tri_tri,read_fem,simplify,read_step}/

corpus/read_mesh/: small valid and broken samples of every format the readers accept (the fuzz
target writes each input under every extension, so the file names are only descriptive).
corpus/tri_tri/: byte patterns for fuzz_tri_tri.cpp (byte 0 = mode | param << 2; see the layout
there): crossing, touching, coplanar, degenerate and nearly degenerate pairs.
Regression inputs (minimised fuzzer findings) are listed in REGRESSIONS below so that they survive
regeneration; the replay tests (ctest -R fuzz_replay) fail while a finding is unfixed.
"""
import math
import os
import shutil
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")

# ---------------------------------------------------------------------------------------------
# Mesh files
# ---------------------------------------------------------------------------------------------
TETRA_V = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def stl_ascii(tris, name="t", kw=str.lower, normal="0 0 0"):
    out = [kw("solid") + " " + name]
    for t in tris:
        out.append(kw("facet normal") + " " + normal)
        out.append("  " + kw("outer loop"))
        for p in t:
            out.append("    " + kw("vertex") + " %r %r %r" % p)
        out.append("  " + kw("endloop"))
        out.append(kw("endfacet"))
    out.append(kw("endsolid") + " " + name)
    return ("\n".join(out) + "\n").encode()


def tetra_tris():
    return [tuple(TETRA_V[i] for i in f) for f in TETRA_F]


def stl_binary(tris, header=b"binary stl", count=None, attr=0):
    h = header.ljust(80, b" ")[:80]
    body = b""
    for t in tris:
        body += struct.pack("<3f", 0, 0, 0)
        for p in t:
            body += struct.pack("<3f", *p)
        body += struct.pack("<H", attr)
    return h + struct.pack("<I", len(tris) if count is None else count) + body


def obj(verts, faces, extra=""):
    s = "# test\n" + extra
    s += "".join("v %r %r %r\n" % v for v in verts)
    s += "".join("f " + " ".join(str(i + 1) for i in f) + "\n" for f in faces)
    return s.encode()


def off(verts, faces, keyword="OFF"):
    s = "%s\n%d %d 0\n" % (keyword, len(verts), len(faces))
    s += "".join("%r %r %r\n" % v for v in verts)
    s += "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    return s.encode()


def ply_header(fmt, nv, nf, vprops=("float x", "float y", "float z"),
               fprop="list uchar int vertex_indices", extra=""):
    h = "ply\nformat %s 1.0\ncomment fuzz seed\nelement vertex %d\n" % (fmt, nv)
    h += "".join("property %s\n" % p for p in vprops)
    h += "element face %d\nproperty %s\n" % (nf, fprop) + extra + "end_header\n"
    return h.encode()


def ply_ascii(verts, faces, **kw):
    s = ply_header("ascii", len(verts), len(faces), **kw).decode()
    s += "".join("%r %r %r\n" % v for v in verts)
    s += "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    return s.encode()


def ply_binary(verts, faces, big=False, coord="f", idx="i", count="B"):
    e = ">" if big else "<"
    names = {"f": "float", "d": "double", "h": "short"}
    cnames = {"B": "uchar", "H": "ushort", "i": "int"}
    inames = {"i": "int", "I": "uint", "H": "ushort", "B": "uchar"}
    fmt = "binary_big_endian" if big else "binary_little_endian"
    h = ply_header(fmt, len(verts), len(faces),
                   vprops=tuple("%s %s" % (names[coord], a) for a in "xyz"),
                   fprop="list %s %s vertex_indices" % (cnames[count], inames[idx]))
    body = b"".join(struct.pack(e + "3" + coord, *v) for v in verts)
    for f in faces:
        body += struct.pack(e + count, len(f)) + struct.pack(e + "%d%s" % (len(f), idx), *f)
    return h + body


CUBE_V = [(x, y, z) for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
CUBE_Q = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def glb(doc, bin_=b""):
    """A GLB (binary glTF 2.0): header, JSON chunk (space-padded), BIN chunk (zero-padded)."""
    import json
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    bin_ += b"\0" * (-len(bin_) % 4)
    body = struct.pack("<I", len(text)) + b"JSON" + text
    if bin_:
        body += struct.pack("<I", len(bin_)) + b"BIN\0" + bin_
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def glb_tetra(node=None, index_type=5125, mode=4, edit=None):
    """The tetrahedron as a GLB: float positions, indices of `index_type`, one node (`node`)."""
    pos = b"".join(struct.pack("<3f", *v) for v in TETRA_V)
    fmt = {5121: "B", 5123: "H", 5125: "I"}[index_type]
    idx = b"".join(struct.pack("<3" + fmt, *f) for f in TETRA_F)
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(pos) + len(idx) + (-len(idx) % 4)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                         {"bufferView": 1, "componentType": index_type, "count": 12, "type": "SCALAR"}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": mode}]}],
           "nodes": [node or {"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    if edit:
        edit(doc)
    return glb(doc, pos + idx)


def gltf_tetra(edit=None):
    """The tetrahedron as JSON glTF: positions and indices in one base64 data: URI buffer."""
    import base64
    import json
    pos = b"".join(struct.pack("<3f", *v) for v in TETRA_V)
    idx = b"".join(struct.pack("<3H", *f) for f in TETRA_F)
    data = pos + idx
    doc = {"asset": {"version": "2.0"},
           "buffers": [{"byteLength": len(data),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                         {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "nodes": [{"mesh": 0, "translation": [1, 0, 0]}], "scenes": [{"nodes": [0]}], "scene": 0}
    if edit:
        edit(doc)
    return json.dumps(doc, indent=1).encode()


def mesh_seeds():
    s = {}
    # STL ASCII
    s["stl_ascii_tetra.stl"] = stl_ascii(tetra_tris())
    s["stl_ascii_upper_two_solids.stl"] = (
        stl_ascii(tetra_tris()[:2], "A", kw=str.upper)
        + stl_ascii(tetra_tris()[2:], "B", normal="nan nan nan"))
    quad = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    s["stl_ascii_quad_loop_crlf_bom.stl"] = b"\xef\xbb\xbf" + stl_ascii([quad]).replace(b"\n", b"\r\n")
    s["stl_ascii_truncated.stl"] = stl_ascii(tetra_tris())[:-30]
    s["stl_ascii_bad_number.stl"] = stl_ascii(tetra_tris()).replace(b"vertex 1.0", b"vertex 1.0e", 1)
    s["stl_ascii_inf_vertex.stl"] = stl_ascii(tetra_tris()).replace(b"vertex 1.0", b"vertex inf", 1)
    s["stl_ascii_two_corners.stl"] = stl_ascii([quad[:2]])
    s["stl_ascii_no_facets.stl"] = b"solid empty\nendsolid empty\n"
    # STL binary
    s["stl_binary_tetra.stl"] = stl_binary(tetra_tris())
    s["stl_binary_solid_header.stl"] = stl_binary(tetra_tris(), header=b"solid exported by a CAD tool")
    s["stl_binary_truncated.stl"] = stl_binary(tetra_tris(), count=5)
    s["stl_binary_extra_bytes.stl"] = stl_binary(tetra_tris()) + b"\0\0\0"
    s["stl_binary_zero_facets.stl"] = stl_binary([])
    nan_tris = tetra_tris()
    nan_tris[1] = ((0.0, 0.0, 0.0), (float("nan"), 0.0, 0.0), (0.0, 0.0, 1.0))
    s["stl_binary_nan.stl"] = stl_binary(nan_tris)
    s["stl_binary_signed_zero_weld.stl"] = stl_binary(
        [((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
         ((-0.0, -0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, -0.0))], attr=7)
    # OBJ
    s["obj_cube_quads.obj"] = obj(CUBE_V, CUBE_Q)
    s["obj_statements.obj"] = (
        b"mtllib a.mtl\no cube\ng g1\ns 1\nusemtl m\n"
        b"v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
        b"vn 0 0 1\nf 1/1/1 3/3/1 2/2/1\nf 1//1 2//1 4//1\nf -4/1 -1/2 -2/3 # relative\n"
        b"l 1 2\np 3\nf 2 3 4\n")
    s["obj_forward_reference.obj"] = b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
    s["obj_index_zero.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"
    s["obj_index_out_of_range.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"
    s["obj_relative_before_first.obj"] = b"v 0 0 0\nv 1 0 0\nf -1 -2 -3\n"
    s["obj_bad_coordinate.obj"] = b"v 0 0 0\nv 1 0x1 0\nv 0 1 0\nf 1 2 3\n"
    s["obj_two_corners.obj"] = b"v 0 0 0\nv 1 0 0\nf 1 2\n"
    s["obj_no_faces.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    s["obj_nan.obj"] = b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"
    # OFF
    s["off_tetra.off"] = off(TETRA_V, TETRA_F)
    s["off_cube_quads_comments.off"] = (b"# cube\n" + off(CUBE_V, CUBE_Q).replace(b"0 0\n", b"0 0 # counts\n", 1))
    coff = "COFF 4 4 6\n" + "".join("%r %r %r 255 0 0 255\n" % v for v in TETRA_V)
    coff += "".join("3 %d %d %d 0.5 0.5 0.5\n" % f for f in TETRA_F)
    s["off_coff_counts_on_keyword_line.off"] = coff.encode()
    s["off_no_keyword.off"] = off(TETRA_V, TETRA_F).split(b"\n", 1)[1]
    s["off_4off.off"] = b"4OFF\n1 1 0\n0 0 0 1\n3 0 0 0\n"
    s["off_noff.off"] = b"nOFF\n3\n1 1 0\n0 0 0\n3 0 0 0\n"
    s["off_binary.off"] = b"OFF BINARY\n" + struct.pack(">3i", 3, 1, 0)
    s["off_too_few_faces.off"] = off(TETRA_V, TETRA_F)[:-8]
    s["off_extra_data.off"] = off(TETRA_V, TETRA_F) + b"3 0 1 2\n"
    s["off_index_out_of_range.off"] = off(TETRA_V, [(0, 1, 4)])
    s["off_counts_too_large.off"] = b"OFF\n99999999 99999999 0\n0 0 0\n"
    # PLY
    s["ply_ascii_tetra_extra_props.ply"] = ply_ascii(
        TETRA_V, TETRA_F, vprops=("float x", "float y", "float z"),
        fprop="list uchar uint vertex_index").replace(
            b"end_header", b"element edge 0\nproperty int vertex1\nend_header")
    props = ("uchar red", "double z", "float nx", "double x", "list uchar float tex", "double y")
    body = "".join("7 %r 0.5 %r 2 0.25 0.75 %r\n" % (v[2], v[0], v[1]) for v in TETRA_V)
    body += "".join("3 %d %d %d\n" % f for f in TETRA_F)
    s["ply_ascii_reordered_props_list.ply"] = ply_header("ascii", 4, 4, vprops=props) + body.encode()
    s["ply_binary_le_double.ply"] = ply_binary(TETRA_V, TETRA_F, coord="d")
    s["ply_binary_be_float_quads.ply"] = ply_binary(CUBE_V, CUBE_Q, big=True, idx="I", count="H")
    s["ply_binary_le_short_coords.ply"] = ply_binary(
        [(0, 0, 0), (3, 0, 0), (0, 3, 0), (0, 0, 3)], TETRA_F, coord="h", idx="H")
    s["ply_binary_truncated.ply"] = ply_binary(TETRA_V, TETRA_F)[:-5]
    s["ply_binary_trailing_bytes.ply"] = ply_binary(TETRA_V, TETRA_F) + b"\0\0"
    s["ply_binary_index_out_of_range.ply"] = ply_binary(TETRA_V, [(0, 1, 9)])
    s["ply_binary_negative_count.ply"] = ply_binary(TETRA_V, TETRA_F, count="i").replace(
        struct.pack("<i", 3), struct.pack("<i", -3), 1)
    s["ply_binary_nan.ply"] = ply_binary([(0.0, 0.0, 0.0), (float("inf"), 0.0, 0.0), (0.0, 1.0, 0.0)], [(0, 1, 2)])
    s["ply_bad_keyword.ply"] = ply_ascii(TETRA_V, TETRA_F).replace(b"comment", b"commment", 1)
    s["ply_no_format.ply"] = ply_ascii(TETRA_V, TETRA_F).replace(b"format ascii 1.0\n", b"")
    s["ply_no_vertex_element.ply"] = b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n"
    s["ply_count_too_large.ply"] = ply_ascii(TETRA_V, TETRA_F).replace(b"element vertex 4", b"element vertex 4000000000")
    s["ply_ascii_two_corners.ply"] = ply_ascii(TETRA_V, [(0, 1)])
    s["ply_crlf_header.ply"] = ply_ascii(TETRA_V, TETRA_F).replace(b"\n", b"\r\n")
    # GLB (binary glTF 2.0)
    s["glb_tetra.glb"] = glb_tetra()
    s["glb_tetra_trs_u8.glb"] = glb_tetra({"mesh": 0, "translation": [1, 2, 3], "rotation": [0, 0, 0.6, 0.8],
                                           "scale": [2, 2, 2]}, index_type=5121)
    s["glb_tetra_matrix_u16.glb"] = glb_tetra({"mesh": 0, "matrix": [0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1]},
                                              index_type=5123)
    s["glb_tetra_truncated.glb"] = glb_tetra()[:-7]
    s["glb_index_out_of_range.glb"] = glb_tetra().replace(struct.pack("<3I", *TETRA_F[-1]), struct.pack("<3I", 0, 1, 9))
    s["glb_view_beyond_bin.glb"] = glb_tetra(edit=lambda d: d["bufferViews"][1].update(byteLength=4096))
    s["glb_node_cycle.glb"] = glb_tetra({"mesh": 0, "children": [0]})
    s["glb_external_buffer.glb"] = glb_tetra(edit=lambda d: d["buffers"][0].update(uri="tetra.bin"))
    s["glb_not_json.glb"] = glb_tetra().replace(b'{"asset"', b'{"asset"!', 1)
    s["glb_tetra_quantized_short.glb"] = glb(
        {"asset": {"version": "2.0"}, "extensionsRequired": ["KHR_mesh_quantization"],
         "buffers": [{"byteLength": 32}], "bufferViews": [{"buffer": 0, "byteLength": 32, "byteStride": 8}],
         "accessors": [{"bufferView": 0, "componentType": 5122, "normalized": True, "count": 4, "type": "VEC3"}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 5}]}],
         "nodes": [{"mesh": 0, "scale": [3, 3, 3]}], "scenes": [{"nodes": [0]}]},
        b"".join(struct.pack("<3hxx", *v) for v in ((0, 0, 0), (32767, 0, 0), (0, 32767, 0), (0, 0, -32768))))
    # JSON glTF: a data: URI buffer, a file buffer (the fuzzer's own input file), bad URIs
    s["gltf_tetra.gltf"] = gltf_tetra()
    s["gltf_file_buffer.gltf"] = gltf_tetra(lambda d: d["buffers"][0].update(uri="in.bin"))
    s["gltf_device_buffer.gltf"] = gltf_tetra(lambda d: d["buffers"][0].update(uri="/dev/zero"))
    s["gltf_http_buffer.gltf"] = gltf_tetra(lambda d: d["buffers"][0].update(uri="http://example.com/a.bin"))
    s["gltf_bad_base64.gltf"] = gltf_tetra(lambda d: d["buffers"][0].update(uri="data:;base64,QUJD!"))
    s["gltf_truncated.gltf"] = gltf_tetra()[:-9]
    # Anything else
    s["empty"] = b""
    s["text_garbage"] = b"hello world\n\x00\x01\x02 solid facet v f 3 ply\n"
    s["binary_garbage"] = bytes((i * 37 + 11) % 256 for i in range(200))
    return s


# ---------------------------------------------------------------------------------------------
# Triangle pairs (fuzz_tri_tri.cpp layout)
# ---------------------------------------------------------------------------------------------
def grid(a, b, exp=0):
    """Mode 1: integer corners in [-8, 8], step 2^exp (exp in [-8, 7])."""
    header = 1 | (((exp + 8) % 16) << 2)
    vals = [c for p in list(a) + list(b) for c in p]
    assert len(vals) == 18 and all(-8 <= v <= 8 for v in vals)
    return bytes([header] + [v + 8 for v in vals])


def jitter(a, b, offset_sel, ulps):
    """Mode 2: integer corners + offset (0, 1024, 2^20, 3*2^40), each moved by ulps[i] in [-8, 7]."""
    vals = [c for p in list(a) + list(b) for c in p]
    return bytes([2 | (offset_sel << 2)] + [v + 8 for v in vals] + [(u << 4) & 0xff for u in ulps])


def raw(a, b):
    """Mode 0: 18 doubles."""
    vals = [c for p in list(a) + list(b) for c in p]
    return bytes([0]) + struct.pack("<18d", *vals)


def int16(a, b, shift=0):
    """Mode 3: int16 corners times 2^-shift."""
    vals = [c for p in list(a) + list(b) for c in p]
    return bytes([3 | (shift << 2)]) + struct.pack("<18h", *vals)


def tri_seeds():
    s = {}
    A = ((0, 0, 0), (4, 0, 0), (0, 4, 0))
    s["grid_cross_pierce"] = grid(A, ((1, 1, -2), (2, 1, 2), (1, 2, 2)))
    s["grid_cross_chain_links"] = grid(((0, 0, 0), (4, 0, 0), (2, 0, 4)), ((2, -2, 1), (2, 2, 1), (2, 0, 6)))
    s["grid_cross_vertex_in_plane"] = grid(A, ((1, 1, 0), (1, 3, 3), (3, 1, -3)))
    s["grid_cross_edge_through_edge"] = grid(A, ((2, -1, -1), (2, -1, 1), (2, 2, 0)))
    s["grid_touch_vertex_on_face"] = grid(A, ((1, 1, 0), (1, 1, 3), (2, 2, 3)))
    s["grid_touch_edge_on_face"] = grid(A, ((1, 1, 0), (2, 1, 0), (1, 1, 3)))
    s["grid_touch_shared_edge"] = grid(A, ((0, 0, 0), (4, 0, 0), (0, 0, 4)))
    s["grid_touch_shared_vertex"] = grid(A, ((0, 0, 0), (-3, 1, 2), (-1, -3, 2)))
    s["grid_touch_vertex_on_edge"] = grid(A, ((2, 2, 0), (2, 2, 4), (5, 5, 2)))
    s["grid_touch_edge_through_edge"] = grid(A, ((2, -1, -1), (2, 1, 1), (2, -3, 3)))
    s["grid_coplanar_overlap"] = grid(A, ((1, 1, 0), (5, 1, 0), (1, 5, 0)))
    s["grid_coplanar_touch_edges"] = grid(A, ((4, 0, 0), (0, 4, 0), (4, 4, 0)))
    s["grid_coplanar_disjoint"] = grid(A, ((3, 3, 0), (6, 3, 0), (3, 6, 0)))
    s["grid_coplanar_identical"] = grid(A, A)
    s["grid_coplanar_contained"] = grid(A, ((1, 1, 0), (2, 1, 0), (1, 2, 0)))
    s["grid_disjoint_parallel"] = grid(A, ((0, 0, 1), (4, 0, 1), (0, 4, 1)))
    s["grid_disjoint_near"] = grid(A, ((1, 1, 1), (3, 1, 1), (1, 1, 5)))
    s["grid_degenerate_segment_cross"] = grid(A, ((1, 1, -2), (1, 1, 2), (1, 1, 0)))
    s["grid_degenerate_segment_in_plane"] = grid(A, ((-1, 1, 0), (3, 1, 0), (1, 1, 0)))
    s["grid_degenerate_point_on_face"] = grid(A, ((1, 1, 0), (1, 1, 0), (1, 1, 0)))
    s["grid_degenerate_point_off"] = grid(A, ((1, 1, 1), (1, 1, 1), (1, 1, 1)))
    s["grid_both_degenerate_collinear"] = grid(((0, 0, 0), (4, 4, 4), (2, 2, 2)), ((3, 3, 3), (8, 8, 8), (5, 5, 5)))
    s["grid_both_degenerate_crossing"] = grid(((0, 0, 0), (4, 0, 0), (2, 0, 0)), ((2, -2, 0), (2, 2, 0), (2, 2, 0)))
    s["grid_both_degenerate_skew"] = grid(((0, 0, 0), (4, 0, 0), (2, 0, 0)), ((2, -2, 1), (2, 2, 1), (2, 0, 1)))
    s["grid_fine_step_cross"] = grid(A, ((1, 1, -2), (2, 1, 2), (1, 2, 2)), exp=-8)
    s["grid_coarse_step_touch"] = grid(A, ((1, 1, 0), (1, 1, 3), (2, 2, 3)), exp=7)
    s["jitter_near_coplanar"] = jitter(A, ((1, 1, 0), (5, 1, 0), (1, 5, 0)), 0, [0] * 11 + [1, 0, 0, 0, 0, -1])
    s["jitter_near_touch_far"] = jitter(A, ((1, 1, 0), (1, 1, 3), (2, 2, 3)), 3, [0] * 9 + [0, 0, -1] + [0] * 6)
    s["jitter_near_degenerate"] = jitter(A, ((-1, 1, 0), (3, 1, 1), (1, 1, 0)), 2, [0] * 12 + [0, 1, 0] + [0] * 3)
    s["jitter_offset_cross"] = jitter(A, ((1, 1, -2), (2, 1, 2), (1, 2, 2)), 1, [3, -2, 1, 0, 0, 5, -8, 7, 0] + [1] * 9)
    s["raw_general_cross"] = raw(((0.1, 0.2, 0.3), (1.7, -0.4, 0.9), (-0.5, 1.3, 0.2)),
                                 ((0.3, 0.1, -1.0), (0.6, 0.8, 1.2), (-0.2, 0.4, 1.1)))
    eps = 2.0 ** -50
    s["raw_nearly_coplanar"] = raw(((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
                                   ((0.2, 0.2, -eps), (0.9, 0.3, eps), (0.3, 0.8, eps)))
    s["raw_far_from_origin"] = raw(((1e12, 1e12, 1e12), (1e12 + 1, 1e12, 1e12), (1e12, 1e12 + 1, 1e12)),
                                   ((1e12 + 0.25, 1e12 + 0.25, 1e12 - 1), (1e12 + 0.25, 1e12 + 0.25, 1e12 + 1),
                                    (1e12 + 0.5, 1e12 + 0.125, 1e12)))
    s["raw_tiny_scale"] = raw(((0.0, 0.0, 0.0), (1e-20, 0.0, 0.0), (0.0, 1e-20, 0.0)),
                              ((2e-21, 2e-21, -1e-20), (3e-21, 2e-21, 1e-20), (2e-21, 3e-21, 1e-20)))
    s["raw_huge_skipped"] = raw(((0.0, 0.0, 0.0), (1e300, 0.0, 0.0), (0.0, 1.0, 0.0)), A)
    s["raw_nan_skipped"] = raw(((math.nan, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), A)
    s["int16_general"] = int16(((100, -200, 300), (-3000, 500, 700), (1200, 1300, -1400)),
                               ((-500, -600, -700), (800, 900, 1000), (1500, -1600, 200)), shift=10)
    s["int16_sliver"] = int16(((0, 0, 0), (30000, 1, 0), (-30000, -1, 1)),
                              ((0, 0, -5), (0, 0, 5), (1, 1, 0)), shift=3)
    # A needle crossing a long thin triangle (found by the fuzzer: Ericson's closest point loses
    # ~1e-9 relative accuracy here, so the checks use their own reference distance).
    s["raw_needle_cross"] = raw(((-0.125, -0.125, 799.0), (0.0, 0.0, 3750.0), (0.125, 0.0, -4090.5)),
                                ((-32.0, 29.0, 0.0), (0.0, 3750.0, 0.125), (0.0, -4091.75, -0.125)))
    s["short_input"] = bytes([1, 8, 8, 8])
    return s


X = float.fromhex


# Minimised fuzzer findings: (target, file name, bytes). Keep them until the library is fixed,
# then keep them as regression tests.
REGRESSIONS = [
    # read_mesh (src/mesh/io/glb.cpp, read_gltf): nlohmann's parser throws out_of_range, not
    # parse_error, for a number beyond double; only parse_error was caught (an uncaught exception).
    # Found by fuzz_read_mesh.
    ("read_mesh", "regression_gltf_number_overflow", b"9e308 world\n\0\0\0\0y\n"),
    # read_fem (src/fem/io/nastran_read.cpp): tab-expanded lines were kept in a std::vector<string>;
    # its growth moved short strings and left the cards' field views dangling (ASan
    # heap-use-after-free). Found by fuzz_read_fem.
    ("read_fem", "regression_nastran_tab_lines_dangling",
     b"BEGIN BULK\n" + b"".join(b"GRID\t%d\t\t%d.\t0.\t0.\n" % (i, i) for i in range(1, 40))
     + b"CTETRA\t1\t1\t1\t2\t3\t4\n"),
    # read_fem (src/fem/io/abaqus_read.cpp, abaqus_type): a TYPE= with a long run of digits
    # overflowed int while parsing the node count (UBSan). Found by fuzz_read_fem.
    ("read_fem", "regression_abaqus_type_digits_overflow",
     b"*NODE\n1,0,0,0\n*ELEMENT, TYPE=C3D" + b"7" * 40 + b"\n1,1\n"),
    # GENERATE over the whole int64 range: first - last overflowed before the size check.
    ("read_fem", "regression_abaqus_generate_int64_range",
     b"*NODE\n1,0,0,0\n*NSET, NSET=a, GENERATE\n-9223372036854775807, 9223372036854775807, 1\n"),
    # read_fem (src/fem/io/scan.cpp read_file_bytes): `INCLUDE /` opened the root directory, whose
    # ftell is huge: std::bad_alloc. Directories (and, for INCLUDE, anything but a regular file) are
    # now refused. Found by fuzz_read_fem.
    ("read_fem", "regression_nastran_include_directory", b"BEGIN BULK\nINCLUDE /\nGRID,1,,0.,0.,0.\n"),
    # write_fem MSH (src/fem/io/msh_write.cpp): a VTU array name with a line break became a
    # $NodeData view name that broke the written file (fuzz_read_fem round trip: "malformed number
    # of real tags"). Names are now written on one line. Found by fuzz_read_fem.
    ("read_fem", "regression_msh_view_name_with_newline",
     b'<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">\n'
     b'<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">\n'
     b'<PointData><DataArray type="Float64" Name="a\nb" NumberOfComponents="3" format="ascii">'
     b"0 0 0 1 1 1 2 2 2 3 3 3</DataArray></PointData>\n"
     b'<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>\n'
     b'<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>'
     b'<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>'
     b'<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells>\n'
     b"</Piece></UnstructuredGrid></VTKFile>\n"),
    # read_fem (src/fem/io/vtk_read.cpp): classic CELLS with a size smaller than the cell count
    # reserved size - n < 0 entries (std::length_error, uncaught). Found by fuzz_read_fem.
    ("read_fem", "regression_vtk_cells_size_below_count",
     b"# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1 float\n0 0 0\n"
     b"CELLS 3 1\n1\nCELL_TYPES 3\n1 1 1\n"),
    # read_fem (src/fem/io/abaqus_read.cpp): an assembly whose instantiated part has nodes but no
    # elements was read "successfully" as a mesh without elements (fuzz_read_fem: "success without
    # elements"); now "no elements". Found by fuzz_read_fem from assembly.inp.
    ("read_fem", "regression_abaqus_instance_without_elements",
     b"*PART, NAME=p\n*NODE\n1, 0., 0., 0.\n*END PART\n*ASSEMBLY, NAME=a\n"
     b"*INSTANCE, NAME=i, PART=p\n*END INSTANCE\n*END ASSEMBLY\n"),
    # closest_point_on_triangle (src/np/distance.cpp) returns NaN: the cross end p = (-4.8, -4.8, -4.8)
    # against A, a needle with a 2^-60-long edge AB at a right angle to AC. p - a and p - b round to
    # the same vector, so d1 = d3 = 0, the edge-AB branch is taken and returns a + ab * (0 / 0).
    # Found by fuzz_tri_tri (mode 2); stored as raw doubles (mode 0).
    ("tri_tri", "regression_closest_point_nan_needle",
     raw(((0.0, 0.0, -2.0 ** -60), (-2.0 ** -60, 0.0, 0.0), (-8.0, X("-0x1.0000000000001p+3"), -8.0)),
         ((-8.0, 8.0, -8.0), (-8.0, -8.0, 0.0), (0.0, -8.0, -8.0)))),
    # closest_point_on_triangle returns (5, -1, -4.5), 1.3 away from p = the first cross end, which
    # lies on edge B1-B2 (exact distance ~1e-15). B0 and B2 are 1 ulp apart (a needle that exact
    # welding keeps): the sliver test looks at the angle at B0 only, which is not small, and the
    # region tests of Ericson §5.1.5 then read rounding noise (d2 = 2e-14). Rotating B's corners
    # gives the right point. Found by fuzz_tri_tri (mode 2); stored as raw doubles.
    ("tri_tri", "regression_closest_point_wrong_needle",
     raw(((8.0, 4.0, X("-0x1.0000000000006p+1")), (3.0, -8.0, -8.0),
          (8.0, X("-0x1.ffffffffffffep+2"), X("-0x1.7fffffffffff9p+2"))),
         ((X("0x1.0000000000001p+3"), X("-0x1.0000000000001p+3"), X("-0x1.0000000000001p+3")),
          (X("0x1.0000000000001p+1"), X("0x1.7ffffffffffffp+2"), -1.0), (8.0, -8.0, -8.0)))),
    # Still NaN after the needle fix (distance.cpp of 09:34): a well-shaped triangle A of size
    # ~2^-58 and a corner p of B 14 away. p - a, p - b and p - c round to the same vector and
    # ab = (1.75, -1.75, 0)·2^-58 is orthogonal to it, so d1 = d3 = 0 and the edge-AB branch returns
    # a + ab * (0 / 0). Found by fuzz_tri_tri (mode 0) against the fixed library.
    ("tri_tri", "regression_closest_point_nan_tiny_far",
     raw(((X("-0x1.cp-58"), X("0x1.cp-58"), 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, X("-0x1.4p-58"))),
         ((X("-0x1p-60"), X("-0x1p-60"), X("-0x1p-60")),
          (X("-0x1.0000000000001p+3"), X("-0x1.0000000000001p+3"), X("-0x1.0000000000001p+3")),
          (X("0x1.8p-59"), 0.0, X("-0x1p-60"))))),
    # tri_tri_exact (src/np/tri_tri_exact.cpp, edge_edge_point): the cross end where edge 2 of A
    # (a2 -> a0) crosses edge 2 of B (b2 -> b0), two edges nearly along (1,1,1), is returned as
    # (-4, -4, -4) instead of the exact (-7.999999999999984, ...) (0x1.fffffffffffeep+2): the
    # projection axis comes from the double cross product of the edges (rounding noise here), the
    # chosen projection makes both edges exactly parallel (direction (1,1) in yz), the two heights
    # are equal, den == 0 and the fallback alpha = 0.5 gives the edge midpoint. The same pair with
    # the axes permuted, (x,y,z) -> (y,z,x), gives the exact point. Found by fuzz_tri_tri (mode 0).
    ("tri_tri", "regression_edge_edge_point_parallel_projection",
     raw(((X("-0x1p-58"), 0.0, 0.0), (4.0, -6.0, X("-0x1.ffffffffffffep+2")), (-8.0, -8.0, -8.0)),
         ((0.0, X("0x1.8p-58"), X("0x1.8p-58")), (X("0x1.8p-58"), X("0x1.8p-58"), X("-0x1.ffffffffffffap+2")),
          (X("-0x1.ffffffffffffap+2"), X("-0x1.ffffffffffffap+2"), X("-0x1.ffffffffffffap+2"))))),
]


def fem_seeds():
    """corpus/read_fem/: the committed FEM test files (tests/data/fem, see its README) and a few
    broken variants."""
    src = os.path.join(HERE, "..", "data", "fem")
    seeds = {}
    for name in sorted(os.listdir(src)):
        if name.endswith((".py", ".md")):
            continue
        with open(os.path.join(src, name), "rb") as f:
            data = f.read()
        seeds[name] = data
        seeds["trunc_" + name] = data[: len(data) * 2 // 3]
    return seeds


def simplify_seeds():
    """corpus/simplify/: byte strings for fuzz_simplify.cpp (byte 0 = shape | feature mode << 2 |
    sharp angle << 4 | guard every collapse << 5 | no batched passes << 6, byte 1 = ratio, byte 2 =
    size, then the shape's bytes), from a fixed linear congruential generator: every shape with every
    feature mode, some with the other flags."""
    state = [12345]

    def rand_bytes(n):
        out = bytearray()
        for _ in range(n):
            state[0] = (state[0] * 1103515245 + 12345) % (1 << 31)
            out.append((state[0] >> 16) & 0xFF)
        return bytes(out)

    seeds = {}
    for shape in range(4):
        for mode in range(4):
            for extra in (0, 1):
                flags = shape | mode << 2 | (extra * (16 if shape != 1 else 32))
                ratio = (7 + 31 * mode + 13 * extra) % 100
                size = (5 + 17 * shape + 3 * mode) % 256
                n = {0: 500, 1: 40, 2: 600, 3: 500}[shape]
                body = rand_bytes(n)
                if shape == 3:  # the exponent byte: very small, very large, moderate
                    body = bytes([(mode * 70 + extra * 20) % 256]) + body
                seeds["shape%d_mode%d_%s" % (shape, mode, "extra" if extra else "plain")] = (
                    bytes([flags, ratio, size]) + body)
    seeds["height_field_no_passes"] = bytes([0 | 1 << 2 | 64, 20, 11]) + rand_bytes(400)
    return seeds


def step_seeds():
    """corpus/read_step/: the committed STEP test files (tests/cli/data, see its README) and broken
    variants: truncated, a syntax error, an unresolved reference, an oriented edge that is its own
    edge (a reference cycle: OCCT's checks recursed until the stack overflowed), an oriented edge
    whose edge is a point (a mistyped reference)."""
    import re
    src = os.path.join(HERE, "..", "cli", "data")
    seeds = {}
    for name in ("counterbored_plate.step", "assembly.step"):
        with open(os.path.join(src, name), "rb") as f:
            text = f.read().decode("latin-1")
        stem = name.split(".")[0]
        seeds[name] = text
        seeds[stem + "_truncated.step"] = text[: len(text) * 3 // 5]
        at = text.index("#30 =")
        seeds[stem + "_syntax.step"] = text[:at] + "#30 = = FOO;\n" + text[at:]
        edge = re.search(r"#(\d+) = ORIENTED_EDGE\('',\*,\*,#(\d+)", text)
        point = re.search(r"#(\d+) = CARTESIAN_POINT", text)
        swap = lambda new: text[: edge.start(2)] + new + text[edge.end(2):]
        seeds[stem + "_unresolved.step"] = swap("99999")
        seeds[stem + "_cycle.step"] = swap(edge.group(1))
        seeds[stem + "_mistyped.step"] = swap(point.group(1))
    return {k: v.encode("latin-1") for k, v in seeds.items()}


def main():
    for target, seeds in (("read_mesh", mesh_seeds()), ("tri_tri", tri_seeds()), ("read_fem", fem_seeds()),
                          ("simplify", simplify_seeds()), ("read_step", step_seeds())):
        d = os.path.join(CORPUS, target)
        if os.path.isdir(d):
            shutil.rmtree(d)
        os.makedirs(d)
        for name, data in seeds.items():
            with open(os.path.join(d, name), "wb") as f:
                f.write(data)
    for target, name, data in REGRESSIONS:
        with open(os.path.join(CORPUS, target, name), "wb") as f:
            f.write(data)
    total = sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(CORPUS) for f in fs)
    count = sum(len(fs) for _, _, fs in os.walk(CORPUS))
    print("wrote %d files, %d bytes, under %s" % (count, total, CORPUS))
    return 0


if __name__ == "__main__":
    sys.exit(main())
