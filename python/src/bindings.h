// Bindings of the library modules, one bind_<module>.cpp each, registered from module.cpp's
// PYBIND11_MODULE. Each function adds its classes and functions to the extension module `m`.
#pragma once
#include <pybind11/pybind11.h>
#include <tbb/global_control.h>

#include <optional>
#include <string>

#include "interfere/core/error.h"

namespace interfere::python {
/// Raises interfere.InputError carrying the error's file, line, byte and reason (errors.cpp).
[[noreturn]] void raise_input_error(const Error& e);

/// oneTBB thread limit for the duration of one call (0 = oneTBB's default, all cores); a negative
/// count is a ValueError whose message ends with `zero_means` in parentheses.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads, const char* zero_means = "0 = all cores") {
    if (threads < 0) throw pybind11::value_error("threads must be >= 0 (" + std::string(zero_means) + ")");
    if (threads > 0) control_.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  }

 private:
  std::optional<tbb::global_control> control_;
};

void bind_probe(pybind11::module_& m);
/// The inspection cell (bind_cell.cpp, issue #28): submodule `interfere.cell`.
void bind_cell(pybind11::module_& m);
void bind_bearing(pybind11::module_& m);

/// FEM module (bind_fem.cpp): FemMesh, read_fem, generators, extract_surface, clash_series.
void bind_fem(pybind11::module_& m);

void bind_simplify(pybind11::module_& m);

/// Scenes (bind_scene.cpp, issue #24): Body, Scene, ClashTest, ClashReport, Clash.
void bind_scene(pybind11::module_& m);
}  // namespace interfere::python
