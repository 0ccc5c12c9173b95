#pragma once
// What the binding files share: errors raised as pdeface.Error subclasses, notes as Python warnings, and
// the registration function of each part of the module.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <pybind11/pybind11.h>

#include <filesystem>
#include <utility>

namespace pdeface::python {

namespace py = pybind11;

//! Raises `error` as the `pdeface.errors` class of its code (with code, message, source, line, column and
//! byte as attributes, and the message the command line prints). Needs the GIL.
[[noreturn]] void raise(const Error& error);

//! The value, or `raise` its error. Needs the GIL.
template <class T> T unwrap(Result<T>&& result) {
  if (!result) raise(result.error());
  return std::move(result).value();
}
inline void unwrap(Result<void>&& result) {
  if (!result) raise(result.error());
}

//! Each note as a `pdeface.Note` warning (what the command line prints as "pdeface: note: ..."). Needs the
//! GIL.
void warn(const Notes& notes);

//! A path-like (str, bytes or os.PathLike) as a filesystem path.
[[nodiscard]] std::filesystem::path to_path(const py::handle& path);

void bind_mesh(py::module_& m);
void bind_io(py::module_& m);
void bind_pipeline(py::module_& m);
void bind_compare(py::module_& m);

} // namespace pdeface::python
