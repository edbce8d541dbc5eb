// Internal to the FEM readers and writers (src/fem/io/*): whole-file loading, a line/token scanner
// over the file's bytes that keeps 1-based line numbers, std::from_chars number parsing (no
// iostreams, no locale), a bounds-checked little/big-endian binary cursor, the node-id -> index map
// and the duplicate-id check every reader uses, and the element node-order tables of the solvers
// (Gmsh, Nastran) against VTK's order (fem_mesh.h). Shared by every format: no format parses text
// or binary on its own.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "interfere/core/error.h"
#include "interfere/fem/fem_mesh.h"
#include "interfere/fem/io.h"
#include "../../mesh/io/text_reader.h"  // the number and keyword scanning shared with the mesh readers

namespace interfere::fem_io {

// ---------------------------------------------------------------- files and errors

/// The whole file in memory (one read). Directories are refused; with `regular_only` (files named
/// by an INCLUDE) anything but a regular file is (a device would never end).
Expected<std::string> read_file_bytes(const std::filesystem::path& path, bool regular_only = false);

inline Error line_error(const std::string& file, std::int64_t line, std::string reason) {
  return Error{.file = file, .line = line, .reason = std::move(reason)};
}
inline Error byte_error(const std::string& file, std::int64_t byte, std::string reason) {
  return Error{.file = file, .byte = byte, .reason = std::move(reason)};
}
inline Error file_error(const std::string& file, std::string reason) {
  return Error{.file = file, .reason = std::move(reason)};
}
/// A name safe on one line between double quotes: control characters and '"' become '_'.
inline std::string one_line_name(std::string_view n) {
  std::string r(n);
  for (char& c : r) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '"') c = '_';
  }
  return r;
}
/// Token quoted for an error message, shortened, control bytes escaped.
std::string quote_tok(std::string_view token);

// ---------------------------------------------------------------- text

using io_detail::iequals;
using io_detail::is_space;
inline char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }
bool istarts_with(std::string_view s, std::string_view prefix);
std::string to_lower(std::string_view s);
std::string_view trim(std::string_view s);

/// Whole token as double / integer (leading '+' allowed; the mesh readers' parsers). NaN/Inf
/// spellings parse as such: the callers reject non-finite values with their own message.
using io_detail::parse_double;
using io_detail::parse_int;

/// Cursor over a text: tokens (crossing line ends) and lines, with 1-based line numbers.
class Text {
 public:
  explicit Text(std::string_view s, std::size_t pos = 0, std::int64_t line = 1) : s_(s), pos_(pos), line_(line), tok_line_(line) {}

  std::string_view token() {
    const std::size_t n = s_.size();
    while (pos_ < n && is_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    tok_line_ = line_;
    const std::size_t b = pos_;
    while (pos_ < n && !is_space(s_[pos_])) ++pos_;
    return s_.substr(b, pos_ - b);
  }
  /// Next line without its end of line; false at the end.
  bool next_line(std::string_view& out) {
    if (pos_ >= s_.size()) return false;
    tok_line_ = line_;
    const std::size_t b = pos_;
    const std::size_t nl = s_.find('\n', pos_);
    std::size_t e = nl == std::string_view::npos ? s_.size() : nl;
    pos_ = nl == std::string_view::npos ? s_.size() : nl + 1;
    if (nl != std::string_view::npos) ++line_;
    if (e > b && s_[e - 1] == '\r') --e;
    out = s_.substr(b, e - b);
    return true;
  }
  /// Moves past the end of the current line.
  void skip_line() {
    const std::size_t nl = s_.find('\n', pos_);
    if (nl == std::string_view::npos) {
      pos_ = s_.size();
    } else {
      pos_ = nl + 1;
      ++line_;
    }
  }
  std::int64_t line() const { return tok_line_; }    ///< line of the last token / line returned
  std::int64_t cur_line() const { return line_; }   ///< line of the current position
  std::size_t pos() const { return pos_; }
  void set_pos(std::size_t p, std::int64_t line) { pos_ = p; line_ = tok_line_ = line; }
  bool at_end() const { return pos_ >= s_.size(); }
  std::string_view text() const { return s_; }

 private:
  std::string_view s_;
  std::size_t pos_;
  std::int64_t line_, tok_line_;
};

// ---------------------------------------------------------------- binary

/// Bounds-checked cursor over bytes; values in the file's byte order (`big` for legacy VTK).
class Bytes {
 public:
  Bytes(std::string_view s, std::size_t pos, bool big = false) : s_(s), pos_(pos), big_(big) {}
  template <class T>
  bool get(T& out) {
    if (s_.size() - pos_ < sizeof(T) || pos_ > s_.size()) return false;
    std::memcpy(&out, s_.data() + pos_, sizeof(T));
    if (big_ != (std::endian::native == std::endian::big)) out = byteswap(out);
    pos_ += sizeof(T);
    return true;
  }
  /// `n` values of T into out (resized); false (nothing consumed) if the bytes run out.
  template <class T>
  bool get_array(std::size_t n, T* out) {
    if (pos_ > s_.size() || n > (s_.size() - pos_) / sizeof(T)) return false;
    std::memcpy(out, s_.data() + pos_, n * sizeof(T));
    if (big_ != (std::endian::native == std::endian::big)) {
      for (std::size_t i = 0; i < n; ++i) out[i] = byteswap(out[i]);
    }
    pos_ += n * sizeof(T);
    return true;
  }
  bool skip(std::size_t n) {
    if (pos_ > s_.size() || n > s_.size() - pos_) return false;
    pos_ += n;
    return true;
  }
  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return pos_ >= s_.size() ? 0 : s_.size() - pos_; }

