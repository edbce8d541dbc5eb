// The verdict model (include/interfere/query/verdict.h; issue #23, item 13).
#include "interfere/query/verdict.h"

#include <array>

namespace interfere {

namespace {
constexpr std::array<const char*, 5> kNames{"clear", "clearance", "contact", "undecided", "clash"};
}

const char* verdict_name(Verdict v) {
  return kNames[static_cast<std::size_t>(v)];
}

std::optional<Verdict> verdict_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (name == kNames[i]) return static_cast<Verdict>(i);
  return std::nullopt;
}

std::optional<FailOn> parse_fail_on(std::string_view text) {
  FailOn f;
  if (text.empty()) return std::nullopt;
  while (true) {
    const std::size_t comma = text.find(',');
    const std::string_view item = text.substr(0, comma);
    if (item == "contact") {
      f.contact = true;
    } else if (item == "clearance") {
      f.clearance = true;
    } else if (item != "clash") {
      return std::nullopt;
    }
    if (comma == std::string_view::npos) break;
    text.remove_prefix(comma + 1);
  }
  return f;
}

int verdict_exit_status(Verdict v, const FailOn& fail_on) {
  switch (v) {
    case Verdict::clash:
      return 1;
    case Verdict::undecided:
      return 3;
    case Verdict::contact:
      return fail_on.contact ? 1 : 0;
    case Verdict::clearance:
      return fail_on.clearance ? 1 : 0;
    case Verdict::clear:
      return 0;
  }
  return 3;
}

}  // namespace interfere
