// VTK XML UnstructuredGrid (.vtu) writer (VTK File Formats, "XML File Formats"), header_type
// UInt64, little-endian. Encodings (FemWriteOptions::vtu_encoding): ascii; binary (inline base64,
// header and data in one base64 stream); appended (raw bytes in <AppendedData encoding="raw">);
// zlib (inline base64, vtkZLibDataCompressor: header [#blocks, block size, last block size,
// compressed sizes] base64-encoded, then the compressed blocks base64-encoded, as VTK writes it).
// Arrays: element_id, group (cell data), node_id (point data), the options' arrays, the fields'
// last step.
#include <zlib.h>

#include "interfere/core/xml_escape.h"
#include "vtk_common.h"

namespace interfere::fem_io {
namespace {

constexpr char kB64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

void b64_encode(std::string_view in, std::string& out) {
  std::size_t i = 0;
  for (; i + 3 <= in.size(); i += 3) {
    const std::uint32_t v = (static_cast<unsigned char>(in[i]) << 16) | (static_cast<unsigned char>(in[i + 1]) << 8) | static_cast<unsigned char>(in[i + 2]);
    out += kB64[(v >> 18) & 63];
    out += kB64[(v >> 12) & 63];
    out += kB64[(v >> 6) & 63];
    out += kB64[v & 63];
  }
  if (i < in.size()) {
    std::uint32_t v = static_cast<unsigned char>(in[i]) << 16;
    if (i + 1 < in.size()) v |= static_cast<unsigned char>(in[i + 1]) << 8;
    out += kB64[(v >> 18) & 63];
    out += kB64[(v >> 12) & 63];
    out += i + 1 < in.size() ? kB64[(v >> 6) & 63] : '=';
    out += '=';
  }
}

struct Out {
  VtuEncoding enc;
  std::string xml;
  std::string appended;

  /// One DataArray: `raw` holds the values as little-endian bytes, `text` the ASCII form.
  void array(const std::string& type, const std::string& name, int comps, const std::string& raw, const std::string& text) {
    xml += "<DataArray type=\"" + type + "\"";
    if (!name.empty()) xml += " Name=\"" + xml_escape(name) + "\"";
    xml += " NumberOfComponents=\"" + std::to_string(comps) + "\"";
    switch (enc) {
      case VtuEncoding::ascii:
        xml += " format=\"ascii\">\n" + text + "\n</DataArray>\n";
        return;
      case VtuEncoding::appended:
        xml += " format=\"appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
        put_raw<std::uint64_t>(appended, raw.size());
        appended += raw;
        return;
      case VtuEncoding::binary: {
        xml += " format=\"binary\">\n";
        std::string all;
        put_raw<std::uint64_t>(all, raw.size());
        all += raw;
        b64_encode(all, xml);
        xml += "\n</DataArray>\n";
        return;
      }
      case VtuEncoding::zlib: {
        xml += " format=\"binary\">\n";
        constexpr std::size_t kBlock = 1 << 16;
        const std::size_t nb = (raw.size() + kBlock - 1) / kBlock;
        std::string head, body;
        put_raw<std::uint64_t>(head, nb);
        put_raw<std::uint64_t>(head, kBlock);
        put_raw<std::uint64_t>(head, nb == 0 ? 0 : raw.size() - (nb - 1) * kBlock);
        for (std::size_t b = 0; b < nb; ++b) {
          const std::size_t len = std::min(kBlock, raw.size() - b * kBlock);
          uLongf cap = compressBound(static_cast<uLong>(len));
          std::string buf(cap, '\0');
          compress2(reinterpret_cast<Bytef*>(buf.data()), &cap, reinterpret_cast<const Bytef*>(raw.data() + b * kBlock), static_cast<uLong>(len), 1);
          buf.resize(cap);
          put_raw<std::uint64_t>(head, cap);
          body += buf;
        }
        b64_encode(head, xml);
        b64_encode(body, xml);
        xml += "\n</DataArray>\n";
        return;
      }
    }
  }
};

template <class T, class V>
void encode(const std::vector<V>& v, std::string& raw, std::string& text, bool want_text) {
  raw.reserve(v.size() * sizeof(T));
  for (const V& x : v) put_raw<T>(raw, static_cast<T>(x));
  if (want_text) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if constexpr (std::is_floating_point_v<T>) put_double(text, static_cast<double>(v[i])); else put_int(text, static_cast<std::int64_t>(v[i]));
      text += (i + 1) % 9 == 0 ? '\n' : ' ';
    }
  }
}

}  // namespace

