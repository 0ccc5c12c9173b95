// compare_scan and compare_scans: every variant of every scan, measured on its decoded bytes.

#include "pdeface/pipeline/report.hpp"
#include "encode_residual.hpp"

#include "pdeface/align/crop.hpp"
#include "pdeface/align/frame.hpp"
#include "pdeface/core/parallel.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/image/image.hpp"
#include "pdeface/metrics/colour.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include "heat_map.hpp"
#include "report_detail.hpp"
#include "variants.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <mutex>

namespace pdeface::pipeline {

std::string_view to_string(Method method) noexcept {
  switch (method) {
  case Method::Raw: return "raw";
  case Method::Gzip: return "raw+gzip";
  case Method::Draco: return "draco";
  case Method::DecimateDraco: return "decimate+draco";
  case Method::Pde: return "pde";
  case Method::DracoColour: return "draco+colour";
  case Method::PdeTexture: return "pde+texture";
  }
  return "?";
}

std::size_t Report::failed() const {
  return static_cast<std::size_t>(
      std::ranges::count_if(scans, [](const ScanReport& s) { return !s.failure.empty(); }));
}

namespace {

using detail::Encoded;

constexpr std::array<formats::Format, 4> kRawFormats{formats::Format::Obj, formats::Format::Ply,
                                                     formats::Format::Vrml, formats::Format::Glb};

std::string extension(formats::Format format) {
  return std::string(formats::info(format).extensions.front());
}

// One variant to make: what it is, and how its bytes are made and decoded.
struct Task {
  Variant variant;
  std::function<Result<Encoded>()> make;
  bool keep_mesh = false; // its decoded mesh is wanted for a heat map
  std::optional<Mesh> decoded;
};

// The variant's row from its encoding: sizes, times and the decoded mesh's counts.
void fill(Variant& v, const Encoded& e, bool keep_bytes) {
  v.bytes = e.bytes.size() + e.beside_bytes;
  v.image_bytes = e.image_bytes;
  v.attribute_bytes = e.attribute_bytes;
  v.encode_ms = e.encode_ms;
  v.decode_ms = e.decode_ms;
  v.vertices = e.decoded.vertex_count();
  v.triangles = e.decoded.triangle_count();
  if (e.bits > 0) v.bits = e.bits;
  if (keep_bytes) v.encoded = e.bytes;
}

bool same_geometry(const Mesh& a, const Mesh& b) {
  return a.positions == b.positions && a.triangles == b.triangles;
}

// Step 1: the scan aligned, in the canonical frame, and its yardstick: the face mask and the evaluation
// profiles of the scan at the default slicing, against which every variant is measured.
struct Prepared {
  align::Alignment alignment;
  CanonicalScan canonical;
  metrics::FaceYardstick yardstick;
};

Result<Prepared> prepare(const Mesh& scan, std::string_view name, const CompareOptions& options) {
  const auto named = [&](Error e) { return with_source(std::move(e), name); };
  Result<align::Alignment> alignment =
      align::align_scan(scan, std::nullopt, name, {}, {.threads = options.threads});
  if (!alignment) return named(std::move(alignment).error());
  CanonicalScan canonical = canonical_scan(scan, *alignment);
  Result<slice::ProfileSet> profiles = extract_profiles(canonical);
  if (!profiles) return named(std::move(profiles).error());
  Result<metrics::FaceYardstick> made =
      metrics::FaceYardstick::make(canonical.mesh, *profiles, options.fidelity);
  if (!made) return named(std::move(made).error());
  return Prepared{*std::move(alignment), std::move(canonical), *std::move(made)};
}

// Step 2: what every variant compresses: the geometry only, positions and triangles (a `.pdef` holds no
// colours either); with `crop_face`, of the face alone, back in the scan's frame (`report` says so).
Result<Mesh> variant_geometry(const Mesh& scan, const CanonicalScan& canonical, const CompareOptions& options,
                              ScanReport& report) {
  Mesh geometry;
  if (options.crop_face) {
    Result<Mesh> face = align::crop_face(canonical.mesh, canonical.landmarks);
    if (!face) return with_source(std::move(face).error(), report.name);
    Mesh back = align::to_scan(*std::move(face), canonical.frame);
    geometry.positions = std::move(back.positions);
    geometry.triangles = std::move(back.triangles);
    report.vertices = geometry.vertex_count();
    report.triangles = geometry.triangle_count();
    report.face_only = true;
  } else {
    geometry.positions = scan.positions;
    geometry.triangles = scan.triangles;
  }
  geometry.units = scan.units;
  geometry.name = scan.name;
  return geometry;
}

// What the colour rows are measured on (step 7): the scan's colours (canonical frame) and points of its
// face, where the scan has colour.
struct ColourYardstick {
  metrics::SurfaceColour colour;
  metrics::SurfaceDistance distance;
  std::vector<Vec3> points; // on the scan, in the face mask

