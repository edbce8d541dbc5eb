// `interfere`: the command-line front end. It only parses, fills requests, calls engines and
// serialises results (ARCHITECTURE.md). Exit status: 0 clear, 1 interference, 2 usage/input error,
// 3 undecided; every --help says which apply (apply_conventions below).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "cad_exec.h"
#include "commands.h"
#include "common.h"
#include "view_output.h"

namespace {

// Exit statuses, stated in every --help (issue #30, item 5).
constexpr const char* kVerdictExit =
    "Exit status: 0 clear, contact or clearance; 1 clash{}; 2 usage or input error (message on stderr, nothing "
    "written); 3 undecided.";
constexpr const char* kPlainExit = "Exit status: 0 done; 2 usage or input error (message on stderr, nothing written).";

std::string replace_braces(std::string s, const std::string& with) {
  if (const auto at = s.find("{}"); at != std::string::npos) s.replace(at, 2, with);
  return s;
}

/// Every --help states the exit statuses; options that apply to one kind of input only are listed
/// under their own heading (FE models, STEP inputs) rather than among the general ones; parse
/// errors read `interfere: error: ...` as every other error does.
void apply_conventions(CLI::App& app) {
  app.footer(std::string("Exit status: 0 clear (or done), 1 clash, 2 usage or input error, 3 undecided; each "
                         "command's --help gives its own. Reports: docs/report.md. Bash completion: "
                         "interfere completion bash."));
  for (CLI::App* sc : app.get_subcommands({})) {
    const std::string name = sc->get_name();
    // (a command with --fail-on exits by verdict_exit_status; these do without it)
    const bool fail_on = sc->get_option_no_throw("--fail-on") != nullptr;
    const bool verdict = fail_on || name == "clash" || name == "distance" || name == "sweep" || name == "bearing" ||
                         name == "assembly-clash";
    sc->footer(verdict ? replace_braces(kVerdictExit, fail_on ? " (and the verdicts --fail-on names)" : "")
                       : std::string(kPlainExit));
    for (CLI::Option* opt : sc->get_options([](CLI::Option*) { return true; })) {
      if (opt->get_group() != "Options") continue;
      const std::string& d = opt->get_description();
      if (d.rfind("FEM: ", 0) == 0 || d.rfind("FE steps: ", 0) == 0)
        opt->group("FE models (FEM input files only; docs/fem.md)");
      else if (d.rfind("STEP inputs: ", 0) == 0)
        opt->group("STEP inputs");
    }
  }
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("interfere: error: ") + e.what() +
           "\nRun 'interfere --help' or 'interfere COMMAND --help' for the usage.\n";
  });
}

}  // namespace

int main(int argc, char** argv) {
  using namespace interfere::cli;
  CLI::App app{"interfere " INTERFERE_VERSION ": exact, parallel interference (clash) checking"};
  app.set_version_flag("--version", INTERFERE_VERSION);
  app.require_subcommand(1);
  app.fallthrough();  // global flags (--quiet) also after the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress lines on stderr (warnings are still printed)");
  int exit_code = kClear;
  add_clash_command(app, exit_code);
  add_distance_command(app, exit_code);
  add_check_command(app, exit_code);
  add_sweep_command(app, exit_code);
  add_cell_command(app, exit_code);
  add_bearing_command(app, exit_code);
  add_surface_command(app, exit_code);
  add_simplify_command(app, exit_code);
  add_features_command(app, exit_code);
  add_assembly_clash_command(app, exit_code);
  add_completion_command(app, exit_code);
  apply_conventions(app);
  app.parse_complete_callback([&] { Progress::set_quiet(quiet); });
  set_command_line(argc, argv);
  remember_arguments(argv);
  use_installed_data_dir();
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kInputError;
  } catch (const InputError& e) {
    std::fprintf(stderr, "interfere: error: %s\n", e.what());
    return kInputError;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "interfere: error: out of memory\n");
    return kInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "interfere: error: %s\n", e.what());
    return kInputError;
  }
  return exit_code;
}
