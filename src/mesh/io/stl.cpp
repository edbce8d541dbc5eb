// STL, ASCII and binary. Binary: 80-byte header, uint32 little-endian facet count, then per facet
// 12 float32 (normal, 3 vertices) and a uint16 attribute count, 50 bytes. The binary reader reads
// the already-loaded bytes with memcpy in parallel blocks; the soup is welded in io.cpp.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "../weld_internal.h"
#include "formats.h"
#include "interfere/core/coordinate_range.h"
#include "text_reader.h"

namespace interfere::io_detail {
namespace {

constexpr std::size_t kHeader = 84;
constexpr std::size_t kFacet = 50;

std::uint32_t load_u32_le(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  if constexpr (std::endian::native == std::endian::big) v = bswap(v);
  return v;
}

bool starts_with_solid(std::string_view d) {
  d = strip_bom(d);
  std::size_t i = 0;
  while (i < d.size() && is_space(d[i])) ++i;
  return d.size() - i >= 5 && iequals(d.substr(i, 5), "solid");
}

std::string plural(std::uint64_t n, std::string_view word) {
  if (n == 1) return "1 " + std::string(word);
  return std::to_string(n) + " " +
         (word == "vertex" ? std::string("vertices") : std::string(word) + "s");
}

}  // namespace

bool stl_is_binary(std::string_view d) {
  if (d.size() >= kHeader) {
    const std::uint64_t n = load_u32_le(d.data() + 80);
    if (kHeader + kFacet * n == d.size()) return true;
  }
  if (!starts_with_solid(d)) return true;
  // "solid" but the size does not match: ASCII unless the first bytes hold control characters,
  // which means a binary file (truncated or padded) whose header happens to start with "solid".
  const std::size_t limit = std::min<std::size_t>(d.size(), 1024);
  for (std::size_t i = 0; i < limit; ++i) {
    const auto c = static_cast<unsigned char>(d[i]);
    if ((c < 0x20 && !is_space(static_cast<char>(c))) || c == 0x7f) return true;
  }
  return false;
}

Expected<TriMesh> read_stl_binary(const std::string& path, std::string_view d, MeshReadInfo& info,
                                  bool weld) {
  info.format = MeshFormat::stl_binary;
  if (d.size() < kHeader) {
    return byte_error(path, static_cast<std::int64_t>(d.size()),
                      "truncated binary STL: " + plural(d.size(), "byte") +
                          ", but the header and facet count alone take 84");
  }
  const std::uint64_t n = load_u32_le(d.data() + 80);
  const std::uint64_t need = kHeader + kFacet * n;
  if (d.size() < need) {
    const std::uint64_t complete = (d.size() - kHeader) / kFacet;
    return byte_error(path, static_cast<std::int64_t>(d.size()),
                      "truncated binary STL: the header declares " + plural(n, "triangle") + " (" +
                          std::to_string(need) + " bytes) but the file has " +
                          std::to_string(d.size()) + " bytes; it ends inside triangle " +
                          std::to_string(complete));
  }
  if (d.size() > need) {
    return byte_error(path, static_cast<std::int64_t>(need),
                      "binary STL has " + plural(d.size() - need, "byte") + " after the " +
                          plural(n, "triangle") + " declared in the header (facet count mismatch)");
  }
  if (n == 0) return byte_error(path, 80, "no triangles: the binary STL header declares 0 facets");
  if (3 * n > std::numeric_limits<std::uint32_t>::max()) {
    return byte_error(path, 80,
                      "too many triangles (" + std::to_string(n) + ") for 32-bit vertex indices");
  }

  const char* base = d.data() + kHeader;
  auto corner_bits = [base](std::uint64_t i, std::uint32_t bits[3]) {
    std::memcpy(bits, base + kFacet * (i / 3) + 12 + 12 * (i % 3), 12);
    if constexpr (std::endian::native == std::endian::big) {
      for (int k = 0; k < 3; ++k) bits[k] = bswap(bits[k]);
    }
  };

  // Finite coordinates only; the first offender (lowest offset) is reported.
  std::atomic<std::uint64_t> first_bad{std::numeric_limits<std::uint64_t>::max()};
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, n, 1 << 14), [&](const auto& r) {
    for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
      std::uint32_t bits[9];
      std::memcpy(bits, base + kFacet * i + 12, sizeof bits);
      bool bad = false;
      for (std::uint32_t b : bits) {
        if constexpr (std::endian::native == std::endian::big) b = bswap(b);
        // Inf, NaN, or above the supported coordinate range (issue #23, item 7): magnitudes over
        // 2^100 (biased exponent 227, mantissa 0); every float is above its lower end, 2^-250.
        bad |= (b & 0x7fffffffu) > (227u << 23);
      }
      if (bad) {
        std::uint64_t cur = first_bad.load(std::memory_order_relaxed);
        while (i < cur && !first_bad.compare_exchange_weak(cur, i)) {
        }
        return;
      }
    }
  });
  if (const std::uint64_t i = first_bad.load(); i != std::numeric_limits<std::uint64_t>::max()) {
    for (int k = 0; k < 9; ++k) {
      std::uint32_t bits[3];
      corner_bits(3 * i + static_cast<std::uint64_t>(k / 3), bits);
      const float c = std::bit_cast<float>(bits[k % 3]);
      if (!std::isfinite(c)) {
        return byte_error(path,
                          static_cast<std::int64_t>(kHeader + kFacet * i + 12 +
                                                    4 * static_cast<std::uint64_t>(k)),
                          std::string("non-finite coordinate (") + (std::isnan(c) ? "NaN" : "Inf") +
                              ") in vertex " + std::to_string(k / 3) + " of triangle " +
                              std::to_string(i));
      }
      if (!coordinate_in_range(c)) {
        Vec3 p;
        p[static_cast<std::size_t>(k % 3)] = c;
        return byte_error(path,
                          static_cast<std::int64_t>(kHeader + kFacet * i + 12 +
                                                    4 * static_cast<std::uint64_t>(k)),
                          "vertex " + std::to_string(k / 3) + " of triangle " + std::to_string(i) +
                              ": " + coordinate_range_reason(p));
      }
    }
  }

  TriMesh m;
  m.triangles.resize(n);
  if (!weld) {
    m.positions.resize(3 * n);
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, 3 * n, 1 << 15), [&](const auto& r) {
      for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
        std::uint32_t bits[3];
        corner_bits(i, bits);
        m.positions[i] = {std::bit_cast<float>(bits[0]), std::bit_cast<float>(bits[1]),
                          std::bit_cast<float>(bits[2])};
      }
      for (std::uint64_t t = (r.begin() + 2) / 3; t < (r.end() + 2) / 3 && t < n; ++t) {
        const auto v = static_cast<std::uint32_t>(3 * t);
        m.triangles[t] = {v, v + 1, v + 2};
      }
    });
    return m;
  }

  // Weld on the float bits (-0.0f == +0.0f): float -> double is exact and injective, so this equals
  // weld_exact on the soup. Corner order is vertex order, so "first use" is "lowest index".
  info.vertices_before_weld = 3 * n;
  weld_detail::ScratchBuffer<std::uint32_t> rep(3 * n);
  weld_detail::representatives<weld_detail::Key32>(
      3 * n,
      [&](std::size_t i, weld_detail::Key32& k) {
        corner_bits(i, k.data());
        for (std::uint32_t& b : k) b = b == 0x80000000u ? 0u : b;
      },
      rep.data());
  // New ids: representatives numbered in index order (= order of first use), chunk-parallel.
  constexpr std::uint64_t kChunk = 1 << 16;
  const std::uint64_t corners = 3 * n, chunks = (corners + kChunk - 1) / kChunk;
  std::vector<std::uint32_t> first_id(chunks + 1, 0);
  tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
    std::uint32_t count = 0;
    for (std::uint64_t i = c * kChunk, e = std::min(corners, i + kChunk); i < e; ++i)
      count += rep[i] == i;
    first_id[c + 1] = count;
  });
  for (std::uint64_t c = 0; c < chunks; ++c) first_id[c + 1] += first_id[c];
  m.positions.resize(first_id[chunks]);
  weld_detail::ScratchBuffer<std::uint32_t> id(corners);
  tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
    std::uint32_t next = first_id[c];
    for (std::uint64_t i = c * kChunk, e = std::min(corners, i + kChunk); i < e; ++i) {
      if (rep[i] != i) continue;
      std::uint32_t bits[3];
      corner_bits(i, bits);
      m.positions[next] = {std::bit_cast<float>(bits[0]), std::bit_cast<float>(bits[1]),
                           std::bit_cast<float>(bits[2])};
      id[i] = next++;
    }
  });
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, n, 1 << 15), [&](const auto& r) {
    for (std::uint64_t t = r.begin(); t != r.end(); ++t) {
      m.triangles[t] = {id[rep[3 * t]], id[rep[3 * t + 1]], id[rep[3 * t + 2]]};
    }
  });
  return m;
}

