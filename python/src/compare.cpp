// The comparison from Python: compare() over paths (the CSV's rows as dicts), and the pieces the Dask batch
// spreads over workers: compare_file() on one scan -> a ScanReport (picklable: it crosses processes and
// machines as bytes), write_report() of the gathered reports -> the command's report folder.

#include "bindings.hpp"

#include "pdeface/core/names.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pipeline/report.hpp"

#include <nlohmann/json.hpp>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace pdeface::python {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- A ScanReport as bytes (CBOR), every field, so that a report gathered from workers writes the same
// files as one made in this process.

json stats_json(const metrics::DistanceStats& d) { return {d.mean, d.rms, d.p95, d.max, d.samples}; }
metrics::DistanceStats stats_from(const json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>(), j.at(3).get<double>(),
          j.at(4).get<std::size_t>()};
}

json variant_json(const pipeline::Variant& v) {
  json j{{"method", static_cast<int>(v.method)},
         {"name", v.name},
         {"extension", v.extension},
         {"bits", v.bits},
         {"budget", v.budget},
         {"ratio", v.ratio},
         {"lossless", v.lossless},
         {"bytes", v.bytes},
         {"ratio_to_ply", v.ratio_to_ply},
         {"encode_ms", v.encode_ms},
         {"decode_ms", v.decode_ms},
         {"vertices", v.vertices},
         {"triangles", v.triangles},
         {"failure", v.failure},
         {"encoded", json::binary(std::vector<std::uint8_t>(v.encoded.begin(), v.encoded.end()))}};
  j["image_bytes"] = v.image_bytes;
  j["attribute_bytes"] = v.attribute_bytes;
  if (v.colour)
    j["colour"] = {v.colour->psnr_db, v.colour->mean_delta_e, v.colour->p95_delta_e, v.colour->samples,
                   v.colour->uncoloured};
  if (v.fidelity)
    j["fidelity"] = {{"share", v.fidelity->coverage.share},
                     {"mask", stats_json(v.fidelity->coverage.distance)},
                     {"to_scan", stats_json(v.fidelity->to_scan)},
                     {"profile", v.fidelity->profile_error},
                     {"profile_mean", v.fidelity->mean_profile_error}};
  return j;
}

std::string bytes_of(const json& j) {
  const auto& b = j.get_binary();
  return {b.begin(), b.end()};
}

pipeline::Variant variant_from(const json& j) {
  pipeline::Variant v{.method = static_cast<pipeline::Method>(j.at("method").get<int>()),
                      .name = j.at("name"),
                      .extension = j.at("extension"),
                      .bits = j.at("bits"),
                      .budget = j.at("budget"),
                      .ratio = j.at("ratio"),
                      .lossless = j.at("lossless"),
                      .bytes = j.at("bytes"),
                      .ratio_to_ply = j.at("ratio_to_ply"),
                      .encode_ms = j.at("encode_ms"),
                      .decode_ms = j.at("decode_ms"),
                      .vertices = j.at("vertices"),
                      .triangles = j.at("triangles"),
                      .failure = j.at("failure"),
                      .encoded = bytes_of(j.at("encoded"))};
  v.image_bytes = j.at("image_bytes");
  v.attribute_bytes = j.at("attribute_bytes");
  if (j.contains("colour")) {
    const json& c = j.at("colour"); // PSNR may be +inf: CBOR keeps it
    v.colour = metrics::ColourError{c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>(),
                                    c.at(3).get<std::size_t>(), c.at(4).get<std::size_t>()};
  }
  if (j.contains("fidelity")) {
    const json& f = j.at("fidelity");
    v.fidelity =
        metrics::MeshFidelity{.coverage = {.share = f.at("share"), .distance = stats_from(f.at("mask"))},
                              .to_scan = stats_from(f.at("to_scan")),
                              .profile_error = f.at("profile"),
                              .mean_profile_error = f.at("profile_mean")};
  }
  return v;
}

std::string scan_state(const pipeline::ScanReport& s) {
  json variants = json::array(), heat_maps = json::array(), textured = json::array();
  for (const pipeline::Variant& v : s.variants)
    variants.push_back(variant_json(v));
  for (const pipeline::TexturedGlb& t : s.textured)
    textured.push_back({{"variant", t.variant},
                        {"file", t.file},
                        {"glb", json::binary(std::vector<std::uint8_t>(t.glb.begin(), t.glb.end()))}});
  for (const pipeline::HeatMap& h : s.heat_maps)
    heat_maps.push_back({{"variant", h.variant},
                         {"file", h.file},
                         {"glb", json::binary(std::vector<std::uint8_t>(h.glb.begin(), h.glb.end()))},
                         {"front_svg", h.front_svg},
                         {"scale_mm", h.scale_mm}});
  const json j{{"name", s.name},
               {"source", s.source},
               {"units", static_cast<int>(s.units)},
               {"units_per_mm", s.units_per_mm},
               {"vertices", s.vertices},
               {"triangles", s.triangles},
               {"face_only", s.face_only},
               {"ply_bytes", s.ply_bytes},
               {"variants", variants},
               {"heat_maps", heat_maps},
               {"textured", textured},
               {"colour", static_cast<int>(s.colour)},
               {"failure", s.failure},
               {"seconds", s.seconds}};
  const std::vector<std::uint8_t> cbor = json::to_cbor(j);
  return {cbor.begin(), cbor.end()};
}

