// ParaView time series of a viewer document (include/interfere/view/pvd.h; issue #25, item 3).
// VTK File Formats, "XML File Formats": PolyData pieces (Points, Lines, Polys; cell data in the
// order verts, lines, polys), header_type UInt64, compressor vtkZLibDataCompressor: per array a
// header [#blocks, block size, last block size, compressed sizes...] base64-encoded, then the
// compressed blocks base64-encoded (as VTK writes it; src/fem/io/vtu_write.cpp does the same).
#include "interfere/view/pvd.h"
#include "interfere/core/xml_escape.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <regex>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "export_checks.h"
#include "interfere/core/atomic_file.h"
#include "interfere/core/base64.h"

namespace interfere::view {
namespace {

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // the library targets little-endian machines (byte_order below)
  out.append(b, sizeof(T));
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.17g", v);
  return s;
}

/// The XML of one PolyData file, built array by array.
class VtpWriter {
 public:
  /// A DataArray of little-endian values `raw` (type: Int32, Int64, UInt8, Float64).
  void array(const char* type, const std::string& name, int components, const std::string& raw) {
    xml_ += "<DataArray type=\"" + std::string(type) + "\" Name=\"" + xml_escape(name) + "\" NumberOfComponents=\"" +
            std::to_string(components) + "\" format=\"binary\">\n";
    constexpr std::size_t kBlock = 1 << 16;
    const std::size_t blocks = (raw.size() + kBlock - 1) / kBlock;
    std::string head, body;
    put<std::uint64_t>(head, blocks);
    put<std::uint64_t>(head, kBlock);
    put<std::uint64_t>(head, blocks == 0 ? 0 : raw.size() - (blocks - 1) * kBlock);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t length = std::min(kBlock, raw.size() - b * kBlock);
      uLongf capacity = compressBound(static_cast<uLong>(length));
      std::string buffer(capacity, '\0');
      if (compress2(reinterpret_cast<Bytef*>(buffer.data()), &capacity, reinterpret_cast<const Bytef*>(raw.data() + b * kBlock),
                    static_cast<uLong>(length), 1) != Z_OK)
        failed_ = true;
      buffer.resize(capacity);
      put<std::uint64_t>(head, capacity);
      body += buffer;
    }
    xml_ += base64_encode(head);
    xml_ += base64_encode(body);
    xml_ += "\n</DataArray>\n";
  }

  /// A VTK string array (ASCII: each string's byte values, ended by 0), as field data.
  void strings(const std::string& name, const std::vector<std::string>& values) {
    xml_ += "<DataArray type=\"String\" Name=\"" + xml_escape(name) + "\" NumberOfTuples=\"" + std::to_string(values.size()) +
            "\" format=\"ascii\">\n";
    for (const std::string& v : values) {
      for (char c : v)
        if (c != '\0') xml_ += std::to_string(static_cast<unsigned char>(c)) + " ";
      xml_ += "0\n";
    }
    xml_ += "</DataArray>\n";
  }

  void text(std::string_view t) { xml_ += t; }
  bool failed() const { return failed_; }
  std::string take() { return std::move(xml_); }

 private:
  std::string xml_;
  bool failed_ = false;
};

std::string vtp_head() {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n<PolyData>\n";
}

std::string piece(std::size_t points, std::size_t lines, std::size_t polys) {
  return "<Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfVerts=\"0\" NumberOfLines=\"" + std::to_string(lines) +
         "\" NumberOfStrips=\"0\" NumberOfPolys=\"" + std::to_string(polys) + "\">\n";
}

/// Points as Float64 x 3.
void points_array(VtpWriter& w, const std::vector<Vec3>& points) {
  std::string raw;
  raw.reserve(24 * points.size());
  for (const Vec3& p : points) put(raw, p.x), put(raw, p.y), put(raw, p.z);
  w.text("<Points>\n");
  w.array("Float64", "Points", 3, raw);
  w.text("</Points>\n");
}

/// A cell block (<Lines> or <Polys>): connectivity and offsets of cells given by their point lists'
/// ends; Int32 while every value fits (half the bytes), Int64 beyond.
void cells(VtpWriter& w, const char* tag, const std::vector<std::int64_t>& connectivity, const std::vector<std::int64_t>& ends) {
  constexpr std::int64_t kInt32Max = std::numeric_limits<std::int32_t>::max();
  const bool narrow = std::all_of(connectivity.begin(), connectivity.end(), [](std::int64_t v) { return v <= kInt32Max; }) &&
                      (ends.empty() || ends.back() <= kInt32Max);
  std::string c, o;
  const auto add = [&](std::string& out, std::int64_t v) {
    if (narrow) put<std::int32_t>(out, static_cast<std::int32_t>(v));
    else put<std::int64_t>(out, v);
  };
  for (std::int64_t i : connectivity) add(c, i);
  for (std::int64_t e : ends) add(o, e);
  w.text(std::string("<") + tag + ">\n");
  w.array(narrow ? "Int32" : "Int64", "connectivity", 1, c);
  w.array(narrow ? "Int32" : "Int64", "offsets", 1, o);
  w.text(std::string("</") + tag + ">\n");
}