Expected<TriMesh> read_stl_ascii(const std::string& path, std::string_view d, MeshReadInfo& info) {
  info.format = MeshFormat::stl_ascii;
  TextReader r(strip_bom(d));
  TriMesh m;
  // A facet takes at least ~60 bytes; reserving from the size keeps reallocation rare and bounded.
  m.triangles.reserve(d.size() / 128);
  m.positions.reserve(3 * (d.size() / 128));

  std::string_view t = r.token();
  if (!iequals(t, "solid")) {
    return text_error(path, r.line(), "ASCII STL must start with 'solid', found " + quoted(t));
  }
  r.skip_line();  // solid name
  auto expect = [&](const char* word, std::int64_t facet_line) -> Expected<bool> {
    const std::string_view w = r.token();
    if (iequals(w, word)) return true;
    if (w.empty()) {
      return text_error(path, r.end_line(),
                        "unexpected end of file inside the facet that starts at line " +
                            std::to_string(facet_line) + " (expected '" + word + "')");
    }
    return text_error(path, r.line(), std::string("expected '") + word + "', found " + quoted(w));
  };
  auto number = [&](const char* what, std::int64_t facet_line, bool finite,
                    double& v) -> Expected<bool> {
    const std::string_view w = r.token();
    if (w.empty()) {
      return text_error(path, r.end_line(),
                        "unexpected end of file inside the facet that starts at line " +
                            std::to_string(facet_line) + " (expected " + what + ")");
    }
    if (!parse_double(w, v))
      return text_error(path, r.line(), "malformed number " + quoted(w) + " (" + what + ")");
    if (finite && !std::isfinite(v)) {
      return text_error(path, r.line(), "non-finite coordinate " + quoted(w) + " (" + what + ")");
    }
    if (finite && !coordinate_in_range(v)) {  // issue #23, item 7
      Vec3 p;
      p[static_cast<std::size_t>(what[7] - 'x')] = v;  // what is "vertex x|y|z"
      return text_error(path, r.line(),
                        "vertex " + std::to_string(m.positions.size()) + " (0-based): " + coordinate_range_reason(p));
    }
    return true;
  };
  static const char* const kAxis[3] = {"vertex x", "vertex y", "vertex z"};

  for (;;) {
    t = r.token();
    if (iequals(t, "facet")) {
      const std::int64_t facet_line = r.line();
      if (auto e = expect("normal", facet_line); !e) return e.error();
      double ignored;
      for (int k = 0; k < 3; ++k) {
        if (auto e = number("normal component", facet_line, false, ignored); !e) return e.error();
      }
      if (auto e = expect("outer", facet_line); !e) return e.error();
      if (auto e = expect("loop", facet_line); !e) return e.error();
      const std::size_t first = m.positions.size();
      for (;;) {
        const std::string_view w = r.token();
        if (iequals(w, "vertex")) {
          Vec3 p;
          for (int k = 0; k < 3; ++k) {
            if (auto e = number(kAxis[k], facet_line, true, p[static_cast<std::size_t>(k)]); !e)
              return e.error();
          }
          m.positions.push_back(p);
        } else if (iequals(w, "endloop")) {
          break;
        } else if (w.empty()) {
          return text_error(path, r.end_line(),
                            "unexpected end of file inside the facet that starts at line " +
                                std::to_string(facet_line) + " (expected 'vertex' or 'endloop')");
        } else {
          return text_error(path, r.line(), "expected 'vertex' or 'endloop', found " + quoted(w));
        }
      }
      const std::size_t corners = m.positions.size() - first;
      if (corners < 3) {
        return text_error(path, r.line(),
                          "facet starting at line " + std::to_string(facet_line) + " has " +
                              plural(corners, "vertex") + "; at least 3 are needed");
      }
      if (m.positions.size() > std::numeric_limits<std::uint32_t>::max()) {
        return text_error(path, r.line(), "too many vertices for 32-bit indices");
      }
      if (corners > 3) ++info.polygons_split;
      const auto v0 = static_cast<std::uint32_t>(first);
      for (std::size_t k = 1; k + 1 < corners; ++k) {
        m.triangles.push_back(
            {v0, static_cast<std::uint32_t>(first + k), static_cast<std::uint32_t>(first + k + 1)});
      }
      if (auto e = expect("endfacet", facet_line); !e) return e.error();
    } else if (iequals(t, "endsolid")) {
      r.skip_line();  // solid name
      const std::string_view next = r.token();
      if (next.empty()) break;
      if (!iequals(next, "solid")) {
        return text_error(
            path, r.line(),
            "expected 'solid' or end of file after 'endsolid', found " + quoted(next));
      }
      r.skip_line();
    } else if (t.empty()) {
      return text_error(path, r.end_line(),
                        "unexpected end of file: missing 'endsolid' (file truncated?)");
    } else {
      return text_error(path, r.line(), "expected 'facet' or 'endsolid', found " + quoted(t));
    }
  }
  if (m.triangles.empty())
    return text_error(path, r.end_line(), "no triangles: the ASCII STL has no facets");
  return m;
}

