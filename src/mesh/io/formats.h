// Internal: per-format readers and writers behind read_mesh/write_mesh (io.cpp), one file each:
// stl.cpp, obj.cpp, ply.cpp, off.cpp.
//
// Readers parse a whole file held in memory and return an unwelded TriMesh (io.cpp welds) whose
// indices are all in range and whose positions are all finite, with triangle i = the i-th triangle
// of the file (polygons fan-split in order). Every error carries the path and a line (text) or byte
// offset (binary). Writers stream into an OutputBuffer; io.cpp has already validated the mesh.
#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "interfere/core/error.h"
#include "interfere/mesh/io.h"
#include "interfere/mesh/tri_mesh.h"

namespace interfere::io_detail {

inline Error text_error(const std::string& path, std::int64_t line, std::string reason) {
  return Error{path, line, -1, std::move(reason)};
}
inline Error byte_error(const std::string& path, std::int64_t byte, std::string reason) {
  return Error{path, -1, byte, std::move(reason)};
}

/// Parses coordinate `axis` (0, 1, 2) of a vertex from a text token (OBJ, OFF); the error names the
/// line, the token and the axis, and rejects malformed numbers, NaN/Inf and coordinates outside the
/// supported range (core/coordinate_range.h; that error also names the vertex number as the format
/// counts it: OBJ from 1, OFF from 0).
Status parse_coordinate(const std::string& path, std::int64_t line, std::string_view token, int axis,
                        double& out, std::int64_t vertex);

/// True when the bytes are a binary STL: the size is exactly 84 + 50·n for the count n in the
/// header (even when the header starts with "solid"), or the file does not start with "solid", or
/// it does but its first bytes are not text (a binary file with a "solid" header whose size is
/// wrong).
bool stl_is_binary(std::string_view data);

Expected<TriMesh> read_stl_ascii(const std::string& path, std::string_view data,
                                 MeshReadInfo& info);
/// With `weld`, the facets are welded straight from the file's float bits (same result as
/// weld_exact on the soup, without building it) and info.vertices_before_weld is set.
Expected<TriMesh> read_stl_binary(const std::string& path, std::string_view data,
                                  MeshReadInfo& info, bool weld = false);
Expected<TriMesh> read_obj(const std::string& path, std::string_view data, MeshReadInfo& info);
/// The flavour (ASCII / binary LE / binary BE) comes from the header.
Expected<TriMesh> read_ply(const std::string& path, std::string_view data, MeshReadInfo& info);
Expected<TriMesh> read_off(const std::string& path, std::string_view data, MeshReadInfo& info);
/// glTF 2.0 (glb.cpp), binary or JSON: the default scene's triangles, placed; buffers named by
/// relative URIs are read from `dir` (the glTF file's folder).
Expected<TriMesh> read_glb(const std::string& path, std::string_view data, MeshReadInfo& info,
                           const std::filesystem::path& dir);
Expected<TriMesh> read_gltf(const std::string& path, std::string_view data, MeshReadInfo& info,
                            const std::filesystem::path& dir);

/// Buffered writer over a FILE*; remembers the first failure (errno) instead of failing per call.
class OutputBuffer {
 public:
  explicit OutputBuffer(std::FILE* f) : f_(f) { buf_.reserve(kCapacity); }
  OutputBuffer(const OutputBuffer&) = delete;
  OutputBuffer& operator=(const OutputBuffer&) = delete;

  void write(std::string_view s) {
    if (buf_.size() + s.size() > kCapacity) flush();
    if (s.size() >= kCapacity) {
      put(s.data(), s.size());
    } else {
      buf_.append(s);
    }
  }
  void write_bytes(const void* p, std::size_t n) {
    write(std::string_view(static_cast<const char*>(p), n));
  }
  void write_char(char c) {
    if (buf_.size() + 1 > kCapacity) flush();
    buf_.push_back(c);
  }
  /// Shortest representation that reads back to the same double (std::to_chars).
  void write_double(double v);
  /// Shortest representation that reads back to the same float.
  void write_float(float v);
  void write_uint(std::uint64_t v);
  /// "x y z\n", shortest round-trip doubles (ASCII vertex lines of every text format).
  void write_xyz_line(const Vec3& p) {
    write_double(p.x);
    write_char(' ');
    write_double(p.y);
    write_char(' ');
    write_double(p.z);
    write_char('\n');
  }
  /// "<prefix>i j k\n" with `base` added to each index (1 for OBJ).
  void write_tri_line(std::string_view prefix, const Tri& t, std::uint64_t base = 0) {
    write(prefix);
    write_uint(t[0] + base);
    write_char(' ');
    write_uint(t[1] + base);
    write_char(' ');
    write_uint(t[2] + base);
    write_char('\n');
  }
  /// Writes what is buffered; false once any write failed.
  bool flush() {
    if (!buf_.empty()) put(buf_.data(), buf_.size());
    buf_.clear();
    return ok_;
  }
  bool ok() const { return ok_; }
  int error_number() const { return errno_; }

 private:
  static constexpr std::size_t kCapacity = 1 << 20;
  void put(const char* p, std::size_t n);
  std::FILE* f_;
  std::string buf_;
  bool ok_ = true;
  int errno_ = 0;
};

void write_stl_binary(OutputBuffer& out, const TriMesh& mesh);
void write_stl_ascii(OutputBuffer& out, const TriMesh& mesh);
void write_obj(OutputBuffer& out, const TriMesh& mesh);
enum class PlyEncoding { ascii, binary_le, binary_be };
void write_ply(OutputBuffer& out, const TriMesh& mesh, PlyEncoding encoding,
               bool float_coordinates);
void write_off(OutputBuffer& out, const TriMesh& mesh);

/// Facet normal computed in double, unit length, or zero for a degenerate triangle.
Vec3 facet_normal(const Vec3& a, const Vec3& b, const Vec3& c);

/// Byte-order helpers for binary formats (files are little endian unless stated).
inline std::uint16_t bswap(std::uint16_t v) {
  return static_cast<std::uint16_t>((v >> 8) | (v << 8));
}
inline std::uint32_t bswap(std::uint32_t v) {
  return __builtin_bswap32(v);
}
inline std::uint64_t bswap(std::uint64_t v) {
  return __builtin_bswap64(v);
}

}  // namespace interfere::io_detail
