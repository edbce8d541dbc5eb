// The picture of every command (issue #25): --html FILE (the self-contained viewer), --glb FILE
// (a glTF 2.0 scene) and --pvd FILE (a ParaView time series), registered on each command and
// written from the command's view::Document after its reports.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "common.h"
#include "interfere/view/document.h"

namespace CLI {
class App;
}

namespace interfere::cli {

struct ViewOutputs {
  std::string html, glb, pvd;
  std::size_t budget = 300000;  ///< --view-budget: display triangles of the bodies (clash regions not counted)
  bool any() const { return !html.empty() || !glb.empty() || !pvd.empty(); }
  /// The outputs with their flags, for check_distinct_files.
  std::vector<NamedPath> paths() const { return {{"--html", html}, {"--glb", glb}, {"--pvd", pvd}}; }
};

/// Registers --html, --glb, --pvd and --view-budget.
void add_view_options(CLI::App& command, ViewOutputs& v);
/// Checks the outputs before any work (extensions, directories). Throws InputError.
void check_view_outputs(const ViewOutputs& v);

/// The command line as run (main() records it), for the page's header and the glTF's extras.
void set_command_line(int argc, char** argv);
const std::string& command_line();

/// Fills the document's command and version, decimates the bodies for display (the HTML page
/// only; glTF and ParaView get full resolution) and writes each requested output. Throws
/// InputError when a write fails.
void write_views(const ViewOutputs& v, view::Document doc);

}  // namespace interfere::cli
