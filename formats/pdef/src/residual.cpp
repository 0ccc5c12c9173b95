// The residual layer (docs/pdef-format.md, "The residual layer"): a grid of offsets, transformed, quantised
// and coded bit-plane by bit-plane; its header; a curve-only file made version 3 with a layer; reading it.

#include "pdeface/pdef/residual.hpp"

#include "bitplane.hpp"
#include "bytes.hpp"
#include "codec.hpp"
#include "entropy.hpp"
#include "residual_layer.hpp"
#include "trim.hpp"
#include "wavelet.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace pdeface::pdef {

using detail::Reader;
using detail::Writer;

namespace {

constexpr std::size_t kMaxPlanes = 40;
constexpr std::size_t kMaxStream = std::size_t{1} << 26;

Error invalid(std::string message) {
  return make_error(ErrorCode::InvalidArgument, "pdef: " + std::move(message));
}

std::size_t node_limit(std::size_t file_bytes) {
  return kFreeResidualNodes + kResidualNodesPerByte * file_bytes;
}

pde::Displacement reconstruct(detail::DecodedPlanes planes, std::size_t width, std::size_t height,
                              std::size_t levels, double step_mm) {
  pde::Displacement field{width, height, std::move(planes.coefficients)};
  for (double& v : field.values)
    v *= step_mm;
  detail::inverse_97(field.values, width, height, levels);
  return field;
}

} // namespace

Result<CodedResidual> code_residual(const pde::Displacement& field, const ResidualOptions& options) {
  const std::size_t w = field.width, h = field.height;
  if (w < 2 || h < 2 || w > kMaxResidualSide || h > kMaxResidualSide || w * h > options.max_nodes)
    return invalid(fmt::format("a residual grid of {} x {}: 2 to {} a side, at most {} nodes", w, h,
                               kMaxResidualSide, options.max_nodes));
  if (field.values.size() != w * h)
    return invalid(fmt::format("{} residual values for a {} x {} grid", field.values.size(), w, h));
  if (!std::ranges::all_of(field.values, [](double v) { return std::isfinite(v); }))
    return make_error(ErrorCode::NonFinite, "pdef: a residual offset is NaN or infinite");
  const double units = std::round(options.step_mm / detail::kStepUnit);
  if (!(units >= 1 && units < static_cast<double>(detail::kMaxStepUnits)))
    return invalid(fmt::format("a residual step of {} mm (2^-20 to 64 mm)", options.step_mm));
  CodedResidual out;
  out.width = w;
  out.height = h;
  out.levels = detail::levels_for(w, h);
  out.step_units = static_cast<std::uint32_t>(units);
  const double step = out.step_units * detail::kStepUnit;
  std::vector<double> c = field.values;
  detail::forward_97(c, w, h, out.levels);
  std::vector<std::int64_t> q(c.size());
  std::uint64_t largest = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double m = std::floor(std::abs(c[i]) / step);
    if (!(m < 0x1p39)) return invalid("a residual offset too large for its step");
    const auto magnitude = static_cast<std::int64_t>(m);
    q[i] = c[i] < 0 ? -magnitude : magnitude;
    largest = std::max(largest, static_cast<std::uint64_t>(magnitude));
  }
  out.planes = std::max<std::size_t>(1, static_cast<std::size_t>(std::bit_width(largest)));
  out.stream = detail::encode_planes(q, w, h, out.levels, out.planes);
  return out;
}

std::string code_trim(const std::vector<std::uint8_t>& trimmed, std::size_t width, std::size_t height) {
  if (width < 2 || height < 2 || trimmed.size() != (width - 1) * (height - 1))
    throw std::invalid_argument("pdef::code_trim: a trim that does not match its grid");
  return detail::encode_trim(trimmed, width - 1, height - 1);
}

std::string residual_header(const CodedResidual& layer, std::size_t stream_bytes, std::size_t trim_bytes) {
  stream_bytes = std::min(stream_bytes, layer.stream.size());
  trim_bytes = std::min(trim_bytes, layer.trim.size());
  Writer w;
  const bool trimmed = trim_bytes > 0; // a trim cut to nothing: a layer of offsets alone
  w.u8(trimmed ? detail::kLayerTrimmed : detail::kLayerOffsets);
  w.varint(layer.width);
  w.varint(layer.height);
  w.u8(static_cast<std::uint8_t>(layer.levels));
  w.varint(layer.step_units);
  w.u8(static_cast<std::uint8_t>(layer.planes));
  if (trimmed) {
    w.varint(trim_bytes);
    w.u32(detail::crc32(std::string_view(layer.trim).substr(0, trim_bytes)));
  }
  w.varint(stream_bytes);
  w.u32(detail::crc32(std::string_view(layer.stream).substr(0, stream_bytes)));
  w.u32(detail::crc32(w.str()));
  return std::move(w.str());
}

