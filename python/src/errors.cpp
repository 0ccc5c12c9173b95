// Errors and notes as Python sees them (the classes live in pdeface/errors.py).

#include "bindings.hpp"

#include <string>

namespace pdeface::python {

void raise(const Error& error) {
  const py::module_ errors = py::module_::import("pdeface.errors");
  const py::object line = error.where.line != 0 ? py::cast(error.where.line) : py::none();
  const py::object column = error.where.column != 0 ? py::cast(error.where.column) : py::none();
  const py::object byte = error.where.byte ? py::cast(*error.where.byte) : py::none();
  const py::object exception = errors.attr("_from_code")(std::string(to_string(error.code)), error.message,
                                                         error.source, line, column, byte, error.to_string());
  PyErr_SetObject(exception.get_type().ptr(), exception.ptr());
  throw py::error_already_set();
}

void warn(const Notes& notes) {
  if (notes.empty()) return;
  const py::object note = py::module_::import("pdeface.errors").attr("Note");
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (const std::string& n : notes)
    warn(n, note, py::arg("stacklevel") = 1); // called from C++: level 1 is the Python caller
}

std::filesystem::path to_path(const py::handle& path) {
  // os.fspath gives str or bytes; both cast to std::string (bytes as they are, str as UTF-8).
  return {py::module_::import("os").attr("fspath")(path).cast<std::string>()};
}

} // namespace pdeface::python
