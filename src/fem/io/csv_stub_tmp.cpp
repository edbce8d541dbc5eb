// TEMPORARY (fem-surface branch): a link stub for read_displacements_csv until the fem-io branch's
// CSV reader lands. Delete this file when merging fem-io's implementation.
#include "interfere/fem/io.h"

namespace interfere {
Expected<NodalSeries> read_displacements_csv(const std::filesystem::path& path, const FemMesh&, CsvDisplacementInfo*) {
  return Error{.file = path.string(), .reason = "displacement CSV reader not implemented yet (fem-io branch)"};
}
}  // namespace interfere
