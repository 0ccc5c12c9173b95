// pdeface align: a scan moved into the canonical face frame, from detected or given landmarks.

#include "common.hpp"

#include <fmt/format.h>

namespace pdeface::cli {
namespace {

struct AlignArgs {
  fs::path in;
  fs::path out;
  fs::path landmarks;     // given landmarks instead of detection (ours or menpo LJSON)
  fs::path landmarks_out; // what was found (or given), with the frame
  fs::path preview;       // SVG
  bool crop = false;
  formats::WriteOptions write;
};

int run_align(const AlignArgs& args) {
  Result<ScanAndLandmarks> input = read_scan_and_landmarks(args.in, args.landmarks);
  if (!input) return fail(input.error());
  Result<align::AlignOutcome> aligned =
      align::align_request(input->scan.mesh, {.landmarks = std::move(input->landmarks),
                                              .crop = args.crop,
                                              .landmarks_json = !args.landmarks_out.empty(),
                                              .preview = !args.preview.empty(),
                                              .source = args.in.string()});
  if (!aligned) return fail(aligned.error());

  Notes notes;
  // The mesh and what it refers to (an OBJ's material library and image, ...), then the other outputs.
  Result<std::vector<OutputFile>> mesh =
      formats::encode_files(aligned->canonical, args.out, args.write, &notes);
  print_notes(notes);
  if (!mesh) return fail(mesh.error());
  std::vector<OutputFile> outputs = *std::move(mesh);
  if (!args.landmarks_out.empty()) outputs.push_back({args.landmarks_out, aligned->landmarks_json});
  if (!args.preview.empty()) outputs.push_back({args.preview, aligned->preview_svg});
  if (Result<void> ok = write_outputs(outputs); !ok) return fail(ok.error());

  const auto& [landmarks_found, frame, confidence] = aligned->alignment;
  const Vec3 tip = *landmarks_found[align::Landmark::NoseTip];
  fmt::print("{}: {} (scan in {}), nose tip at ({:.4g}, {:.4g}, {:.4g})\n", args.in.string(),
             confidence ? fmt::format("face found, confidence {:.2f}", *confidence)
                        : std::string("landmarks given"),
             to_string(frame.scan_units), tip.x(), tip.y(), tip.z());
  fmt::print("{}: canonical frame, mm, {} vertices, {} triangles{}\n", args.out.string(),
             aligned->canonical.vertex_count(), aligned->canonical.triangle_count(),
             args.crop ? ", cropped to the face" : "");
  return 0;
}

} // namespace

void align_command(CLI::App& app, int& status) {
  auto args = std::make_shared<AlignArgs>();
  CLI::App* cmd = app.add_subcommand(
      "align",
      "Move a scan into the canonical face frame (nose tip at the origin, x to the face's left, y up, "
      "z to the viewer, mm), from detected or given landmarks");
  add_input(cmd, args->in, "Scan to align (any readable format)");
  add_output(cmd, args->out, "Aligned mesh to write (any writable format)");
  add_landmarks(cmd, args->landmarks);
  cmd->add_option("--landmarks-out", args->landmarks_out,
                  "Write the landmarks (scan frame) and the transform as JSON");
  cmd->add_option("--preview", args->preview,
                  "Write an SVG of the frontal view with the landmarks and the symmetry line");
  cmd->add_flag("--crop", args->crop,
                "Keep only the face region (between the face's top and bottom, cheek to cheek)");
  add_write_options(cmd, args->write);
  cmd->callback([args, &status] { status = run_align(*args); });
}

} // namespace pdeface::cli
