#include "variants.hpp"
#include "encode_residual.hpp"
#include "encode_texture.hpp"

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pipeline/encode.hpp"

#include <fmt/format.h>
#include <meshoptimizer.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace pdeface::pipeline::detail {
namespace {

std::string file_name(formats::Format format) {
  return "variant" + std::string(formats::info(format).extensions.front());
}

Result<Mesh> decode(std::string_view bytes, formats::Format format) {
  Result<formats::LoadedMesh> loaded = formats::read_mesh(bytes, file_name(format), {.format = format});
  if (!loaded) return std::move(loaded).error();
  return std::move(loaded->mesh);
}

} // namespace

std::string gzip(std::string_view bytes, int level) {
  z_stream z{};
  if (deflateInit2(&z, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::invalid_argument(fmt::format("gzip: level {} is not 0..9", level));
  std::string out(deflateBound(&z, static_cast<uLong>(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data())); // zlib's API is not const
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::logic_error("gzip: deflateBound was too small");
  return out;
}

Result<std::string> gunzip(std::string_view bytes) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) return make_error(ErrorCode::Malformed, "gunzip: zlib failed");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  std::string out;
  int status = Z_OK;
  while (status == Z_OK) {
    const std::size_t done = out.size();
    out.resize(std::max<std::size_t>(2 * done, 1 << 16));
    z.next_out = reinterpret_cast<Bytef*>(out.data() + done);
    z.avail_out = static_cast<uInt>(out.size() - done);
    status = inflate(&z, Z_NO_FLUSH);
    out.resize(z.total_out);
  }
  inflateEnd(&z);
  if (status != Z_STREAM_END)
    return make_error(ErrorCode::Malformed, "not gzip data, or truncated", {}, Location::at_byte(z.total_in));
  return out;
}

Result<Encoded> encode_raw(const Mesh& geometry, formats::Format format, bool gzipped, int gzip_level) {
  Encoded e;
  Clock::time_point start = Clock::now();
  Result<std::string> bytes = formats::encode_mesh(geometry, file_name(format), {.format = format});
  if (!bytes) return std::move(bytes).error();
  e.bytes = gzipped ? gzip(*bytes, gzip_level) : *std::move(bytes);
  e.encode_ms = milliseconds_since(start);
  start = Clock::now();
  std::string unpacked;
  if (gzipped) {
    Result<std::string> plain = gunzip(e.bytes);
    if (!plain) return std::move(plain).error();
    unpacked = *std::move(plain);
  }
  Result<Mesh> mesh = decode(gzipped ? std::string_view(unpacked) : std::string_view(e.bytes), format);
  if (!mesh) return std::move(mesh).error();
  e.decode_ms = milliseconds_since(start);
  e.decoded = *std::move(mesh);
  return e;
}

Result<Encoded> encode_draco(const Mesh& geometry, int bits, int level, int uv_bits, int color_bits) {
  Encoded e;
  Clock::time_point start = Clock::now();
  Result<std::string> bytes = formats::encode_mesh(
      geometry, file_name(formats::Format::Draco),
      {.draco_bits = bits, .draco_level = level, .draco_uv_bits = uv_bits, .draco_color_bits = color_bits});
  if (!bytes) return std::move(bytes).error();
  e.bytes = *std::move(bytes);
  e.encode_ms = milliseconds_since(start);
  start = Clock::now();
  Result<Mesh> mesh = decode(e.bytes, formats::Format::Draco);
  if (!mesh) return std::move(mesh).error();
  e.decode_ms = milliseconds_since(start);
  e.decoded = *std::move(mesh);
  e.bits = bits;
  return e;
}

Mesh simplify(const Mesh& geometry, std::size_t target, bool lock_border) {
  std::vector<float> positions;
  positions.reserve(3 * geometry.positions.size());
  for (const Vec3& p : geometry.positions)
    positions.insert(positions.end(),
                     {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  std::vector<unsigned> indices;
  indices.reserve(3 * geometry.triangles.size());
  for (const Triangle& t : geometry.triangles)
    indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> kept(indices.size());
  // The triangle count is the target: the error bound (relative to the mesh's extent) is no limit.
  float error = 0.0F;
  kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), positions.data(),
                               geometry.positions.size(), 3 * sizeof(float), 3 * target, 1.0F,
                               lock_border ? static_cast<unsigned>(meshopt_SimplifyLockBorder) : 0U, &error));
  Mesh out;
  out.units = geometry.units;
  out.name = geometry.name;
  std::vector<std::uint32_t> remap(geometry.positions.size(), std::numeric_limits<std::uint32_t>::max());
  for (std::size_t i = 0; i + 2 < kept.size(); i += 3) {
    Triangle t{};
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t& r = remap[kept[i + k]];
      if (r == std::numeric_limits<std::uint32_t>::max()) {
        r = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(geometry.positions[kept[i + k]]);
      }
      t[k] = r;
    }
    out.triangles.push_back(t);
  }
  return out;
}

