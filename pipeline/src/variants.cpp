#include "variants.hpp"

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

Result<Encoded> encode_draco(const Mesh& geometry, int bits, int level) {
  Encoded e;
  Clock::time_point start = Clock::now();
  Result<std::string> bytes = formats::encode_mesh(geometry, file_name(formats::Format::Draco),
                                                   {.draco_bits = bits, .draco_level = level});
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

Result<Decimated> decimate_to_budget(const Mesh& geometry, std::size_t budget, const CompareOptions& options,
                                     const std::function<double(const Mesh&)>& error) {
  if (geometry.triangles.empty())
    return make_error(ErrorCode::InvalidArgument, "a point cloud has no triangles to simplify");
  const auto lowest =
      static_cast<std::size_t>(std::ceil((1.0 - options.budget_slack) * static_cast<double>(budget)));
  const double aim = 0.5 * (static_cast<double>(lowest) + static_cast<double>(budget));
  std::optional<Decimated> best;
  double best_error = std::numeric_limits<double>::infinity();
  std::size_t tried = 0, under = 0;
  int worse_in_a_row = 0;
  // Bytes per triangle of Draco on decimated faces: about 1.5 (a start; the search corrects it).
  double triangles_guess = static_cast<double>(budget) / 1.5;
  for (int bits : options.decimate_bits) {
    // The most triangles whose bytes fit: secant steps on log(bytes) against log(triangles), kept inside
    // the bracket [fits, too big] found so far.
    std::size_t fits = 0, too_big = geometry.triangles.size() + 1;
    std::optional<Encoded> fitting;
    auto t = static_cast<std::size_t>(triangles_guess);
    for (int step = 0; step < 12; ++step) {
      t = std::clamp<std::size_t>(t, 4, geometry.triangles.size());
      if (t <= fits || t >= too_big) t = fits + (too_big - fits) / 2;
      if (t <= fits || t >= too_big) break; // the bracket is closed
      Clock::time_point start = Clock::now();
      const Mesh simplified = simplify(geometry, t, options.lock_border);
      Result<Encoded> e = encode_draco(simplified, bits, options.draco_level);
      ++tried;
      if (!e) return std::move(e).error();
      e->encode_ms = milliseconds_since(start) - e->decode_ms; // simplifying and encoding
      const double bytes = static_cast<double>(e->bytes.size());
      if (e->bytes.size() <= budget) {
        fits = t;
        fitting = *std::move(e);
        if (bytes >= static_cast<double>(lowest)) break;
      } else {
        too_big = t;
      }
      t = static_cast<std::size_t>(static_cast<double>(t) * aim / bytes);
    }
    if (!fitting) continue;
    if (fitting->bytes.size() < lowest) { // the whole scan at these bits is smaller than the budget asks
      under = std::max(under, fitting->bytes.size());
      continue;
    }
    triangles_guess = static_cast<double>(fits) * 0.95; // more bits, fewer triangles
    const double e = error(fitting->decoded);
    if (e < best_error) {
      best_error = e;
      best = Decimated{*std::move(fitting), bits, 0};
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

Result<Encoded> encode_pde(const Mesh& scan, const align::Alignment& alignment, double ratio, bool lossless,
                           pde::Scheme scheme, std::string_view source, std::optional<std::size_t> size) {
  EncodeRequest request;
  request.residual.size_bytes = size;
  request.profiles.ratio = ratio;
  request.encoding.lossless = lossless;
  request.source = source;
  request.pde.scheme = scheme;
  request.check.reset(); // measured and checked by the caller, on the scan's yardstick
  Encoded e;
  Clock::time_point start = Clock::now();
  Result<EncodeOutcome> made = encode_aligned(scan, alignment, request);
  if (!made) return std::move(made).error();
  e.bytes = std::move(made->encoded.bytes);
  e.encode_ms = milliseconds_since(start);
  // What a reader of the file does: parse its bytes, solve the surface and mesh it in the scan's frame.
  start = Clock::now();
  Result<pdef::Face> face = pdef::decode(e.bytes, source);
  if (!face) return std::move(face).error();
  Result<Mesh> mesh = pdef::to_mesh(*face, std::nullopt, source);
  if (!mesh) return std::move(mesh).error();
  e.decode_ms = milliseconds_since(start);
  e.decoded = *std::move(mesh);
  return e;
}

} // namespace pdeface::pipeline::detail
