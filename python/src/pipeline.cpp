// The method on a mesh in memory, as the commands run it: detect_landmarks, align, profiles, reconstruct,
// encode (to .pdef bytes). Every call that takes time releases the GIL.

#include "bindings.hpp"

#include "pdeface/align/detect.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/align/pipeline.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/requests.hpp"

#include <nlohmann/json.hpp>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace pdeface::python {
namespace {

py::dict landmarks_dict(const align::Landmarks& landmarks) {
  py::dict out;
  for (std::size_t i = 0; i < align::kLandmarkCount; ++i) {
    const auto l = static_cast<align::Landmark>(i);
    if (const std::optional<Vec3>& p = landmarks[l]) out[py::str(std::string(align::name(l)))] = Vec3(*p);
  }
  return out;
}

// `landmarks`: None (detect them), a landmark file (ours or menpo LJSON) or a dict name -> (x, y, z) in the
// scan's frame and units.
align::LandmarkSource landmark_source(const py::object& landmarks) {
  if (landmarks.is_none()) return {};
  if (py::isinstance<py::dict>(landmarks)) {
    align::Landmarks given;
    for (const auto& [key, value] : landmarks.cast<py::dict>()) {
      const std::string name = py::str(key);
      const std::optional<align::Landmark> l = align::landmark_from_name(name);
      if (!l) throw py::value_error("unknown landmark '" + name + "'");
      given[*l] = value.cast<Vec3>();
    }
    return {.bytes = align::write_landmarks_json(given), .name = "landmarks"};
  }
  const std::filesystem::path path = to_path(landmarks);
  std::ifstream in(path, std::ios::binary);
  if (!in) raise(make_error(ErrorCode::Io, "cannot open the landmark file", path.string()));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return {.bytes = bytes.str(), .name = path.string()};
}

template <class E> E named(std::span<const NamedValue<E>> table, const std::string& name, const char* what) {
  if (const std::optional<E> e = value_named(table, name)) return *e;
  std::string names;
  for (const std::string& n : all_names(table))
    names += (names.empty() ? "" : ", ") + n;
  throw py::value_error(std::string("unknown ") + what + " '" + name + "' (" + names + ")");
}

struct CurveArgs {
  double ratio = 0.10;
  std::optional<std::size_t> points;
  std::size_t curves = 28;
  std::string scheme = "spline";
  std::optional<std::size_t> modes;
  std::optional<double> smoothing;

