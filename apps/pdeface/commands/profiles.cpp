// pdeface profiles: a scan sliced into the paper's profile curves and the 4 evaluation profiles.

#include "common.hpp"

#include "pdeface/pipeline/requests.hpp"

#include <fmt/format.h>

namespace pdeface::cli {
namespace {

struct ProfilesArgs {
  fs::path in;
  fs::path out; // JSON
  fs::path svg; // picture
  CurveArgs curves;
};

int run_profiles(const ProfilesArgs& args) {
  Result<ScanAndLandmarks> input = read_scan_and_landmarks(args.in, args.curves.landmarks);
  if (!input) return fail(input.error());
  Result<pipeline::ProfilesOutcome> made =
      pipeline::profiles_request(input->scan.mesh, {.landmarks = std::move(input->landmarks),
                                                    .profiles = args.curves.profile_options(),
                                                    .svg = !args.svg.empty(),
                                                    .source = args.in.string()});
  if (!made) return fail(made.error());
  std::vector<OutputFile> outputs{{args.out, made->json}};
  if (!args.svg.empty()) outputs.push_back({args.svg, made->svg});
  if (Result<void> ok = write_outputs(outputs); !ok) return fail(ok.error());

  const slice::ProfileSet& set = made->profiles;
  fmt::print("{}: {} curves at x = {:.1f} .. {:.1f} mm, y = {:.1f} .. {:.1f} mm, K = {} points ({:.1f} % of "
             "{}; the scan's profiles have {} raw points), 4 evaluation profiles -> {}\n",
             args.in.string(), set.curves.size(), set.curves.front().x, set.curves.back().x,
             set.height_range[0], set.height_range[1], set.k, 100.0 * set.ratio, set.reference_points,
             set.raw_points, args.out.string());
  print_holes_and_gaps(set);
  return 0;
}

} // namespace

void profiles_command(CLI::App& app, int& status) {
  auto args = std::make_shared<ProfilesArgs>();
  CLI::App* cmd = app.add_subcommand(
      "profiles",
      "Slice a scan into the paper's profile curves (28 by default), holes filled, fit and sample "
      "them, and extract the 4 evaluation profiles; JSON out, SVG picture optional");
  add_input(cmd, args->in, "Scan (any readable format, mesh or point cloud)");
  add_output(cmd, args->out, "Profiles to write as JSON");
  cmd->add_option("--svg", args->svg,
                  "Also write a picture: the curves over the face, and the symmetry profile before and after "
                  "fitting");
  args->curves.add_to(cmd);
  cmd->callback([args, &status] { status = run_profiles(*args); });
}

} // namespace pdeface::cli
