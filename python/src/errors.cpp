// Helpers shared by the bind_<module>.cpp files (python/src/bindings.h).
#include <pybind11/pybind11.h>

#include "bindings.h"

namespace py = pybind11;

namespace interfere::python {

void raise_input_error(const Error& e) {
  py::object type = py::module_::import("interfere._interfere").attr("InputError");
  py::object exc = type(e.message());
  exc.attr("file") = e.file.empty() ? py::object(py::none()) : py::object(py::str(e.file));
  exc.attr("line") = e.line >= 0 ? py::object(py::int_(e.line)) : py::object(py::none());
  exc.attr("byte") = e.byte >= 0 ? py::object(py::int_(e.byte)) : py::object(py::none());
  exc.attr("reason") = py::str(e.reason);
  PyErr_SetObject(type.ptr(), exc.ptr());
  throw py::error_already_set();
}

}  // namespace interfere::python
