// Fuzz target for the mesh readers (mesh/io.h): the input bytes are written to a file with each
// extension (.stl .obj .ply .off .glb .gltf, and .bin for detection by content) and read with read_mesh,
// with and without welding.
//
// Checked on every read (abort = finding):
//  - no crash, hang, sanitizer report, or allocation out of proportion to the input;
//  - on error: a non-empty reason, Error::file equal to the path passed, never both a line and a
//    byte offset, a line within the file's lines / a byte offset within its size, and a location
//    unless the reason is about the whole file (empty, no triangles, cannot open/read, format
//    unknown for the content-detected file); never "out of memory" (inputs are small);
//  - on success: at least one triangle, every index < positions.size(), every coordinate finite,
//    MeshReadInfo consistent (format of the extension's family, polygons_split <= triangles);
//  - welding changes vertices only: the welded and unwelded reads fail with the same error or both
//    succeed with the same triangles corner for corner, the welded mesh equals weld_exact applied
//    to the unwelded one (bit for bit; this also checks the binary STL reader's direct weld), its
//    vertices are all used, distinct and numbered in order of first use; an unwelded STL without
//    polygons has 3 vertices per triangle;
//  - the content-detected read (.bin) gives the same result as the read with the extension of
//    the family it detected;
//  - the first mesh read successfully survives write_mesh + read_mesh in every format: exactly
//    for OBJ, OFF, PLY (ASCII, binary LE/BE) and ASCII STL; binary STL gives the float-rounded
//    corners; both STL flavours may refuse a coordinate that overflows float (documented).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "fuzz_common.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/validate.h"

namespace {

namespace fs = std::filesystem;
using interfere::Error;
using interfere::Expected;
using interfere::MeshFormat;
using interfere::MeshReadInfo;
using interfere::ReadOptions;
using interfere::TriMesh;
using interfere::Vec3;

const fs::path& work_dir() { return interfere::fuzz::work_dir("mesh"); }
using interfere::fuzz::put_file;

using Family = interfere::MeshFamily;
Family family_of(MeshFormat f) { return interfere::mesh_family(f); }

struct Read {
  bool ok = false;
  TriMesh mesh;
  MeshReadInfo info;
  Error error;
};

Read read(const fs::path& path, bool weld) {
  Read r;
  Expected<TriMesh> m = interfere::read_mesh(path, ReadOptions{.weld = weld}, &r.info);
  r.ok = m.has_value();
  if (r.ok) {
    r.mesh = std::move(*m);
  } else {
    r.error = m.error();
  }
  return r;
}

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

std::string where(const fs::path& path, bool weld) {
  return " [" + path.filename().string() + (weld ? ", welded" : ", unwelded") + "]";
}

void check_error(const Error& e, const fs::path& path, bool weld, std::int64_t lines,
                 std::size_t size, bool detect) {
  const std::string at = where(path, weld) + ": " + e.message();
  FUZZ_CHECK(!e.reason.empty(), "empty error reason" + at);
  FUZZ_CHECK(e.file == path.string(), "Error::file is '" + e.file + "'" + at);
  FUZZ_CHECK(!(e.line >= 0 && e.byte >= 0), "error has both a line and a byte offset" + at);
  FUZZ_CHECK(e.line == -1 || (e.line >= 1 && e.line <= lines),
             "error line outside the file's " + std::to_string(lines) + " lines" + at);
  FUZZ_CHECK(e.byte == -1 || (e.byte >= 0 && static_cast<std::uint64_t>(e.byte) <= size),
             "error byte offset outside the file's " + std::to_string(size) + " bytes" + at);
  FUZZ_CHECK(!starts_with(e.reason, "out of memory"), "out of memory on a small input" + at);
  if (e.line < 0 && e.byte < 0) {
    const bool whole_file =
        starts_with(e.reason, "file is empty") || starts_with(e.reason, "no triangles") ||
        starts_with(e.reason, "cannot open") || starts_with(e.reason, "cannot read") ||
        (detect && starts_with(e.reason, "cannot tell the mesh format"));
    FUZZ_CHECK(whole_file, "error without a line or byte offset" + at);
  }
  FUZZ_CHECK(e.message().find(e.file) != std::string::npos,
             "message() does not name the file" + at);
}

void check_mesh(const Read& r, const fs::path& path, bool weld, Family family) {
  const TriMesh& m = r.mesh;
  const std::string at = where(path, weld);
  FUZZ_CHECK(!m.triangles.empty(), "success without triangles" + at);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (std::uint32_t v : m.triangles[t]) {
      FUZZ_CHECK(v < m.positions.size(), "triangle " + std::to_string(t) + " references vertex " +
                                             std::to_string(v) + " of " +
                                             std::to_string(m.positions.size()) + at);
    }
  }
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    FUZZ_CHECK(interfere::is_finite(m.positions[i]),
               "non-finite position " + std::to_string(i) + at);
  }
  FUZZ_CHECK(
      family == Family::unknown || family_of(r.info.format) == family,
      std::string("MeshReadInfo::format is ") + interfere::mesh_format_name(r.info.format) + at);
  FUZZ_CHECK(family_of(r.info.format) != Family::unknown, "MeshReadInfo::format not set" + at);
  FUZZ_CHECK(r.info.polygons_split <= m.triangles.size(), "polygons_split > triangles" + at);
  FUZZ_CHECK(r.info.vertices_before_weld >= m.positions.size(),
             "vertices_before_weld < vertices" + at);
  if (!weld) {
    FUZZ_CHECK(r.info.vertices_before_weld == m.positions.size(),
               "unwelded: vertices_before_weld != vertices" + at);
    if (family_of(r.info.format) == Family::stl && r.info.polygons_split == 0) {
      FUZZ_CHECK(m.positions.size() == 3 * m.triangles.size(),
                 "unwelded STL without 3 vertices per facet" + at);
    }
    return;
  }
  // Welded: vertices used, numbered in order of first use, bitwise distinct (+0 == -0).
  std::uint32_t next = 0;
  for (const auto& tri : m.triangles) {
    for (std::uint32_t v : tri) {
      FUZZ_CHECK(v <= next, "welded vertices not numbered in order of first use" + at);
      if (v == next) ++next;
    }
  }
  FUZZ_CHECK(next == m.positions.size(), "welded mesh keeps unused vertices" + at);
  std::vector<std::array<double, 3>> keys;
  keys.reserve(m.positions.size());
  for (const Vec3& p : m.positions) keys.push_back({p.x + 0.0, p.y + 0.0, p.z + 0.0});  // -0 -> +0
  std::vector<std::array<std::uint64_t, 3>> bits(keys.size());
  std::memcpy(bits.data(), keys.data(), keys.size() * sizeof keys[0]);
  std::sort(bits.begin(), bits.end());
  FUZZ_CHECK(std::adjacent_find(bits.begin(), bits.end()) == bits.end(),
             "welded mesh has two bit-identical positions" + at);
}