namespace {

// Draco's bytes grow as a power of the triangle count: bytes ≈ c · triangles^slope. The slope between two
// tries, kept within what Draco gives on decimated faces (about 0.55-0.85), else `fallback`.
double slope_between(double t0, double b0, double t1, double b1, double fallback) {
  if (t0 <= 0.0 || t1 <= 0.0 || b0 <= 0.0 || b1 <= 0.0 || std::abs(std::log(t1 / t0)) < 0.01) return fallback;
  return std::clamp(std::log(b1 / b0) / std::log(t1 / t0), 0.3, 1.5);
}

// The triangle count whose bytes should be `aim`, from a try of `t` triangles that gave `bytes`.
double predict(double t, double bytes, double aim, double slope) {
  return t * std::pow(aim / bytes, 1.0 / slope);
}

Result<std::string> draco_bytes(const Mesh& mesh, int bits, int level) {
  return formats::encode_mesh(mesh, file_name(formats::Format::Draco),
                              {.draco_bits = bits, .draco_level = level});
}

} // namespace

Result<Decimated> decimate_to_budget(const Mesh& geometry, std::size_t budget, const CompareOptions& options,
                                     const std::function<double(const Mesh&)>& error,
                                     const std::map<int, std::size_t>& whole_bytes) {
  if (geometry.triangles.empty())
    return make_error(ErrorCode::InvalidArgument, "a point cloud has no triangles to simplify");
  const auto lowest =
      static_cast<std::size_t>(std::ceil((1.0 - options.budget_slack) * static_cast<double>(budget)));
  // Aim high in the range (the most triangles that fit), with room for the prediction's error (~3 %).
  const double aim = static_cast<double>(lowest) + 0.75 * static_cast<double>(budget - lowest);
  const auto all = static_cast<double>(geometry.triangles.size());
  std::optional<Decimated> best;
  double best_error = std::numeric_limits<double>::infinity();
  std::size_t tried = 0, under = 0;
  int worse_in_a_row = 0;
  // Where the search at the next bits starts: the last fitting mesh encoded at those bits (one Draco
  // encode, no simplification), moved along the slope found so far.
  double slope = 0.75;
  std::optional<Mesh> last_fit;
  for (int bits : options.decimate_bits) {
    // The whole scan at these bits (the Draco rows): smaller than the budget asks, nothing to decimate; else
    // a first point of the curve bytes(triangles).
    std::optional<std::pair<double, double>> anchor;
    if (const auto whole = whole_bytes.find(bits); whole != whole_bytes.end()) {
      if (whole->second < lowest) {
        under = std::max(under, whole->second);
        continue;
      }
      anchor.emplace(all, static_cast<double>(whole->second));
    }
    std::optional<std::pair<double, double>> previous = anchor; // the last point of the curve at these bits
    if (last_fit) {
      Result<std::string> probe = draco_bytes(*last_fit, bits, options.draco_level);
      if (!probe) return std::move(probe).error();
      previous.emplace(static_cast<double>(last_fit->triangle_count()), static_cast<double>(probe->size()));
    }
    // Without a point: Draco on decimated faces takes about 1.5 bytes a triangle.
    const double guess =
        previous ? predict(previous->first, previous->second, aim, slope) : static_cast<double>(budget) / 1.5;
    // The most triangles whose bytes fit: secant steps on log(bytes) against log(triangles), kept inside
    // the bracket [fits, too big] found so far.
    std::size_t fits = 0, too_big = geometry.triangles.size() + 1;
    std::optional<std::string> fitting;
    std::optional<Mesh> fitting_mesh;
    double fitting_ms = 0.0;
    auto t = static_cast<std::size_t>(guess);
    for (int step = 0; step < 12; ++step) {
      t = std::clamp<std::size_t>(t, 4, geometry.triangles.size());
      if (t <= fits || t >= too_big) t = fits + (too_big - fits) / 2;
      if (t <= fits || t >= too_big) break; // the bracket is closed
      const Clock::time_point start = Clock::now();
      Mesh simplified = simplify(geometry, t, options.lock_border);
      Result<std::string> bytes = draco_bytes(simplified, bits, options.draco_level);
      ++tried;
      if (!bytes) return std::move(bytes).error();
      const double ms = milliseconds_since(start); // simplifying and encoding
      const auto size = static_cast<double>(bytes->size());
      const auto made = static_cast<double>(t);
      if (previous) slope = slope_between(previous->first, previous->second, made, size, slope);
      previous.emplace(made, size);
      if (bytes->size() <= budget) {
        fits = t;
        fitting = *std::move(bytes);
        fitting_mesh = std::move(simplified);
        fitting_ms = ms;
        if (size >= static_cast<double>(lowest)) break;
      } else {
        too_big = t;
      }
      t = static_cast<std::size_t>(predict(made, size, aim, slope));
    }
    if (!fitting) continue;
    if (fitting->size() < lowest) { // the whole scan at these bits is smaller than the budget asks
      under = std::max(under, fitting->size());
      continue;
    }
    last_fit = std::move(fitting_mesh);
    // What a reader of the file gets, decoded once, for the error and the row.
    Encoded e;
    e.bytes = *std::move(fitting);
    e.encode_ms = fitting_ms;
    e.bits = bits;
    const Clock::time_point start = Clock::now();
    Result<Mesh> decoded = decode(e.bytes, formats::Format::Draco);
    if (!decoded) return std::move(decoded).error();
    e.decode_ms = milliseconds_since(start);
    e.decoded = *std::move(decoded);
    const double err = error(e.decoded);
    if (err < best_error) {
      best_error = err;
      best = Decimated{std::move(e), bits, 0};
      worse_in_a_row = 0;
    } else if (++worse_in_a_row == 2) {
      break; // the error grows with the bits from here on
    }
  }
  if (!best && under > 0)
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("nothing to decimate: the whole scan takes at most {} bytes with {} bits, more "
                    "than {:g} % under the budget (see the Draco rows)",
                    under, fmt::join(options.decimate_bits, ", "), 100.0 * options.budget_slack));
  if (!best)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("no decimated mesh fits in {} bytes with {} bits", budget,
                                  fmt::join(options.decimate_bits, ", ")));
  best->tried = tried;
  return *std::move(best);
}