std::string bodies_file(const Document& doc, std::size_t k, bool framed) {
  std::vector<Vec3> points;
  std::vector<std::int64_t> connectivity, ends;
  std::string body, clash, region, source, depth;
  bool any_source = false, any_depth = false, any_region = false;
  for (const ViewBody& b : doc.bodies) {
    const std::uint32_t m = framed && !b.frame_meshes.empty() ? b.frame_meshes[k] : b.mesh;
    any_source = any_source || !doc.meshes[m].source_ids.empty();
  }
  // (penetration_depth in every file of a series when any mesh has it, for ParaView's colouring)
  for (const ViewMesh& m : doc.meshes) {
    any_depth = any_depth || !m.point_depth.empty();
    any_region = any_region || !m.clash_region.empty();  // (likewise in every file of a series)
  }
  for (std::size_t bi = 0; bi < doc.bodies.size(); ++bi) {
    const ViewBody& b = doc.bodies[bi];
    const ViewMesh& vm = doc.meshes[framed && !b.frame_meshes.empty() ? b.frame_meshes[k] : b.mesh];
    const Transform& pose = framed && !b.frame_poses.empty() ? b.frame_poses[k] : b.pose;
    const auto first = static_cast<std::int64_t>(points.size());
    for (const Vec3& p : vm.mesh.positions) points.push_back(pose.apply(p));
    for (std::size_t t = 0; t < vm.mesh.num_triangles(); ++t) {
      for (std::uint32_t v : vm.mesh.triangles[t]) connectivity.push_back(first + v);
      ends.push_back(static_cast<std::int64_t>(connectivity.size()));
      put<std::int32_t>(body, static_cast<std::int32_t>(bi));
      put<std::uint8_t>(clash, vm.clash_flags.empty() ? 0 : vm.clash_flags[t]);
      if (any_region) put<std::int32_t>(region, vm.clash_region.empty() ? -1 : vm.clash_region[t]);
      if (any_source) put<std::int64_t>(source, vm.source_ids.empty() ? -1 : vm.source_ids[t]);
    }
    if (any_depth)
      for (std::size_t v = 0; v < vm.mesh.num_vertices(); ++v)
        put<double>(depth, vm.point_depth.empty() ? std::numeric_limits<double>::quiet_NaN() : vm.point_depth[v]);
  }
  VtpWriter w;
  w.text(vtp_head());
  std::vector<std::string> names, ids;
  for (const ViewBody& b : doc.bodies) names.push_back(b.name), ids.push_back(b.id);
  w.text("<FieldData>\n");
  w.strings("body_names", names);
  w.strings("body_ids", ids);
  w.text("</FieldData>\n");
  w.text(piece(points.size(), 0, ends.size()));
  w.text("<PointData>\n");
  if (any_depth) w.array("Float64", "penetration_depth", 1, depth);
  w.text("</PointData>\n<CellData>\n");
  w.array("Int32", "body", 1, body);
  w.array("UInt8", "clash", 1, clash);
  if (any_region) w.array("Int32", "clash_region", 1, region);
  if (any_source) w.array("Int64", "source_id", 1, source);
  w.text("</CellData>\n");
  points_array(w, points);
  cells(w, "Polys", connectivity, ends);
  w.text("</Piece>\n</PolyData>\n</VTKFile>\n");
  return w.failed() ? std::string() : w.take();
}

std::uint8_t verdict_code(const std::string& verdict) {
  if (verdict == "clash") return 1;
  if (verdict == "contact") return 2;
  if (verdict == "clearance") return 3;
  return 0;
}

