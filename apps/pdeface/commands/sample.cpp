// pdeface sample: the built-in synthetic face scan

#include "common.hpp"

#include "pdeface/core/sample_face.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace pdeface::cli {
namespace {

struct SampleRequest {
  fs::path out;
  SampleFaceOptions face;
  bool no_holes = false;
  bool no_colors = false;
  formats::WriteOptions write;
};

int run_sample(SampleRequest request) {
  request.face.holes = !request.no_holes;
  request.face.colors = !request.no_colors;
  const Mesh mesh = sample_face(request.face);
  Notes notes;
  Result<std::size_t> written = formats::write_mesh(mesh, request.out, request.write, &notes);
  print_notes(notes);
  if (!written) return fail(written.error());
  fmt::print("{}: sample face, {} vertices, {} triangles, {} bytes\n", request.out.string(),
             mesh.vertex_count(), mesh.triangle_count(), *written);
  return 0;
}

} // namespace

void sample_command(CLI::App& app, int& status) {
  auto request = std::make_shared<SampleRequest>();
  SampleRequest& r = *request;
  CLI::App* cmd = app.add_subcommand("sample", "Write the built-in synthetic face scan (mm, frontal)");
  cmd->add_option("output", r.out, "File to write, any writable format")->required();
  cmd->add_option("--spacing", r.face.spacing_mm, "Grid step in mm")
      ->check(CLI::Range(0.2, 20.0))
      ->capture_default_str();
  cmd->add_option("--noise", r.face.noise_mm, "Depth noise amplitude in mm")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--seed", r.face.seed, "Varies the outline and the noise")->capture_default_str();
  cmd->add_flag("--no-holes", r.no_holes, "Do not punch holes");
  cmd->add_flag("--no-colors", r.no_colors, "Do not add vertex colours");
  add_write_options(cmd, r.write);
  cmd->callback([request, &status] { status = run_sample(*request); });
}

} // namespace pdeface::cli
