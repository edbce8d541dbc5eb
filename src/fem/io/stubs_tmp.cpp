#include "scan.h"
namespace interfere::fem_io {
Expected<FemMesh> read_abaqus(const std::filesystem::path& p, std::string_view) { return file_error(p.string(), "todo"); }
Status write_vtk_legacy(const FemMesh&, const FemWriteOptions&, std::string&) { return Error{.reason = "todo"}; }
Status write_vtu(const FemMesh&, const FemWriteOptions&, std::string&) { return Error{.reason = "todo"}; }
Status write_nastran(const FemMesh&, const FemWriteOptions&, std::string&) { return Error{.reason = "todo"}; }
Status write_abaqus(const FemMesh&, const FemWriteOptions&, std::string&) { return Error{.reason = "todo"}; }
}