  template <class T>
  static T byteswap(T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

 private:
  std::string_view s_;
  std::size_t pos_;
  bool big_;
};

/// 1-based line number of byte `pos` (for errors found after a binary block; counts newlines).
std::int64_t line_of(std::string_view s, std::size_t pos);

// ---------------------------------------------------------------- ids

/// Solver id -> index. Dense table when the ids are compact, hash map otherwise.
class IdMap {
 public:
  /// Builds the map; returns the index of the first repeated id (the second occurrence), or -1.
  std::int64_t build(const std::vector<std::int64_t>& ids);
  /// Index of `id`, or -1.
  std::int64_t find(std::int64_t id) const {
    if (dense_) {
      const std::uint64_t k = static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(lo_);
      if (k >= table_.size()) return -1;
      const std::uint32_t v = table_[k];
      return v == kNone ? -1 : static_cast<std::int64_t>(v);
    }
    auto it = hash_.find(id);
    return it == hash_.end() ? -1 : static_cast<std::int64_t>(it->second);
  }

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  bool dense_ = true;
  std::int64_t lo_ = 0;
  std::vector<std::uint32_t> table_;
  std::unordered_map<std::int64_t, std::uint32_t> hash_;
};

/// Index of the second occurrence of the first repeated id (in index order of that occurrence's
/// partner), or -1. `first` receives the first occurrence.
std::int64_t find_duplicate(const std::vector<std::int64_t>& ids, std::int64_t* first = nullptr);

/// Checks element-level properties the readers guarantee (unique element ids) and names the
/// element's location: `where[e]` is its line (text) or byte offset (binary, `bytes` true).
Status check_element_ids(const FemMesh& m, const std::vector<std::int64_t>& where, bool bytes);

/// Group index by name in `m.groups`, adding {name, id, dim} if absent.
std::int32_t group_index(FemMesh& m, std::unordered_map<std::string, std::int32_t>& by_name, const std::string& name,
                         std::int64_t id, int dim);

/// Removes elements whose dimension is below the highest one present; `where` is compacted
/// alongside. Adds warnings to m.warnings counting the 1-D and point elements skipped, and the 2-D
/// elements of a volume mesh that are not faces of its 3-D elements (those on faces are the
/// boundary an exporter wrote, not a body).
void drop_lower_dimension(FemMesh& m, std::vector<std::int64_t>* where);

// ---------------------------------------------------------------- node orders

/// perm[i] = position in the solver's order of VTK node i (vtk[i] = solver[perm[i]]); nullptr when
/// the orders agree.
const int* gmsh_to_vtk(ElemType t);
const int* nastran_to_vtk(ElemType t);
/// Reorders `n` node values in place: out[i] = in[perm[i]].
template <class T>
inline void permute(const int* perm, T* v, int n) {
  if (!perm) return;
  T tmp[32];
  for (int i = 0; i < n; ++i) tmp[i] = v[perm[i]];
  for (int i = 0; i < n; ++i) v[i] = tmp[i];
}
/// Inverse: writes the solver's order from VTK order.
template <class T>
inline void unpermute(const int* perm, T* v, int n) {
  if (!perm) return;
  T tmp[32];
  for (int i = 0; i < n; ++i) tmp[perm[i]] = v[i];
  for (int i = 0; i < n; ++i) v[i] = tmp[i];
}

/// VTK cell type -> ElemType; false if not one of ours.
bool elem_type_from_vtk(int vtk, ElemType& out);

// ---------------------------------------------------------------- per format (one file each)

Expected<FemMesh> read_msh(const std::string& file, std::string_view bytes);
Expected<FemMesh> read_nastran(const std::filesystem::path& path, std::string_view bytes);
Expected<FemMesh> read_vtk_legacy(const std::string& file, std::string_view bytes);
Expected<FemMesh> read_vtu(const std::string& file, std::string_view bytes);
Expected<FemMesh> read_abaqus(const std::filesystem::path& path, std::string_view bytes);
Expected<FemMesh> read_frd(const std::string& file, std::string_view bytes);  // frd_read.cpp
Expected<FemMesh> read_frd_file(const std::filesystem::path& path);         // frd_read.cpp (maps a large file)
Expected<FemMesh> read_exodus(const std::filesystem::path& path);           // exodus_read.cpp (opens the file itself)

/// Writers fill `out` with the whole file; write_fem writes it atomically.
Status write_msh(const FemMesh& m, const FemWriteOptions& o, std::string& out);
Status write_vtk_legacy(const FemMesh& m, const FemWriteOptions& o, std::string& out);
Status write_vtu(const FemMesh& m, const FemWriteOptions& o, std::string& out);
Status write_nastran(const FemMesh& m, const FemWriteOptions& o, std::string& out);
Status write_abaqus(const FemMesh& m, const FemWriteOptions& o, std::string& out);

// ---------------------------------------------------------------- output helpers

void put_double(std::string& out, double v);  ///< shortest round-trip text
void put_int(std::string& out, std::int64_t v);
template <class T>
inline void put_raw(std::string& out, T v, bool big = false) {
  if (big != (std::endian::native == std::endian::big)) v = Bytes::byteswap(v);
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace interfere::fem_io