void write_stl_binary(OutputBuffer& out, const TriMesh& mesh) {
  char header[kHeader];
  std::memset(header, ' ', 80);
  static constexpr char kText[] = "binary STL written by interfere";
  std::memcpy(header, kText, sizeof kText - 1);
  std::uint32_t n = static_cast<std::uint32_t>(mesh.triangles.size());
  if constexpr (std::endian::native == std::endian::big) n = bswap(n);
  std::memcpy(header + 80, &n, 4);
  out.write_bytes(header, kHeader);

  constexpr std::size_t kBatch = 4096;
  std::string buf(kBatch * kFacet, '\0');
  std::size_t used = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto c = mesh.corners(t);
    const Vec3 nrm = facet_normal(c[0], c[1], c[2]);
    float f[12] = {static_cast<float>(nrm.x), static_cast<float>(nrm.y), static_cast<float>(nrm.z)};
    for (int k = 0; k < 3; ++k) {
      f[3 + 3 * k] = static_cast<float>(c[static_cast<std::size_t>(k)].x);
      f[4 + 3 * k] = static_cast<float>(c[static_cast<std::size_t>(k)].y);
      f[5 + 3 * k] = static_cast<float>(c[static_cast<std::size_t>(k)].z);
    }
    char* p = buf.data() + used * kFacet;
    for (int k = 0; k < 12; ++k) {
      auto bits = std::bit_cast<std::uint32_t>(f[k]);
      if constexpr (std::endian::native == std::endian::big) bits = bswap(bits);
      std::memcpy(p + 4 * k, &bits, 4);
    }
    p[48] = p[49] = 0;  // attribute byte count
    if (++used == kBatch) {
      out.write_bytes(buf.data(), used * kFacet);
      used = 0;
    }
  }
  out.write_bytes(buf.data(), used * kFacet);
}

void write_stl_ascii(OutputBuffer& out, const TriMesh& mesh) {
  out.write("solid interfere\n");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto c = mesh.corners(t);
    const Vec3 nrm = facet_normal(c[0], c[1], c[2]);
    out.write("facet normal ");
    out.write_float(static_cast<float>(nrm.x));
    out.write_char(' ');
    out.write_float(static_cast<float>(nrm.y));
    out.write_char(' ');
    out.write_float(static_cast<float>(nrm.z));
    out.write("\n  outer loop\n");
    for (const Vec3& p : c) {
      out.write("    vertex ");
      out.write_xyz_line(p);
    }
    out.write("  endloop\nendfacet\n");
  }
  out.write("endsolid interfere\n");
}

}  // namespace interfere::io_detail