struct PdeFiles::AtRatio {
  std::once_flag sliced_once;
  std::optional<Result<SlicedScan>> sliced;
  double slice_ms = 0.0;
  std::once_flag lossy_once; // the lossy file under the files with a residual layer
  std::optional<Result<EncodeOutcome>> lossy;
  double lossy_ms = 0.0;
  std::mutex grids_mutex;
  ResidualGrids grids;
  // The texels of texture layers, by texel size (every quality of one size shares them), with their times.
  struct SampledTexels {
    std::once_flag once;
    std::optional<Result<Texels>> texels;
    double ms = 0.0;
  };
  std::mutex texels_mutex;
  std::map<double, std::unique_ptr<SampledTexels>> texels;
};

PdeFiles::PdeFiles(const align::Alignment& alignment, const CanonicalScan& canonical, pde::Scheme scheme,
                   std::string source)
    : alignment_(alignment), canonical_(canonical), scheme_(scheme), source_(std::move(source)) {}

PdeFiles::~PdeFiles() = default;

EncodeRequest PdeFiles::request(double ratio, bool lossless, std::optional<std::size_t> size,
                                const TextureRequest& texture) const {
  EncodeRequest request; // what `pdeface encode` asks with its defaults, unchecked (measured by the caller)
  request.residual.size_bytes = size;
  request.texture = texture;
  request.profiles.ratio = ratio;
  request.encoding.lossless = lossless;
  request.source = source_;
  request.pde.scheme = scheme_;
  request.check.reset();
  return request;
}

PdeFiles::AtRatio& PdeFiles::at(double ratio) {
  const std::lock_guard lock(mutex_);
  std::unique_ptr<AtRatio>& r = ratios_[ratio];
  if (!r) r = std::make_unique<AtRatio>();
  return *r;
}

