// Length units of inputs (issue #23, item 6): every input carries its own unit and all geometry is
// converted to one working unit before any query (docs/robustness.md, "Units").
#pragma once
#include <optional>
#include <string_view>

namespace interfere {

/// Millimetres per unit for the unit names the project accepts: mm, cm, m, um, in, ft; nullopt
/// for any other name.
std::optional<double> millimetres_per_unit(std::string_view unit);

/// The names millimetres_per_unit accepts, for messages: "mm, cm, m, um, in, ft".
const char* known_units();

}  // namespace interfere
