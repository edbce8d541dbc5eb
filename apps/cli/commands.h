// Subcommands; each registers itself on the app and sets `exit_code` when it runs.
#pragma once
#include <string>

namespace CLI {
class App;
}

namespace interfere::cli {
void add_clash_command(CLI::App& app, int& exit_code);
void add_distance_command(CLI::App& app, int& exit_code);
void add_check_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
/// `interfere cell` (cmd_cell.cpp, issue #28): the inspection cell along a joint path.
void add_cell_command(CLI::App& app, int& exit_code);
void add_bearing_command(CLI::App& app, int& exit_code);
void add_surface_command(CLI::App& app, int& exit_code);
void add_simplify_command(CLI::App& app, int& exit_code);
void add_features_command(CLI::App& app, int& exit_code);
void add_assembly_clash_command(CLI::App& app, int& exit_code);
/// `interfere completion bash` (cmd_completion.cpp); bash_completion(app) is the script it prints.
void add_completion_command(CLI::App& app, int& exit_code);
std::string bash_completion(const CLI::App& app);
}  // namespace interfere::cli
