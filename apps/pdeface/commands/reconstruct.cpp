// pdeface reconstruct: scan -> aligned -> profile curves -> PDE surface, in the scan's frame and units.

#include "common.hpp"

#include "pdeface/pipeline/requests.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace pdeface::cli {
namespace {

struct ReconstructArgs {
  fs::path in;
  fs::path out;
  fs::path profiles; // the curves as JSON too
  fs::path preview;  // SVG: scan and reconstruction side by side
  CurveArgs curves;
  SurfaceArgs surface;
  ResolutionArg resolution;
  formats::WriteOptions write;
  bool force = false;
};

void print_fidelity(const pipeline::ReconstructOutcome& made) {
  if (!made.fidelity) {
    fmt::print(stderr, "pdeface: note: fidelity not measured: {}\n", made.fidelity_failure);
    return;
  }
  const metrics::Fidelity& f = *made.fidelity;
  const metrics::DistanceStats& d = f.surface.both;
  fmt::print("fidelity (mm, face region): profile error {:.3f} (symmetry {:.3f}, eyes {:.3f}, diagonals "
             "{:.3f} / {:.3f}); surface distance mean {:.3f}, RMS {:.3f}, p95 {:.3f}, max {:.2f}\n",
             f.mean_profile_error, f.profile_error[0], f.profile_error[1], f.profile_error[2],
             f.profile_error[3], d.mean, d.rms, d.p95, d.max);
  fmt::print("  = mean {:.3g}, max {:.3g} {} in the scan's units; max {:.2e} of the face region's diagonal\n",
             d.mean * made.scan_units_per_mm, d.max * made.scan_units_per_mm,
             to_string(made.reconstruction.scan.units), d.max / f.surface.diagonal);
  const metrics::Coverage& c = f.coverage;
  fmt::print("coverage of the face (the outline its landmarks give): {:.1f} % of the scan within 1 mm of the "
             "reconstruction; scan -> reconstruction mean {:.3f}, p95 {:.3f} mm; reconstruction -> scan mean "
             "{:.3f} mm\n",
             100.0 * c.share, c.distance.mean, c.distance.p95, f.surface.b_to_a.mean);
}

int run_reconstruct(const ReconstructArgs& args) {
  Result<ScanAndLandmarks> input = read_scan_and_landmarks(args.in, args.curves.landmarks);
  if (!input) return fail(input.error());
  pipeline::ReconstructRequest request{
      .landmarks = std::move(input->landmarks),
      .options = {.profiles = args.curves.profile_options(), .pde = args.surface.pde_options()},
      .profiles_json = !args.profiles.empty(),
      .preview = !args.preview.empty(),
      .source = args.in.string(),
      .force = args.force};
  request.options.resolution = args.resolution.grid();
  Result<pipeline::ReconstructOutcome> made = pipeline::reconstruct_request(input->scan.mesh, request);
  if (!made) return fail(made.error());

  // Everything is encoded before anything is written, and written as a set: a failure (an unknown output
  // format, a missing folder) leaves no output behind.
  Notes notes;
  Result<std::string> encoded = formats::encode_mesh(made->reconstruction.scan, args.out, args.write, &notes);
  print_notes(notes);
  if (!encoded) return fail(encoded.error());
  const std::size_t bytes = encoded->size();
  std::vector<OutputFile> outputs{{args.out, *std::move(encoded)}};
  if (!args.profiles.empty()) outputs.push_back({args.profiles, made->profiles_json});
  if (!args.preview.empty()) outputs.push_back({args.preview, made->preview_svg});
  if (Result<void> ok = write_outputs(outputs); !ok) return fail(ok.error());

  const pipeline::Reconstruction& r = made->reconstruction;
  const slice::ProfileSet& p = r.profiles;
  const pde::Surface& s = r.surface;
  fmt::print("{}: {} curves x {} points ({:.1f} % of {}), {} scheme, N = {} modes{}, a = {:.3f}\n",
             args.in.string(), p.curves.size(), p.k, 100.0 * p.ratio, p.reference_points,
             pde::to_string(s.scheme()), s.modes(), s.has_remainder() ? " + remainder" : "", s.smoothing());
  fmt::print("{}: {} x {} grid, {} vertices, {} triangles, {} bytes, in the scan's frame ({})\n",
             args.out.string(), r.grid.u, r.grid.v, r.scan.vertex_count(), r.scan.triangle_count(), bytes,
             to_string(r.scan.units));
  print_fidelity(*made);
  print_check(made->check);
  print_holes_and_gaps(p);
  return 0;
}

} // namespace

void reconstruct_command(CLI::App& app, int& status) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand("reconstruct",
                                     "Scan -> aligned -> profile curves -> PDE surface, written as a mesh in "
                                     "the scan's frame and units; prints how far it lies from the scan");
  add_input(cmd, args->in, "Scan (any readable format, mesh or point cloud)");
  add_output(cmd, args->out, "Surface mesh to write (.glb .obj .ply .wrl ...)");
  cmd->add_option("--profiles", args->profiles, "Also write the curves as JSON");
  cmd->add_option("--preview", args->preview,
                  "Also write an SVG: the scan and the reconstruction side by side, and turned");
  add_resolution(cmd, args->resolution);
  args->curves.add_to(cmd);
  args->surface.add_to(cmd);
  add_write_options(cmd, args->write);
  add_force(cmd, args->force);
  cmd->callback([args, &status] { status = run_reconstruct(*args); });
}

} // namespace pdeface::cli
