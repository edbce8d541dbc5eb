// Internal (src/cad only): where the installed JSON data (feature library, semantic rules) lives.
#pragma once
#include <filesystem>
#include <string>

namespace interfere::cad {
/// $INTERFERE_DATA_DIR/features/name, else the install's share/interfere/features/name, else the
/// source tree's data/features/name.
std::filesystem::path data_file(const std::string& name);
}  // namespace interfere::cad
