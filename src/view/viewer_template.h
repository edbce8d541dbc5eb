// The viewer page template (issue #25, item 1): viewer/ bundled by esbuild at build time into one HTML
// file, compiled into the library by cmake/viewer.cmake. Empty when the build has no viewer
// (INTERFERE_WITH_VIEWER=OFF: Node.js/npm not found); view/html.h then reports an error.
#pragma once
#include <string_view>

namespace interfere::view::detail {

/// The page with its two placeholders (docs/viewer.md): /*INTERFERE_VIEWER_DATA*/ and INTERFERE_VIEWER_TITLE.
std::string_view viewer_template();

}  // namespace interfere::view::detail
