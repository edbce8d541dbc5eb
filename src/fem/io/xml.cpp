// Minimal XML tokenizer for VTK XML files (xml.h), after the XML 1.0 grammar (W3C, sections 2.5
// comments, 2.6 processing instructions, 3.1 start-tags/end-tags, 4.6 predefined entities).
#include "xml.h"

#include "scan.h"

namespace interfere::fem_io {
namespace {

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':' || c == '-' || c == '.';
}

std::string unescape(std::string_view v) {
  std::string r;
  r.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] != '&') {
      r += v[i];
      continue;
    }
    const std::size_t semi = v.find(';', i);
    const std::string_view ent = semi == std::string_view::npos ? std::string_view() : v.substr(i + 1, semi - i - 1);
    if (ent == "lt") r += '<';
    else if (ent == "gt") r += '>';
    else if (ent == "amp") r += '&';
    else if (ent == "quot") r += '"';
    else if (ent == "apos") r += '\'';
    else {
      r += '&';
      continue;
    }
    i = semi;
  }
  return r;
}

}  // namespace

Expected<XmlDocument> parse_xml(const std::string& file, std::string_view s) {
  XmlDocument doc;
  std::vector<XmlNode*> stack;
  std::size_t i = 0;
  const std::size_t n = s.size();
  auto fail = [&](std::size_t at, std::string r) { return byte_error(file, static_cast<std::int64_t>(at), "XML: " + std::move(r)); };
  if (s.substr(0, 3) == "\xEF\xBB\xBF") i = 3;
  while (i < n) {
    const std::size_t lt = s.find('<', i);
    if (lt == std::string_view::npos) {
      if (!trim(s.substr(i)).empty() && !stack.empty()) return fail(i, "unexpected end of file inside <" + stack.back()->name + ">");
      break;
    }
    // Character content: the first run that is not only white space (VTK writes InformationKey
    // children before the data of a DataArray).
    if (!stack.empty() && trim(stack.back()->text).empty() && lt > i && (stack.back()->text.empty() || !trim(s.substr(i, lt - i)).empty())) {
      stack.back()->text = s.substr(i, lt - i);
      stack.back()->text_offset = i;
    } else if (stack.empty() && !trim(s.substr(i, lt - i)).empty()) {
      return fail(i, "text outside the root element");
    }
    i = lt;
    if (s.substr(i, 4) == "<!--") {
      const std::size_t e = s.find("-->", i + 4);
      if (e == std::string_view::npos) return fail(i, "unterminated comment");
      i = e + 3;
      continue;
    }
    if (s.substr(i, 2) == "<?" || s.substr(i, 2) == "<!") {
      const std::size_t e = s.find('>', i);
      if (e == std::string_view::npos) return fail(i, "unterminated declaration");
      i = e + 1;
      continue;
    }
    if (s.substr(i, 2) == "</") {
      std::size_t j = i + 2;
      while (j < n && name_char(s[j])) ++j;
      const std::string_view name = s.substr(i + 2, j - i - 2);
      while (j < n && is_space(s[j])) ++j;
      if (j >= n || s[j] != '>') return fail(i, "malformed end tag");
      if (stack.empty() || stack.back()->name != name) {
        return fail(i, "end tag </" + std::string(name) + "> does not match " + (stack.empty() ? std::string("any open element") : "<" + stack.back()->name + ">"));
      }
      stack.pop_back();
      i = j + 1;
      if (stack.empty()) break;
      continue;
    }
    // Start tag.
    std::size_t j = i + 1;
    while (j < n && name_char(s[j])) ++j;
    if (j == i + 1) return fail(i, "malformed tag");
    auto node = std::make_unique<XmlNode>();
    node->name = std::string(s.substr(i + 1, j - i - 1));
    node->offset = i;
    bool self_close = false;
    for (;;) {
      while (j < n && is_space(s[j])) ++j;
      if (j >= n) return fail(i, "unterminated tag <" + node->name + ">");
      if (s[j] == '>') {
        ++j;
        break;
      }
      if (s[j] == '/') {
        if (j + 1 >= n || s[j + 1] != '>') return fail(j, "malformed tag <" + node->name + ">");
        self_close = true;
        j += 2;
        break;
      }
      const std::size_t k0 = j;
      while (j < n && name_char(s[j])) ++j;
      if (j == k0) return fail(j, "malformed attribute in <" + node->name + ">");
      std::string key(s.substr(k0, j - k0));
      while (j < n && is_space(s[j])) ++j;
      if (j >= n || s[j] != '=') return fail(j, "attribute " + key + " without a value");
      ++j;
      while (j < n && is_space(s[j])) ++j;
      if (j >= n || (s[j] != '"' && s[j] != '\'')) return fail(j, "attribute " + key + ": value not quoted");
      const char q = s[j];
      const std::size_t e = s.find(q, j + 1);
      if (e == std::string_view::npos) return fail(j, "attribute " + key + ": unterminated value");
      node->attrs.emplace_back(std::move(key), unescape(s.substr(j + 1, e - j - 1)));
      j = e + 1;
    }
    XmlNode* raw = node.get();
    if (stack.empty()) {
      if (doc.root) return fail(i, "second root element");
      doc.root = std::move(node);
    } else {
      stack.back()->children.push_back(std::move(node));
    }
    i = j;
    if (raw->name == "AppendedData" && !self_close) {
      const std::string* enc = raw->attr("encoding");
      doc.appended_encoding = enc ? *enc : "raw";
      const std::size_t us = s.find('_', i);
      if (us == std::string_view::npos) return fail(i, "AppendedData without the '_' marker");
      doc.appended = us + 1;
      break;  // raw bytes follow: nothing more to tokenize
    }
    if (!self_close) stack.push_back(raw);
  }
  if (!doc.root) return fail(0, "no root element");
  if (!stack.empty() && doc.appended == std::string_view::npos) return fail(n, "unexpected end of file inside <" + stack.back()->name + ">");
  return doc;
}

}  // namespace interfere::fem_io