pipeline::ScanReport scan_from_state(const std::string& state) {
  const json j = json::from_cbor(state);
  pipeline::ScanReport s{.name = j.at("name"),
                         .source = j.at("source"),
                         .units = static_cast<Units>(j.at("units").get<int>()),
                         .units_per_mm = j.at("units_per_mm"),
                         .vertices = j.at("vertices"),
                         .triangles = j.at("triangles"),
                         .face_only = j.at("face_only"),
                         .ply_bytes = j.at("ply_bytes"),
                         .failure = j.at("failure"),
                         .seconds = j.at("seconds")};
  for (const json& v : j.at("variants"))
    s.variants.push_back(variant_from(v));
  for (const json& h : j.at("heat_maps"))
    s.heat_maps.push_back({.variant = h.at("variant"),
                           .file = h.at("file"),
                           .glb = bytes_of(h.at("glb")),
                           .front_svg = h.at("front_svg"),
                           .scale_mm = h.at("scale_mm")});
  for (const json& t : j.at("textured"))
    s.textured.push_back({.variant = t.at("variant"), .file = t.at("file"), .glb = bytes_of(t.at("glb"))});
  s.colour = static_cast<metrics::ColourSource>(j.at("colour").get<int>());
  return s;
}

// ---- Options from keyword arguments (the command's defaults).

pipeline::CompareOptions options_from(const py::dict& kwargs) {
  pipeline::CompareOptions o;
  for (const auto& [key, value] : kwargs) {
    const std::string k = py::str(key);
    if (k == "ratios")
      o.ratios = value.cast<std::vector<double>>();
    else if (k == "scheme") {
      const std::optional<pde::Scheme> s =
          value_named<pde::Scheme>(pde::kSchemeNames, value.cast<std::string>());
      if (!s) throw py::value_error("unknown scheme (spline, paper, patch4)");
      o.scheme = *s;
    } else if (k == "lossy")
      o.pde_lossy = value.cast<bool>();
    else if (k == "lossless")
      o.pde_lossless = value.cast<bool>();
    else if (k == "draco_bits")
      o.draco_bits = value.cast<std::vector<int>>();
    else if (k == "draco_level")
      o.draco_level = value.cast<int>();
    else if (k == "budgets")
      o.budgets = value.cast<std::vector<std::size_t>>();
    else if (k == "decimate_bits")
      o.decimate_bits = value.cast<std::vector<int>>();
    else if (k == "pde_budgets")
      o.budgets_at_pde = value.cast<bool>();
    else if (k == "pdef_sizes")
      o.pde_budgets = value.cast<std::vector<std::size_t>>();
    else if (k == "heat_max")
      o.heat_max_mm = value.cast<double>();
    else if (k == "crop_face")
      o.crop_face = value.cast<bool>();
    else if (k == "files")
      o.keep_bytes = value.cast<bool>();
    else if (k == "threads")
      o.threads = value.cast<unsigned>();
    else if (k == "colour")
      o.colour = value.cast<bool>();
    else if (k == "draco_uv_bits")
      o.draco_uv_bits = value.cast<int>();
    else
      throw py::type_error("compare: unexpected option '" + k + "'");
  }
  for (const double r : o.ratios)
    if (r < 0.05 || r > 0.6) throw py::value_error("ratios must be within 0.05 and 0.6");
  for (const int b : o.draco_bits)
    if (b < 1 || b > 24) throw py::value_error("draco_bits must be within 1 and 24");
  if (o.draco_level < 0 || o.draco_level > 10) throw py::value_error("draco_level must be within 0 and 10");
  if (o.draco_uv_bits < 1 || o.draco_uv_bits > 24)
    throw py::value_error("draco_uv_bits must be within 1 and 24");
  if (!(o.heat_max_mm > 0)) throw py::value_error("heat_max must be positive");
  return o;
}

// The report folder as `pdeface compare --out` writes it: every file or none.
void write_folder(const pipeline::Report& report, const fs::path& folder) {
  Result<std::size_t> written = [&] {
    const py::gil_scoped_release release;
    return pipeline::write_report(report, folder);
  }();
  unwrap(std::move(written));
}

