// The self-contained HTML viewer (issue #25, item 1; docs/viewer.md): the page template built from
// viewer/ (three.js bundled by esbuild, compiled into the library by cmake/viewer.cmake) with the
// document's JSON (view/json.h) and title filled in. One file, no network at view time.
//
// The template holds exactly one data placeholder, /*INTERFERE_VIEWER_DATA*/ inside
// <script id="interfere-data" type="application/json">, and one title placeholder,
// INTERFERE_VIEWER_TITLE inside <title>. The JSON goes in with every "</" written as "<\/" (and
// "<!--" as "<\u0021--"), so that no text of the document can end the script element or open an
// HTML comment in it; both are JSON escapes that JSON.parse reads back unchanged. The title is
// HTML-escaped.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

#include "interfere/core/error.h"
#include "interfere/view/document.h"

namespace interfere::view {

/// Whether this build has the page template (built with Node.js and npm: INTERFERE_WITH_VIEWER=ON).
bool has_html_viewer();

/// The page: the built-in template filled with `doc`. Errors: a build without the template ("this
/// build of interfere has no HTML viewer: ..."), an invalid document (document_json's errors).
Expected<std::string> html_page(const Document& doc);

/// The same with another template (tests, embedding): an empty template is the no-viewer error;
/// a template without exactly one of each placeholder is an error naming it.
Expected<std::string> html_page(const Document& doc, std::string_view page_template);

/// Writes html_page(doc) to `path` atomically (core/atomic_file.h: a temporary file renamed over
/// the target, a symbolic link written through, a special file written directly); "-" writes to
/// standard output. The caller checks that `path` is not one of its inputs.
Status write_html(const std::filesystem::path& path, const Document& doc);

/// Text with & < > " ' replaced by their HTML character references.
std::string html_escape(std::string_view text);

/// JSON text made safe inside a <script> element: "</" -> "<\/", "<!--" -> "<\u0021--".
std::string script_safe_json(std::string_view json);

}  // namespace interfere::view