std::string clashes_file(const Document& doc, std::size_t k, bool framed) {
  struct Cells {
    std::vector<std::int64_t> connectivity, ends;
    std::string index, verdict, geometry, clash;
    /// Ends the cell whose points were just appended to `connectivity` (VTK offsets: cell ends).
    void add(std::size_t c, std::uint8_t v, std::uint8_t g, std::uint8_t flag) {
      ends.push_back(static_cast<std::int64_t>(connectivity.size()));
      put<std::int32_t>(index, static_cast<std::int32_t>(c));
      put<std::uint8_t>(verdict, v), put<std::uint8_t>(geometry, g), put<std::uint8_t>(clash, flag);
    }
  } lines, polys;
  std::vector<Vec3> points;
  const auto polyline = [&](std::size_t c, const std::vector<Vec3>& line, std::uint8_t geometry) {
    if (line.size() < 2) return;
    for (const Vec3& p : line) {
      lines.connectivity.push_back(static_cast<std::int64_t>(points.size()));
      points.push_back(p);
    }
    lines.add(c, verdict_code(doc.clashes[c].verdict), geometry, 0);
  };
  for (std::size_t c = 0; c < doc.clashes.size(); ++c) {
    const ViewClash& clash = doc.clashes[c];
    if (framed && !clash.frames.empty() && std::find(clash.frames.begin(), clash.frames.end(), k) == clash.frames.end()) continue;
    for (const auto& curve : clash.curves) polyline(c, curve, 1);
    if (clash.has_witness) polyline(c, {clash.witness_a, clash.witness_b}, 2);
    if (clash.region_mesh < 0) continue;
    const TriMesh& region = doc.meshes[static_cast<std::size_t>(clash.region_mesh)].mesh;
    const auto first = static_cast<std::int64_t>(points.size());
    points.insert(points.end(), region.positions.begin(), region.positions.end());
    for (const Tri& t : region.triangles) {
      for (std::uint32_t v : t) polys.connectivity.push_back(first + v);
      polys.add(c, verdict_code(clash.verdict), 0, clash.verdict == "clash" ? 1 : 0);
    }
  }
  VtpWriter w;
  w.text(vtp_head());
  std::vector<std::string> ids;
  for (const ViewClash& c : doc.clashes) ids.push_back(c.id);
  w.text("<FieldData>\n");
  w.strings("clash_ids", ids);
  w.strings("verdict_names", {"undecided", "clash", "contact", "clearance"});
  w.text("</FieldData>\n");
  w.text(piece(points.size(), lines.ends.size(), polys.ends.size()));
  w.text("<PointData>\n</PointData>\n<CellData>\n");
  w.array("Int32", "clash_index", 1, lines.index + polys.index);
  w.array("UInt8", "verdict", 1, lines.verdict + polys.verdict);
  w.array("UInt8", "geometry", 1, lines.geometry + polys.geometry);
  w.array("UInt8", "clash", 1, lines.clash + polys.clash);
  w.text("</CellData>\n");
  points_array(w, points);
  cells(w, "Lines", lines.connectivity, lines.ends);
  cells(w, "Polys", polys.connectivity, polys.ends);
  w.text("</Piece>\n</PolyData>\n</VTKFile>\n");
  return w.failed() ? std::string() : w.take();
}

std::string step_name(const char* what, std::size_t k, std::size_t steps) {
  const int width = std::max<int>(4, static_cast<int>(std::to_string(steps - 1).size()));
  char s[64];
  std::snprintf(s, sizeof s, "%s_%0*zu.vtp", what, width, k);
  return s;
}

}  // namespace

std::filesystem::path pvd_files_folder(const std::filesystem::path& pvd) {
  return pvd.parent_path() / (pvd.stem().string() + "_files");
}

Status write_pvd(const std::filesystem::path& pvd, const Document& doc) {
  const std::string file = pvd.string();
  if (const std::string bad = detail::check_for_export(doc); !bad.empty()) return Error{.file = file, .reason = "ParaView series: " + bad};
  if (pvd.filename().empty() || pvd.stem().empty()) return Error{.file = file, .reason = "ParaView series: not a file name"};
  const std::filesystem::path folder = pvd_files_folder(pvd);
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder))
    return Error{.file = folder.string(), .reason = "ParaView series: cannot make the folder (" + (ec ? ec.message() : "not a directory") + ")"};

  const std::size_t frames = detail::frame_count(doc);
  const bool framed = frames > 0;
  const std::size_t steps = framed ? frames : 1;
  const auto& t = doc.frames.times;
  bool increasing = t.size() == frames && frames > 0;
  for (std::size_t k = 1; increasing && k < t.size(); ++k) increasing = t[k] > t[k - 1];

  std::set<std::string> written;
  std::string collection = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n<Collection>\n";
  const std::string folder_name = folder.filename().string();
  for (std::size_t k = 0; k < steps; ++k) {
    const std::string time = number(increasing ? t[k] : static_cast<double>(k));
    const auto write = [&](const char* what, int part, const std::string& xml) -> Status {
      const std::string name = step_name(what, k, steps);
      if (xml.empty()) return Error{.file = (folder / name).string(), .reason = "ParaView series: zlib compression failed"};
      if (Status s = write_file_atomic(folder / name, xml); !s) return s;
      written.insert(name);
      collection += "<DataSet timestep=\"" + time + "\" group=\"\" part=\"" + std::to_string(part) + "\" name=\"" + what +
                    "\" file=\"" + xml_escape(folder_name + "/" + name) + "\"/>\n";
      return {};
    };
    if (Status s = write("bodies", 0, bodies_file(doc, k, framed)); !s) return s;
    if (!doc.clashes.empty())
      if (Status s = write("clashes", 1, clashes_file(doc, k, framed)); !s) return s;
  }
  collection += "</Collection>\n</VTKFile>\n";
  if (Status s = write_file_atomic(pvd, collection); !s) return s;
  // Step files of an earlier series under the same names (a longer one, or one with clashes).
  static const std::regex ours(R"((bodies|clashes)_[0-9]{4,}\.vtp)");
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file(ec) && std::regex_match(name, ours) && !written.count(name)) std::filesystem::remove(entry.path(), ec);
  }
  return {};
}

}  // namespace interfere::view