Result<std::string> with_residual(std::string_view curves_file, const CodedResidual& layer,
                                  std::size_t max_bytes, const ResidualCut& cut) {
  if (curves_file.size() < detail::kMinFileBytes || curves_file.substr(0, 4) != kMagic ||
      static_cast<std::uint8_t>(curves_file[4]) != detail::kVersion)
    return invalid("a residual layer goes after a version 2 file");
  const std::size_t fixed = curves_file.size() + residual_header(layer, 0, 0).size();
  if (max_bytes < fixed)
    return invalid(
        fmt::format("{} bytes cannot hold the curves and the layer's header ({} bytes)", max_bytes, fixed));
  // The header grows with the streams' lengths (varints): cut the trim, then the stream, until all fit.
  const auto size = [&](std::size_t trim, std::size_t stream) {
    return curves_file.size() + residual_header(layer, stream, trim).size() + trim + stream;
  };
  std::size_t trim = std::min({cut.trim_bytes, layer.trim.size(), max_bytes - fixed});
  while (trim > 0 && size(trim, 0) > max_bytes)
    --trim;
  std::size_t stream = std::min(layer.stream.size(), max_bytes - fixed - trim);
  while (stream > 0 && size(trim, stream) > max_bytes)
    --stream;
  std::string out(curves_file);
  out[4] = static_cast<char>(detail::kVersionResidual);
  const std::size_t body = out.size() - detail::kChecksumBytes;
  const std::uint32_t crc = detail::crc32(std::string_view(out).substr(0, body));
  for (int i = 0; i < 4; ++i)
    out[body + i] = static_cast<char>(crc >> (8 * i));
  out += residual_header(layer, stream, trim);
  out.append(layer.trim, 0, trim);
  out.append(layer.stream, 0, stream);
  return out;
}

pde::Displacement decode_residual(const CodedResidual& layer, std::size_t stream_bytes) {
  const std::string_view stream =
      std::string_view(layer.stream).substr(0, std::min(stream_bytes, layer.stream.size()));
  detail::DecodedPlanes planes =
      detail::decode_planes(stream, layer.width, layer.height, layer.levels, layer.planes);
  return reconstruct(std::move(planes), layer.width, layer.height, layer.levels,
                     layer.step_units * detail::kStepUnit);
}

