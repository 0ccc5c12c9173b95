// pdeface info: what a mesh file holds: format, counts, units, extent, topology

#include "common.hpp"

#include "pdeface/core/summary.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>

namespace pdeface::cli {
namespace {

struct InfoRequest {
  std::vector<fs::path> files;
  bool json = false;
};

nlohmann::json to_json(const fs::path& file, const formats::LoadedMesh& loaded, const MeshSummary& s) {
  nlohmann::json j;
  j["file"] = file.string();
  j["format"] = formats::info(loaded.format).name;
  j["bytes"] = loaded.bytes;
  j["vertices"] = s.vertices;
  j["triangles"] = s.triangles;
  j["point_cloud"] = s.triangles == 0;
  j["units"] = to_string(s.units);
  j["attributes"] = {{"normals", s.normals}, {"colors", s.colors}, {"texcoords", s.texcoords}};
  if (!s.box.empty()) {
    j["bbox"] = {{"min", {s.box.min.x(), s.box.min.y(), s.box.min.z()}},
                 {"max", {s.box.max.x(), s.box.max.y(), s.box.max.z()}},
                 {"size", {s.box.size().x(), s.box.size().y(), s.box.size().z()}}};
  }
  j["components"] = s.topology.components;
  j["boundary_loops"] = s.topology.boundary_loops;
  j["unreferenced_vertices"] = s.topology.unreferenced_vertices;
  j["non_manifold_triangles"] = s.topology.non_manifold_triangles;
  return j;
}

// What a .pdef file holds, from its bytes.
struct PdefInfo {
  pdef::Face face;
  std::vector<pdef::Section> sections;
};

Result<PdefInfo> pdef_info(const fs::path& file) {
  Result<std::string> bytes = read_file(file);
  if (!bytes) return bytes.error();
  Result<pdef::Face> face = pdef::decode(*bytes, file.string());
  if (!face) return face.error();
  Result<std::vector<pdef::Section>> sections = pdef::sections(*bytes, file.string());
  if (!sections) return sections.error();
  return PdefInfo{*std::move(face), *std::move(sections)};
}

std::size_t filled_samples(const pdef::Face& face) {
  std::size_t n = 0;
  for (const std::vector<bool>& curve : face.filled)
    n += static_cast<std::size_t>(std::ranges::count(curve, true));
  return n;
}

nlohmann::json to_json(const PdefInfo& info) {
  const pdef::Face& f = info.face;
  const std::array<double, 2> size = pdef::face_size(f);
  nlohmann::json j;
  j["lossless"] = f.storage.lossless;
  if (!f.storage.lossless) {
    j["step_mm"] = f.storage.step_mm;
    j["heights_stride"] = f.storage.heights_stride;
    j["heights_bits"] = f.storage.heights_bits;
  }
  j["curves"] = f.curve_count();
  j["samples_per_curve"] = f.sample_count();
  j["planes_mm"] = {f.planes.front(), f.planes.back()};
  j["width_mm"] = size[0];
  j["height_mm"] = size[1];
  j["filled_samples"] = filled_samples(f);
  j["scheme"] = pde::to_string(f.pde.scheme);
  j["spacing"] = pde::to_string(f.pde.spacing);
  j["modes"] = *f.pde.modes;
  j["remainder"] = f.pde.remainder;
  j["smoothing"] = *f.pde.smoothing;
  j["scan_units"] = to_string(f.frame.scan_units);
  j["scale_mm_per_unit"] = f.frame.scale;
  nlohmann::json landmarks = nlohmann::json::object();
  for (const pdef::Landmark& l : f.landmarks)
    landmarks[l.name] = {l.position.x(), l.position.y(), l.position.z()};
  j["landmarks"] = landmarks;
  j["name"] = f.name;
  if (f.residual) {
    const pdef::Residual& r = *f.residual;
    j["residual"] = {{"width", r.field.width},
                     {"height", r.field.height},
                     {"step_mm", r.step_mm},
                     {"levels", r.levels},
                     {"planes", r.planes},
                     {"planes_read", r.planes_read},
                     {"stream_bytes", r.stream_bytes},
                     {"bytes_read", r.bytes_read},
                     {"complete", r.complete},
                     {"trim_bytes", r.trim_bytes},
                     {"trimmed_cells", static_cast<std::size_t>(std::ranges::count(r.trimmed, 1))}};
  } else {
    j["residual"] = nullptr;
  }
  nlohmann::json sections = nlohmann::json::array();
  for (const pdef::Section& s : info.sections)
    sections.push_back({{"name", s.name}, {"offset", s.offset}, {"bytes", s.bytes}});
  j["sections"] = sections;
  return j;
}

void print_text(const PdefInfo& info) {
  const pdef::Face& f = info.face;
  const std::array<double, 2> size = pdef::face_size(f);
  if (f.storage.lossless)
    fmt::print("  storage         lossless (float64)\n");
  else
    fmt::print("  storage         lossy: samples on a {:.4f} mm grid, planes on {:.5f} mm, y {}\n",
               f.storage.step_mm, f.storage.plane_step_mm,
               f.storage.heights_stride == 0
                   ? std::string("predicted")
                   : fmt::format("as heights (anchors every {} curves, on a grid of 1/{})",
                                 f.storage.heights_stride, 1U << f.storage.heights_bits));
  fmt::print(
      "  curves          {} x {} samples, x = {:.1f} .. {:.1f} mm, {:.1f} x {:.1f} mm, {} samples filled\n",
      f.curve_count(), f.sample_count(), f.planes.front(), f.planes.back(), size[0], size[1],
      filled_samples(f));
  fmt::print("  surface         {} scheme, N = {} modes{}, a = {:.4f}, {} spacing\n",
             pde::to_string(f.pde.scheme), *f.pde.modes, f.pde.remainder ? " + remainder" : "",
             *f.pde.smoothing, pde::to_string(f.pde.spacing));
  fmt::print("  scan frame      units {}, {:.6g} mm per unit\n", to_string(f.frame.scan_units),
             f.frame.scale);
  std::string names;
  for (const pdef::Landmark& l : f.landmarks)
    names += (names.empty() ? "" : ", ") + l.name;
  fmt::print("  landmarks       {}\n", names.empty() ? "none" : names);
  if (!f.name.empty()) fmt::print("  name            {}\n", f.name);
  std::string parts;
  for (const pdef::Section& s : info.sections)
    parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", s.name, s.bytes);
  fmt::print("  bytes           {}\n", parts);
  if (pdef::has_offsets(f)) {
    const pdef::Residual& r = *f.residual;
    fmt::print(
        "  residual        {} x {} grid, finest step {:.4g} mm, {} wavelet levels, {} of {} bit-planes "
        "reached, {}, {} cells trimmed\n",
        r.field.width, r.field.height, r.step_mm, r.levels, r.planes_read, r.planes,
        r.complete ? std::string("the stream whole")
                   : fmt::format("a prefix of the stream: {} of {} bytes", r.bytes_read, r.stream_bytes),
        std::ranges::count(r.trimmed, 1));
    fmt::print(
        "  (the counts and the box above are the surface with its residual layer, decoded on the layer's "
        "{} x {} grid)\n",
        r.field.width, r.field.height);
  } else {
    fmt::print("  (the counts and the box above are the surface decoded at about 1 mm spacing)\n");
  }
}

void print_text(const fs::path& file, const formats::LoadedMesh& loaded, const MeshSummary& s) {
  fmt::print("{}\n", file.string());
  fmt::print("  format          {} ({} bytes)\n", formats::info(loaded.format).name, loaded.bytes);
  fmt::print("  vertices        {}\n", s.vertices);
  fmt::print("  triangles       {}{}\n", s.triangles, s.triangles == 0 ? " (point cloud)" : "");
  std::string attributes;
  for (auto [has, name] :
       {std::pair{s.normals, "normals"}, {s.colors, "colours"}, {s.texcoords, "texcoords"}})
    if (has) attributes += attributes.empty() ? name : fmt::format(", {}", name);
  fmt::print("  attributes      {}\n", attributes.empty() ? "positions only" : "positions, " + attributes);
  fmt::print("  units           {}\n", to_string(s.units));
  if (!s.box.empty()) {
    const Vec3 size = s.box.size();
    fmt::print("  bounding box    [{:.4g}, {:.4g}, {:.4g}] .. [{:.4g}, {:.4g}, {:.4g}]\n", s.box.min.x(),
               s.box.min.y(), s.box.min.z(), s.box.max.x(), s.box.max.y(), s.box.max.z());
    fmt::print("  size            {:.4g} x {:.4g} x {:.4g}\n", size.x(), size.y(), size.z());
  }
  if (s.triangles > 0) {
    fmt::print("  components      {}\n", s.topology.components);
    fmt::print("  boundary loops  {}\n", s.topology.boundary_loops);
    if (s.topology.unreferenced_vertices > 0)
      fmt::print("  unreferenced    {} vertices on no triangle\n", s.topology.unreferenced_vertices);
    if (s.topology.non_manifold_triangles > 0)
      fmt::print("  non-manifold    {} triangles\n", s.topology.non_manifold_triangles);
  }
}

int run_info(const InfoRequest& request) {
  int status = 0;
  nlohmann::json all = nlohmann::json::array();
  for (const fs::path& file : request.files) {
    Notes notes;
    Result<formats::LoadedMesh> loaded = formats::read_mesh(file, {}, &notes);
    print_notes(notes);
    if (!loaded) {
      status = fail(loaded.error());
      continue;
    }
    std::optional<PdefInfo> pdef;
    if (loaded->format == formats::Format::Pdef) {
      Result<PdefInfo> read = pdef_info(file);
      if (!read) {
        status = fail(read.error());
        continue;
      }
      pdef = *std::move(read);
    }
    const MeshSummary summary = summarize(loaded->mesh);
    if (request.json) {
      all.push_back(to_json(file, *loaded, summary));
      if (pdef) all.back()["pdef"] = to_json(*pdef);
      continue;
    }
    print_text(file, *loaded, summary);
    if (pdef) print_text(*pdef);
  }
  // File names may be any bytes: invalid UTF-8 is written as U+FFFD, never an exception.
  if (request.json) fmt::print("{}\n", all.dump(2, ' ', false, nlohmann::json::error_handler_t::replace));
  return status;
}

} // namespace

void info_command(CLI::App& app, int& status) {
  auto request = std::make_shared<InfoRequest>();
  InfoRequest& r = *request;
  CLI::App* cmd = app.add_subcommand("info", "Describe mesh files: format, counts, units, extent, topology");
  cmd->add_option("files", r.files, "Files to describe")->required()->check(CLI::ExistingPath);
  cmd->add_flag("--json", r.json, "Print JSON for machines");
  cmd->callback([request, &status] { status = run_info(*request); });
}

} // namespace pdeface::cli
