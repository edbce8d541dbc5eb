// --html / --glb / --pvd on every command (view_output.h; issue #25).
#include "view_output.h"

#include <CLI/CLI.hpp>

#include "interfere/view/budget.h"
#include "interfere/view/gltf.h"
#include "interfere/view/pvd.h"
#include "interfere/view/html.h"

namespace interfere::cli {
namespace {
std::string g_command_line;
}

void add_view_options(CLI::App& c, ViewOutputs& v) {
  c.add_option("--html", v.html, "write the result as a self-contained HTML viewer (no network, no server)");
  c.add_option("--glb", v.glb, "write the result as a glTF 2.0 scene (.glb: bodies, clash regions, curves)");
  c.add_option("--pvd", v.pvd, "write the result as a ParaView time series (.pvd + per-frame .vtp files)");
  c.add_option("--view-budget", v.budget,
               "triangles of the bodies in the HTML page; above it they are decimated for display (default 300000)");
}

void check_view_outputs(const ViewOutputs& v) {
  check_output(v.html, {".html", ".htm"}, "--html");
  if (!v.html.empty() && !view::has_html_viewer())  // before any work: nothing is written
    throw InputError("--html " + v.html + ": this build of interfere has no HTML viewer (configure with Node.js and npm: "
                     "INTERFERE_WITH_VIEWER=ON); --glb and --pvd need no viewer");
  check_output(v.glb, {".glb"}, "--glb");
  check_output(v.pvd, {".pvd"}, "--pvd");
  if (v.budget < 1000) throw InputError("--view-budget must be at least 1000 triangles, got " + std::to_string(v.budget));
}

void set_command_line(int argc, char** argv) {
  g_command_line.clear();
  for (int i = 0; i < argc; ++i) {
    std::string a = i == 0 ? std::string("interfere") : std::string(argv[i]);
    const bool quote = a.empty() || a.find_first_of(" \t\"'$\\") != std::string::npos;
    if (!g_command_line.empty()) g_command_line += ' ';
    g_command_line += quote ? "'" + a + "'" : a;
  }
}
const std::string& command_line() { return g_command_line; }

void write_views(const ViewOutputs& v, view::Document doc) {
  if (!v.any()) return;
  doc.command = g_command_line;
  doc.tool_version = INTERFERE_VERSION;
  if (!v.glb.empty()) {
    Progress progress("writing " + v.glb);
    write_or_throw(view::write_glb(v.glb, doc));
  }
  if (!v.pvd.empty()) {
    Progress progress("writing " + v.pvd);
    write_or_throw(view::write_pvd(v.pvd, doc));
  }
  if (!v.html.empty()) {
    Progress progress("writing " + v.html);
    view::decimate_for_display(doc, {.triangle_budget = v.budget});
    write_or_throw(view::write_html(v.html, doc));
  }
}

}  // namespace interfere::cli