namespace detail {

Result<Residual> read_residual(std::string_view bytes, std::size_t offset, std::string_view source) {
  Residual out;
  out.offset = offset;
  Reader r(bytes.substr(offset), offset, source);
  // A prefix that ends inside the header holds no offsets: the surface of the curves alone.
  const auto cut = [&]() { return r.error().code == ErrorCode::Truncated; };
  const std::size_t kind_at = r.offset();
  const std::uint8_t kind = r.u8("the residual layer's kind");
  if (!r.ok()) return cut() ? Result<Residual>(out) : r.error();
  if (kind != kLayerOffsets && kind != kLayerTrimmed)
    return make_error(ErrorCode::UnsupportedFormat,
                      fmt::format("residual layer kind {} (this reader knows {} and {})", kind, kLayerOffsets,
                                  kLayerTrimmed),
                      std::string(source), Location::at_byte(kind_at));
  const std::size_t size_at = r.offset();
  const std::uint64_t width = r.varint("the residual grid's width");
  const std::uint64_t height = r.varint("the residual grid's height");
  const std::size_t levels_at = r.offset();
  const std::uint8_t levels = r.u8("the residual's wavelet levels");
  const std::size_t step_at = r.offset();
  const std::uint64_t step = r.varint("the residual's step");
  const std::size_t planes_at = r.offset();
  const std::uint8_t planes = r.u8("the residual's bit-planes");
  std::size_t trim_length_at = 0, trim_crc_at = 0;
  std::uint64_t trim_length = 0;
  std::uint32_t trim_crc = 0;
  if (kind == kLayerTrimmed) {
    trim_length_at = r.offset();
    trim_length = r.varint("the residual trim's length");
    trim_crc_at = r.offset();
    trim_crc = r.u32("the residual trim's checksum");
  }
  const std::size_t length_at = r.offset();
  const std::uint64_t length = r.varint("the residual stream's length");
  const std::uint32_t stream_crc = r.u32("the residual stream's checksum");
  const std::size_t crc_at = r.offset();
  const std::uint32_t header_crc = r.u32("the residual header's checksum");
  if (!r.ok()) return cut() ? Result<Residual>(out) : r.error();
  const std::string src(source);
  auto fail = [&](ErrorCode code, std::string message, std::size_t at) {
    return make_error(code, std::move(message), src, Location::at_byte(at));
  };
  if (header_crc != crc32(bytes.substr(offset, crc_at - offset)))
    return fail(ErrorCode::ChecksumMismatch, "the residual layer's header does not match its checksum",
                crc_at);
  if (width < 2 || height < 2)
    return fail(ErrorCode::Malformed,
                fmt::format("a residual grid of {} x {} (at least 2 x 2)", width, height), size_at);
  if (width > kMaxResidualSide || height > kMaxResidualSide || width * height > node_limit(bytes.size()))
    return fail(
        ErrorCode::CountTooLarge,
        fmt::format("a residual grid of {} x {}: at most {} a side and {} nodes in a file of {} bytes", width,
                    height, kMaxResidualSide, node_limit(bytes.size()), bytes.size()),
        size_at);
  if (levels > levels_for(width, height))
    return fail(ErrorCode::Malformed,
                fmt::format("{} wavelet levels on a {} x {} grid (at most {})", levels, width, height,
                            levels_for(width, height)),
                levels_at);
  if (step == 0 || step >= kMaxStepUnits)
    return fail(ErrorCode::Malformed,
                fmt::format("a residual step of {} units (1 to {})", step, kMaxStepUnits - 1), step_at);
  if (planes == 0 || planes > kMaxPlanes)
    return fail(ErrorCode::Malformed, fmt::format("{} bit-planes (1 to {})", planes, kMaxPlanes), planes_at);
  if (trim_length > kMaxStream)
    return fail(ErrorCode::CountTooLarge,
                fmt::format("a residual trim of {} bytes (at most {})", trim_length, kMaxStream),
                trim_length_at);
  if (length > kMaxStream)
    return fail(ErrorCode::CountTooLarge,
                fmt::format("a residual stream of {} bytes (at most {})", length, kMaxStream), length_at);
  const std::size_t trim_at = r.offset();
  const std::size_t stream_at = trim_at + static_cast<std::size_t>(trim_length);
  const std::size_t after = bytes.size() - trim_at; // the trim's bytes and the stream's, as far as held
  if (after > trim_length + length)
    return fail(ErrorCode::Malformed,
                fmt::format("{} bytes after the residual stream's {}", after - trim_length - length, length),
                stream_at + static_cast<std::size_t>(length));
  const std::string_view trim = bytes.substr(trim_at, std::min<std::size_t>(after, trim_length));
  out.trim_bytes = static_cast<std::size_t>(trim_length);
  out.trim_bytes_read = trim.size();
  out.trim_complete = kind == kLayerTrimmed && trim.size() == trim_length;
  if (out.trim_complete && crc32(trim) != trim_crc)
    return fail(ErrorCode::ChecksumMismatch, "the residual trim does not match its checksum: it was damaged",
                trim_crc_at);
  const std::size_t held = after > trim_length ? after - static_cast<std::size_t>(trim_length) : 0;
  const std::string_view stream = held > 0 ? bytes.substr(stream_at) : std::string_view();
  out.complete = held == length;
  if (out.complete && crc32(stream) != stream_crc)
    return fail(ErrorCode::ChecksumMismatch,
                "the residual stream does not match its checksum: it was damaged", crc_at - 4);
  out.step_mm = static_cast<double>(step) * kStepUnit;
  out.levels = levels;
  out.planes = planes;
  out.header_bytes = trim_at - offset;
  out.stream_bytes = static_cast<std::size_t>(length);
  out.bytes_read = held;
  if (kind == kLayerTrimmed) {
    DecodedTrim decoded = decode_trim(trim, width - 1, height - 1);
    if (std::ranges::any_of(decoded.cells, [](std::uint8_t c) { return c != 0; }))
      out.trimmed = std::move(decoded.cells);
  }
  DecodedPlanes decoded = decode_planes(stream, width, height, levels, planes);
  out.planes_read = planes - decoded.lowest_plane;
  out.field = reconstruct(std::move(decoded), width, height, levels, out.step_mm);
  return out;
}

} // namespace detail
} // namespace pdeface::pdef
