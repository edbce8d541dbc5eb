#include "interfere/core/error.h"

#include <cstdio>

namespace interfere {

// Out of line, with the warning silenced here only: GCC 12 reports a false -Wrestrict (bug 105651)
// for std::string appends after inlining.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif
std::string Error::message() const {
  std::string m;
  m.reserve(file.size() + reason.size() + 48);
  m.append(file);
  if (line >= 0) m.append(":").append(std::to_string(line));
  if (!file.empty() || line >= 0) m.append(": ");
  if (byte >= 0) m.append("byte ").append(std::to_string(byte)).append(": ");
  m.append(reason);
  return m;
}

std::string short_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace interfere
