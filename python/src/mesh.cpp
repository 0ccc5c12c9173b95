// pdeface.Mesh: a pdeface::Mesh seen from numpy. The arrays are read-only views of the mesh's own storage
// (no copy; they keep the mesh alive); a mesh is made from arrays by copying them in, and is immutable, so
// a view can never outlive or alias storage that moved.

#include "bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>

namespace pdeface::python {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Triangle) == 3 * sizeof(std::uint32_t) &&
                  sizeof(Vec3f) == 3 * sizeof(float) && sizeof(Vec4f) == 4 * sizeof(float) &&
                  sizeof(Vec2f) == 2 * sizeof(float),
              "the views below assume packed rows");

// A read-only n x columns view of `data`, owned by the Python object `owner`.
template <class Scalar>
py::array view(const void* data, std::size_t rows, std::size_t columns, const py::handle& owner) {
  py::array_t<Scalar> a({rows, columns}, {columns * sizeof(Scalar), sizeof(Scalar)},
                        static_cast<const Scalar*>(data), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// A C-contiguous copy of an array-like as rows x columns of Scalar, or ValueError naming `what`.
template <class Scalar>
py::array_t<Scalar, py::array::c_style | py::array::forcecast>
rows_of(const py::handle& values, std::size_t columns, const char* what) {
  auto a = py::array_t<Scalar, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!a || a.ndim() != 2 || static_cast<std::size_t>(a.shape(1)) != columns)
    throw py::value_error(std::string(what) + " must be an array of shape (n, " + std::to_string(columns) +
                          ")");
  return a;
}

template <class Row, class Scalar>
std::vector<Row> copy_rows(const py::handle& values, std::size_t columns, const char* what) {
  const auto a = rows_of<Scalar>(values, columns, what);
  std::vector<Row> out(static_cast<std::size_t>(a.shape(0)));
  std::memcpy(static_cast<void*>(out.data()), a.data(), out.size() * sizeof(Row));
  return out;
}

Mesh make_mesh(const py::handle& vertices, const py::handle& faces, const py::handle& normals,
               const py::handle& colors, const py::handle& texcoords, const std::string& units,
               const std::string& name) {
  Mesh mesh;
  mesh.positions = copy_rows<Vec3, double>(vertices, 3, "vertices");
  if (!faces.is_none()) {
    const auto a = rows_of<std::int64_t>(faces, 3, "faces");
    mesh.triangles.resize(static_cast<std::size_t>(a.shape(0)));
    const std::int64_t* f = a.data();
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        const std::int64_t index = f[3 * i + k];
        if (index < 0 || static_cast<std::uint64_t>(index) >= mesh.positions.size())
          throw py::index_error("faces[" + std::to_string(i) + "] refers to vertex " + std::to_string(index) +
                                " of " + std::to_string(mesh.positions.size()));
        mesh.triangles[i][k] = static_cast<std::uint32_t>(index);
      }
  }
  if (!normals.is_none()) mesh.normals = copy_rows<Vec3f, float>(normals, 3, "normals");
  if (!colors.is_none()) mesh.colors = copy_rows<Vec4f, float>(colors, 4, "colors");
  if (!texcoords.is_none()) mesh.texcoords = copy_rows<Vec2f, float>(texcoords, 2, "texcoords");
  const std::optional<Units> u =
      units == to_string(Units::Unknown) ? Units::Unknown : units_from_string(units);
  if (!u) throw py::value_error("unknown units '" + units + "' (mm, cm, m, in or unknown)");
  mesh.units = *u;
  mesh.name = name;
  // Sizes that do not match, coordinates that are not finite: a wrong call, as any constructor would say.
  if (Result<void> valid = validate(mesh, "Mesh"); !valid) throw py::value_error(valid.error().to_string());
  return mesh;
}

py::object optional_view(bool has, py::array a) { return has ? py::object(std::move(a)) : py::none(); }

} // namespace

void bind_mesh(py::module_& m) {
  py::class_<Mesh>(m, "Mesh",
                   R"doc(A triangle mesh or a point cloud (no faces), in its file's frame and units.

The arrays are read-only views of the mesh's storage, without a copy: ``vertices`` (n, 3) float64,
``faces`` (m, 3) int32 (indices into vertices), and, when the mesh has them, ``normals`` (n, 3) float32,
``colors`` (n, 4) float32 linear RGBA in [0, 1] and ``texcoords`` (n, 2) float32; each is None otherwise.
A mesh is immutable: make a new one from modified copies, ``Mesh(m.vertices * 2, m.faces)``.)doc")
      .def(py::init(&make_mesh), py::arg("vertices"), py::arg("faces") = py::none(),
           py::arg("normals") = py::none(), py::arg("colors") = py::none(), py::arg("texcoords") = py::none(),
           py::arg("units") = "unknown", py::arg("name") = "",
           "A mesh from array-likes (copied); ValueError if their shapes or sizes disagree or a coordinate "
           "is not finite, IndexError for a face index out of range.")
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return view<double>(mesh.positions.data(), mesh.positions.size(), 3, self);
          },
          "(n, 3) float64, read-only")
      .def_property_readonly(
          "faces",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return view<std::int32_t>(mesh.triangles.data(), mesh.triangles.size(), 3, self);
          },
          "(m, 3) int32, read-only; (0, 3) for a point cloud")
      .def_property_readonly(
          "normals",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return optional_view(mesh.has_normals(),
                                 view<float>(mesh.normals.data(), mesh.normals.size(), 3, self));
          },
          "(n, 3) float32 unit vectors, or None")
      .def_property_readonly(
          "colors",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return optional_view(mesh.has_colors(),
                                 view<float>(mesh.colors.data(), mesh.colors.size(), 4, self));
          },
          "(n, 4) float32 linear RGBA in [0, 1], or None")
      .def_property_readonly(
          "texcoords",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return optional_view(mesh.has_texcoords(),
                                 view<float>(mesh.texcoords.data(), mesh.texcoords.size(), 2, self));
          },
          "(n, 2) float32, or None")
      .def_property_readonly(
          "units", [](const Mesh& mesh) { return std::string(to_string(mesh.units)); },
          "the units the file states: 'mm', 'cm', 'm', 'in' or 'unknown' (never guessed)")
      .def_property_readonly("name", [](const Mesh& mesh) { return mesh.name; })
      .def_property_readonly("is_point_cloud", &Mesh::is_point_cloud)
      .def("__len__", &Mesh::vertex_count)
      .def("__repr__",
           [](const Mesh& mesh) {
             return "<pdeface.Mesh " + std::to_string(mesh.vertex_count()) + " vertices, " +
                    std::to_string(mesh.triangle_count()) + " faces, units " +
                    std::string(to_string(mesh.units)) + ">";
           })
      .def(py::pickle(
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return py::make_tuple(self.attr("vertices"), self.attr("faces"), self.attr("normals"),
                                  self.attr("colors"), self.attr("texcoords"),
                                  std::string(to_string(mesh.units)), mesh.name);
          },
          [](const py::tuple& t) {
            if (t.size() != 7) throw std::runtime_error("pdeface.Mesh: bad pickled state");
            return make_mesh(t[0], t[1], t[2], t[3], t[4], t[5].cast<std::string>(),
                             t[6].cast<std::string>());
          }));
}

} // namespace pdeface::python
