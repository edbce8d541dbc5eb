// Text cells shared by the line-based readers (core/text_cells.h).
#include "interfere/core/text_cells.h"

#include <charconv>
#include <cstdlib>
#include <string>
#include <system_error>

namespace interfere {

std::string_view trim_blanks(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_csv_cells(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      out.push_back(trim_blanks(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return out;
}

bool parse_number_cell(std::string_view cell, double& out) {
  const char* first = cell.data();
  const char* last = first + cell.size();
  if (first != last && *first == '+') {
    ++first;
    if (first != last && (*first == '+' || *first == '-')) return false;
  }
  if (first == last) return false;
  const auto [ptr, ec] = std::from_chars(first, last, out, std::chars_format::general);
  if (ptr != last) return false;
  // out of range leaves `out` untouched: strtod gives the overflow (inf) or underflow (0, denormal)
  if (ec == std::errc::result_out_of_range) out = std::strtod(std::string(first, last).c_str(), nullptr);
  return ec == std::errc() || ec == std::errc::result_out_of_range;
}

}  // namespace interfere
