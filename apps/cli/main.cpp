// `interfere`: the command-line front end. It only parses, fills requests, calls engines and
// serialises results (ARCHITECTURE.md). Exit status: 0 clear, 1 interference, 2 usage/input error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "cad_exec.h"
#include "commands.h"
#include "common.h"
#include "view_output.h"

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
