# The HTML viewer's page (issue #25): viewer/ (three.js, bundled by esbuild from npm) built into one
# HTML template and compiled into interfere_view as ${INTERFERE_VIEWER_TEMPLATE_SOURCE}.
# Placeholder until the npm build lands: no viewer.
set(INTERFERE_WITH_VIEWER OFF)
set(INTERFERE_VIEWER_TEMPLATE_SOURCE ${CMAKE_CURRENT_BINARY_DIR}/generated/viewer_template.cpp)
file(WRITE ${INTERFERE_VIEWER_TEMPLATE_SOURCE}
"#include \"view/viewer_template.h\"\nnamespace interfere::view::detail {\nstd::string_view viewer_template() { return {}; }\n}\n")