  static std::optional<ColourYardstick> make(const Prepared& prepared, const CompareOptions& options,
                                             std::string_view name) {
    if (!options.colour) return std::nullopt;
    const Mesh& scan = prepared.canonical.mesh;
    Result<metrics::SurfaceColour> colour = metrics::SurfaceColour::of(scan, name);
    if (!colour || colour->source() == metrics::ColourSource::None) return std::nullopt;
    std::vector<Vec3> points;
    for (const Vec3& p :
         metrics::sample_surface(scan, options.colour_spacing_mm, prepared.yardstick.mask().box()))
      if (prepared.yardstick.mask().contains(p)) points.push_back(p);
    if (points.empty()) return std::nullopt;
    return ColourYardstick{*std::move(colour), metrics::SurfaceDistance(scan), std::move(points)};
  }
};

// Steps 3 and 5: tasks made in parallel and each decoded variant measured on the yardstick.
class Measurer {
public:
  Measurer(const Prepared& prepared, const CompareOptions& options,
           const std::function<void(std::string_view)>& tick)
      : prepared_(prepared), options_(options), tick_(tick) {}

  [[nodiscard]] Mesh in_canonical(const Mesh& decoded) const {
    return align::to_canonical(decoded, prepared_.canonical.frame);
  }
  [[nodiscard]] const metrics::FaceYardstick& yardstick() const { return prepared_.yardstick; }
  void measure_colour_on(const ColourYardstick* colour) { colour_ = colour; }

  void run(std::vector<Task>& tasks) const {
    parallel_for(tasks.size(), options_.threads, [&](std::size_t i) {
      measure(tasks[i], tasks[i].make());
      tick_(tasks[i].variant.name);
    });
  }

private:
  void measure(Task& task, const Result<Encoded>& e) const {
    if (!e) {
      task.variant.failure = e.error().message;
      return;
    }
    fill(task.variant, *e, options_.keep_bytes);
    const Mesh mesh = in_canonical(e->decoded);
    const bool coloured =
        task.variant.method == Method::DracoColour || task.variant.method == Method::PdeTexture;
    if (coloured && colour_) {
      Result<metrics::SurfaceColour> colour = metrics::SurfaceColour::of(mesh, task.variant.name);
      if (!colour) {
        task.variant.failure = colour.error().message;
        return;
      }
      const metrics::SurfaceDistance on_mesh(mesh);
      task.variant.colour =
          metrics::colour_error(colour_->colour, colour_->distance, *colour, on_mesh, colour_->points);
    }
    const bool pde = task.variant.method == Method::Pde || task.variant.method == Method::PdeTexture;
    if (task.variant.method != Method::Raw && task.variant.method != Method::Gzip) {
      Result<metrics::MeshFidelity> f = yardstick().measure(mesh);
      if (!f) {
        task.variant.failure = f.error().message;
      } else if (const metrics::SelfCheck check = metrics::self_check(
                     *f, metrics::facing_away(mesh, yardstick().mask()),
                     task.variant.budget > 0 && task.variant.method == Method::Pde
                         ? with_scans_folds(options_.check, prepared_.canonical.mesh, yardstick().mask())
                         : options_.check);
                 pde && !check.passed()) {
        // What `pdeface encode` would refuse to write is a failed row, never a silent number.
        task.variant.failure = "self-check failed: " + check.summary();
        task.keep_mesh = false;
      } else {
        task.variant.fidelity = *f;
      }
    }
    if (task.keep_mesh || coloured || task.variant.method == Method::Raw ||
        task.variant.method == Method::Gzip)
      task.decoded = e->decoded;
  }

