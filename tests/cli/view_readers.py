"""Small independent readers of the pictures the commands write (issue #25), for the CLI tests:
the binary glTF container and its JSON chunk (glTF 2.0, section 4.4), accessors, and ParaView's
.pvd collections with their VTK XML PolyData pieces (ascii, or base64 with zlib-compressed blocks).
Standard library only; shares no code with the writers (src/view/gltf.cpp, pvd.cpp)."""
import base64
import json
import struct
import xml.etree.ElementTree as ET
import zlib


def read_glb(p):
    """(JSON chunk, BIN chunk) of a binary glTF file, checking the container (glTF 2.0, section 4.4)."""
    with open(p, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert magic == 0x46546C67 and version == 2 and length == len(data), (magic, version, length, len(data))
    chunks, off = [], 12
    while off < len(data):
        n, kind = struct.unpack_from("<II", data, off)
        assert n % 4 == 0, n
        chunks.append((kind, data[off + 8:off + 8 + n]))
        off += 8 + n
    assert off == len(data)
    assert chunks[0][0] == 0x4E4F534A, "first chunk is not JSON"
    doc = json.loads(chunks[0][1].decode("utf-8"))
    binary = chunks[1][1] if len(chunks) > 1 and chunks[1][0] == 0x004E4942 else b""
    return doc, binary


def accessor_values(doc, binary, index):
    """The values of a float32/uint32 accessor as a list of tuples."""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    comps = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[acc["type"]]
    fmt = {5126: "f", 5125: "I", 5123: "H", 5121: "B"}[acc["componentType"]]
    size = struct.calcsize(fmt)
    stride = view.get("byteStride", comps * size)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return [struct.unpack_from("<%d%s" % (comps, fmt), binary, start + i * stride) for i in range(acc["count"])]


def vtk_array(element):
    """The values of a VTK XML DataArray: ascii, or binary zlib-compressed with a UInt64 header
    [#blocks, block size, last block size, compressed sizes...] (vtkZLibDataCompressor)."""
    kind = {"Int32": "i", "Int64": "q", "UInt8": "B", "Float64": "d", "Float32": "f", "UInt64": "Q"}[element.get("type")]
    text = "".join(element.text.split())
    if element.get("format") == "ascii":
        return [float(x) if kind in "df" else int(x) for x in text.split()]
    first = base64.b64decode(text[:32])  # 24 bytes: the first three header words
    nblocks = struct.unpack_from("<Q", first, 0)[0]
    head_len = 8 * (3 + nblocks)
    head_chars = 4 * ((head_len + 2) // 3)
    head = base64.b64decode(text[:head_chars])
    sizes = struct.unpack_from("<%dQ" % nblocks, head, 24)
    body = base64.b64decode(text[head_chars:])
    raw, off = b"", 0
    for s in sizes:
        raw += zlib.decompress(body[off:off + s])
        off += s
    n = len(raw) // struct.calcsize(kind)
    return list(struct.unpack("<%d%s" % (n, kind), raw))


def read_vtp(p):
    """{name: values} of a PolyData piece's cell data, point data, points and polygons, plus counts."""
    piece = ET.parse(p).getroot().find("PolyData").find("Piece")
    out = {"points": int(piece.get("NumberOfPoints")), "polys": int(piece.get("NumberOfPolys")),
           "lines": int(piece.get("NumberOfLines")), "cell": {}, "point": {}}
    for section, key in (("CellData", "cell"), ("PointData", "point")):
        node = piece.find(section)
        if node is not None:
            for a in node.findall("DataArray"):
                out[key][a.get("Name")] = vtk_array(a)
    pts = piece.find("Points")
    if pts is not None and out["points"]:
        flat = vtk_array(pts.find("DataArray"))
        out["xyz"] = [tuple(flat[i:i + 3]) for i in range(0, len(flat), 3)]
    polys = piece.find("Polys")
    if polys is not None and out["polys"]:
        arrays = {a.get("Name"): vtk_array(a) for a in polys.findall("DataArray")}
        conn, offs = arrays["connectivity"], arrays["offsets"]
        out["poly_points"] = [conn[(offs[i - 1] if i else 0):offs[i]] for i in range(len(offs))]
    return out


def read_pvd(p):
    """The collection's data sets as (timestep, part, name, file) in file order."""
    root = ET.parse(p).getroot()
    assert root.get("type") == "Collection", root.get("type")
    return [(float(d.get("timestep")), int(d.get("part", "0")), d.get("name"), d.get("file"))
            for d in root.find("Collection").findall("DataSet")]