  [[nodiscard]] slice::ProfileOptions profiles() const {
    if (ratio < 0.05 || ratio > 0.6)
      throw py::value_error("ratio must be within 0.05 and 0.6 (the paper's 5-60 %)");
    if (points && *points < 4) throw py::value_error("points must be at least 4");
    slice::ProfileOptions o;
    o.ratio = ratio;
    o.points = points;
    o.planes.curves = curves;
    return o;
  }
  [[nodiscard]] pde::Options pde() const {
    return {.scheme = named<pde::Scheme>(pde::kSchemeNames, scheme, "scheme"),
            .smoothing = smoothing,
            .modes = modes,
            .spacing = pde::Spacing::Physical};
  }
};

class Alignment {
public:
  explicit Alignment(align::Alignment a) : a_(std::move(a)) {}
  [[nodiscard]] const align::Alignment& get() const { return a_; }
  [[nodiscard]] py::dict landmarks() const { return landmarks_dict(a_.landmarks); }
  [[nodiscard]] double scale() const { return a_.frame.scale; }
  [[nodiscard]] Eigen::Matrix3d rotation() const { return a_.frame.rotation; }
  [[nodiscard]] Vec3 translation() const { return a_.frame.translation; }
  [[nodiscard]] std::string units() const { return std::string(to_string(a_.frame.scan_units)); }
  [[nodiscard]] std::optional<double> confidence() const { return a_.confidence; }
  // (n, 3) points from the scan's frame to the canonical one (mm) or back.
  [[nodiscard]] Eigen::MatrixX3d map(const Eigen::MatrixX3d& points, bool to_canonical) const {
    Eigen::MatrixX3d out(points.rows(), 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      const Vec3 p = points.row(i).transpose();
      out.row(i) = (to_canonical ? a_.frame.to_canonical(p) : a_.frame.to_scan(p)).transpose();
    }
    return out;
  }

private:
  align::Alignment a_;
};

Alignment align_mesh(const Mesh& mesh, const py::object& landmarks, const std::string& source) {
  const align::LandmarkSource given = landmark_source(landmarks);
  Result<align::Alignment> a = [&] {
    const py::gil_scoped_release release;
    return align::align_from(mesh, given, source);
  }();
  return Alignment(unwrap(std::move(a)));
}

py::dict detect(const Mesh& mesh, const std::string& source) {
  Result<align::Detection> d = [&] {
    const py::gil_scoped_release release;
    return align::detect_landmarks(mesh);
  }();
  if (!d) raise(with_source(std::move(d).error(), source));
  return landmarks_dict(d->landmarks);
}

py::object profiles(const Mesh& mesh, const CurveArgs& curves, const py::object& landmarks,
                    const std::string& source) {
  const pipeline::ProfilesRequest request{
      .landmarks = landmark_source(landmarks), .profiles = curves.profiles(), .source = source};
  Result<pipeline::ProfilesOutcome> out = [&] {
    const py::gil_scoped_release release;
    return pipeline::profiles_request(mesh, request);
  }();
  const pipeline::ProfilesOutcome made = unwrap(std::move(out));
  warn(made.profiles.missing);
  return py::module_::import("json").attr("loads")(made.json);
}

Mesh reconstruct(const Mesh& mesh, const CurveArgs& curves, const py::object& resolution,
                 const py::object& landmarks, bool force, const std::string& source) {
  pipeline::ReconstructRequest request{
      .landmarks = landmark_source(landmarks), .source = source, .force = force};
  request.options.profiles = curves.profiles();
  request.options.pde = curves.pde();
  if (!resolution.is_none()) {
    if (py::isinstance<py::int_>(resolution)) {
      request.options.resolution = pipeline::Resolution{0, resolution.cast<std::size_t>()};
    } else {
      const auto uv = resolution.cast<std::pair<std::size_t, std::size_t>>();
      request.options.resolution = pipeline::Resolution{uv.first, uv.second};
    }
  }
  Result<pipeline::ReconstructOutcome> out = [&] {
    const py::gil_scoped_release release;
    return pipeline::reconstruct_request(mesh, request);
  }();
  pipeline::ReconstructOutcome made = unwrap(std::move(out));
  warn(made.reconstruction.profiles.missing);
  if (!made.check.passed()) warn({"self-check failed, returned anyway (force): " + made.check.summary()});
  return std::move(made.reconstruction.scan);
}

struct LayerArgs {
  std::optional<std::size_t> size;
  std::optional<double> target_error;
  std::string target_measure = "p95";
  bool texture = false;
  double texel = 0.5;
  int texture_quality = 80;
};

py::bytes encode(const Mesh& mesh, const CurveArgs& curves, const LayerArgs& layer, double max_error,
                 bool lossless, const py::object& landmarks, bool store_landmarks, const std::string& name,
                 bool force, const std::string& source) {
  if (max_error < 0.001 || max_error > 10.0)
    throw py::value_error("max_error must be within 0.001 and 10 mm");
  if (layer.size && layer.target_error) throw py::value_error("give size or target_error, not both");
  if (layer.target_error && !(*layer.target_error > 0))
    throw py::value_error("target_error must be positive");
  if (layer.texel < 0.05 || layer.texel > 5.0) throw py::value_error("texel must be within 0.05 and 5 mm");
  if (layer.texture_quality < 1 || layer.texture_quality > 100)
    throw py::value_error("texture_quality must be within 1 and 100");
  const pipeline::EncodeRequest request{
      .landmarks = landmark_source(landmarks),
      .profiles = curves.profiles(),
      .pde = curves.pde(),
      .encoding = {.lossless = lossless, .max_error_mm = max_error},
      .residual = {.size_bytes = layer.size,
                   .target_error_mm = layer.target_error,
                   .target_measure = named<pipeline::TargetMeasure>(pipeline::kTargetMeasureNames,
                                                                    layer.target_measure, "target_measure")},
      .texture = {.wanted = layer.texture, .texel_mm = layer.texel, .quality = layer.texture_quality},
      .store_landmarks = store_landmarks,
      .name = name,
      .source = source,
      .force = force};
  Result<pipeline::EncodeOutcome> out = [&] {
    const py::gil_scoped_release release;
    return pipeline::encode_request(mesh, request);
  }();
  pipeline::EncodeOutcome made = unwrap(std::move(out));
  warn(made.profiles.missing);
  if (made.check && !made.check->passed())
    warn({"self-check failed, returned anyway (force): " + made.check->summary()});
  return py::bytes(made.encoded.bytes);
}

} // namespace

