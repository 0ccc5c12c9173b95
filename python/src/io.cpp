// Reading and writing meshes, files or bytes, as `pdeface convert` does: pdeface.read, write, to_bytes,
// from_bytes and decode (a .pdef's surface).

#include "bindings.hpp"

#include "pdeface/formats/formats.hpp"

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pdeface::python {
namespace {

std::optional<formats::Format> format_of(const std::optional<std::string>& name) {
  if (!name) return std::nullopt;
  Result<formats::Format> f = formats::format_from_name(*name);
  if (!f) throw py::value_error(f.error().message);
  return *f;
}

// `resolution`: None (about 1 mm between vertices), V (points along the face's height) or (U, V).
formats::ReadOptions read_options(const std::optional<std::string>& format, const py::object& resolution) {
  formats::ReadOptions options{.format = format_of(format)};
  if (resolution.is_none()) return options;
  if (py::isinstance<py::int_>(resolution)) {
    options.surface_v = resolution.cast<std::size_t>();
  } else {
    const auto uv = resolution.cast<std::pair<std::size_t, std::size_t>>();
    options.surface_u = uv.first;
    options.surface_v = uv.second;
  }
  return options;
}

formats::WriteOptions write_options(const std::optional<std::string>& format, bool ascii, int draco_bits,
                                    int draco_level, bool draco_in_gltf) {
  return {.format = format_of(format),
          .ascii = ascii,
          .draco_in_gltf = draco_in_gltf,
          .draco_bits = draco_bits,
          .draco_level = draco_level};
}

Mesh read(const py::object& path, const std::optional<std::string>& format, const py::object& resolution) {
  const std::filesystem::path p = to_path(path);
  const formats::ReadOptions options = read_options(format, resolution);
  Notes notes;
  Result<formats::LoadedMesh> loaded = [&] {
    const py::gil_scoped_release release;
    return formats::read_mesh(p, options, &notes);
  }();
  warn(notes);
  return unwrap(std::move(loaded)).mesh;
}

Mesh from_bytes(const py::bytes& data, const std::string& source, const std::optional<std::string>& format,
                const py::object& resolution) {
  const std::string_view bytes = data; // the bytes object outlives the call
  const formats::ReadOptions options = read_options(format, resolution);
  Notes notes;
  Result<formats::LoadedMesh> loaded = [&] {
    const py::gil_scoped_release release;
    return formats::read_mesh(bytes, source, options, &notes);
  }();
  warn(notes);
  return unwrap(std::move(loaded)).mesh;
}

std::size_t write(const Mesh& mesh, const py::object& path, const std::optional<std::string>& format,
                  bool ascii, int draco_bits, int draco_level, bool draco_in_gltf) {
  const std::filesystem::path p = to_path(path);
  const formats::WriteOptions options = write_options(format, ascii, draco_bits, draco_level, draco_in_gltf);
  Notes notes;
  Result<std::size_t> written = [&] {
    const py::gil_scoped_release release;
    return formats::write_mesh(mesh, p, options, &notes);
  }();
  warn(notes);
  return unwrap(std::move(written));
}

py::bytes to_bytes(const Mesh& mesh, const std::string& format, bool ascii, int draco_bits, int draco_level,
                   bool draco_in_gltf) {
  const formats::WriteOptions options = write_options(format, ascii, draco_bits, draco_level, draco_in_gltf);
  Notes notes;
  Result<std::string> encoded = [&] {
    const py::gil_scoped_release release;
    return formats::encode_mesh(mesh, "mesh", options, &notes);
  }();
  warn(notes);
  return py::bytes(unwrap(std::move(encoded)));
}

} // namespace

void bind_io(py::module_& m) {
  m.def("read", &read, py::arg("path"), py::kw_only(), py::arg("format") = py::none(),
        py::arg("resolution") = py::none(),
        R"doc(Reads a mesh or point cloud: VRML, OBJ, PLY, OFF, STL, glTF/GLB, Draco, or a .pdef's surface.

The format comes from ``format`` (a name such as "ply"), else the content, else the extension. A .pdef is
decoded at ``resolution``: None (about 1 mm between vertices), V points along the face, or (U, V).
Raises a pdeface.Error naming the file and the line or byte.)doc");
  m.def("from_bytes", &from_bytes, py::arg("data"), py::arg("source"), py::kw_only(),
        py::arg("format") = py::none(), py::arg("resolution") = py::none(),
        "read() from bytes in memory; ``source`` names them in errors (and its extension picks the format "
        "when the content does not)");
  m.def("write", &write, py::arg("mesh"), py::arg("path"), py::kw_only(), py::arg("format") = py::none(),
        py::arg("ascii") = false, py::arg("draco_bits") = 14, py::arg("draco_level") = 7,
        py::arg("draco_in_gltf") = false,
        R"doc(Writes a mesh in the format of the path's extension (or ``format``), atomically: on an error no
file is left behind. Attributes the format cannot hold are dropped with a pdeface.Note warning. Returns the
bytes written. A .pdef is made from a scan by encode(), not here.)doc");
  m.def("to_bytes", &to_bytes, py::arg("mesh"), py::arg("format"), py::kw_only(), py::arg("ascii") = false,
        py::arg("draco_bits") = 14, py::arg("draco_level") = 7, py::arg("draco_in_gltf") = false,
        "The bytes write() would write in ``format`` (\"ply\", \"glb\", \"drc\", ...)");
  m.def(
      "formats", [] { return formats::format_names(); }, "The format names read() and write() know");
}

} // namespace pdeface::python
