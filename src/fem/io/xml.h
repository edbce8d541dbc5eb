// Internal: a small XML tokenizer sufficient for VTK XML files (no XML library): elements with
// attributes, text content, comments, processing instructions, CDATA-free. The VTK <AppendedData>
// element is special: its content after the '_' marker is raw bytes and is not tokenized. Every
// node keeps its byte offset for error messages.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "interfere/core/error.h"

namespace interfere::fem_io {

struct XmlNode {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attrs;
  std::vector<std::unique_ptr<XmlNode>> children;
  std::string_view text;     ///< character content (first text run), unescaped only by the user
  std::size_t offset = 0;    ///< byte offset of '<'
  std::size_t text_offset = 0;
  const std::string* attr(std::string_view key) const {
    for (const auto& [k, v] : attrs) {
      if (k == key) return &v;
    }
    return nullptr;
  }
  const XmlNode* child(std::string_view n) const {
    for (const auto& c : children) {
      if (c->name == n) return c.get();
    }
    return nullptr;
  }
};

struct XmlDocument {
  std::unique_ptr<XmlNode> root;
  std::size_t appended = std::string_view::npos;  ///< offset of the byte after '_' in AppendedData
  std::string appended_encoding;                  ///< "raw" or "base64"
};

/// Parses `s`; errors name the byte offset.
Expected<XmlDocument> parse_xml(const std::string& file, std::string_view s);

}  // namespace interfere::fem_io
