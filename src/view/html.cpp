// The HTML viewer page (include/interfere/view/html.h; issue #25, item 1; docs/viewer.md).
#include "interfere/view/html.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include "interfere/core/atomic_file.h"
#include "interfere/view/json.h"
#include "view/viewer_template.h"

namespace interfere::view {
namespace {

constexpr std::string_view kDataPlaceholder = "/*INTERFERE_VIEWER_DATA*/";
constexpr std::string_view kTitlePlaceholder = "INTERFERE_VIEWER_TITLE";

/// The one position of `needle` in `text`, or an error naming how often it occurs.
Expected<std::size_t> only_occurrence(std::string_view text, std::string_view needle) {
  const std::size_t first = text.find(needle);
  std::size_t count = 0;
  for (std::size_t p = first; p != std::string_view::npos; p = text.find(needle, p + needle.size())) ++count;
  if (count != 1)
    return Error{.reason = "viewer template: the placeholder " + std::string(needle) + " occurs " + std::to_string(count) +
                           " times (expected exactly once)"};
  return first;
}

void replace_all(std::string& s, std::string_view from, std::string_view to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
}

}  // namespace

bool has_html_viewer() { return !detail::viewer_template().empty(); }

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string script_safe_json(std::string_view json) {
  std::string s(json);
  // '<' only occurs inside JSON strings, where \/ and \u0021 are escapes of '/' and '!'.
  replace_all(s, "</", "<\\/");
  replace_all(s, "<!--", "<\\u0021--");
  return s;
}

Expected<std::string> html_page(const Document& doc) { return html_page(doc, detail::viewer_template()); }

Expected<std::string> html_page(const Document& doc, std::string_view page_template) {
  if (page_template.empty())
    return Error{.reason = "this build of interfere has no HTML viewer: configure with Node.js and npm "
                           "(INTERFERE_WITH_VIEWER=ON)"};
  const Expected<std::size_t> data_at = only_occurrence(page_template, kDataPlaceholder);
  if (!data_at) return data_at.error();
  const Expected<std::size_t> title_at = only_occurrence(page_template, kTitlePlaceholder);
  if (!title_at) return title_at.error();
  Expected<std::string> text = document_json(doc);
  if (!text) return text.error();
  const std::string data = script_safe_json(*text);
  const std::string title = html_escape(doc.title.empty() ? std::string("interfere viewer") : doc.title);

  // Spliced in template order, so that neither inserted text is searched for the other placeholder.
  struct Piece {
    std::size_t at, length;
    const std::string* with;
  };
  Piece first{*data_at, kDataPlaceholder.size(), &data}, second{*title_at, kTitlePlaceholder.size(), &title};
  if (second.at < first.at) std::swap(first, second);
  std::string page;
  page.reserve(page_template.size() + data.size() + title.size());
  page.append(page_template.substr(0, first.at));
  page += *first.with;
  page.append(page_template.substr(first.at + first.length, second.at - first.at - first.length));
  page += *second.with;
  page.append(page_template.substr(second.at + second.length));
  return page;
}

Status write_html(const std::filesystem::path& path, const Document& doc) {
  Expected<std::string> page = html_page(doc);
  if (!page) {
    Error e = page.error();
    e.file = path.string();
    return e;
  }
  const std::string& text = *page;
  const auto body = [&text](std::FILE* f) {
    return std::fwrite(text.data(), 1, text.size(), f) == text.size() ? 0 : (errno ? errno : EIO);
  };
  if (path == "-") return write_to_descriptor(STDOUT_FILENO, "standard output", body);
  return write_file_atomic(path, body);
}

}  // namespace interfere::view
