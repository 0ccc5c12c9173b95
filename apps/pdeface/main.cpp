// pdeface: the command line. It maps arguments onto library calls and prints their outcome; no logic here.

#include "pdeface/align/crop.hpp"
#include "pdeface/align/detect.hpp"
#include "pdeface/align/frame.hpp"
#include "pdeface/align/preview.hpp"
#include "pdeface/compare/fidelity.hpp"
#include "pdeface/compare/preview.hpp"
#include "pdeface/compare/reconstruct.hpp"
#include "pdeface/compare/table.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/core/summary.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/slice/output.hpp"
#include "pdeface/slice/profiles.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace pdeface;

namespace {

constexpr int kDataError = 1;  // the input or output could not be read, converted or written
constexpr int kUsageError = 2; // the command line itself is wrong

// Prints the notes collected so far and forgets them, so that the next step's are printed once.
void print_notes(Notes& notes) {
  for (const std::string& note : notes)
    fmt::print(stderr, "pdeface: note: {}\n", note);
  notes.clear();
}

int fail(const Error& error) {
  fmt::print(stderr, "pdeface: error: {}\n", error.to_string());
  return kDataError;
}

std::optional<formats::Format> parse_format(const std::string& name) {
  if (name.empty()) return std::nullopt;
  return formats::format_from_path(fs::path("x." + name));
}

// ---- info ----------------------------------------------------------------------------------------------

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

// ---- convert -------------------------------------------------------------------------------------------

struct ConvertRequest {
  fs::path in;
  fs::path out;
  std::string from;
  std::string to;
  formats::WriteOptions write;
};

int run_convert(ConvertRequest request) {
  Notes notes;
  request.write.format = parse_format(request.to);
  if (!request.to.empty() && !request.write.format)
    return fail(
        make_error(ErrorCode::UnsupportedFormat, fmt::format("unknown output format '{}'", request.to)));
  const formats::ReadOptions read{.format = parse_format(request.from)};
  if (!request.from.empty() && !read.format)
    return fail(
        make_error(ErrorCode::UnsupportedFormat, fmt::format("unknown input format '{}'", request.from)));
  Result<formats::ConvertReport> report =
      formats::convert(request.in, request.out, read, request.write, &notes);
  print_notes(notes);
  if (!report) return fail(report.error());
  fmt::print("{} ({}, {} bytes) -> {} ({}, {} bytes): {} vertices, {} triangles\n", request.in.string(),
             formats::info(report->from).name, report->bytes_in, request.out.string(),
             formats::info(report->to).name, report->bytes_out, report->vertices, report->triangles);
  return 0;
}

// ---- sample --------------------------------------------------------------------------------------------

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

// ---- align --------------------------------------------------------------------------------------------

struct AlignRequest {
  fs::path in;
  fs::path out;
  fs::path landmarks;     // given landmarks instead of detection (ours or menpo LJSON)
  fs::path landmarks_out; // what was found (or given), with the frame
  fs::path preview;       // SVG
  bool crop = false;
  formats::WriteOptions write;
};

// A scan's alignment: detected, or from a landmark file (ours or menpo LJSON).
Result<align::Alignment> align_scan(const Mesh& mesh, const fs::path& in, const fs::path& landmarks_file) {
  if (landmarks_file.empty()) return align::align_scan(mesh, std::nullopt, in.string());
  Result<std::string> bytes = read_file(landmarks_file);
  if (!bytes) return bytes.error();
  Result<align::Landmarks> given = align::read_landmarks(*bytes, landmarks_file.string());
  if (!given) return given.error();
  return align::align_scan(mesh, *std::move(given), in.string(), landmarks_file.string());
}

int run_align(const AlignRequest& request) {
  Notes notes;
  Result<formats::LoadedMesh> scan = formats::read_mesh(request.in, {}, &notes);
  print_notes(notes);
  if (!scan) return fail(scan.error());
  const Mesh& mesh = scan->mesh;

  Result<align::Alignment> alignment = align_scan(mesh, request.in, request.landmarks);
  if (!alignment) return fail(alignment.error());
  const auto& [landmarks, frame, confidence] = *alignment;

  Mesh aligned = align::to_canonical(mesh, frame);
  if (request.crop) {
    Result<Mesh> cropped = align::crop_face(aligned, align::to_canonical(landmarks, frame));
    if (!cropped) {
      Error e = std::move(cropped).error();
      e.source = request.in.string();
      return fail(e);
    }
    aligned = std::move(cropped).value();
  }
  Result<std::size_t> written = formats::write_mesh(aligned, request.out, request.write, &notes);
  print_notes(notes);
  if (!written) return fail(written.error());
  if (!request.landmarks_out.empty())
    if (Result<void> ok = write_file_atomic(request.landmarks_out,
                                            align::write_alignment_json(landmarks, frame, confidence));
        !ok)
      return fail(ok.error());
  if (!request.preview.empty()) {
    const std::string title =
        confidence ? fmt::format("{}: found, confidence {:.2f}", request.in.filename().string(), *confidence)
                   : fmt::format("{}: landmarks from {}", request.in.filename().string(),
                                 request.landmarks.filename().string());
    if (Result<void> ok =
            write_file_atomic(request.preview, align::preview_svg(mesh, frame, landmarks, {.title = title}));
        !ok)
      return fail(ok.error());
  }
  const Vec3 tip = *landmarks[align::Landmark::NoseTip];
  fmt::print("{}: {} (scan in {}), nose tip at ({:.4g}, {:.4g}, {:.4g})\n", request.in.string(),
             confidence ? fmt::format("face found, confidence {:.2f}", *confidence)
                        : std::string("landmarks given"),
             to_string(frame.scan_units), tip.x(), tip.y(), tip.z());
  fmt::print("{}: canonical frame, mm, {} vertices, {} triangles{}\n", request.out.string(),
             aligned.vertex_count(), aligned.triangle_count(), request.crop ? ", cropped to the face" : "");
  return 0;
}

// ---- profiles, reconstruct, table: the options they share ---------------------------------------------

// How a scan becomes curves: landmarks given or detected, and the slicing options.
struct CurveArgs {
  fs::path landmarks; // given landmarks instead of detection
  std::string parameter = "arc";
  std::string sampling = "local";
  std::string fit = "cosine";
  std::optional<std::size_t> points;
  slice::ProfileOptions options;