  const Prepared& prepared_;
  const CompareOptions& options_;
  const std::function<void(std::string_view)>& tick_;
  const ColourYardstick* colour_ = nullptr;
};

// Step 3's tasks: raw files (and gzipped), Draco at each quantisation, and the PDE at each ratio (what the
// `.pdef` files share made once, `PdeFiles`). The tasks refer to `geometry`, `pde` and `options`, which must
// outlive them.
std::vector<Task> encoding_tasks(const Mesh& geometry, detail::PdeFiles& pde, const CompareOptions& options) {
  std::vector<Task> tasks;
  for (bool gzipped : {false, true})
    for (formats::Format f : kRawFormats) {
      const std::string ext = extension(f) + (gzipped ? ".gz" : "");
      tasks.push_back(
          {.variant = {.method = gzipped ? Method::Gzip : Method::Raw,
                       .name = ext.substr(1),
                       .extension = ext,
                       .lossless = true},
           .make = [&, f, gzipped] { return detail::encode_raw(geometry, f, gzipped, options.gzip_level); }});
    }
  for (int bits : options.draco_bits)
    tasks.push_back({.variant = {.method = Method::Draco,
                                 .name = fmt::format("draco {} bits", bits),
                                 .extension = ".drc",
                                 .bits = bits,
                                 .lossless = false},
                     .make = [&, bits] { return detail::encode_draco(geometry, bits, options.draco_level); },
                     .keep_mesh = bits == options.heat_draco_bits});
  for (double ratio : options.ratios)
    for (bool lossless : {false, true}) {
      if ((lossless && !options.pde_lossless) || (!lossless && !options.pde_lossy)) continue;
      tasks.push_back(
          {.variant = {.method = Method::Pde,
                       .name = fmt::format("pde {:g} % {}", 100.0 * ratio, lossless ? "lossless" : "lossy"),
                       .extension = ".pdef",
                       .ratio = ratio,
                       .lossless = lossless},
           .make = [&pde, ratio, lossless] { return pde.make(ratio, lossless); },
           .keep_mesh = !lossless && std::abs(ratio - options.heat_ratio) < 1e-9});
    }
  for (const std::size_t budget : options.pde_budgets)
    tasks.push_back({.variant = {.method = Method::Pde,
                                 .name = fmt::format("pde {:g} % + residual {} B",
                                                     100.0 * options.pde_budget_ratio, budget),
                                 .extension = ".pdef",
                                 .budget = budget,
                                 .ratio = options.pde_budget_ratio,
                                 .lossless = false},
                     .make = [&, budget] { return pde.make(options.pde_budget_ratio, false, budget); }});
  return tasks;
}

// Step 4: the raw files decode to the same float32 geometry: measured once, on the first decoded, and each
// other row shares it only when its decoded geometry is the same.
void share_raw_fidelity(std::vector<Task>& tasks, const Measurer& measurer) {
  std::optional<metrics::MeshFidelity> raw_fidelity;
  const Mesh* raw_mesh = nullptr;
  for (Task& t : tasks) {
    if (!t.decoded || (t.variant.method != Method::Raw && t.variant.method != Method::Gzip)) continue;
    if (!raw_mesh || !same_geometry(*raw_mesh, *t.decoded)) {
      Result<metrics::MeshFidelity> f = measurer.yardstick().measure(measurer.in_canonical(*t.decoded));
      if (!f) {
        t.variant.failure = f.error().message;
        continue;
      }
      raw_mesh = &*t.decoded;
      raw_fidelity = *f;
    }
    t.variant.fidelity = raw_fidelity;
  }
}

// Step 5's tasks: decimate + Draco at each budget, and at each `.pdef` variant's size (the one at the size
// of the PDE variant shown as a heat map keeps its mesh). They refer to `geometry`, `options` and
// `measurer`, which must outlive them.
std::vector<Task> decimation_tasks(const std::vector<Task>& tasks, const Mesh& geometry,
                                   const CompareOptions& options, const Measurer& measurer) {
  std::vector<std::pair<std::size_t, std::string>> budgets;
  for (std::size_t budget : options.budgets)
    budgets.emplace_back(budget, fmt::format("decimate+draco {} B", budget));
  // The whole geometry's Draco bytes at each bits, where a Draco row has them (same geometry and level).
  std::map<int, std::size_t> whole_bytes;
  for (const Task& t : tasks)
    if (t.variant.method == Method::Draco && t.variant.failure.empty() && t.variant.bytes > 0 &&
        t.variant.bits > 0)
      whole_bytes.emplace(t.variant.bits, t.variant.bytes);
  std::string heat_label;
  if (options.budgets_at_pde)
    for (const Task& t : tasks)
      if (t.variant.method == Method::Pde && t.variant.bytes > 0 && t.variant.budget == 0) {
        budgets.emplace_back(t.variant.bytes, "decimate+draco = " + t.variant.name);
        if (t.keep_mesh) heat_label = budgets.back().second;
      }
  std::vector<Task> decimated;
  for (const auto& entry : budgets) {
    const std::size_t budget = entry.first;
    const std::string& label = entry.second;
    decimated.push_back({.variant = {.method = Method::DecimateDraco,
                                     .name = label,
                                     .extension = ".drc",
                                     .budget = budget,
                                     .lossless = false},
                         .make = [&, budget, whole_bytes]() -> Result<Encoded> {
                           Result<detail::Decimated> d = detail::decimate_to_budget(
                               geometry, budget, options,
                               [&](const Mesh& decoded) {
                                 return measurer.yardstick().quick_mask_mean(measurer.in_canonical(decoded));
                               },
                               whole_bytes);
                           if (!d) return std::move(d).error();
                           return std::move(d->encoded);
                         },
                         .keep_mesh = label == heat_label});
  }
  return decimated;
}

// Step 7's mesh: the geometry with the scan's colour attributes (texture coordinates and their seams, vertex
// colours) and no normals or material (Draco keeps neither: the photograph goes beside the file).
Mesh colour_geometry(const Mesh& scan, const CanonicalScan& canonical, const CompareOptions& options) {
  Mesh out = scan;
  if (options.crop_face)
    if (Result<Mesh> face = align::crop_face(canonical.mesh, canonical.landmarks); face)
      out = align::to_scan(*std::move(face), canonical.frame);
  out.normals.clear();
  out.material.reset();
  return out;
}

// The photograph at `scale` of its size: the scan's own image file at 1, else resized and encoded as JPEG.
Result<Image> photo_at(const Image& photo, double scale, int quality, std::string_view name) {
  if (scale >= 1.0) return photo;
  Result<image::Pixels> pixels = image::decode(photo, name);
  if (!pixels) return std::move(pixels).error();
  const auto side = [&](std::uint32_t n) {
    return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(n * scale)));
  };
  const image::Pixels small = image::resized(*pixels, side(pixels->width), side(pixels->height));
  return Image{image::encode_jpeg(small, {.quality = quality}), "image/jpeg", {}};
}

