// pdeface info: what a mesh file holds: format, counts, units, extent, topology

#include "common.hpp"

#include "pdeface/core/summary.hpp"

#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <cstdio>

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
    const MeshSummary summary = summarize(loaded->mesh);
    if (request.json)
      all.push_back(to_json(file, *loaded, summary));
    else
      print_text(file, *loaded, summary);
  }
  if (request.json) fmt::print("{}\n", all.dump(2));
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