bool same_bits(const TriMesh& x, const TriMesh& y) {
  return x.triangles == y.triangles && x.positions.size() == y.positions.size() &&
         (x.positions.empty() || std::memcmp(x.positions.data(), y.positions.data(),
                                             x.positions.size() * sizeof(Vec3)) == 0);
}

bool same_error(const Error& x, const Error& y) {
  return x.line == y.line && x.byte == y.byte && x.reason == y.reason;
}

/// Welded vs unwelded read of the same file.
void check_weld_pair(const Read& welded, const Read& plain, const fs::path& path) {
  const std::string at = " [" + path.filename().string() + "]";
  FUZZ_CHECK(welded.ok == plain.ok,
             std::string("welded read ") + (welded.ok ? "succeeds" : "fails") + ", unwelded " +
                 (plain.ok ? "succeeds" : "fails") + ": " +
                 (welded.ok ? plain.error.message() : welded.error.message()) + at);
  if (!welded.ok) {
    FUZZ_CHECK(same_error(welded.error, plain.error),
               "welding changes the error: " + welded.error.message() + " vs " +
                   plain.error.message() + at);
    return;
  }
  FUZZ_CHECK(welded.info.format == plain.info.format, "welding changes the detected format" + at);
  FUZZ_CHECK(welded.info.polygons_split == plain.info.polygons_split,
             "welding changes polygons_split" + at);
  FUZZ_CHECK(welded.info.vertices_before_weld == plain.mesh.positions.size(),
             "vertices_before_weld " + std::to_string(welded.info.vertices_before_weld) +
                 " != unwelded vertex count " + std::to_string(plain.mesh.positions.size()) + at);
  FUZZ_CHECK(welded.mesh.triangles.size() == plain.mesh.triangles.size(),
             "welding changes the triangle count" + at);
  for (std::size_t t = 0; t < plain.mesh.triangles.size(); ++t) {
    FUZZ_CHECK(welded.mesh.corners(t) == plain.mesh.corners(t),
               "welding moves a corner of triangle " + std::to_string(t) + at);
  }
  TriMesh rewelded = plain.mesh;
  interfere::weld_exact(rewelded);
  FUZZ_CHECK(same_bits(rewelded, welded.mesh),
             "welded read differs from weld_exact(unwelded read)" + at);
}