  [[nodiscard]] slice::ProfileOptions profile_options() const {
    slice::ProfileOptions o = options;
    o.points = points;
    o.parameter = parameter == "height" ? slice::Parameter::Height : slice::Parameter::ArcLength;
    o.fit = fit == "spline" ? slice::Fit::Spline : slice::Fit::Cosine;
    o.sampling = sampling == "parameter" ? slice::Sampling::Parameter
                 : sampling == "local"   ? slice::Sampling::LocalHeights
                                         : slice::Sampling::SharedHeights;
    return o;
  }
};

// A scan read and aligned, or the reason it could not be.
struct AlignedScan {
  formats::LoadedMesh scan;
  align::Alignment alignment;
};

Result<AlignedScan> read_and_align(const fs::path& in, const fs::path& landmarks) {
  Notes notes;
  Result<formats::LoadedMesh> scan = formats::read_mesh(in, {}, &notes);
  print_notes(notes);
  if (!scan) return scan.error();
  Result<align::Alignment> alignment = align_scan(scan->mesh, in, landmarks);
  if (!alignment) return alignment.error();
  return AlignedScan{std::move(scan).value(), std::move(alignment).value()};
}

// ---- profiles -----------------------------------------------------------------------------------------

// What slicing filled and what the scan lacks, as notes.
void print_holes_and_gaps(const slice::ProfileSet& set) {
  if (set.holes() > 0)
    fmt::print(stderr,
               "pdeface: note: {} holes filled ({:.1f} % of the curves' length, the longest {:.1f} mm)\n",
               set.holes(), 100.0 * set.filled_fraction, set.longest_hole_mm());
  for (const std::string& m : set.missing)
    fmt::print(stderr, "pdeface: note: missing from the scan: {}\n", m);
}

struct ProfilesRequest {
  fs::path in;
  fs::path out; // JSON
  fs::path svg; // picture
  CurveArgs curves;
};

int run_profiles(const ProfilesRequest& request) {
  Result<AlignedScan> aligned = read_and_align(request.in, request.curves.landmarks);
  if (!aligned) return fail(aligned.error());
  const compare::CanonicalScan canonical = compare::canonical_scan(aligned->scan.mesh, aligned->alignment);
  Result<slice::ProfileSet> set = compare::extract_profiles(canonical, request.curves.profile_options());
  if (!set) {
    Error e = std::move(set).error();
    e.source = request.in.string();
    return fail(e);
  }
  // Both documents are made before either is written, so a failure leaves no output behind.
  const std::string json = slice::write_profiles_json(*set);
  const std::string svg =
      request.svg.empty()
          ? std::string()
          : slice::profiles_svg(
                canonical.mesh, *set,
                {.title = fmt::format("{}: {} curves, K = {} ({:.1f} % of {} reference points), {}",
                                      request.in.filename().string(), set->curves.size(), set->k,
                                      100.0 * set->ratio, set->reference_points,
                                      slice::to_string(set->parameter))});
  if (Result<void> ok = write_file_atomic(request.out, json); !ok) return fail(ok.error());
  if (!request.svg.empty())
    if (Result<void> ok = write_file_atomic(request.svg, svg); !ok) return fail(ok.error());
  fmt::print("{}: {} curves at x = {:.1f} .. {:.1f} mm, y = {:.1f} .. {:.1f} mm, K = {} points ({:.1f} % of "
             "{}; the scan's profiles have {} raw points), 4 evaluation profiles -> {}\n",
             request.in.string(), set->curves.size(), set->curves.front().x, set->curves.back().x,
             set->height_range[0], set->height_range[1], set->k, 100.0 * set->ratio, set->reference_points,
             set->raw_points, request.out.string());
  print_holes_and_gaps(*set);
  return 0;
}

// ---- reconstruct ---------------------------------------------------------------------------------------

// How curves become a surface.
struct SurfaceArgs {
  std::string scheme = "spline";
  std::string spacing = "physical";
  pde::Options options;

