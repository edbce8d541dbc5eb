// glTF 2.0 reader, binary (GLB) and JSON (.gltf): the triangles of the default scene, every mesh
// instance placed by its nodes' transforms (Khronos glTF 2.0 specification §3.5 "Nodes and
// hierarchy", §3.6 "Binary data storage", §3.7 "Geometry"), so that a digital-twin model
// (`interfere simplify ... OUT.glb`, or any renderer's glTF) can be clash-checked as it is placed.
// Coordinates are the file's (glTF: metres).
//
// Read: buffers from the GLB's BIN chunk (buffer 0 without a `uri`), from `data:` URIs (base64,
// §3.6.1.1) or from files named by relative URIs (percent-encoded, resolved against the glTF
// file's folder; a URI with a scheme such as http: is an error: nothing is fetched), each cut to
// its byteLength; buffer views with byteStride, accessors (VEC3 positions, FLOAT or, with
// KHR_mesh_quantization, integers, normalized or not, as gltfpack writes them; UNSIGNED_BYTE/SHORT/
// INT indices or none), primitives of mode TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (points and
// lines carry no surface and are skipped), node `matrix` or translation/rotation/scale composed in
// double (a mirroring node's triangles reversed, §3.7.2.1). Sparse accessors, Draco and any other
// required extension are errors naming the accessor or the extension. Every index, offset and
// length is checked before it is used. One walk of the scene's nodes (walk_gltf, glb.h) serves
// the flattening reader and scene::read_gltf_bodies.
#include "glb.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formats.h"
#include "interfere/core/base64.h"
#include "interfere/core/transform.h"

namespace interfere::io_detail {
namespace {

std::uint32_t u32_at(std::string_view d, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, d.data() + at, 4);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  return v;
}

using Json = nlohmann::json;

Mat4 identity() {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[col * 4 + k];
      c[col * 4 + row] = s;
    }
  return c;
}

// The reader of one file: the document, the BIN chunk, and errors that name the JSON path.
class GlbReader {
 public:
  // `glb`: the document came from a GLB (buffer 0 may be its BIN chunk); `dir`: the folder
  // relative buffer URIs are resolved against.
  GlbReader(const std::string& path, const GlbChunks& chunks, Json doc, bool glb,
            std::filesystem::path dir)
      : path_(path), chunks_(chunks), doc_(std::move(doc)), glb_(glb), dir_(std::move(dir)) {}

  // Visits every node with a mesh of the default scene, depth first in the scene's order, with
  // its world matrix and its mesh in node coordinates (parsed once per glTF mesh).
  Status walk(const GltfVisitor& visitor) {
    visitor_ = &visitor;
    if (!doc_.is_object()) return fail("", "the JSON chunk is not an object");
    if (const Json* ext = member(doc_, "extensionsRequired"); ext && ext->is_array())
      for (const Json& e : *ext)
        if (e.is_string() &&
            e.get<std::string>() != "KHR_mesh_quantization")  // (read: integer positions)
          return fail("extensionsRequired",
                      "extension " + e.get<std::string>() + " is not supported");
    if (Status s = load_buffers(); !s) return s.error();
    // The scene: `scene`, else scene 0; with no scenes, every root node (a node no other names).
    std::vector<std::size_t> roots;
    const Json* nodes = member(doc_, "nodes");
    const std::size_t node_count = nodes && nodes->is_array() ? nodes->size() : 0;
    if (const Json* scenes = member(doc_, "scenes");
        scenes && scenes->is_array() && !scenes->empty()) {
      std::size_t s = 0;
      if (const Json* sc = member(doc_, "scene")) {
        if (!index_of(*sc, scenes->size(), s)) return fail("scene", "not an index of scenes");
      }
      const Json& scene = (*scenes)[s];
      if (const Json* list = member(scene, "nodes")) {
        if (!list->is_array())
          return fail("scenes[" + std::to_string(s) + "].nodes", "not an array");
        for (std::size_t k = 0; k < list->size(); ++k) {
          std::size_t n = 0;
          if (!index_of((*list)[k], node_count, n))
            return fail("scenes[" + std::to_string(s) + "].nodes[" + std::to_string(k) + "]",
                        "not an index of nodes");
          roots.push_back(n);
        }
      }
    } else {
      std::vector<char> child(node_count, 0);
      for (std::size_t n = 0; n < node_count; ++n)
        if (const Json* c = member((*nodes)[n], "children"); c && c->is_array())
          for (const Json& x : *c)
            if (std::size_t k = 0; index_of(x, node_count, k)) child[k] = 1;
      for (std::size_t n = 0; n < node_count; ++n)
        if (!child[n]) roots.push_back(n);
    }
    visited_.assign(node_count, 0);
    for (std::size_t r : roots)
      if (Status s = visit(r, identity(), ""); !s) return s.error();
    return {};
  }