// Step 7's tasks (issue 20): Draco with the colour attributes beside the photograph at each scale (or the
// vertex colours alone), and the `.pdef` with a texture layer at each setting. They refer to `coloured`,
// `pde`, `scan` and `options`, which must outlive them.
std::vector<Task> colour_tasks(const Mesh& coloured, const Mesh& scan, detail::PdeFiles& pde,
                               const CompareOptions& options, std::size_t plain_draco_bytes,
                               std::string_view name) {
  std::vector<Task> tasks;
  const bool photo = scan.material && scan.material->base_color_image &&
                     !scan.material->base_color_image->bytes.empty() && !scan.texcoords.empty();
  const int bits = options.colour_draco_bits;
  const std::vector<double> scales = photo ? options.photo_scales : std::vector<double>{0.0};
  for (const double scale : scales) {
    const std::string what = !photo ? "colours"
                             : scale >= 1.0
                                 ? "photo"
                                 : fmt::format("photo {:g} % q{}", 100.0 * scale, options.photo_quality);
    tasks.push_back({.variant = {.method = Method::DracoColour,
                                 .name = fmt::format("draco {} bits + {}", bits, what),
                                 .extension = ".drc",
                                 .bits = bits,
                                 .lossless = false},
                     .make = [&, scale, photo, bits, plain_draco_bytes, name]() -> Result<Encoded> {
                       Result<Encoded> e =
                           detail::encode_draco(coloured, bits, options.draco_level, options.draco_uv_bits,
                                                options.draco_color_bits);
                       if (!e) return e;
                       if (plain_draco_bytes > 0 && e->bytes.size() > plain_draco_bytes)
                         e->attribute_bytes = e->bytes.size() - plain_draco_bytes;
                       if (photo) {
                         Result<Image> image =
                             photo_at(*scan.material->base_color_image, scale, options.photo_quality, name);
                         if (!image) return std::move(image).error();
                         e->beside_bytes = e->image_bytes = image->bytes.size();
                         e->decoded.material = Material{"photo", Vec4f::Ones(), *std::move(image)};
                       }
                       return e;
                     }});
  }
  for (const CompareOptions::Texture& t : options.textures)
    tasks.push_back({.variant = {.method = Method::PdeTexture,
                                 .name = fmt::format("pde {:g} % + texture {:g} mm q{}",
                                                     100.0 * options.texture_ratio, t.texel_mm, t.quality),
                                 .extension = ".pdef",
                                 .ratio = options.texture_ratio,
                                 .lossless = false},
                     .make = [&, t]() -> Result<Encoded> {
                       Result<Encoded> e =
                           pde.make(options.texture_ratio, false, std::nullopt,
                                    {.wanted = true, .texel_mm = t.texel_mm, .quality = t.quality});
                       if (!e) return e;
                       if (e->decoded.material && e->decoded.material->base_color_image)
                         e->image_bytes = e->decoded.material->base_color_image->bytes.size();
                       return e;
                     }});
  return tasks;
}