py::list csv_rows(const pipeline::Report& report) {
  const py::module_ csv = py::module_::import("csv");
  const py::module_ io = py::module_::import("io");
  py::list rows;
  for (const py::handle& row : csv.attr("DictReader")(io.attr("StringIO")(pipeline::report_csv(report)))) {
    py::dict d;
    for (const auto& [key, value] : row.cast<py::dict>()) {
      const std::string k = py::str(key), text = py::str(value);
      if (k == "scan" || k == "units" || k == "method" || k == "variant" || k == "failure" || text.empty()) {
        d[key] =
            text.empty() && k != "scan" && k != "failure" && k != "variant" ? py::object(py::none()) : value;
      } else if (k == "lossless") {
        d[key] = py::bool_(text == "1");
      } else if (text.find_first_of(".eE") != std::string::npos || text == "nan" || text == "inf") {
        d[key] = py::float_(std::stod(text));
      } else {
        d[key] = py::int_(std::stoll(text));
      }
    }
    rows.append(d);
  }
  return rows;
}

} // namespace

void bind_compare(py::module_& m) {
  py::class_<pipeline::ScanReport>(m, "ScanReport",
                                   "One scan's comparison: every variant measured, or why not")
      .def_readonly("name", &pipeline::ScanReport::name)
      .def_readonly("source", &pipeline::ScanReport::source)
      .def_readonly("failure", &pipeline::ScanReport::failure, "empty when the scan was compared")
      .def_readonly("seconds", &pipeline::ScanReport::seconds)
      .def_property_readonly(
          "variants", [](const pipeline::ScanReport& s) { return s.variants.size(); },
          "how many variants were measured")
      .def("__repr__",
           [](const pipeline::ScanReport& s) {
             return "<pdeface.ScanReport " + s.name + ": " +
                    (s.failure.empty() ? std::to_string(s.variants.size()) + " variants"
                                       : "failed: " + s.failure) +
                    ">";
           })
      .def(py::pickle([](const pipeline::ScanReport& s) { return py::bytes(scan_state(s)); },
                      [](const py::bytes& state) { return scan_from_state(state); }));

  m.def(
      "compare_file",
      [](const py::object& path, const std::string& name, const py::kwargs& kwargs) {
        const pipeline::CompareOptions o = options_from(kwargs);
        const fs::path file = to_path(path);
        const py::gil_scoped_release release;
        return pipeline::compare_file(file, name, o);
      },
      py::arg("path"), py::arg("name"),
      "One scan compared (the options of compare()); a scan that cannot be read or has no face is a report "
      "with its failure, not an exception");
  m.def(
      "write_report",
      [](const std::vector<pipeline::ScanReport>& scans, const py::object& out, double seconds,
         const py::kwargs& kwargs) {
        const pipeline::Report report{.scans = scans, .options = options_from(kwargs), .seconds = seconds};
        write_folder(report, to_path(out));
        return csv_rows(report);
      },
      py::arg("scans"), py::arg("out"), py::arg("seconds") = 0.0,
      "The report folder of these scans' reports (report.md, .json, .csv, .html, rd.svg, heat-map GLBs), "
      "written as one set; returns the CSV's rows");
  m.def(
      "report_rows",
      [](const std::vector<pipeline::ScanReport>& scans, const py::kwargs& kwargs) {
        return csv_rows({.scans = scans, .options = options_from(kwargs)});
      },
      py::arg("scans"), "The rows of report.csv for these scans' reports, as dicts (nothing written)");
  m.def(
      "scan_names", [](const std::vector<fs::path>& inputs) { return pipeline::scan_names(inputs); },
      py::arg("inputs"), "The names compare gives these scan files: file names, repeated ones made unique");
  m.def(
      "expand_inputs",
      [](const std::vector<fs::path>& inputs) { return unwrap(pipeline::expand_inputs(inputs)); },
      py::arg("inputs"), "Scan files, folders expanded to the mesh files in them (sorted)");
  m.def(
      "compare",
      [](const std::vector<fs::path>& inputs, const std::optional<fs::path>& out, const py::kwargs& kwargs) {
        const pipeline::CompareOptions o = options_from(kwargs);
        std::vector<fs::path> files = unwrap(pipeline::expand_inputs(inputs));
        const pipeline::Report report = [&] {
          const py::gil_scoped_release release;
          return pipeline::compare_scans({.inputs = std::move(files), .options = o});
        }();
        if (out) write_folder(report, *out);
        return csv_rows(report);
      },
      py::arg("inputs"), py::arg("out") = py::none(),
      R"doc(`pdeface compare` in this process: every scan (files, folders) against raw meshes, Draco and
decimation + Draco, as a list of dicts with the columns of report.csv; with ``out``, the report folder too.
Options as keywords: ratios, scheme, lossy, lossless, draco_bits, draco_level, budgets, decimate_bits,
pde_budgets (bool: decimate + Draco at the .pdef sizes), pdef_sizes (the .pdef + residual rows' sizes),
heat_max, crop_face, files, threads.)doc");
}

} // namespace pdeface::python
