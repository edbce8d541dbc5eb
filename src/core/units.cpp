// Length units (include/interfere/core/units.h).
#include "interfere/core/units.h"

namespace interfere {

std::optional<double> millimetres_per_unit(std::string_view unit) {
  if (unit == "mm") return 1.0;
  if (unit == "cm") return 10.0;
  if (unit == "m") return 1000.0;
  if (unit == "um") return 1e-3;
  if (unit == "in") return 25.4;
  if (unit == "ft") return 304.8;
  return std::nullopt;
}

const char* known_units() {
  return "mm, cm, m, um, in, ft";
}

}  // namespace interfere
