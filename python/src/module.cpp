// The extension module pdeface._pdeface; python/pdeface/__init__.py is the package users import.

#include "bindings.hpp"

#include <pybind11/stl.h>

#include <string>

PYBIND11_MODULE(_pdeface, m) {
  namespace py = pybind11;
  m.doc() = "pdeface's C++ core: meshes, formats, the PDE face pipeline and the comparison";
  pdeface::python::bind_mesh(m);
  pdeface::python::bind_io(m);
  pdeface::python::bind_pipeline(m);
  pdeface::python::bind_compare(m);
  m.attr("__version__") = PDEFACE_VERSION;
  m.def("_error_codes", [] {
    std::vector<std::string> codes;
    for (int c = 0; c <= static_cast<int>(pdeface::ErrorCode::SelfCheck); ++c)
      codes.emplace_back(pdeface::to_string(static_cast<pdeface::ErrorCode>(c)));
    return codes;
  });
}