void bind_pipeline(py::module_& m) {
  py::class_<Alignment>(m, "Alignment", R"doc(Where a face is in a scan: its landmarks and the similarity
transform to the canonical frame (mm; x to the face's left as seen, y up, z towards the viewer, the nose tip
at the origin): ``canonical = scale * rotation @ p + translation``.)doc")
      .def_property_readonly("landmarks", &Alignment::landmarks,
                             "dict: landmark name -> (3,) position in the scan's frame and units")
      .def_property_readonly("scale", &Alignment::scale, "millimetres per scan unit")
      .def_property_readonly("rotation", &Alignment::rotation, "(3, 3) proper rotation")
      .def_property_readonly("translation", &Alignment::translation, "(3,) in mm")
      .def_property_readonly("units", &Alignment::units, "the units the scan was found to be in")
      .def_property_readonly("confidence", &Alignment::confidence, "0..1 when detected, None when given")
      .def(
          "to_canonical", [](const Alignment& a, const Eigen::MatrixX3d& p) { return a.map(p, true); },
          py::arg("points"), "(n, 3) points of the scan in the canonical frame (mm)")
      .def(
          "to_scan", [](const Alignment& a, const Eigen::MatrixX3d& p) { return a.map(p, false); },
          py::arg("points"), "(n, 3) canonical points (mm) back in the scan's frame and units");

  m.def("detect_landmarks", &detect, py::arg("mesh"), py::kw_only(), py::arg("source") = "mesh",
        "The face's landmarks found on the scan: dict name -> (3,) in the scan's frame and units. Raises "
        "pdeface.NoFaceError when there is no face.");
  m.def("align", &align_mesh, py::arg("mesh"), py::kw_only(), py::arg("landmarks") = py::none(),
        py::arg("source") = "mesh",
        "The face's alignment: landmarks detected, or ``landmarks`` (a landmark file, or a dict name -> "
        "(x, y, z) in the scan's frame) completed on the scan.");

  const auto curve_args = [](double ratio, std::optional<std::size_t> points, std::size_t curves,
                             std::string scheme, std::optional<std::size_t> modes,
                             std::optional<double> smoothing) {
    return CurveArgs{ratio, points, curves, std::move(scheme), modes, smoothing};
  };
  m.def(
      "profiles",
      [curve_args](const Mesh& mesh, double ratio, std::optional<std::size_t> points, std::size_t curves,
                   const py::object& landmarks, const std::string& source) {
        return profiles(mesh, curve_args(ratio, points, curves, "spline", std::nullopt, std::nullopt),
                        landmarks, source);
      },
      py::arg("mesh"), py::kw_only(), py::arg("ratio") = 0.10, py::arg("points") = py::none(),
      py::arg("curves") = 28, py::arg("landmarks") = py::none(), py::arg("source") = "mesh",
      "The 28 profile curves, as the document `pdeface profiles` writes (a dict parsed from its JSON).");
  m.def(
      "reconstruct",
      [curve_args](const Mesh& mesh, double ratio, std::optional<std::size_t> points, std::size_t curves,
                   const std::string& scheme, std::optional<std::size_t> modes,
                   std::optional<double> smoothing, const py::object& resolution, const py::object& landmarks,
                   bool force, const std::string& source) {
        return reconstruct(mesh, curve_args(ratio, points, curves, scheme, modes, smoothing), resolution,
                           landmarks, force, source);
      },
      py::arg("mesh"), py::kw_only(), py::arg("ratio") = 0.10, py::arg("points") = py::none(),
      py::arg("curves") = 28, py::arg("scheme") = "spline", py::arg("modes") = py::none(),
      py::arg("smoothing") = py::none(), py::arg("resolution") = py::none(),
      py::arg("landmarks") = py::none(), py::arg("force") = false, py::arg("source") = "mesh",
      R"doc(The PDE surface through the scan's curves, as a mesh with normals in the scan's frame and units
(what `pdeface reconstruct` writes). Raises pdeface.SelfCheckError when it is off the scan, unless ``force``.)doc");
  m.def(
      "encode",
      [curve_args](const Mesh& mesh, std::optional<double> ratio, std::optional<std::size_t> points,
                   std::size_t curves, const std::string& scheme, std::optional<std::size_t> modes,
                   std::optional<double> smoothing, std::optional<std::size_t> size,
                   std::optional<double> target_error, const std::string& target_measure, bool texture,
                   double texel, int texture_quality, double max_error, bool lossless,
                   const py::object& landmarks, bool store_landmarks, const std::string& name, bool force,
                   const std::string& source) {
        // As `pdeface encode`: without a ratio, 5 % curves under a residual layer, else 10 %.
        const double r =
            ratio.value_or(pipeline::default_ratio({.size_bytes = size, .target_error_mm = target_error}));
        return encode(mesh, curve_args(r, points, curves, scheme, modes, smoothing),
                      LayerArgs{size, target_error, target_measure, texture, texel, texture_quality},
                      max_error, lossless, landmarks, store_landmarks, name, force, source);
      },
      py::arg("mesh"), py::kw_only(), py::arg("ratio") = py::none(), py::arg("points") = py::none(),
      py::arg("curves") = 28, py::arg("scheme") = "spline", py::arg("modes") = py::none(),
      py::arg("smoothing") = py::none(), py::arg("size") = py::none(), py::arg("target_error") = py::none(),
      py::arg("target_measure") = "p95", py::arg("texture") = false, py::arg("texel") = 0.5,
      py::arg("texture_quality") = 80, py::arg("max_error") = 0.05, py::arg("lossless") = false,
      py::arg("landmarks") = py::none(), py::arg("store_landmarks") = false, py::arg("name") = "",
      py::arg("force") = false, py::arg("source") = "mesh",
      R"doc(The scan as a .pdef file's bytes, those `pdeface encode` writes with the same options. With ``size``
(bytes) or ``target_error`` (mm, of ``target_measure``: "mean", "p95" or "max") a residual layer follows
the curves (version 3; ``ratio`` 0.05 unless given, else 0.10): the best error within the size, or the
fewest bytes meeting the error; any prefix
of the file decodes (``decode(data[:n])``). With ``texture`` a texture layer holds the scan's photograph (or
vertex colours) over the face as one JPEG (``texel`` mm apart, ``texture_quality`` 1-100), and ``decode``
gives a textured mesh. Raises pdeface.SelfCheckError when the decoded file is off the scan, unless
``force``.)doc");
}

} // namespace pdeface::python
