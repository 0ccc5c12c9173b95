// pdeface encode: scan -> aligned -> profile curves -> a .pdef document (the curves, what rebuilds the
// surface through them and the frame back to the scan).

#include "common.hpp"

#include <fmt/format.h>

namespace pdeface::cli {
namespace {

struct EncodeArgs {
  fs::path in;
  fs::path out;
  CurveArgs curves;
  SurfaceArgs surface;
  double max_error = pdef::kDefaultMaxError;
  bool lossless = false;
  bool store_landmarks = false;
  std::string name;
  bool force = false;
  std::optional<std::size_t> size;
  std::optional<double> target_error;
  std::string target_measure = "p95";
  std::optional<double> residual_spacing;
  bool texture = false;
  double texel = 0.5;
  int texture_quality = 80;
};

int run_encode(const EncodeArgs& args) {
  Result<align::LandmarkSource> landmarks = landmark_source(args.curves.landmarks);
  if (!landmarks) return fail(landmarks.error());
  pipeline::EncodeRequest request{
      .landmarks = *std::move(landmarks),
      .profiles = args.curves.profile_options(),
      .pde = args.surface.pde_options(),
      .encoding = {.lossless = args.lossless, .max_error_mm = args.max_error},
      .residual = {.size_bytes = args.size,
                   .target_error_mm = args.target_error,
                   .target_measure = *value_named<pipeline::TargetMeasure>(pipeline::kTargetMeasureNames,
                                                                           args.target_measure),
                   .spacing_mm = args.residual_spacing},
      .texture = {.wanted = args.texture, .texel_mm = args.texel, .quality = args.texture_quality},
      .store_landmarks = args.store_landmarks,
      .name = args.name,
      .source = args.in.string(),
      .force = args.force};
  if (!args.curves.ratio_given()) request.profiles.ratio = pipeline::default_ratio(request.residual);
  return encode_scan(args.in, args.out, request);
}

} // namespace

void encode_command(CLI::App& app, int& status) {
  auto args = std::make_shared<EncodeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "encode",
      "Scan -> aligned -> profile curves -> a .pdef file: the curves, the PDE surface's settings and "
      "the frame back to the scan (docs/pdef-format.md)");
  add_input(cmd, args->in, "Scan (any readable format, mesh or point cloud)");
  add_output(cmd, args->out, "The .pdef file to write");
  cmd->add_option("--max-error", args->max_error,
                  "Lossy: every sample, and the surface decoded, within this distance (mm) of the original")
      ->check(CLI::Range(0.001, 10.0))
      ->capture_default_str();
  cmd->add_flag("--lossless", args->lossless, "Store the curves exactly (float64, compressed)");
  cmd->add_flag("--store-landmarks", args->store_landmarks, "Also store the landmarks (canonical frame)");
  cmd->add_option("--name", args->name, "A name to store in the file");
  CLI::Option* size =
      cmd->add_option("--size", args->size,
                      "Add a residual layer (.pdef version 3): the whole file at most this many bytes, the "
                      "best error")
          ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 26));
  CLI::Option* target =
      cmd->add_option(
             "--target-error", args->target_error,
             "Add a residual layer: the fewest bytes whose decoded surface lies within this distance "
             "(mm, --target-measure) of the scan in the face mask, measured")
          ->check(CLI::Range(0.0001, 10.0));
  size->excludes(target);
  cmd->add_option("--target-measure", args->target_measure, "What --target-error bounds: mean, p95 or max")
      ->check(CLI::IsMember(all_names<pipeline::TargetMeasure>(pipeline::kTargetMeasureNames)))
      ->capture_default_str();
  cmd->add_option("--residual-spacing", args->residual_spacing,
                  "The residual grid's spacing (mm; default by the layer's size: 1, 0.5 or 0.35, a point "
                  "cloud's 0.5 at most; 0.7 for --target-error)")
      ->check(CLI::Range(0.2, 5.0));
  CLI::Option* texture = cmd->add_flag(
      "--texture", args->texture,
      "Add a texture layer: the scan's photograph (or vertex colours) over the face as one JPEG image");
  cmd->add_option("--texel", args->texel, "The texture layer's texel spacing on the face (mm)")
      ->check(CLI::Range(0.05, 5.0))
      ->capture_default_str()
      ->needs(texture);
  cmd->add_option("--texture-quality", args->texture_quality, "The texture layer's JPEG quality (1-100)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str()
      ->needs(texture);
  args->curves.add_to(cmd);
  args->curves.ratio_option->description(fmt::format(
      "Sampling ratio: K = ratio x 300 reference points (0.05..0.6; {:g} with --size or --target-error)",
      pipeline::kResidualRatio));
  args->surface.add_to(cmd);
  add_force(cmd, args->force);
  cmd->callback([args, &status] { status = run_encode(*args); });
}

} // namespace pdeface::cli
