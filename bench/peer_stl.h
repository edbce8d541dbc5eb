// The whole-process peers' STL input (bench/peer_process_*.cpp): a binary STL file read whole and
// turned into a triangle soup of doubles (3 corners per facet, no welding: neither FCL's BVHModel
// nor CGAL's box sweep needs shared vertices). The minimum any program reading STL does; checked
// only for the size a binary STL must have.
#pragma once
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace interfere::bench {

using Corner = std::array<double, 3>;
using Facet = std::array<Corner, 3>;

inline std::vector<Facet> read_binary_stl(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error(path + ": cannot open");
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size > 0 ? size : 0));
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), f);
  std::fclose(f);
  std::uint32_t n = 0;
  if (got != bytes.size() || bytes.size() < 84) throw std::runtime_error(path + ": short file");
  std::memcpy(&n, bytes.data() + 80, 4);
  if (bytes.size() != 84 + 50 * static_cast<std::size_t>(n))
    throw std::runtime_error(path + ": not a binary STL");
  std::vector<Facet> out(n);
  for (std::size_t t = 0; t < n; ++t) {
    float v[9];
    std::memcpy(v, bytes.data() + 84 + 50 * t + 12, sizeof v);
    for (int c = 0; c < 3; ++c) out[t][c] = {v[3 * c], v[3 * c + 1], v[3 * c + 2]};
  }
  return out;
}

}  // namespace interfere::bench