// Step 6: the rows in a reading order (raw, gzip, Draco, decimate + Draco, PDE), their sizes against the
// raw PLY's, and the heat maps of the variants that kept their meshes.
void add_rows(ScanReport& report, std::vector<Task>& tasks, std::vector<Task>& decimated,
              std::vector<Task>& coloured, const Measurer& measurer, const CompareOptions& options) {
  std::vector<Task*> order;
  for (Method m : {Method::Raw, Method::Gzip, Method::Draco})
    for (Task& t : tasks)
      if (t.variant.method == m) order.push_back(&t);
  for (Task& t : decimated)
    order.push_back(&t);
  for (Task& t : tasks)
    if (t.variant.method == Method::Pde) order.push_back(&t);
  for (Task& t : coloured)
    order.push_back(&t);
  for (const Task* t : order)
    if (t->variant.method == Method::Raw && t->variant.extension == ".ply")
      report.ply_bytes = t->variant.bytes;
  // The heat maps, each a few thousand distances and a picture, made in parallel, kept in the rows' order.
  std::vector<const Task*> heated;
  for (const Task* t : order)
    if (t->keep_mesh && t->decoded && t->variant.fidelity) heated.push_back(t);
  std::vector<HeatMap> heat_maps(heated.size());
  parallel_for(heated.size(), options.threads, [&](std::size_t i) {
    const Task& t = *heated[i];
    heat_maps[i] = detail::heat_map(measurer.in_canonical(*t.decoded), measurer.yardstick(),
                                    options.heat_max_mm, t.variant.name,
                                    detail::slug(report.name) + "_" + detail::slug(t.variant.name) + ".glb");
  });
  report.heat_maps.insert(report.heat_maps.end(), std::make_move_iterator(heat_maps.begin()),
                          std::make_move_iterator(heat_maps.end()));
  for (Task* t : order) {
    if (report.ply_bytes > 0)
      t->variant.ratio_to_ply = static_cast<double>(t->variant.bytes) / static_cast<double>(report.ply_bytes);
    const bool colour = t->variant.method == Method::DracoColour || t->variant.method == Method::PdeTexture;
    if (colour && t->decoded && t->variant.colour)
      if (Result<std::string> glb =
              formats::encode_mesh(measurer.in_canonical(*t->decoded), "textured.glb", {});
          glb)
        report.textured.push_back(
            {t->variant.name,
             detail::slug(report.name) + "_" + detail::slug(t->variant.name) + "_textured.glb",
             *std::move(glb)});
    report.variants.push_back(std::move(t->variant));
  }
}

} // namespace