Status write_vtu(const FemMesh& m, const FemWriteOptions& o, std::string& result) {
  Out out{.enc = o.vtu_encoding};
  const bool text = o.vtu_encoding == VtuEncoding::ascii;
  std::string& x = out.xml;
  x += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (o.vtu_encoding == VtuEncoding::zlib) x += " compressor=\"vtkZLibDataCompressor\"";
  x += ">\n<UnstructuredGrid>\n";
  const VtkOutArrays arrays = vtk_out_arrays(m, o);
  if (!arrays.group_names.empty()) {
    // Group names as a VTK string array (ASCII: the characters' codes, each string ended by 0),
    // so that a read back names the groups; other readers show it as field data.
    x += "<FieldData>\n<DataArray type=\"String\" Name=\"group_names\" NumberOfTuples=\"" + std::to_string(arrays.group_names.size()) + "\" format=\"ascii\">\n";
    for (const std::string& n : arrays.group_names) {
      for (char c : n) {
        put_int(x, static_cast<unsigned char>(c));
        x += ' ';
      }
      x += "0\n";
    }
    x += "</DataArray>\n</FieldData>\n";
  }
  x += "<Piece NumberOfPoints=\"" + std::to_string(m.num_nodes()) + "\" NumberOfCells=\"" + std::to_string(m.num_elements()) + "\">\n";
  auto emit = [&](const VtkArray& a) {
    std::string raw, t;
    if (a.integer) {
      encode<std::int64_t>(a.ints, raw, t, text);
      out.array("Int64", a.name, a.components, raw, t);
    } else {
      encode<double>(a.reals, raw, t, text);
      out.array("Float64", a.name, a.components, raw, t);
    }
  };
  x += "<PointData>\n";
  for (const VtkArray& a : arrays.point) emit(a);
  x += "</PointData>\n<CellData>\n";
  for (const VtkArray& a : arrays.cell) emit(a);
  x += "</CellData>\n<Points>\n";
  {
    std::vector<double> p;
    p.reserve(3 * m.num_nodes());
    for (const Vec3& v : m.nodes) {
      p.push_back(v.x);
      p.push_back(v.y);
      p.push_back(v.z);
    }
    std::string raw, t;
    encode<double>(p, raw, t, text);
    out.array("Float64", "Points", 3, raw, t);
  }
  x += "</Points>\n<Cells>\n";
  {
    std::string raw, t;
    encode<std::int64_t>(m.elem_nodes, raw, t, text);
    out.array("Int64", "connectivity", 1, raw, t);
    std::vector<std::uint64_t> offs(m.elem_offsets.begin() + 1, m.elem_offsets.end());
    raw.clear();
    t.clear();
    encode<std::int64_t>(offs, raw, t, text);
    out.array("Int64", "offsets", 1, raw, t);
    std::vector<std::uint8_t> types(m.num_elements());
    for (std::size_t e = 0; e < types.size(); ++e) types[e] = static_cast<std::uint8_t>(elem_info(m.elem_types[e]).vtk_cell_type);
    raw.clear();
    t.clear();
    encode<std::uint8_t>(types, raw, t, text);
    out.array("UInt8", "types", 1, raw, t);
  }
  x += "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
  if (o.vtu_encoding == VtuEncoding::appended) {
    x += "<AppendedData encoding=\"raw\">\n_";
    x += out.appended;
    x += "\n</AppendedData>\n";
  }
  x += "</VTKFile>\n";
  result = std::move(x);
  return {};
}

}  // namespace interfere::fem_io
