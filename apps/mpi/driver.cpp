// interfere-mpi's time-series subcommands: the shared output write (driver.h; issue #31).
#include "driver.h"

#include <filesystem>

namespace interfere::mpi {

void write_file(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return;
  }
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error(path + ": cannot write");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error(path + ": cannot write");
  std::filesystem::rename(tmp, path);
}

}  // namespace interfere::mpi