Result<ScanReport> compare_scan(const Mesh& scan, std::string_view name, const CompareOptions& options,
                                const std::function<void(std::string_view)>& step) {
  const detail::Clock::time_point start = detail::Clock::now();
  const std::function<void(std::string_view)> tick = [&](std::string_view what) {
    if (step) step(what);
  };
  ScanReport report{.name = std::string(name),
                    .source = std::string(name),
                    .units = scan.units,
                    .vertices = scan.vertex_count(),
                    .triangles = scan.triangle_count()};
  Result<Prepared> prepared = prepare(scan, name, options);
  if (!prepared) return std::move(prepared).error();
  report.units_per_mm = 1.0 / prepared->canonical.frame.scale;
  tick("aligned");
  Result<Mesh> geometry = variant_geometry(scan, prepared->canonical, options, report);
  if (!geometry) return std::move(geometry).error();

  Measurer measurer(*prepared, options, tick);
  detail::PdeFiles pde(prepared->alignment, prepared->canonical, options.scheme, std::string(name));
  std::vector<Task> tasks = encoding_tasks(*geometry, pde, options);
  measurer.run(tasks);
  share_raw_fidelity(tasks, measurer);
  std::vector<Task> decimated = decimation_tasks(tasks, *geometry, options, measurer);
  measurer.run(decimated);
  // Colour, where the scan has it.
  const std::optional<ColourYardstick> colour = ColourYardstick::make(*prepared, options, name);
  std::vector<Task> coloured;
  Mesh with_colour;
  if (colour) {
    report.colour = colour->colour.source();
    measurer.measure_colour_on(&*colour);
    with_colour = colour_geometry(scan, prepared->canonical, options);
    std::size_t plain = 0; // the geometry's Draco bytes at the colour rows' bits
    for (const Task& t : tasks)
      if (t.variant.method == Method::Draco && t.variant.bits == options.colour_draco_bits)
        plain = t.variant.bytes;
    coloured = colour_tasks(with_colour, scan, pde, options, plain, name);
    measurer.run(coloured);
  }
  add_rows(report, tasks, decimated, coloured, measurer, options);
  report.seconds = std::chrono::duration<double>(detail::Clock::now() - start).count();
  return report;
}

Result<std::vector<std::filesystem::path>> expand_inputs(std::span<const std::filesystem::path> inputs) {
  std::vector<std::filesystem::path> out;
  for (const std::filesystem::path& in : inputs) {
    std::error_code ec;
    if (std::filesystem::is_directory(in, ec)) {
      std::vector<std::filesystem::path> files;
      for (const auto& entry : std::filesystem::directory_iterator(in, ec))
        if (entry.is_regular_file(ec) && formats::format_from_path(entry.path()))
          files.push_back(entry.path());
      if (ec) return make_error(ErrorCode::Io, ec.message(), in.string());
      std::ranges::sort(files);
      out.insert(out.end(), files.begin(), files.end());
    } else if (std::filesystem::is_regular_file(in, ec)) {
      out.push_back(in);
    } else {
      return make_error(ErrorCode::Io, "no such file or folder", in.string());
    }
  }
  return out;
}

std::string Progress::what() const {
  switch (event) {
  case ProgressEvent::Done: return fmt::format("done in {:.1f} s", seconds);
  case ProgressEvent::Failed: return "failed: " + failure;
  case ProgressEvent::Step: break;
  }
  return step;
}