Result<Encoded> PdeFiles::make(double ratio, bool lossless, std::optional<std::size_t> size,
                               const TextureRequest& texture) {
  if (size && texture.wanted)
    throw std::invalid_argument("PdeFiles::make: a residual layer or a texture layer");
  const EncodeRequest asked = request(ratio, lossless, size, texture);
  AtRatio& r = at(ratio);
  std::call_once(r.sliced_once, [&] {
    const Clock::time_point start = Clock::now();
    r.sliced = slice_and_solve(canonical_, asked);
    r.slice_ms = milliseconds_since(start);
  });
  if (!*r.sliced) return r.sliced->error();
  Encoded e;
  std::string bytes;
  const auto lossy_curves = [&]() -> const Result<EncodeOutcome>& { // the curves alone, lossy, made once
    std::call_once(r.lossy_once, [&] {
      const Clock::time_point start = Clock::now();
      r.lossy = encode_sliced(canonical_, alignment_, **r.sliced, request(ratio, false, std::nullopt));
      r.lossy_ms = milliseconds_since(start);
    });
    return *r.lossy;
  };
  if (texture.wanted && !lossless) {
    // The lossy curves with a texture layer: what encode_sliced writes with `texture`, from the curves and
    // texels shared by every texture of the ratio (the layer is the file's last section: `with_texture`).
    if (!lossy_curves()) return lossy_curves().error();
    AtRatio::SampledTexels* sampled = nullptr;
    {
      const std::lock_guard lock(r.texels_mutex);
      std::unique_ptr<AtRatio::SampledTexels>& slot = r.texels[texture.texel_mm];
      if (!slot) slot = std::make_unique<AtRatio::SampledTexels>();
      sampled = slot.get();
    }
    std::call_once(sampled->once, [&] {
      const Clock::time_point start = Clock::now();
      sampled->texels = sample_texels(canonical_.mesh, (*r.sliced)->surface, texture.texel_mm, source_);
      sampled->ms = milliseconds_since(start);
    });
    if (!*sampled->texels) return with_source(sampled->texels->error(), source_);
    const Clock::time_point start = Clock::now();
    Result<std::string> file = pdef::with_texture(lossy_curves()->encoded.bytes,
                                                  encode_texels(**sampled->texels, texture.quality).texture);
    if (!file) return std::move(file).error();
    e.encode_ms = r.slice_ms + r.lossy_ms + sampled->ms + milliseconds_since(start);
    bytes = *std::move(file);
  } else if (!size) {
    const Clock::time_point start = Clock::now();
    Result<EncodeOutcome> made = encode_sliced(canonical_, alignment_, **r.sliced, asked);
    if (!made) return std::move(made).error();
    e.encode_ms = r.slice_ms + milliseconds_since(start);
    bytes = std::move(made->encoded.bytes);
  } else {
    // The curves alone, then the layer on them: what encode_sliced does with `size`, in two steps.
    if (!lossy_curves()) return lossy_curves().error();
    EncodeOutcome outcome = *lossy_curves();
    const std::lock_guard lock(r.grids_mutex);
    std::map<double, double> before; // the grids made already (by spacing as made): their times
    for (const auto& entry : r.grids.by_spacing)
      before.emplace(entry.second.spacing_mm, entry.second.made_ms);
    const Clock::time_point start = Clock::now();
    Result<ResidualOutcome> layer = add_residual(canonical_, outcome, asked.residual, source_, &r.grids);
    if (!layer) return with_source(std::move(layer).error(), source_);
    e.encode_ms = r.slice_ms + r.lossy_ms + milliseconds_since(start);
    if (const auto reused = before.find(layer->spacing_mm); reused != before.end())
      e.encode_ms += reused->second; // the grid this file's layer was cut from, made for another size
    bytes = std::move(outcome.encoded.bytes);
  }
  e.bytes = std::move(bytes);
  // What a reader of the file does: parse its bytes, solve the surface and mesh it in the scan's frame.
  const Clock::time_point start = Clock::now();
  Result<pdef::Face> face = pdef::decode(e.bytes, source_);
  if (!face) return std::move(face).error();
  Result<Mesh> mesh = pdef::to_mesh(*face, std::nullopt, source_);
  if (!mesh) return std::move(mesh).error();
  e.decode_ms = milliseconds_since(start);
  e.decoded = *std::move(mesh);
  return e;
}

} // namespace pdeface::pipeline::detail
