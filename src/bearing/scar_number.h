// Numbers in the scar importers' error messages (scar_import.cpp, scar_png.cpp, scar_points.cpp):
// every digit of the double (%.17g), so a message names exactly the value read.
#pragma once
#include <cstdio>
#include <string>

namespace interfere::bearing::detail {

inline std::string scar_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace interfere::bearing::detail