Report compare_scans(const CompareRequest& request) {
  const detail::Clock::time_point start = detail::Clock::now();
  Report report{.options = request.options};
  const bool sample = request.inputs.empty();
  const std::size_t count = sample ? 1 : request.inputs.size();
  report.scans.resize(count);
  // Steps per scan: aligning, then every variant (the decimated rows at the PDE sizes included).
  const std::size_t pde_rows = request.options.ratios.size() *
                               ((request.options.pde_lossy ? 1 : 0) + (request.options.pde_lossless ? 1 : 0));
  const std::size_t steps = 1 + 2 * kRawFormats.size() + request.options.draco_bits.size() + pde_rows +
                            request.options.budgets.size() + (request.options.budgets_at_pde ? pde_rows : 0);
  Progress progress{.steps_total = steps * count, .scans_total = count};
  std::mutex mutex;
  // `event` carries the scan, the kind and what goes with it; the counts are the batch's.
  const auto report_progress = [&](Progress event, std::size_t steps_done) {
    const std::lock_guard lock(mutex);
    progress.steps_done = std::min(progress.steps_total, progress.steps_done + steps_done);
    const bool finished = event.event != ProgressEvent::Step;
    progress.scans_done += finished ? 1 : 0;
    progress.scans_failed += event.event == ProgressEvent::Failed ? 1 : 0;
    progress.scan = std::move(event.scan);
    progress.event = event.event;
    progress.step = std::move(event.step);
    progress.seconds = event.seconds;
    progress.failure = std::move(event.failure);
    if (request.progress) request.progress(progress);
  };

  const unsigned workers = std::min<unsigned>(static_cast<unsigned>(count), cores());
  CompareOptions options = request.options;
  if (options.threads == 0) options.threads = std::max(1U, cores() / workers);
  const std::vector<std::string> names =
      sample ? std::vector<std::string>{"sample face"} : scan_names(request.inputs);
  parallel_for(count, workers, [&](std::size_t i) {
    ScanReport& out = report.scans[i];
    const std::string& name = names[i];
    std::size_t done = 0;
    const auto step = [&](std::string_view what) {
      ++done;
      report_progress({.scan = name, .step = std::string(what)}, 1);
    };
    if (sample) {
      Result<ScanReport> made = compare_scan(sample_face(), name, options, step);
      if (made) {
        out = *std::move(made);
      } else {
        Error e = std::move(made).error();
        e.source = name;
        out = ScanReport{.name = name, .failure = e.to_string()};
      }
      out.source = name;
    } else {
      out = compare_file(request.inputs[i], name, options, step);
    }
    if (!out.failure.empty())
      report_progress({.scan = name, .event = ProgressEvent::Failed, .failure = out.failure}, steps - done);
    else
      report_progress({.scan = name, .event = ProgressEvent::Done, .seconds = out.seconds},
                      done < steps ? steps - done : 0);
  });
  report.seconds = std::chrono::duration<double>(detail::Clock::now() - start).count();
  return report;
}

ScanReport compare_file(const std::filesystem::path& path, std::string_view name,
                        const CompareOptions& options, const std::function<void(std::string_view)>& step) {
  const std::string source = path.string();
  const auto failed = [&](const Error& e) {
    return ScanReport{.name = std::string(name), .source = source, .failure = e.to_string()};
  };
  Result<formats::LoadedMesh> loaded = formats::read_mesh(path);
  if (!loaded) return failed(loaded.error());
  Result<ScanReport> made = compare_scan(loaded->mesh, name, options, step);
  if (!made) {
    Error e = std::move(made).error();
    e.source = source; // the file, not the name the scan was compared under
    return failed(e);
  }
  made->source = source;
  return *std::move(made);
}

std::vector<std::string> scan_names(std::span<const std::filesystem::path> inputs) {
  std::vector<std::string> names;
  std::map<std::string, int> seen;
  for (const std::filesystem::path& p : inputs) {
    names.push_back(p.filename().string());
    if (const int n = seen[names.back()]++; n > 0) names.back() += fmt::format(" ({})", n + 1);
  }
  return names;
}

} // namespace pdeface::pipeline
