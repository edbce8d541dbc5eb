// Cells of the line-based text files the readers take (CSV paths, joint paths, motion files):
// one definition of "blank", of a comma-separated row and of a number cell, so every reader
// accepts the same spelling and reports the same failures.
#pragma once

#include <cmath>
#include <string_view>
#include <vector>

namespace interfere {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
std::string_view trim_blanks(std::string_view s);

/// The comma-separated cells of one line, each trimmed (an empty line gives one empty cell).
std::vector<std::string_view> split_csv_cells(std::string_view line);

/// The whole cell as a number (decimal or exponent notation, an optional leading '+'; no blanks).
/// False when the cell is empty or not entirely a number. True for a number outside the double
/// range: `out` is then +-inf (overflow) or 0 / a denormal (underflow), as strtod gives it, and the
/// caller decides whether a non-finite value is an error.
bool parse_number_cell(std::string_view cell, double& out);

/// parse_number_cell, and the value is finite.
inline bool parse_finite_cell(std::string_view cell, double& out) {
  return parse_number_cell(cell, out) && std::isfinite(out);
}

}  // namespace interfere
