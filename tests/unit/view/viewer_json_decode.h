// Independent decoding of the viewer JSON's buffers for the tests (issue #25): a base64 decoder
// written from RFC 4648 (not the library's), little-endian reads of float32/uint32/uint16, and the
// column-major pose matrix applied to a point.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace interfere::view::testing {

inline std::string decode_base64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  if (text.size() % 4 != 0) throw std::runtime_error("base64 length not a multiple of 4");
  std::string out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const std::size_t v = alphabet.find(c);
    if (v == std::string::npos) throw std::runtime_error("not base64");
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

inline std::uint32_t le_u32(const std::string& b, std::size_t i) {
  const auto u = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(b[i + k])); };
  return u(0) | (u(1) << 8) | (u(2) << 16) | (u(3) << 24);
}
inline float le_f32(const std::string& b, std::size_t i) {
  const std::uint32_t bits = le_u32(b, i);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}
inline std::uint16_t le_u16(const std::string& b, std::size_t i) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(b[i]) | (static_cast<unsigned char>(b[i + 1]) << 8));
}

/// m (16 numbers, column-major) times (x, y, z, 1).
inline std::array<double, 3> apply_column_major(const std::vector<double>& m, double x, double y, double z) {
  return {m[0] * x + m[4] * y + m[8] * z + m[12], m[1] * x + m[5] * y + m[9] * z + m[13],
          m[2] * x + m[6] * y + m[10] * z + m[14]};
}

}  // namespace interfere::view::testing