  // The flattened scene: every node's mesh placed by its world matrix, in double.
  Expected<TriMesh> read() {
    TriMesh out;
    const Status s = walk([&](const GltfMeshNode& n) -> Status {
      const Mat4& m = n.world;
      const auto base = static_cast<std::uint32_t>(out.positions.size());
      if (n.local->positions.size() > std::uint64_t{0xffffffffu} - base)
        return fail("nodes[" + std::to_string(n.node) + "]", "too many vertices");
      for (std::size_t i = 0; i < n.local->positions.size(); ++i) {
        const Vec3& f = n.local->positions[i];
        double p[3];
        for (int r = 0; r < 3; ++r) p[r] = m[r] * f.x + m[4 + r] * f.y + m[8 + r] * f.z + m[12 + r];
        const Vec3 q{p[0], p[1], p[2]};
        if (!is_finite(q))
          return fail("nodes[" + std::to_string(n.node) + "]",
                      "vertex " + std::to_string(i) + " of meshes[" + std::to_string(n.mesh) +
                          "] is not finite once placed");
        out.positions.push_back(q);
      }
      // A mirroring node (negative determinant, decided exactly) turns its faces clockwise
      // (§3.7.2.1): reversed here, so that outward faces stay outward.
      Transform lin;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) lin.r[r][c] = m[c * 4 + r];
      const bool mirrored = lin.determinant_sign() < 0;
      for (const Tri& t : n.local->triangles)
        out.triangles.push_back(mirrored ? Tri{base + t[0], base + t[2], base + t[1]}
                                         : Tri{base + t[0], base + t[1], base + t[2]});
      return {};
    });
    if (!s) return s.error();
    if (out.triangles.empty())
      return fail("", "no triangles: the scene has no triangle primitives");
    return out;
  }

 private:
  Error fail(const std::string& where, const std::string& why) const {
    return byte_error(path_, chunks_.json_at,
                      "glTF " + (where.empty() ? std::string("document") : where) + ": " + why);
  }
  static const Json* member(const Json& j, const char* key) {
    if (!j.is_object()) return nullptr;
    const auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
  }
  static bool index_of(const Json& j, std::size_t size, std::size_t& out) {
    if (!j.is_number_unsigned() && !(j.is_number_integer() && j.get<std::int64_t>() >= 0))
      return false;
    const auto v = j.get<std::uint64_t>();
    if (v >= size) return false;
    out = static_cast<std::size_t>(v);
    return true;
  }
  // An unsigned integer member (default when absent).
  bool count_of(const Json& j, const char* key, std::uint64_t& out, std::uint64_t fallback) const {
    const Json* m = member(j, key);
    if (!m) {
      out = fallback;
      return true;
    }
    if (!m->is_number_unsigned() && !(m->is_number_integer() && m->get<std::int64_t>() >= 0))
      return false;
    out = m->get<std::uint64_t>();
    return true;
  }

  // Every buffer's bytes (buffers_[b], cut to its byteLength): the BIN chunk, a data: URI or a
  // file.
  Status load_buffers() {
    const Json* buffers = member(doc_, "buffers");
    if (!buffers) return {};
    if (!buffers->is_array()) return fail("buffers", "not an array");
    owned_.resize(buffers->size());  // (not resized again: buffers_ points into it)
    for (std::size_t b = 0; b < buffers->size(); ++b) {
      const std::string where = "buffers[" + std::to_string(b) + "]";
      std::uint64_t length = 0;
      if (!count_of((*buffers)[b], "byteLength", length, 0))
        return fail(where + ".byteLength", "not a length");
      std::string_view bytes;
      std::string source;
      if (const Json* uri = member((*buffers)[b], "uri")) {
        if (!uri->is_string()) return fail(where + ".uri", "not a string");
        auto fetched = fetch(uri->get<std::string>(), where + ".uri", length);
        if (!fetched) return fetched.error();
        owned_[b] = std::move(*fetched);
        bytes = owned_[b];
        source = "its uri holds";
      } else {
        if (!glb_)
          return fail(where, "no uri: a .gltf file keeps its buffers in files or data: URIs");
        if (b > 0) return fail(where, "no uri: only buffer 0 can be the GLB's BIN chunk");
        bytes = chunks_.bin;
        source = "the BIN chunk has";
      }
      if (length > bytes.size())
        return fail(where + ".byteLength", std::to_string(length) + " bytes, but " + source + " " +
                                               std::to_string(bytes.size()));
      buffers_.push_back(bytes.substr(0, length));
    }
    return {};
  }

  // The bytes a buffer URI names: base64 data, or the first `length` bytes (or fewer, when it is
  // shorter) of a regular file relative to the glTF file's folder (not a device or a pipe, which
  // could be endless).
  Expected<std::string> fetch(const std::string& uri, const std::string& where,
                              std::uint64_t length) const {
    if (uri.rfind("data:", 0) == 0) {
      const std::size_t comma = uri.find(',');
      if (comma == std::string::npos || uri.compare(0, comma, "data:") == 0 || comma < 7 ||
          uri.compare(comma - 7, 7, ";base64") != 0)
        return fail(where, "a data: URI must be base64 (data:<type>;base64,<data>)");
      std::size_t bad = 0;
      auto bytes = base64_decode(std::string_view(uri).substr(comma + 1), bad);
      if (!bytes)
        return fail(where, "not base64 at character " + std::to_string(comma + 2 + bad) +
                               " of the URI (from 1)");
      return std::move(*bytes);
    }
    // A scheme (RFC 3986 §3.1: a letter, then letters, digits, + - ., then ':') before any '/'.
    if (const std::size_t colon = uri.find(':');
        colon != std::string::npos && colon > 0 && uri.find('/') > colon) {
      bool scheme = std::isalpha(static_cast<unsigned char>(uri[0])) != 0;
      for (std::size_t i = 1; i < colon && scheme; ++i)
        scheme = std::isalnum(static_cast<unsigned char>(uri[i])) || uri[i] == '+' ||
                 uri[i] == '-' || uri[i] == '.';
      if (scheme)
        return fail(
            where,
            "'" + uri + "': only relative file paths and data: URIs are read (nothing is fetched)");
    }
    std::string name;  // percent-decoded (RFC 3986 §2.1)
    for (std::size_t i = 0; i < uri.size(); ++i) {
      if (uri[i] != '%') {
        name.push_back(uri[i]);
        continue;
      }
      const auto hex = [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return !std::isxdigit(u) ? -1 : std::isdigit(u) ? c - '0' : (c | 32) - 'a' + 10;
      };
      if (i + 2 >= uri.size() || hex(uri[i + 1]) < 0 || hex(uri[i + 2]) < 0)
        return fail(where, "'" + uri + "': a bad percent escape at character " +
                               std::to_string(i + 1) + " (from 1)");
      name.push_back(static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2])));
      i += 2;
    }
    if (name.empty() || name.find('\0') != std::string::npos) return fail(where, "not a file name");
    const std::filesystem::path file = dir_ / std::filesystem::path(name);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      return fail(where, "cannot open " + file.string() + " (no such file)");
    const std::uint64_t size = std::filesystem::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    if (ec || !in) return fail(where, "cannot open " + file.string());
    std::string bytes(static_cast<std::size_t>(std::min(size, length)), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
      return fail(where, "cannot read " + file.string());
    return bytes;
  }

  // The bytes of accessor `a` as (pointer to element 0, stride, count), checked against its view
  // and the BIN chunk; `components` and `component_bytes` are the element's.
  struct View {
    const char* first = nullptr;
    std::uint64_t stride = 0, count = 0;
    std::uint32_t component_type = 0;
    bool normalized = false;
  };
  Expected<View> accessor(std::size_t a, const std::string& type, bool index) {
    const Json* accessors = member(doc_, "accessors");
    const std::string where = "accessors[" + std::to_string(a) + "]";
    if (!accessors || !accessors->is_array() || a >= accessors->size())
      return fail(where, "no such accessor");
    const Json& acc = (*accessors)[a];
    if (member(acc, "sparse")) return fail(where, "sparse accessors are not supported");
    const Json* t = member(acc, "type");
    if (!t || !t->is_string() || t->get<std::string>() != type)
      return fail(where + ".type", "must be " + type + (index ? " (indices)" : " (POSITION)"));
    std::uint64_t ct = 0, count = 0, offset = 0;
    if (!count_of(acc, "componentType", ct, 0))
      return fail(where + ".componentType", "not a number");
    std::uint64_t size = 0;
    if (index) {
      size = ct == 5121 ? 1 : ct == 5123 ? 2 : ct == 5125 ? 4 : 0;
      if (size == 0)
        return fail(where + ".componentType",
                    std::to_string(ct) + " is not an unsigned byte, short or int");
    } else {
      // FLOAT, or KHR_mesh_quantization's (normalized) BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT.
      size = ct == 5126 ? 12 : ct == 5120 || ct == 5121 ? 3 : ct == 5122 || ct == 5123 ? 6 : 0;
      if (size == 0)
        return fail(where + ".componentType",
                    std::to_string(ct) +
                        ": positions must be FLOAT (5126) or, quantized (KHR_mesh_quantization), "
                        "BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT (5120-5123)");
    }
    bool normalized = false;
    if (const Json* nm = member(acc, "normalized")) {
      if (!nm->is_boolean()) return fail(where + ".normalized", "not a boolean");
      normalized = nm->get<bool>();
      if (normalized && (index || ct == 5126))
        return fail(where + ".normalized", "only integer positions are normalized");
    }
    if (!count_of(acc, "count", count, 0) || count == 0)
      return fail(where + ".count", "must be at least 1");
    if (!count_of(acc, "byteOffset", offset, 0))
      return fail(where + ".byteOffset", "not an offset");
    std::size_t v = 0;
    const Json* views = member(doc_, "bufferViews");
    const Json* bv = member(acc, "bufferView");
    if (!bv) return fail(where, "an accessor without a bufferView (all zeros) carries no geometry");
    if (!views || !views->is_array() || !index_of(*bv, views->size(), v))
      return fail(where + ".bufferView", "not an index of bufferViews");
    const Json& view = (*views)[v];
    const std::string vwhere = "bufferViews[" + std::to_string(v) + "]";
    std::uint64_t buffer = 0, voffset = 0, vlength = 0, stride = 0;
    if (!count_of(view, "buffer", buffer, 0) || buffer >= buffers_.size())
      return fail(vwhere + ".buffer", "not an index of buffers");
    if (!count_of(view, "byteOffset", voffset, 0))
      return fail(vwhere + ".byteOffset", "not an offset");
    if (!count_of(view, "byteLength", vlength, 0))
      return fail(vwhere + ".byteLength", "not a length");
    if (!count_of(view, "byteStride", stride, 0) ||
        (stride != 0 && (stride < size || stride > 252)))
      return fail(vwhere + ".byteStride", "must lie in [element size, 252]");
    if (stride == 0 || index) stride = size;  // (indices are tightly packed)
    const std::string_view data = buffers_[buffer];
    const std::uint64_t bin = data.size();
    if (voffset > bin || vlength > bin - voffset)
      return fail(vwhere, "bytes " + std::to_string(voffset) + " + " + std::to_string(vlength) +
                              " lie beyond buffers[" + std::to_string(buffer) + "] (" +
                              std::to_string(bin) + " bytes)");
    // The last element's end: offset + (count - 1) * stride + size, overflow-checked.
    if (count - 1 > (vlength - std::min(vlength, offset)) / stride || offset > vlength ||
        offset + (count - 1) * stride + size > vlength)
      return fail(where, std::to_string(count) + " elements from byte " + std::to_string(offset) +
                             " do not fit " + vwhere + " (" + std::to_string(vlength) + " bytes)");
    return View{data.data() + voffset + offset, stride, count, static_cast<std::uint32_t>(ct),
                normalized};
  }

  // Component k of an integer position (KHR_mesh_quantization; little endian), normalized as glTF
  // §3.11 says: max(c / 127, -1), c / 255, max(c / 32767, -1), c / 65535.
  static double quantized(const char* e, int k, std::uint32_t type, bool normalized) {
    const auto byte = [&](int i) { return static_cast<unsigned char>(e[i]); };
    switch (type) {
      case 5120: {
        const double c = static_cast<signed char>(byte(k));
        return normalized ? std::max(c / 127.0, -1.0) : c;
      }
      case 5121:
        return normalized ? byte(k) / 255.0 : byte(k);
      case 5122: {
        const double c = static_cast<std::int16_t>(
            static_cast<std::uint16_t>(byte(2 * k) | byte(2 * k + 1) << 8));
        return normalized ? std::max(c / 32767.0, -1.0) : c;
      }
      default: {
        const double c = static_cast<std::uint16_t>(byte(2 * k) | byte(2 * k + 1) << 8);
        return normalized ? c / 65535.0 : c;
      }
    }
  }

  // Appends the primitive's triangles to `mesh_` (node coordinates).
  Status primitive(const Json& prim, const std::string& where) {
    std::uint64_t mode = 4;
    if (!count_of(prim, "mode", mode, 4) || mode > 6)
      return fail(where + ".mode", "not a primitive mode");
    if (mode < 4) return {};  // points and lines: no surface
    if (const Json* ext = member(prim, "extensions");
        ext && member(*ext, "KHR_draco_mesh_compression"))
      return fail(where, "Draco-compressed primitives are not supported");
    const Json* attrs = member(prim, "attributes");
    const Json* pos = attrs ? member(*attrs, "POSITION") : nullptr;
    std::size_t pa = 0;
    if (!pos || !index_of(*pos, std::numeric_limits<std::size_t>::max(), pa))
      return fail(where + ".attributes.POSITION", "missing");
    auto pv = accessor(pa, "VEC3", false);
    if (!pv) return pv.error();
    const auto base = static_cast<std::uint32_t>(mesh_.positions.size());
    if (pv->count > std::uint64_t{0xffffffffu} - base) return fail(where, "too many vertices");
    for (std::uint64_t i = 0; i < pv->count; ++i) {
      double f[3];
      const char* e = pv->first + i * pv->stride;
      for (int k = 0; k < 3; ++k) {
        if (pv->component_type == 5126) {
          const std::uint32_t bits = u32_at({e + 4 * k, 4}, 0);
          float x;
          std::memcpy(&x, &bits, 4);
          if (!std::isfinite(x))
            return fail("accessors[" + std::to_string(pa) + "]",
                        "vertex " + std::to_string(i) + " is not finite");
          f[k] = x;
        } else {
          f[k] = quantized(e, k, pv->component_type, pv->normalized);
        }
      }
      mesh_.positions.push_back({f[0], f[1], f[2]});
    }
    // Indices: the accessor, or 0..count-1.
    std::vector<std::uint32_t> idx;
    if (const Json* ind = member(prim, "indices")) {
      std::size_t ia = 0;
      if (!index_of(*ind, std::numeric_limits<std::size_t>::max(), ia))
        return fail(where + ".indices", "not an index");
      auto iv = accessor(ia, "SCALAR", true);
      if (!iv) return iv.error();
      idx.resize(iv->count);
      for (std::uint64_t i = 0; i < iv->count; ++i) {
        const char* e = iv->first + i * iv->stride;
        std::uint32_t v = 0;
        if (iv->component_type == 5121)
          v = static_cast<unsigned char>(*e);
        else if (iv->component_type == 5123)
          v = static_cast<std::uint32_t>(static_cast<unsigned char>(e[0]) |
                                         (static_cast<unsigned char>(e[1]) << 8));
        else
          v = u32_at({e, 4}, 0);
        if (v >= pv->count)
          return fail("accessors[" + std::to_string(ia) + "]",
                      "index " + std::to_string(i) + " is " + std::to_string(v) + ", beyond the " +
                          std::to_string(pv->count) + " vertices");
        idx[i] = v;
      }
    } else {
      idx.resize(pv->count);
      for (std::uint32_t i = 0; i < idx.size(); ++i) idx[i] = i;
    }
    const auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      mesh_.triangles.push_back({base + a, base + b, base + c});
    };
    if (mode == 4) {
      if (idx.size() % 3 != 0)
        return fail(where,
                    std::to_string(idx.size()) + " indices: not a multiple of 3 (TRIANGLES)");
      for (std::size_t i = 0; i + 2 < idx.size(); i += 3) tri(idx[i], idx[i + 1], idx[i + 2]);
    } else if (mode == 5) {  // strip: every other triangle reversed to keep the winding
      for (std::size_t i = 0; i + 2 < idx.size(); ++i)
        i % 2 == 0 ? tri(idx[i], idx[i + 1], idx[i + 2]) : tri(idx[i + 1], idx[i], idx[i + 2]);
    } else {  // fan
      for (std::size_t i = 1; i + 1 < idx.size(); ++i) tri(idx[0], idx[i], idx[i + 1]);
    }
    return {};
  }

  Expected<Mat4> local(const Json& node, const std::string& where) const {
    const auto numbers = [&](const char* key, std::size_t n, std::vector<double>& out) -> Status {
      const Json* v = member(node, key);
      if (!v) return {};
      if (!v->is_array() || v->size() != n)
        return fail(where + "." + key, "must hold " + std::to_string(n) + " numbers");
      for (const Json& x : *v) {
        if (!x.is_number() || !std::isfinite(x.get<double>()))
          return fail(where + "." + key, "not a finite number");
        out.push_back(x.get<double>());
      }
      return {};
    };
    std::vector<double> mat, t, r, s;
    if (Status st = numbers("matrix", 16, mat); !st) return st.error();
    if (!mat.empty()) {
      Mat4 m;
      std::copy(mat.begin(), mat.end(), m.begin());
      return m;
    }
    if (Status st = numbers("translation", 3, t); !st) return st.error();
    if (Status st = numbers("rotation", 4, r); !st) return st.error();
    if (Status st = numbers("scale", 3, s); !st) return st.error();
    // T * R * S (§3.5.3), the quaternion (x, y, z, w) normalised.
    double qx = 0, qy = 0, qz = 0, qw = 1;
    if (!r.empty()) {
      const double l = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
      if (!(l > 0)) return fail(where + ".rotation", "a zero quaternion");
      qx = r[0] / l, qy = r[1] / l, qz = r[2] / l, qw = r[3] / l;
    }
    const double sx = s.empty() ? 1 : s[0], sy = s.empty() ? 1 : s[1], sz = s.empty() ? 1 : s[2];
    Mat4 m = identity();
    const double R[3][3] = {
        {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)},
        {2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)},
        {2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)}};
    const double S[3] = {sx, sy, sz};
    for (int c = 0; c < 3; ++c)
      for (int row = 0; row < 3; ++row) m[c * 4 + row] = R[row][c] * S[c];
    if (!t.empty()) m[12] = t[0], m[13] = t[1], m[14] = t[2];
    return m;
  }

  // The mesh `k` in its own coordinates, parsed at its first use.
  Expected<std::shared_ptr<const TriMesh>> mesh(std::size_t k) {
    if (k < meshes_.size() && meshes_[k]) return meshes_[k];
    const Json* prims = member(doc_["meshes"][k], "primitives");
    const std::string mw = "meshes[" + std::to_string(k) + "].primitives";
    if (!prims || !prims->is_array()) return fail(mw, "missing");
    mesh_ = TriMesh{};
    for (std::size_t p = 0; p < prims->size(); ++p)
      if (Status s = primitive((*prims)[p], mw + "[" + std::to_string(p) + "]"); !s)
        return s.error();
    if (meshes_.size() <= k) meshes_.resize(k + 1);
    meshes_[k] = std::make_shared<const TriMesh>(std::move(mesh_));
    return meshes_[k];
  }

  Status visit(std::size_t n, const Mat4& parent, const std::string& parent_path, int depth = 0) {
    const Json& nodes = doc_["nodes"];
    const std::string where = "nodes[" + std::to_string(n) + "]";
    if (visited_[n])
      return fail(where, "reached twice (glTF nodes form a tree: one parent each, no cycles)");
    if (depth > kMaxDepth)
      return fail(where, "nested deeper than " + std::to_string(kMaxDepth) + " nodes");
    visited_[n] = 1;
    const Json& node = nodes[n];
    auto l = local(node, where);
    if (!l) return l.error();
    const Mat4 m = multiply(parent, *l);
    std::string name;
    if (const Json* nm = member(node, "name"); nm && nm->is_string()) name = nm->get<std::string>();
    const std::string path = parent_path + "/" + (name.empty() ? "node" + std::to_string(n) : name);
    if (const Json* mi = member(node, "mesh")) {
      const Json* meshes = member(doc_, "meshes");
      std::size_t k = 0;
      if (!meshes || !meshes->is_array() || !index_of(*mi, meshes->size(), k))
        return fail(where + ".mesh", "not an index of meshes");
      auto local = mesh(k);
      if (!local) return local.error();
      GltfMeshNode visit_node{
          .node = n, .mesh = k, .name = name, .path = path, .world = m, .local = *local};
      if (Status s = (*visitor_)(visit_node); !s) return s;
    }
    if (const Json* children = member(node, "children")) {
      if (!children->is_array()) return fail(where + ".children", "not an array");
      for (std::size_t c = 0; c < children->size(); ++c) {
        std::size_t k = 0;
        if (!index_of((*children)[c], nodes.size(), k))
          return fail(where + ".children[" + std::to_string(c) + "]", "not an index of nodes");
        if (Status s = visit(k, m, path, depth + 1); !s) return s;
      }
    }
    return {};
  }

  static constexpr int kMaxDepth = 1000;  // (the recursion's stack)
  const std::string& path_;
  GlbChunks chunks_;
  Json doc_;
  bool glb_ = true;
  std::filesystem::path dir_;
  std::vector<std::string> owned_;                      // buffers read from URIs
  std::vector<std::string_view> buffers_;               // every buffer, cut to its byteLength
  TriMesh mesh_;                                        // the mesh being parsed
  std::vector<std::shared_ptr<const TriMesh>> meshes_;  // parsed meshes, by index
  std::vector<char> visited_;
  const GltfVisitor* visitor_ = nullptr;
};

}  // namespace