  [[nodiscard]] pde::Options pde_options() const {
    pde::Options o = options;
    o.scheme = pde::scheme_from_string(scheme).value_or(pde::Scheme::Spline);
    o.spacing = spacing == "physical" ? pde::Spacing::Physical : pde::Spacing::Uniform;
    return o;
  }
};

struct ReconstructRequest {
  fs::path in;
  fs::path out;
  fs::path profiles; // the curves as JSON too
  fs::path preview;  // SVG: scan and reconstruction side by side
  CurveArgs curves;
  SurfaceArgs surface;
  std::vector<std::size_t> resolution; // {v} or {u, v}
  formats::WriteOptions write;
};

int run_reconstruct(const ReconstructRequest& request) {
  Result<AlignedScan> aligned = read_and_align(request.in, request.curves.landmarks);
  if (!aligned) return fail(aligned.error());
  compare::ReconstructOptions options{.profiles = request.curves.profile_options(),
                                      .pde = request.surface.pde_options()};
  if (request.resolution.size() == 1) options.resolution = compare::Resolution{0, request.resolution[0]};
  if (request.resolution.size() == 2)
    options.resolution = compare::Resolution{request.resolution[0], request.resolution[1]};
  const compare::CanonicalScan canonical = compare::canonical_scan(aligned->scan.mesh, aligned->alignment);
  Result<compare::Reconstruction> made = compare::reconstruct(canonical, options, request.in.string());
  if (!made) return fail(made.error());
  Result<compare::Fidelity> fidelity =
      compare::measure_fidelity(canonical.mesh, made->profiles, made->canonical);

  // The mesh is encoded before anything is written, so that a failure (e.g. an unknown output format)
  // leaves no output behind.
  Notes notes;
  Result<std::string> encoded = formats::encode_mesh(made->scan, request.out, request.write, &notes);
  print_notes(notes);
  if (!encoded) return fail(encoded.error());
  if (Result<void> ok = write_file_atomic(request.out, *encoded); !ok) return fail(ok.error());
  if (!request.profiles.empty())
    if (Result<void> ok = write_file_atomic(request.profiles, slice::write_profiles_json(made->profiles));
        !ok)
      return fail(ok.error());
  if (!request.preview.empty())
    if (Result<void> ok = write_file_atomic(
            request.preview,
            compare::reconstruction_preview_svg(
                canonical.mesh, made->canonical, made->profiles,
                {.title = fmt::format("{}: {} curves x {} points", request.in.filename().string(),
                                      made->profiles.curves.size(), made->profiles.k)}));
        !ok)
      return fail(ok.error());

  const slice::ProfileSet& p = made->profiles;
  const pde::Surface& s = made->surface;
  fmt::print("{}: {} curves x {} points ({:.1f} % of {}), {} scheme, N = {} modes{}, a = {:.3f}\n",
             request.in.string(), p.curves.size(), p.k, 100.0 * p.ratio, p.reference_points,
             pde::to_string(s.scheme()), s.modes(), s.has_remainder() ? " + remainder" : "", s.smoothing());
  fmt::print("{}: {} x {} grid, {} vertices, {} triangles, {} bytes, in the scan's frame ({})\n",
             request.out.string(), made->grid.u, made->grid.v, made->scan.vertex_count(),
             made->scan.triangle_count(), encoded->size(), to_string(made->scan.units));
  if (fidelity) {
    const metrics::DistanceStats& d = fidelity->surface.both;
    fmt::print("fidelity (mm, face region): profile error {:.3f} (symmetry {:.3f}, eyes {:.3f}, diagonals "
               "{:.3f} / {:.3f}); surface distance mean {:.3f}, RMS {:.3f}, p95 {:.3f}, max {:.2f}\n",
               fidelity->mean_profile_error, fidelity->profile_error[0], fidelity->profile_error[1],
               fidelity->profile_error[2], fidelity->profile_error[3], d.mean, d.rms, d.p95, d.max);
    const align::FaceFrame& frame = canonical.frame;
    fmt::print(
        "  = mean {:.3g}, max {:.3g} {} in the scan's units; max {:.2e} of the face region's diagonal\n",
        d.mean / frame.scale, d.max / frame.scale, to_string(made->scan.units),
        d.max / fidelity->surface.diagonal);
    const compare::Coverage& c = fidelity->coverage;
    fmt::print(
        "coverage of the face (the outline its landmarks give): {:.1f} % of the scan within 1 mm of the "
        "reconstruction; scan -> reconstruction mean {:.3f}, p95 {:.3f} mm; reconstruction -> scan mean "
        "{:.3f} mm\n",
        100.0 * c.share, c.distance.mean, c.distance.p95, fidelity->surface.b_to_a.mean);
  } else {
    fmt::print(stderr, "pdeface: note: fidelity not measured: {}\n", fidelity.error().message);
  }
  print_holes_and_gaps(p);
  return 0;
}

// ---- table ---------------------------------------------------------------------------------------------

struct TableRequest {
  std::vector<fs::path> in;
  fs::path out; // Markdown; stdout when empty
  fs::path csv;
  std::vector<double> ratios{compare::kPaperRatios.begin(), compare::kPaperRatios.end()};
  std::vector<std::string> schemes{"spline", "paper", "patch4"};
  CurveArgs curves;
  SurfaceArgs surface;
};

int run_table(const TableRequest& request) {
  compare::TableOptions options{.ratios = request.ratios,
                                .schemes = {},
                                .profiles = request.curves.profile_options(),
                                .pde = request.surface.pde_options()};
  for (const std::string& name : request.schemes)
    options.schemes.push_back(pde::scheme_from_string(name).value_or(pde::Scheme::Spline));
  std::vector<compare::TableRow> rows;
  for (const fs::path& in : request.in) {
    Result<AlignedScan> aligned = read_and_align(in, {});
    if (!aligned) return fail(aligned.error());
    Result<std::vector<compare::TableRow>> scan_rows =
        compare::table_rows(aligned->scan.mesh, aligned->alignment, options, in.filename().string());
    if (!scan_rows) {
      Error e = std::move(scan_rows).error();
      e.source = in.string();
      return fail(e);
    }
    for (const compare::TableRow& r : *scan_rows)
      if (!r.fidelity)
        fmt::print(stderr, "pdeface: note: {}: {:g} %, {}: {}\n", in.string(), 100 * r.ratio,
                   pde::to_string(r.scheme), r.failure);
    rows.insert(rows.end(), scan_rows->begin(), scan_rows->end());
  }
  const std::string markdown = compare::table_markdown(rows);
  if (!request.csv.empty())
    if (Result<void> ok = write_file_atomic(request.csv, compare::table_csv(rows)); !ok)
      return fail(ok.error());
  if (request.out.empty()) {
    fmt::print("{}", markdown);
  } else {
    if (Result<void> ok = write_file_atomic(request.out, markdown); !ok) return fail(ok.error());
    fmt::print("{} scans x {} ratios x {} schemes -> {}\n", request.in.size(), request.ratios.size(),
               options.schemes.size(), request.out.string());
  }
  return 0;
}

void add_write_options(CLI::App* cmd, formats::WriteOptions& write) {
  cmd->add_option("--draco-bits", write.draco_bits, "Draco position quantisation bits (1..24)")
      ->check(CLI::Range(1, 24))
      ->capture_default_str();
  cmd->add_option("--draco-level", write.draco_level, "Draco compression level (0..10; 0 keeps vertex order)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->add_flag("--draco", write.draco_in_gltf, "GLB output: compress with KHR_draco_mesh_compression");
  cmd->add_flag("--ascii", write.ascii, "PLY and STL output: ASCII instead of binary");
}

void add_input(CLI::App* cmd, fs::path& in, const std::string& description) {
  cmd->add_option("input", in, description)->required()->check(CLI::ExistingFile);
}

void add_curve_options(CLI::App* cmd, CurveArgs& curves, bool with_landmarks = true) {
  if (with_landmarks)
    cmd->add_option("--landmarks", curves.landmarks,
                    "Use these landmarks (pdeface JSON or menpo LJSON) instead of detecting them")
        ->check(CLI::ExistingFile);
  CLI::Option* ratio =
      cmd->add_option("--ratio", curves.options.ratio, "Sampling ratio: K = ratio x raw points (0.05..0.6)")
          ->check(CLI::Range(slice::kMinRatio, slice::kMaxRatio))
          ->capture_default_str();
  cmd->add_option("--points", curves.points, "Points per curve K, instead of the ratio (>= 4)")
      ->check(CLI::Range(std::size_t{4}, pde::max_samples))
      ->excludes(ratio);
  cmd->add_option("--curves", curves.options.planes.curves,
                  "Number of curves: 3 x patches + 1, odd patches (4, 10, 16, 22, 28, ...)")
      ->capture_default_str();
  cmd->add_option("--parameter", curves.parameter, "Spline parameter: arc (length) or height")
      ->check(CLI::IsMember({"arc", "height"}))
      ->capture_default_str();
  cmd->add_option(
         "--sampling", curves.sampling,
         "Where the K points go: local (at the heights the curves near each one share), parameter "
         "(evenly in each curve's own arc length) or shared (the same relative heights on every curve)")
      ->check(CLI::IsMember({"shared", "parameter", "local"}))
      ->capture_default_str();
  cmd->add_option("--fit", curves.fit,
                  "How the K points are made: cosine (the least-squares fit the PDE surface can draw) or "
                  "spline (a least-squares cubic spline, sampled)")
      ->check(CLI::IsMember({"cosine", "spline"}))
      ->capture_default_str();
  cmd->add_option("--max-gap", curves.options.max_hole_mm,
                  "Longest hole filled along a curve, mm (default: a quarter of the face's height)")
      ->check(CLI::Range(0.0, 200.0));
}

void add_surface_options(CLI::App* cmd, SurfaceArgs& surface, bool with_scheme = true) {
  if (with_scheme)
    cmd->add_option("--scheme", surface.scheme,
                    "spline (C2 through every curve), paper (the paper's patches) or patch4 (four positions "
                    "per patch, refused where unstable)")
        ->check(CLI::IsMember({"spline", "paper", "patch4"}))
        ->capture_default_str();
  cmd->add_option("--modes", surface.options.modes, "Fourier modes N (default: all, K - 1)");
  cmd->add_option("--smoothing", surface.options.smoothing,
                  "Smoothing parameter a (default: isotropic, pi W / L; 1 as in the paper)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spacing", surface.spacing,
                  "Curve positions in u: physical (by the planes' spacing) or uniform (the paper)")
      ->check(CLI::IsMember({"uniform", "physical"}))
      ->capture_default_str();
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "pdeface: 3D face scans to compact PDE surfaces and back, and conversion between mesh formats"};
  app.set_version_flag("--version", std::string("pdeface ") + PDEFACE_VERSION);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
    return fmt::format("pdeface{}: error: {} (see --help)\n",
                       failed && failed->get_parent() ? " " + failed->get_name() : "", e.what());
  });

  InfoRequest info;
  CLI::App* info_cmd =
      app.add_subcommand("info", "Describe mesh files: format, counts, units, extent, topology");
  info_cmd->add_option("files", info.files, "Files to describe")->required()->check(CLI::ExistingPath);
  info_cmd->add_flag("--json", info.json, "Print JSON for machines");

  ConvertRequest convert;
  CLI::App* convert_cmd = app.add_subcommand(
      "convert", "Convert between formats chosen by extension: .wrl .obj .ply .off .stl .gltf .glb .drc");
  add_input(convert_cmd, convert.in, "File to read");
  convert_cmd->add_option("output", convert.out, "File to write (replaced atomically)")->required();
  convert_cmd->add_option("--from", convert.from, "Input format when the extension is misleading (e.g. ply)");
  convert_cmd->add_option("--to", convert.to, "Output format when the extension is misleading (e.g. glb)");
  add_write_options(convert_cmd, convert.write);

  SampleRequest sample;
  CLI::App* sample_cmd = app.add_subcommand("sample", "Write the built-in synthetic face scan (mm, frontal)");
  sample_cmd->add_option("output", sample.out, "File to write, any writable format")->required();
  sample_cmd->add_option("--spacing", sample.face.spacing_mm, "Grid step in mm")
      ->check(CLI::Range(0.2, 20.0))
      ->capture_default_str();
  sample_cmd->add_option("--noise", sample.face.noise_mm, "Depth noise amplitude in mm")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  sample_cmd->add_option("--seed", sample.face.seed, "Varies the outline and the noise")
      ->capture_default_str();
  sample_cmd->add_flag("--no-holes", sample.no_holes, "Do not punch holes");
  sample_cmd->add_flag("--no-colors", sample.no_colors, "Do not add vertex colours");
  add_write_options(sample_cmd, sample.write);

  AlignRequest align_request;
  CLI::App* align_cmd = app.add_subcommand(
      "align",
      "Move a scan into the canonical face frame (nose tip at the origin, x to the face's left, y up, "
      "z to the viewer, mm), from detected or given landmarks");
  add_input(align_cmd, align_request.in, "Scan to align (any readable format)");
  align_cmd->add_option("-o,--output", align_request.out, "Aligned mesh to write (any writable format)")
      ->required();
  align_cmd
      ->add_option("--landmarks", align_request.landmarks,
                   "Use these landmarks (pdeface JSON or menpo LJSON) instead of detecting them")
      ->check(CLI::ExistingFile);
  align_cmd->add_option("--landmarks-out", align_request.landmarks_out,
                        "Write the landmarks (scan frame) and the transform as JSON");
  align_cmd->add_option("--preview", align_request.preview,
                        "Write an SVG of the frontal view with the landmarks and the symmetry line");
  align_cmd->add_flag("--crop", align_request.crop,
                      "Keep only the face region (between the face's top and bottom, cheek to cheek)");
  add_write_options(align_cmd, align_request.write);

  ProfilesRequest profiles;
  CLI::App* profiles_cmd = app.add_subcommand(
      "profiles", "Slice a scan into the paper's profile curves (28 by default), fit and resample them, and "
                  "extract the 4 evaluation profiles; JSON out, SVG picture optional");
  add_input(profiles_cmd, profiles.in, "Scan (any readable format, mesh or point cloud)");
  profiles_cmd->add_option("-o,--output", profiles.out, "Profiles to write as JSON")->required();
  profiles_cmd->add_option("--svg", profiles.svg,
                           "Also write a picture: the curves over the face, and the "
                           "symmetry profile before and after fitting");
  add_curve_options(profiles_cmd, profiles.curves);

  ReconstructRequest reconstruct;
  CLI::App* reconstruct_cmd = app.add_subcommand(
      "reconstruct",
      "Scan -> aligned -> profile curves -> PDE surface, written as a mesh in the scan's frame "
      "and units; prints how far it lies from the scan");
  add_input(reconstruct_cmd, reconstruct.in, "Scan (any readable format, mesh or point cloud)");
  reconstruct_cmd
      ->add_option("-o,--output", reconstruct.out, "Surface mesh to write (.glb .obj .ply .wrl ...)")
      ->required();
  reconstruct_cmd->add_option("--profiles", reconstruct.profiles, "Also write the curves as JSON");
  reconstruct_cmd->add_option("--preview", reconstruct.preview,
                              "Also write an SVG: the scan and the reconstruction side by side, and turned");
  reconstruct_cmd
      ->add_option("--resolution", reconstruct.resolution,
                   "Grid: V points along the face's height (across in proportion), or UxV; default about "
                   "1 mm spacing")
      ->delimiter('x')
      ->expected(1, 2)
      ->check(CLI::Range(std::size_t{2}, std::size_t{4000}));
  add_curve_options(reconstruct_cmd, reconstruct.curves);
  add_surface_options(reconstruct_cmd, reconstruct.surface);
  add_write_options(reconstruct_cmd, reconstruct.write);

  TableRequest table;
  CLI::App* table_cmd = app.add_subcommand(
      "table", "The paper's Table I on the given scans: profile error and surface distance per sampling "
               "ratio and scheme, as Markdown (and CSV)");
  table_cmd->add_option("input", table.in, "Scans (any readable format)")
      ->required()
      ->check(CLI::ExistingFile);
  table_cmd->add_option("-o,--output", table.out, "Markdown file to write (default: standard output)");
  table_cmd->add_option("--csv", table.csv, "Also write every row as CSV");
  table_cmd->add_option("--ratios", table.ratios, "Sampling ratios, comma-separated (0.05..0.6)")
      ->delimiter(',')
      ->check(CLI::Range(slice::kMinRatio, slice::kMaxRatio))
      ->capture_default_str();
  table_cmd->add_option("--schemes", table.schemes, "Schemes to compare, comma-separated")
      ->delimiter(',')
      ->check(CLI::IsMember({"spline", "paper", "patch4"}))
      ->capture_default_str();
  add_curve_options(table_cmd, table.curves, /*with_landmarks=*/false);
  add_surface_options(table_cmd, table.surface, /*with_scheme=*/false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kUsageError; // --help and --version exit 0
  }
  if (info_cmd->parsed()) return run_info(info);
  if (convert_cmd->parsed()) return run_convert(convert);
  if (sample_cmd->parsed()) return run_sample(sample);
  if (align_cmd->parsed()) return run_align(align_request);
  if (profiles_cmd->parsed()) return run_profiles(profiles);
  if (reconstruct_cmd->parsed()) return run_reconstruct(reconstruct);
  if (table_cmd->parsed()) return run_table(table);
  return 0;
}
