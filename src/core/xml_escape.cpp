#include "interfere/core/xml_escape.h"

namespace interfere {

std::string xml_escape(std::string_view text) {
  std::string r;
  r.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '&': r += "&amp;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

}  // namespace interfere