Expected<std::uint32_t> glb_json_length(const std::string& path, std::string_view d,
                                        std::uint64_t size) {
  if (d.size() < 12 || !is_glb(d)) return byte_error(path, 0, "not a GLB file (no 'glTF' header)");
  if (const std::uint32_t version = u32_at(d, 4); version != 2)
    return byte_error(path, 4,
                      "GLB version " + std::to_string(version) + ": only glTF 2.0 is supported");
  if (const std::uint32_t length = u32_at(d, 8); length != size)
    return byte_error(path, 8,
                      "the header gives " + std::to_string(length) + " bytes, the file has " +
                          std::to_string(size) + (length > size ? " (truncated)" : ""));
  if (d.size() < 20) return byte_error(path, 12, "no JSON chunk");
  const std::uint32_t length = u32_at(d, 12);
  if (u32_at(d, 16) != 0x4E4F534Au) return byte_error(path, 16, "the first chunk is not JSON");
  if (length > size - 20)
    return byte_error(path, 12, "chunk of " + std::to_string(length) + " bytes runs past the end");
  return length;
}

Expected<GlbChunks> split_glb(const std::string& path, std::string_view d) {
  auto json_length = glb_json_length(path, d.substr(0, 20), d.size());
  if (!json_length) return json_length.error();
  GlbChunks out;
  out.json = d.substr(20, *json_length), out.json_at = 20;
  std::size_t at = 20 + std::size_t{*json_length};
  for (int chunk = 1; at < d.size(); ++chunk) {
    if (d.size() - at < 8)
      return byte_error(path, static_cast<std::int64_t>(at), "truncated chunk header");
    const std::uint32_t length = u32_at(d, at), type = u32_at(d, at + 4);
    if (length > d.size() - at - 8)
      return byte_error(path, static_cast<std::int64_t>(at),
                        "chunk of " + std::to_string(length) + " bytes runs past the end");
    if (chunk == 1 && type == 0x004E4942u)
      out.bin = d.substr(at + 8, length), out.bin_at = static_cast<std::int64_t>(at + 8);
    at += 8 + std::size_t{length};  // (other chunk types are skipped)
  }
  return out;
}

