#include "common.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace pdeface::cli {

void print_notes(Notes& notes) {
  for (const std::string& note : notes)
    fmt::print(stderr, "pdeface: note: {}\n", note);
  notes.clear();
}

int fail(const Error& error) {
  fmt::print(stderr, "pdeface: error: {}\n", error.to_string());
  return kDataError;
}

Result<formats::LoadedMesh> read_scan(const std::filesystem::path& in) {
  Notes notes;
  Result<formats::LoadedMesh> scan = formats::read_mesh(in, {}, &notes);
  print_notes(notes);
  return scan;
}

Result<align::LandmarkSource> landmark_source(const std::filesystem::path& file) {
  // One command, one scan: detection may use every core.
  if (file.empty()) return align::LandmarkSource{.detect = {.threads = 0}};
  Result<std::string> bytes = read_file(file);
  if (!bytes) return bytes.error();
  return align::LandmarkSource{*std::move(bytes), file.string(), {}};
}

Result<ScanAndLandmarks> read_scan_and_landmarks(const std::filesystem::path& in,
                                                 const std::filesystem::path& landmarks) {
  Result<formats::LoadedMesh> scan = read_scan(in);
  if (!scan) return scan.error();
  Result<align::LandmarkSource> source = landmark_source(landmarks);
  if (!source) return source.error();
  return ScanAndLandmarks{*std::move(scan), *std::move(source)};
}

Result<void> write_outputs(std::span<const OutputFile> files) { return write_files_atomic(files); }

void add_input(CLI::App* cmd, std::filesystem::path& in, const std::string& description) {
  cmd->add_option("input", in, description)->required()->check(CLI::ExistingFile);
}

void add_output(CLI::App* cmd, std::filesystem::path& out, const std::string& description) {
  cmd->add_option("-o,--output", out, description)->required();
}

void add_landmarks(CLI::App* cmd, std::filesystem::path& landmarks) {
  cmd->add_option("--landmarks", landmarks,
                  "Use these landmarks (pdeface JSON or menpo LJSON) instead of detecting them")
      ->check(CLI::ExistingFile);
}

std::optional<pipeline::Resolution> ResolutionArg::grid() const {
  if (values.size() == 1) return pipeline::Resolution{0, values[0]};
  if (values.size() == 2) return pipeline::Resolution{values[0], values[1]};
  return std::nullopt;
}

void add_resolution(CLI::App* cmd, ResolutionArg& resolution) {
  cmd->add_option("--resolution", resolution.values,
                  "Grid: V points along the face's height (across in proportion), or UxV; default about 1 mm "
                  "spacing")
      ->delimiter('x')
      ->expected(1, 2)
      ->check(CLI::Range(std::size_t{2}, std::size_t{4000}));
}

void add_write_options(CLI::App* cmd, formats::WriteOptions& write) {
  cmd->add_option("--draco-bits", write.draco_bits, "Draco position quantisation bits (1..24)")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_option("--draco-level", write.draco_level, "Draco compression level (0..10; 0 keeps vertex order)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->add_option("--draco-uv-bits", write.draco_uv_bits,
                  "Draco texture coordinate quantisation bits (1..24; draco_encoder -qt)")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_option("--draco-color-bits", write.draco_color_bits,
                  "Draco colours as normalised integers of 8 or 16 bits")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_flag("--draco", write.draco_in_gltf, "GLB output: compress with KHR_draco_mesh_compression");
  cmd->add_flag("--ascii", write.ascii, "PLY and STL output: ASCII instead of binary");
}

void CurveArgs::add_to(CLI::App* cmd, bool with_landmarks) {
  if (with_landmarks) add_landmarks(cmd, landmarks);
  CLI::Option* ratio = ratio_option =
      cmd->add_option("--ratio", options.ratio,
                      "Sampling ratio: K = ratio x 300 reference points (0.05..0.6)")
          ->check(CLI::Range(slice::kMinRatio, slice::kMaxRatio))
          ->capture_default_str();
  cmd->add_option("--points", points, "Points per curve K, instead of the ratio (>= 4)")
      ->check(CLI::Range(std::size_t{4}, pde::max_samples))
      ->excludes(ratio);
  cmd->add_option("--curves", options.planes.curves,
                  "Number of curves: 3 x patches + 1, odd patches (4, 10, 16, 22, 28, ...)")
      ->capture_default_str();
  cmd->add_option("--parameter", parameter, "Spline parameter: arc (length) or height")
      ->check(one_of<slice::Parameter>(slice::kParameterNames))
      ->capture_default_str();
  cmd->add_option(
         "--sampling", sampling,
         "Where the K points go: local (at the heights the curves near each one share), parameter "
         "(evenly in each curve's own arc length) or shared (the same relative heights on every curve)")
      ->check(one_of<slice::Sampling>(slice::kSamplingNames))
      ->capture_default_str();
  cmd->add_option("--fit", fit,
                  "How the K points are made: cosine (the least-squares fit the PDE surface can draw) or "
                  "spline (a least-squares cubic spline, sampled)")
      ->check(one_of<slice::Fit>(slice::kFitNames))
      ->capture_default_str();
  cmd->add_option("--max-gap", options.max_hole_mm,
                  "Longest hole filled along a curve, mm (default: a quarter of the face's height)")
      ->check(CLI::Range(0.0, 200.0));
}