void check_same_result(const Read& x, const Read& y, const std::string& what) {
  FUZZ_CHECK(x.ok == y.ok, what + ": one read succeeds, the other fails");
  if (!x.ok) {
    FUZZ_CHECK(same_error(x.error, y.error),
               what + ": " + x.error.message() + " vs " + y.error.message());
    return;
  }
  FUZZ_CHECK(x.info.format == y.info.format && same_bits(x.mesh, y.mesh),
             what + ": different meshes");
}

/// write_mesh + read_mesh in every format.
void check_round_trip(const TriMesh& m) {
  struct Out {
    const char* file;
    MeshFormat format;
    bool exact;
  };
  static const Out kOuts[] = {
      {"rt.obj", MeshFormat::obj, true},
      {"rt.off", MeshFormat::off, true},
      {"rt_a.ply", MeshFormat::ply_ascii, true},
      {"rt_le.ply", MeshFormat::ply_binary_le, true},
      {"rt_be.ply", MeshFormat::ply_binary_be, true},
      {"rt_a.stl", MeshFormat::stl_ascii, true},
      {"rt_b.stl", MeshFormat::stl_binary, false},
  };
  for (const Out& o : kOuts) {
    const fs::path p = work_dir() / o.file;
    const std::string at =
        std::string(" [round trip through ") + interfere::mesh_format_name(o.format) + "]";
    const interfere::Status s = interfere::write_mesh(p, m, {.format = o.format});
    if (!s) {
      // Documented (io.h): STL, ASCII included, refuses coordinates that overflow float.
      const bool stl = o.format == MeshFormat::stl_ascii || o.format == MeshFormat::stl_binary;
      FUZZ_CHECK(stl && s.error().reason.find("overflows float") != std::string::npos,
                 "write_mesh fails: " + s.error().message() + at);
      continue;
    }
    Expected<TriMesh> back = interfere::read_mesh(p);
    FUZZ_CHECK(back.has_value(), "written mesh does not read back: " + back.error().message() + at);
    if (o.exact) {
      FUZZ_CHECK(same_bits(*back, m), "mesh changes in the round trip" + at);
      continue;
    }
    FUZZ_CHECK(back->triangles.size() == m.triangles.size(),
               "triangle count changes in the round trip" + at);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      auto c = m.corners(t);
      for (Vec3& v : c) v = {double(float(v.x)), double(float(v.y)), double(float(v.z))};
      FUZZ_CHECK(back->corners(t) == c, "corner not float-rounded in the round trip" + at);
    }
  }
}

int entry(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;
  std::int64_t lines = 1;
  for (std::size_t i = 0; i < size; ++i) lines += data[i] == '\n';

  struct Input {
    const char* file;
    Family family;
  };
  static const Input kInputs[] = {{"in.stl", Family::stl},
                                  {"in.obj", Family::obj},
                                  {"in.ply", Family::ply},
                                  {"in.off", Family::off},
                                  {"in.glb", Family::glb},
                                  {"in.gltf", Family::gltf},
                                  {"in.bin", Family::unknown}};
  Read welded_by_family[7];  // indexed by MeshFamily (unknown stays empty)
  const TriMesh* first_ok = nullptr;
  // Every file first: a glTF buffer URI may name one of them (the same bytes for every read).
  for (const Input& in : kInputs) put_file(work_dir() / in.file, data, size);
  for (const Input& in : kInputs) {
    const fs::path path = work_dir() / in.file;
    const bool detect = in.family == Family::unknown;
    Read w = read(path, true);
    Read u = read(path, false);
    for (const Read* r : {&w, &u}) {
      const bool weld = r == &w;
      if (r->ok) {
        check_mesh(*r, path, weld, in.family);
      } else {
        check_error(r->error, path, weld, lines, size, detect);
      }
    }
    check_weld_pair(w, u, path);
    if (!detect) {
      welded_by_family[static_cast<int>(in.family)] = std::move(w);
      if (!first_ok && welded_by_family[static_cast<int>(in.family)].ok)
        first_ok = &welded_by_family[static_cast<int>(in.family)].mesh;
    } else if (w.ok) {
      // Detected by content: the same reader ran as for that family's extension.
      check_same_result(w, welded_by_family[static_cast<int>(family_of(w.info.format))],
                        "content detection vs extension");
    } else if (!starts_with(w.error.reason, "cannot tell the mesh format")) {
      bool matched = false;
      for (const Read& r : welded_by_family) matched |= !r.ok && same_error(r.error, w.error);
      FUZZ_CHECK(matched,
                 "content detection fails with an error no extension gives: " + w.error.message());
    }
  }
  if (first_ok) check_round_trip(*first_ok);
  return 0;
}

}  // namespace

INTERFERE_FUZZ_TARGET("read_mesh", entry);
