// pdeface decode: a .pdef file -> its PDE surface as a mesh with normals, in the scan's frame and units.

#include "common.hpp"

#include <fmt/format.h>

namespace pdeface::cli {
namespace {

struct DecodeArgs {
  fs::path in;
  fs::path out;
  ResolutionArg resolution;
  formats::WriteOptions write;
  std::size_t max_bytes = 0;
};

int run_decode(const DecodeArgs& args) {
  formats::ReadOptions read{.format = formats::Format::Pdef};
  if (const std::optional<pipeline::Resolution> grid = args.resolution.grid()) {
    read.surface_u = grid->u;
    read.surface_v = grid->v;
  }
  read.pdef_max_bytes = args.max_bytes;
  Notes notes;
  Result<formats::ConvertReport> report = formats::convert(args.in, args.out, read, args.write, &notes);
  print_notes(notes);
  if (!report) return fail(report.error());
  fmt::print("{} ({} bytes) -> {}: {} vertices, {} triangles, {} bytes, in the scan's frame ({})\n",
             args.in.string(), report->bytes_in, args.out.string(), report->vertices, report->triangles,
             report->bytes_out, to_string(report->units));
  return 0;
}

} // namespace

void decode_command(CLI::App& app, int& status) {
  auto args = std::make_shared<DecodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "decode", "A .pdef file -> its PDE surface as a mesh with normals, in the scan's frame and units");
  add_input(cmd, args->in, "The .pdef file");
  cmd->add_option("-o,--output", args->out, "Mesh to write (.glb .gltf .obj .ply .wrl .drc .off .stl)")
      ->required();
  add_resolution(cmd, args->resolution);
  cmd->add_option("--max-bytes", args->max_bytes,
                  "Read only the file's first N bytes: a file with a residual layer cut in it decodes to a "
                  "coarser surface")
      ->check(CLI::PositiveNumber);
  add_write_options(cmd, args->write);
  cmd->callback([args, &status] { status = run_decode(*args); });
}

} // namespace pdeface::cli