slice::ProfileOptions CurveArgs::profile_options() const {
  slice::ProfileOptions o = options;
  o.points = points;
  o.parameter = named<slice::Parameter>(slice::kParameterNames, parameter);
  o.sampling = named<slice::Sampling>(slice::kSamplingNames, sampling);
  o.fit = named<slice::Fit>(slice::kFitNames, fit);
  return o;
}

void SurfaceArgs::add_to(CLI::App* cmd, bool with_scheme) {
  if (with_scheme)
    cmd->add_option("--scheme", scheme,
                    "spline (C2 through every curve), paper (the paper's patches) or patch4 (four positions "
                    "per patch, refused where unstable)")
        ->check(one_of<pde::Scheme>(pde::kSchemeNames))
        ->capture_default_str();
  cmd->add_option("--modes", options.modes, "Fourier modes N (default: all, K - 1)");
  cmd->add_option("--smoothing", options.smoothing,
                  "Smoothing parameter a (default: isotropic, pi W / L; 1 as in the paper)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spacing", spacing,
                  "Curve positions in u: physical (by the planes' spacing) or uniform (the paper)")
      ->check(one_of<pde::Spacing>(pde::kSpacingNames))
      ->capture_default_str();
}

pde::Options SurfaceArgs::pde_options() const {
  pde::Options o = options;
  o.scheme = named<pde::Scheme>(pde::kSchemeNames, scheme);
  o.spacing = named<pde::Spacing>(pde::kSpacingNames, spacing);
  return o;
}

void print_holes_and_gaps(const slice::ProfileSet& set) {
  if (set.holes() > 0)
    fmt::print(stderr,
               "pdeface: note: {} holes filled ({:.1f} % of the curves' length, the longest {:.1f} mm)\n",
               set.holes(), 100.0 * set.filled_fraction, set.longest_hole_mm());
  for (const std::string& m : set.missing)
    fmt::print(stderr, "pdeface: note: missing from the scan: {}\n", m);
}

void add_force(CLI::App* cmd, bool& force) {
  cmd->add_flag("--force", force,
                "Write the result even when its self-check against the scan fails (docs/pipeline.md, "
                "\"Self-check\"), with a warning");
}

void print_check(const metrics::SelfCheck& check) {
  if (check.passed())
    fmt::print("self-check on the face: {}\n", check.summary());
  else
    fmt::print(stderr, "pdeface: warning: written with --force although its self-check failed: {}\n",
               check.summary());
}

int encode_scan(const std::filesystem::path& in, const std::filesystem::path& out,
                const pipeline::EncodeRequest& request) {
  if (formats::format_from_path(out) != formats::Format::Pdef) {
    fmt::print(stderr,
               "pdeface: error: {}: the output of encode is a .pdef file (decode or reconstruct write "
               "meshes)\n",
               out.string());
    return kUsageError;
  }
  Result<formats::LoadedMesh> scan = read_scan(in);
  if (!scan) return fail(scan.error());
  Result<pipeline::EncodeOutcome> made = pipeline::encode_request(std::move(scan->mesh), request);
  if (!made) return fail(made.error());
  const std::array<OutputFile, 1> outputs{OutputFile{out, made->encoded.bytes}};
  if (Result<void> ok = write_outputs(outputs); !ok) return fail(ok.error());

  const slice::ProfileSet& p = made->profiles;
  const pdef::Face& f = made->face;
  fmt::print("{}: {} curves x {} points ({:.1f} % of {}), {} scheme, N = {} modes, a = {:.3f}\n", in.string(),
             f.curve_count(), f.sample_count(), 100.0 * p.ratio, p.reference_points,
             pde::to_string(f.pde.scheme), *f.pde.modes, *f.pde.smoothing);
  const pdef::Encoded& e = made->encoded;
  if (request.encoding.lossless)
    fmt::print("{}: {} bytes, lossless\n", out.string(), e.bytes.size());
  else
    fmt::print(
        "{}: {} bytes, lossy: samples on a {:.4f} mm grid, every sample within {:.4f} mm and the surface "
        "within {:.4f} mm of the original (at most {} mm)\n",
        out.string(), e.bytes.size(), e.step_mm, e.max_sample_error, e.max_surface_error,
        request.encoding.max_error_mm);
  if (const std::optional<pipeline::ResidualOutcome>& r = made->residual) {
    fmt::print("residual layer: {} bytes ({} x {} grid at {} mm, the scan found at {:.1f} % of it{}; the "
               "whole stream {} bytes)\n",
               r->layer_bytes, r->width, r->height, r->spacing_mm, 100.0 * r->found_share,
               r->trim_bytes > 0 ? fmt::format(", {:.2f} % of its cells trimmed in {} bytes",
                                               100.0 * r->trimmed_share, r->trim_bytes)
                                 : std::string(),
               r->whole_stream);
    if (r->measured)
      fmt::print(
          "measured: the decoded file lies mean {:.4f}, p95 {:.4f}, max {:.3f} mm from the scan in the "
          "face mask\n",
          r->measured->to_scan.mean, r->measured->to_scan.p95, r->measured->to_scan.max);
  }
  if (const std::optional<pipeline::TextureOutcome>& t = made->texture)
    fmt::print("texture layer: {} bytes ({} x {} texels from the scan's {}, which {:.1f} % of them met)\n",
               t->bytes, t->width, t->height,
               t->source == metrics::ColourSource::Texture ? "photograph" : "vertex colours",
               100.0 * t->found_share);
  if (made->check) print_check(*made->check);
  print_holes_and_gaps(p);
  return 0;
}

} // namespace pdeface::cli
