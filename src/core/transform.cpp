#include "interfere/core/transform.h"

#include <charconv>
#include <cmath>
#include <vector>

namespace interfere {

Expected<Transform> Transform::parse(std::string_view text) {
  std::vector<double> v;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == ',' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
      continue;
    }
    double x = 0;
    const char* first = text.data() + i;
    const auto [ptr, ec] = std::from_chars(first, text.data() + text.size(), x);
    if (ec != std::errc() || ptr == first) {
      return Error{.reason = "transform: not a number at character " + std::to_string(i + 1) +
                             " of \"" + std::string(text) + "\""};
    }
    if (!std::isfinite(x)) {
      return Error{.reason = "transform: value " + std::to_string(v.size() + 1) + " is not finite"};
    }
    v.push_back(x);
    i = static_cast<std::size_t>(ptr - text.data());
  }
  if (v.size() != 12) {
    return Error{.reason = "transform: expected 12 numbers \"r00 r01 r02 tx r10 r11 r12 ty r20 r21 "
                           "r22 tz\", got " +
                           std::to_string(v.size())};
  }
  Transform t;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) t.r[row][col] = v[row * 4 + col];
    t.t[row] = v[row * 4 + 3];
  }
  return t;
}

std::array<double, 12> Transform::to_row_major() const {
  std::array<double, 12> out{};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out[row * 4 + col] = r[row][col];
    out[row * 4 + 3] = t[row];
  }
  return out;
}

std::array<std::array<double, 4>, 3> Transform::to_rows() const {
  std::array<std::array<double, 4>, 3> out{};
  for (int row = 0; row < 3; ++row) out[row] = {r[row][0], r[row][1], r[row][2], t[row]};
  return out;
}

}  // namespace interfere
