# The HTML viewer's page (issue #25, item 1; docs/viewer.md "How the page is built"): viewer/
# (three.js, bundled by esbuild from npm) built into one HTML template and compiled into
# interfere_view as ${INTERFERE_VIEWER_TEMPLATE_SOURCE}, which defines
# interfere::view::detail::viewer_template() (src/view/viewer_template.h).
#
#   INTERFERE_WITH_VIEWER (option, ON when Node.js >= 18 and npm are found): build the page.
#     1. `npm ci` of viewer/package-lock.json into <build>/viewer/node_modules (again only when
#        package.json or package-lock.json change: a stamp file);
#     2. `node viewer/build.mjs` -> <build>/viewer/viewer.html (again when viewer/src/* change);
#     3. `node viewer/embed_cpp.mjs` -> <build>/generated/viewer_template.cpp (raw string pieces).
#   OFF: viewer_template() returns an empty page; view/html.h then reports an error.
#   INTERFERE_VIEWER_NODE_MODULES: the node_modules the build installed (three, esbuild and
#     puppeteer-core for the browser tests in tests/viewer); INTERFERE_VIEWER_HTML: the template.
#   Target interfere_viewer builds the template alone.
find_program(INTERFERE_NODE_EXECUTABLE NAMES node nodejs)
find_program(INTERFERE_NPM_EXECUTABLE NAMES npm)
set(_interfere_viewer_why "")
if(NOT INTERFERE_NODE_EXECUTABLE OR NOT INTERFERE_NPM_EXECUTABLE)
  set(_interfere_viewer_why "Node.js and npm not found")
else()
  execute_process(COMMAND ${INTERFERE_NODE_EXECUTABLE} --version OUTPUT_VARIABLE _interfere_node_version
                  OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _interfere_node_rc)
  string(REGEX REPLACE "^v" "" _interfere_node_version "${_interfere_node_version}")
  if(NOT _interfere_node_rc EQUAL 0 OR _interfere_node_version VERSION_LESS 18)
    set(_interfere_viewer_why "Node.js ${_interfere_node_version} is older than 18")
  endif()
endif()
if(_interfere_viewer_why STREQUAL "")
  set(_interfere_viewer_default ON)
else()
  set(_interfere_viewer_default OFF)
endif()
option(INTERFERE_WITH_VIEWER "Build the HTML viewer page (needs Node.js >= 18 and npm; npm ci reaches the npm registry once)"
       ${_interfere_viewer_default})

set(_interfere_viewer_src ${CMAKE_CURRENT_SOURCE_DIR}/viewer)
set(_interfere_viewer_bin ${CMAKE_CURRENT_BINARY_DIR}/viewer)
if(INTERFERE_WITH_VIEWER)
  if(NOT _interfere_viewer_why STREQUAL "")
    message(FATAL_ERROR "INTERFERE_WITH_VIEWER=ON but ${_interfere_viewer_why} (install Node.js >= 18 with npm, or -DINTERFERE_WITH_VIEWER=OFF)")
  endif()
  message(STATUS "interfere viewer: ON (Node.js ${_interfere_node_version}): the HTML page is built from viewer/ with npm ci + esbuild")
  set(INTERFERE_VIEWER_TEMPLATE_SOURCE ${CMAKE_CURRENT_BINARY_DIR}/generated/viewer_template.cpp)
  set(INTERFERE_VIEWER_HTML ${_interfere_viewer_bin}/viewer.html)
  set(INTERFERE_VIEWER_NODE_MODULES ${_interfere_viewer_bin}/node_modules)
  set(INTERFERE_VIEWER_NODE_MODULES ${INTERFERE_VIEWER_NODE_MODULES} CACHE INTERNAL "node_modules of the viewer build (tests/viewer)")
  file(MAKE_DIRECTORY ${_interfere_viewer_bin} ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(_stamp ${_interfere_viewer_bin}/npm-ci.stamp)
  add_custom_command(
    OUTPUT ${_stamp}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${_interfere_viewer_src}/package.json
            ${_interfere_viewer_src}/package-lock.json ${_interfere_viewer_bin}
    COMMAND ${INTERFERE_NPM_EXECUTABLE} ci --no-audit --no-fund --ignore-scripts --loglevel=error
    COMMAND ${CMAKE_COMMAND} -E touch ${_stamp}
    DEPENDS ${_interfere_viewer_src}/package.json ${_interfere_viewer_src}/package-lock.json
    WORKING_DIRECTORY ${_interfere_viewer_bin}
    COMMENT "viewer: npm ci (three, esbuild, puppeteer-core) into ${_interfere_viewer_bin}/node_modules"
    VERBATIM)
  file(GLOB _interfere_viewer_inputs CONFIGURE_DEPENDS ${_interfere_viewer_src}/src/*)
  add_custom_command(
    OUTPUT ${INTERFERE_VIEWER_HTML}
    COMMAND ${INTERFERE_NODE_EXECUTABLE} ${_interfere_viewer_src}/build.mjs --node-modules ${INTERFERE_VIEWER_NODE_MODULES}
            ${INTERFERE_VIEWER_HTML}
    DEPENDS ${_stamp} ${_interfere_viewer_src}/build.mjs ${_interfere_viewer_inputs}
    COMMENT "viewer: bundling viewer/src with esbuild into ${INTERFERE_VIEWER_HTML}"
    VERBATIM)
  add_custom_command(
    OUTPUT ${INTERFERE_VIEWER_TEMPLATE_SOURCE}
    COMMAND ${INTERFERE_NODE_EXECUTABLE} ${_interfere_viewer_src}/embed_cpp.mjs ${INTERFERE_VIEWER_HTML}
            ${INTERFERE_VIEWER_TEMPLATE_SOURCE}
    DEPENDS ${INTERFERE_VIEWER_HTML} ${_interfere_viewer_src}/embed_cpp.mjs
    COMMENT "viewer: embedding the page in ${INTERFERE_VIEWER_TEMPLATE_SOURCE}"
    VERBATIM)
  add_custom_target(interfere_viewer DEPENDS ${INTERFERE_VIEWER_HTML})
else()
  if(_interfere_viewer_why STREQUAL "")
    set(_interfere_viewer_why "switched off")
  endif()
  message(STATUS "interfere viewer: OFF (${_interfere_viewer_why}): no HTML viewer page, --html reports an error; "
                 "install Node.js >= 18 with npm and configure with -DINTERFERE_WITH_VIEWER=ON to build it")
  set(INTERFERE_VIEWER_TEMPLATE_SOURCE ${CMAKE_CURRENT_BINARY_DIR}/generated/viewer_template_stub.cpp)
  set(INTERFERE_VIEWER_HTML "")
  set(INTERFERE_VIEWER_NODE_MODULES "")
  set(INTERFERE_VIEWER_NODE_MODULES "" CACHE INTERNAL "node_modules of the viewer build (tests/viewer)")
  file(CONFIGURE OUTPUT ${INTERFERE_VIEWER_TEMPLATE_SOURCE} CONTENT
"// Generated by cmake/viewer.cmake (INTERFERE_WITH_VIEWER=OFF): no viewer page.
#include \"view/viewer_template.h\"
namespace interfere::view::detail {
std::string_view viewer_template() { return {}; }
}  // namespace interfere::view::detail
")
endif()