namespace {

// Parses the document (GLB or JSON, by `glb`) and runs `f` on its reader.
template <class F>
auto with_reader(const std::string& path, std::string_view data, bool glb,
                 const std::filesystem::path& dir, F&& f)
    -> decltype(f(std::declval<GlbReader&>())) {
  GlbChunks chunks{.json = data, .bin = {}, .json_at = 0, .bin_at = 0};
  Json doc;
  if (glb) {
    auto split = split_glb(path, data);
    if (!split) return split.error();
    chunks = *split;
    doc = Json::parse(chunks.json, nullptr, false);
    if (doc.is_discarded())
      return byte_error(path, chunks.json_at, "the JSON chunk is not valid JSON");
  } else {
    try {
      doc = Json::parse(data);
    } catch (const Json::parse_error& e) {
      return byte_error(path, static_cast<std::int64_t>(e.byte > 0 ? e.byte - 1 : 0),
                        "not valid JSON (glTF)");
    } catch (const Json::exception& e) {  // a number beyond double ("9e308")
      return byte_error(path, 0, std::string("not valid glTF JSON: ") + e.what());
    }
  }
  GlbReader reader(path, chunks, std::move(doc), glb, dir);
  return f(reader);
}

}  // namespace

Expected<TriMesh> read_glb(const std::string& path, std::string_view data, MeshReadInfo& info,
                           const std::filesystem::path& dir) {
  info.format = MeshFormat::glb;
  return with_reader(path, data, true, dir, [](GlbReader& r) { return r.read(); });
}

Expected<TriMesh> read_gltf(const std::string& path, std::string_view data, MeshReadInfo& info,
                            const std::filesystem::path& dir) {
  info.format = MeshFormat::gltf;
  return with_reader(path, data, false, dir, [](GlbReader& r) { return r.read(); });
}

Status walk_gltf(const std::string& path, std::string_view data, const std::filesystem::path& dir,
                 const GltfVisitor& visitor) {
  return with_reader(path, data, is_glb(data), dir, [&](GlbReader& r) { return r.walk(visitor); });
}

}  // namespace interfere::io_detail
