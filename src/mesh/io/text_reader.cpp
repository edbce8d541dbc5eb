#include "text_reader.h"

#include <cmath>

#include "formats.h"
#include "interfere/core/coordinate_range.h"

#include <charconv>
#include <cstdio>
#include <system_error>

namespace interfere::io_detail {

bool parse_double(std::string_view t, double& out) {
  if (t.empty()) return false;
  const char* b = t.data();
  const char* e = b + t.size();
  if (*b == '+') {
    ++b;
    if (b == e || *b == '-' || *b == '+') return false;
  }
  const auto r = std::from_chars(b, e, out, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == e;
}

bool parse_int(std::string_view t, std::int64_t& out) {
  if (t.empty()) return false;
  const char* b = t.data();
  const char* e = b + t.size();
  if (*b == '+') {
    ++b;
    if (b == e || *b == '-' || *b == '+') return false;
  }
  const auto r = std::from_chars(b, e, out, 10);
  return r.ec == std::errc() && r.ptr == e;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

std::string quoted(std::string_view t) {
  constexpr std::size_t kMax = 40;
  std::string s = "'";
  for (std::size_t i = 0; i < t.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(t[i]);
    if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      s += buf;
    } else {
      s += static_cast<char>(c);
    }
  }
  if (t.size() > kMax) s += "...";
  return s + "'";
}

std::string_view strip_comment(std::string_view line) {
  const std::size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  std::size_t b = 0, e = line.size();
  while (b < e && is_space(line[b])) ++b;
  while (e > b && is_space(line[e - 1])) --e;
  return line.substr(b, e - b);
}

Status parse_coordinate(const std::string& path, std::int64_t line, std::string_view token, int axis,
                        double& out, std::int64_t vertex) {
  static const char* const kAxis[3] = {"x", "y", "z"};
  if (!parse_double(token, out)) {
    return text_error(path, line, "malformed number " + quoted(token) + " (vertex " + kAxis[axis] + ")");
  }
  if (!std::isfinite(out)) {
    return text_error(path, line, "non-finite coordinate " + quoted(token) + " (vertex " + kAxis[axis] + ")");
  }
  if (!coordinate_in_range(out)) {  // issue #23, item 7: the predicates' range
    Vec3 p;
    p[static_cast<std::size_t>(axis)] = out;
    return text_error(path, line, "vertex " + std::to_string(vertex) + ": " + coordinate_range_reason(p));
  }
  return {};
}

}  // namespace interfere::io_detail
