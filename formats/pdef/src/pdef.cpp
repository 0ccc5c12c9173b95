// The `.pdef` container and its sections (docs/pdef-format.md): writing a face, reading it back.

#include "pdeface/pdef/pdef.hpp"

#include "pdeface/core/image.hpp"

#include "bytes.hpp"
#include "codec.hpp"
#include "entropy.hpp"
#include "frame.hpp"
#include "heights.hpp"
#include "lossy.hpp"
#include "residual_layer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace pdeface::pdef {

using detail::Grid;
using detail::Quantised;
using detail::Reader;
using detail::Writer;

std::array<double, 2> Face::extent(std::size_t j) const {
  const pde::Curve& c = curves.samples.at(j);
  return {c(0, 1), c(c.rows() - 1, 1)};
}

std::uint32_t checksum(std::string_view bytes) { return detail::crc32(bytes); }

namespace {

// The units as the format numbers them (independent of the enum's order).
constexpr std::array<Units, 5> kUnitCodes{Units::Unknown, Units::Millimetres, Units::Centimetres,
                                          Units::Metres, Units::Inches};
std::uint8_t unit_code(Units u) {
  return static_cast<std::uint8_t>(std::ranges::find(kUnitCodes, u) - kUnitCodes.begin());
}

constexpr std::array<pde::Scheme, 3> kSchemeCodes{pde::Scheme::Spline, pde::Scheme::Paper,
                                                  pde::Scheme::Patch4};
std::uint8_t scheme_code(pde::Scheme s) {
  return static_cast<std::uint8_t>(std::ranges::find(kSchemeCodes, s) - kSchemeCodes.begin());
}
constexpr std::uint8_t kPhysicalSpacing = 0x04;
constexpr std::uint8_t kRemainder = 0x08;

std::size_t sample_limit(std::size_t file_bytes) { return kFreeSamples + kSamplesPerByte * file_bytes; }

bool printable(std::string_view s) {
  return std::ranges::none_of(s, [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 || u == 0x7f;
  });
}

Error invalid(std::string message) {
  return make_error(ErrorCode::InvalidArgument, "pdef: " + std::move(message));
}

// ---------------------------------------------------------------------------------------------------------
// Checks on a face before it is encoded.

std::optional<Error> check_face(const Face& face, const EncodeOptions& options) {
  const std::size_t curves = face.curve_count(), samples = face.sample_count();
  if (curves < kMinCurves || curves > kMaxCurves)
    return invalid(fmt::format("{} curves: a document holds {} to {}", curves, kMinCurves, kMaxCurves));
  if (samples < 2 || samples > kMaxSamples)
    return invalid(fmt::format("{} samples per curve: a document holds 2 to {}", samples, kMaxSamples));
  if (face.planes.size() != curves || face.filled.size() != curves)
    throw std::invalid_argument("pdef::encode: planes and filled need one entry per curve");
  for (std::size_t j = 0; j < curves; ++j) {
    if (static_cast<std::size_t>(face.curves.samples[j].rows()) != samples ||
        face.filled[j].size() != samples)
      throw std::invalid_argument(fmt::format("pdef::encode: curve {} does not have {} samples", j, samples));
    if (!face.curves.samples[j].allFinite() || !std::isfinite(face.planes[j]))
      return make_error(ErrorCode::NonFinite, fmt::format("pdef: curve {} has a NaN or infinite value", j));
    if (j > 0 && !(face.planes[j] > face.planes[j - 1]))
      return invalid(fmt::format("the curves' planes must ascend: x = {} (curve {}) after {}", face.planes[j],
                                 j, face.planes[j - 1]));
  }
  const pde::Options& p = face.pde;
  if (!p.smoothing || !(*p.smoothing > 0) || !std::isfinite(*p.smoothing))
    return invalid("the smoothing parameter a must be set, positive and finite");
  if (!p.modes || *p.modes > samples - 1)
    return invalid(fmt::format("the modes N must be set and at most K - 1 = {}", samples - 1));
  if (p.scheme != pde::Scheme::Spline && curves % 3 != 1)
    return invalid(
        fmt::format("the {} scheme needs 3p + 1 curves, not {}", pde::to_string(p.scheme), curves));
  const Frame& f = face.frame;
  if (!f.rotation.allFinite() || !f.translation.allFinite() || !std::isfinite(f.scale))
    return make_error(ErrorCode::NonFinite, "pdef: the frame has a NaN or infinite value");
  if (!(f.scale > 0)) return invalid("the frame's scale must be positive");
  if (face.landmarks.size() > kMaxLandmarks)
    return invalid(fmt::format("{} landmarks: at most {}", face.landmarks.size(), kMaxLandmarks));
  for (const Landmark& l : face.landmarks) {
    if (l.name.empty() || l.name.size() > kMaxLandmarkName || !printable(l.name))
      return invalid(
          fmt::format("landmark name '{}': 1 to {} printable characters", l.name, kMaxLandmarkName));
    if (!l.position.allFinite())
      return make_error(ErrorCode::NonFinite, fmt::format("pdef: landmark {} is not finite", l.name));
  }
  if (face.name.size() > kMaxName || !printable(face.name))
    return invalid(fmt::format("the name: at most {} printable characters", kMaxName));
  if (face.texture) {
    const Result<ImageInfo> info = inspect_image(face.texture->bytes, "the texture");
    if (!info || info->mime_type != "image/jpeg")
      return invalid("the texture must be one JPEG image" +
                     (info ? std::string() : ": " + info.error().message));
  }
  if (!options.lossless && (!(options.max_error_mm > 0) || !std::isfinite(options.max_error_mm)))
    return invalid(fmt::format("the maximum error must be positive, not {}", options.max_error_mm));
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------------------
// Writing.

std::string face_section(const Face& face, bool lossless, const Grid& grid, bool frame64) {
  Writer w;
  w.u8(unit_code(face.frame.scan_units));
  detail::write_frame(w, face.frame, frame64);
  const pde::Options& p = face.pde;
  w.u8(static_cast<std::uint8_t>(scheme_code(p.scheme) |
                                 (p.spacing == pde::Spacing::Physical ? kPhysicalSpacing : 0) |
                                 (p.remainder ? kRemainder : 0)));
  w.f64(*p.smoothing);
  w.varint(face.curve_count());
  w.varint(face.sample_count());
  w.varint(*p.modes);
  if (!lossless) {
    w.varint(grid.step);
    w.varint(grid.plane_step);
  }
  return std::move(w.str());
}

// The filled samples as runs, sample by sample across the curves (sample 0 of every curve, then sample 1,
// ...): holes (the eyes) are wide across the curves and short along them.
void write_runs(Writer& w, const Face& face) {
  std::vector<std::uint64_t> runs{0};
  bool current = false;
  for (std::size_t k = 0; k < face.sample_count(); ++k)
    for (const std::vector<bool>& curve : face.filled) {
      if (curve[k] != current) {
        runs.push_back(0);
        current = curve[k];
      }
      ++runs.back();
    }
  w.varint(runs.size());
  for (const std::uint64_t r : runs)
    w.varint(r);
}

std::string curves_section(const Face& face, const Quantised* q) {
  Writer w;
  write_runs(w, face);
  const std::size_t curves = face.curve_count(), samples = face.sample_count();
  if (q == nullptr) { // lossless: every double as it is, compressed
    for (const double x : face.planes)
      w.f64(x);
    // x (as its bits XOR its plane's: mostly zeros), then y, then z, each byte-shuffled, in one zstd frame
    std::string values;
    for (int d = 0; d < 3; ++d) {
      Writer coordinate;
      for (std::size_t j = 0; j < curves; ++j)
        for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(samples); ++k) {
          const double v = face.curves.samples[j](k, d);
          d == 0
              ? coordinate.u64(std::bit_cast<std::uint64_t>(v) ^ std::bit_cast<std::uint64_t>(face.planes[j]))
              : coordinate.f64(v);
        }
      values += detail::shuffle(coordinate.str(), 8);
    }
    w.bytes(detail::zstd_compress(values, 19));
    return std::move(w.str());
  }
  for (std::size_t j = 0; j < curves; ++j) // the planes: x_0, then first and second differences
    w.svarint(j == 0   ? q->planes[0]
              : j == 1 ? q->planes[1] - q->planes[0]
                       : q->planes[j] - 2 * q->planes[j - 1] + q->planes[j - 2]);
  if (q->heights.used()) {
    w.u8(detail::kHeightsKind);
    w.bytes(detail::write_heights(q->heights, q->y, curves, samples));
  } else {
    w.bytes(detail::write_predicted(q->y, q->planes, samples, 0));
  }
  w.bytes(detail::write_predicted(q->z, q->planes, samples, 1));

  return std::move(w.str());
}

std::string landmarks_section(const Face& face, const Grid* grid) {
  Writer w;
  w.varint(face.landmarks.size());
  for (const Landmark& l : face.landmarks) {
    w.varint(l.name.size());
    w.bytes(l.name);
    for (int i = 0; i < 3; ++i)
      grid ? w.svarint(std::llround(l.position(i) / grid->step_mm())) : w.f64(l.position(i));
  }
  return std::move(w.str());
}

void append_section(Writer& file, std::uint8_t tag, std::string_view content) {
  file.u8(tag);
  file.varint(content.size());
  file.bytes(content);
}

std::string write_file(const Face& face, const Quantised* q, const Grid& grid, bool frame64) {
  const bool lossless = q == nullptr;
  Writer file;
  file.bytes(kMagic);
  file.u8(detail::kVersion);
  file.u8(lossless ? detail::kFlagLossless : 0);
  file.u32(0); // the length, filled in below
  append_section(file, detail::kTagFace, face_section(face, lossless, grid, frame64));
  append_section(file, detail::kTagCurves, curves_section(face, q));
  if (!face.landmarks.empty())
    append_section(file, detail::kTagLandmarks, landmarks_section(face, lossless ? nullptr : &grid));
  if (!face.name.empty()) append_section(file, detail::kTagName, face.name);
  if (face.texture) // an ancillary section, so that a reader of shape alone skips it
    append_section(file, detail::kTagTexture,
                   std::string(1, static_cast<char>(detail::kTextureJpeg)) + face.texture->bytes);
  std::string& bytes = file.str();
  const auto length = static_cast<std::uint32_t>(bytes.size() + detail::kChecksumBytes);
  for (int i = 0; i < 4; ++i)
    bytes[6 + i] = static_cast<char>(length >> (8 * i));
  file.u32(detail::crc32(bytes));
  return std::move(bytes);
}

// ---------------------------------------------------------------------------------------------------------
// Reading.

struct Container {
  bool lossless = false;
  bool residual = false; // version 3: a residual layer follows the checksum
  struct Part {
    std::uint8_t tag;
    std::size_t offset; // of the tag
    std::size_t content;
    std::size_t size; // of the content
  };
  std::vector<Part> parts;
  std::size_t length = 0;
};

Result<Container> read_container(std::string_view bytes, std::string_view source) {
  const std::string src(source);
  if (bytes.empty()) return make_error(ErrorCode::Empty, "the file is empty", src, Location::at_byte(0));
  const std::size_t magic = std::min(bytes.size(), kMagic.size());
  if (bytes.substr(0, magic) != kMagic.substr(0, magic))
    return make_error(ErrorCode::BadMagic, "not a .pdef file (it does not start with \"PDEF\")", src,
                      Location::at_byte(0));
  const std::uint8_t version = bytes.size() > 4 ? static_cast<std::uint8_t>(bytes[4]) : detail::kVersion;
  if (version != detail::kVersion && version != detail::kVersionResidual)
    return make_error(ErrorCode::UnsupportedVersion,
                      fmt::format("version {} (this reader knows versions {} and {})", version,
                                  detail::kVersion, detail::kVersionResidual),
                      src, Location::at_byte(4));
  const std::uint8_t flags = bytes.size() > 5 ? static_cast<std::uint8_t>(bytes[5]) : 0;
  if ((flags & ~detail::kKnownFlags) != 0)
    return make_error(ErrorCode::UnsupportedFormat,
                      fmt::format("unknown required flags 0x{:02x} (a newer writer's feature)",
                                  flags & ~detail::kKnownFlags),
                      src, Location::at_byte(5));
  if (bytes.size() < detail::kHeaderBytes)
    return make_error(ErrorCode::Truncated,
                      fmt::format("the file ends after {} bytes, inside its {}-byte header", bytes.size(),
                                  detail::kHeaderBytes),
                      src, Location::at_byte(bytes.size()));
  Reader header(bytes.substr(6, 4), 6, source);
  const std::uint32_t length = header.u32("the file's length");
  if (length < detail::kMinFileBytes)
    return make_error(
        ErrorCode::Malformed,
        fmt::format("a length of {} bytes is below the smallest file ({})", length, detail::kMinFileBytes),
        src, Location::at_byte(6));
  if (length > kMaxFileBytes)
    return make_error(
        ErrorCode::CountTooLarge,
        fmt::format("a length of {} bytes is above the largest file ({})", length, kMaxFileBytes), src,
        Location::at_byte(6));
  if (bytes.size() < length)
    return make_error(
        ErrorCode::Truncated,
        fmt::format("the file ends after {} of the {} bytes its header states", bytes.size(), length), src,
        Location::at_byte(bytes.size()));
  if (bytes.size() > length && version != detail::kVersionResidual) // version 3: the layer follows
    return make_error(ErrorCode::Malformed,
                      fmt::format("{} bytes after the end of the file its header states ({} bytes)",
                                  bytes.size() - length, length),
                      src, Location::at_byte(length));
  const std::size_t body_end = length - detail::kChecksumBytes;
  Reader tail(bytes.substr(body_end), body_end, source);
  const std::uint32_t stored = tail.u32("the checksum");
  if (stored != detail::crc32(bytes.substr(0, body_end)))
    return make_error(
        ErrorCode::ChecksumMismatch,
        fmt::format("the checksum 0x{:08x} does not match the data (0x{:08x}): the file was damaged", stored,
                    detail::crc32(bytes.substr(0, body_end))),
        src, Location::at_byte(body_end));

  Container out;
  out.residual = version == detail::kVersionResidual;
  out.lossless = (flags & detail::kFlagLossless) != 0;
  out.length = length;
  Reader r(bytes.substr(detail::kHeaderBytes, body_end - detail::kHeaderBytes), detail::kHeaderBytes, source);
  std::uint8_t last_known = 0;
  while (r.ok() && !r.at_end()) {
    const std::size_t at = r.offset();
    const std::uint8_t tag = r.u8("a section's tag");
    const std::uint64_t size = r.varint("a section's length");
    if (!r.ok()) break;
    if (size > r.remaining())
      return make_error(ErrorCode::Truncated,
                        fmt::format("section 0x{:02x} claims {} bytes, {} remain before the checksum", tag,
                                    size, r.remaining()),
                        src, Location::at_byte(at));
    if (tag < detail::kFirstAncillaryTag) {
      if (tag < detail::kTagFace || tag > detail::kTagName)
        return make_error(ErrorCode::UnsupportedFormat,
                          fmt::format("unknown required section 0x{:02x} (a newer writer's feature)", tag),
                          src, Location::at_byte(at));
      if (tag <= last_known)
        return make_error(ErrorCode::Malformed,
                          fmt::format("section 0x{:02x} out of order (the known sections come once each, in "
                                      "ascending order)",
                                      tag),
                          src, Location::at_byte(at));
      if (tag > detail::kTagFace && last_known == 0)
        return make_error(ErrorCode::Malformed, "the face section must come first", src,
                          Location::at_byte(at));
      if (tag > detail::kTagCurves && last_known < detail::kTagCurves)
        return make_error(ErrorCode::Malformed, "the curves section is missing", src, Location::at_byte(at));
      last_known = tag;
    }
    out.parts.push_back({tag, at, r.offset(), static_cast<std::size_t>(size)});
    r.take(static_cast<std::size_t>(size), "a section");
  }
  if (!r.ok()) return r.error();
  if (last_known < detail::kTagCurves)
    return make_error(ErrorCode::Malformed,
                      last_known == 0 ? "the face section is missing" : "the curves section is missing", src,
                      Location::at_byte(body_end));
  return out;
}

struct Meta {
  std::size_t curves = 0;
  std::size_t samples = 0;
  Grid grid;
  bool frame64 = true;
};

Meta read_face_section(Reader& r, Face& face, bool lossless, std::size_t file_bytes) {
  Meta m;
  std::size_t at = r.offset();
  const std::uint8_t units = r.u8("the units");
  if (r.ok() && units >= kUnitCodes.size())
    r.fail(ErrorCode::Malformed, fmt::format("unknown units code {}", units), at);
  if (r.ok()) face.frame.scan_units = kUnitCodes[units];
  const Frame frame = detail::read_frame(r, m.frame64);
  if (!r.ok()) return m;
  face.frame.rotation = frame.rotation;
  face.frame.translation = frame.translation;
  face.frame.scale = frame.scale;
  at = r.offset();
  const std::uint8_t surface = r.u8("the surface's scheme");
  if (r.ok() && ((surface & 0x03) >= kSchemeCodes.size() || (surface & 0xf0) != 0))
    r.fail(ErrorCode::Malformed, fmt::format("unknown scheme byte 0x{:02x}", surface), at);
  face.pde.scheme = kSchemeCodes[std::min<std::size_t>(surface & 0x03, kSchemeCodes.size() - 1)];
  face.pde.spacing = (surface & kPhysicalSpacing) != 0 ? pde::Spacing::Physical : pde::Spacing::Uniform;
  face.pde.remainder = (surface & kRemainder) != 0;
  at = r.offset();
  const double a = r.f64("the smoothing parameter");
  if (r.ok() && !std::isfinite(a)) r.fail(ErrorCode::NonFinite, "the smoothing parameter is not finite", at);
  if (r.ok() && !(a > 0))
    r.fail(ErrorCode::Malformed, fmt::format("the smoothing parameter {} is not positive", a), at);
  face.pde.smoothing = a;
  const std::size_t count_at = r.offset();
  m.curves = r.varint("the curve count");
  m.samples = r.varint("the samples per curve");
  const std::size_t modes_at = r.offset();
  const std::uint64_t modes = r.varint("the modes");
  if (!r.ok()) return m;
  if (m.curves < kMinCurves || m.samples < 2)
    r.fail(ErrorCode::Malformed,
           fmt::format("{} curves of {} samples (at least {} of 2)", m.curves, m.samples, kMinCurves),
           count_at);
  else if (m.curves > kMaxCurves || m.samples > kMaxSamples ||
           m.curves * m.samples > sample_limit(file_bytes))
    r.fail(
        ErrorCode::CountTooLarge,
        fmt::format("{} curves of {} samples: more than the limits ({} curves, {} samples, {} samples in a "
                    "file of {} bytes)",
                    m.curves, m.samples, kMaxCurves, kMaxSamples, sample_limit(file_bytes), file_bytes),
        count_at);
  else if (modes > m.samples - 1)
    r.fail(ErrorCode::Malformed, fmt::format("{} modes for {} samples (at most K - 1)", modes, m.samples),
           modes_at);
  else if (face.pde.scheme != pde::Scheme::Spline && m.curves % 3 != 1)
    r.fail(
        ErrorCode::Malformed,
        fmt::format("the {} scheme needs 3p + 1 curves, not {}", pde::to_string(face.pde.scheme), m.curves),
        count_at);
  face.pde.modes = static_cast<std::size_t>(modes);
  if (!lossless) {
    at = r.offset();
    m.grid.step = static_cast<std::uint32_t>(r.varint("the step"));
    m.grid.plane_step = static_cast<std::uint32_t>(r.varint("the planes' step"));
    if (r.ok() && (m.grid.step == 0 || m.grid.plane_step == 0 || m.grid.step >= detail::kMaxStepUnits ||
                   m.grid.plane_step >= detail::kMaxStepUnits))
      r.fail(ErrorCode::Malformed,
             fmt::format("steps of {} and {} units (1 to {})", m.grid.step, m.grid.plane_step,
                         detail::kMaxStepUnits - 1),
             at);
  }
  if (r.ok() && !r.at_end())
    r.fail_here(ErrorCode::Malformed, "bytes left over at the end of the face section");
  return m;
}

void read_runs(Reader& r, Face& face, const Meta& m) {
  const std::size_t at = r.offset();
  const std::uint64_t count = r.varint("the filled runs' count");
  if (!r.ok()) return;
  const std::uint64_t total = m.curves * m.samples;
  if (count == 0 || count > total + 1 || count > r.remaining()) {
    r.fail(
        ErrorCode::CountTooLarge,
        fmt::format("{} runs of filled samples: 1 to {} (and at most one per byte left)", count, total + 1),
        at);
    return;
  }
  face.filled.assign(m.curves, std::vector<bool>(m.samples, false));
  std::uint64_t done = 0;
  for (std::uint64_t i = 0; i < count && r.ok(); ++i) {
    const std::size_t run_at = r.offset();
    const std::uint64_t run = r.varint("a run of filled samples");
    if (!r.ok()) return;
    if ((i > 0 && run == 0) || run > total - done) {
      r.fail(ErrorCode::Malformed,
             fmt::format("a run of {} samples ({} of {} placed; runs after the first are at least 1)", run,
                         done, total),
             run_at);
      return;
    }
    if (i % 2 == 1)
      for (std::uint64_t s = done; s < done + run; ++s)
        face.filled[s % m.curves][s / m.curves] = true;
    done += run;
  }
  if (done != total)
    r.fail(ErrorCode::Malformed,
           fmt::format("the runs of filled samples cover {} of {} samples", done, total), at);
}

void read_lossless_curves(Reader& r, Face& face, const Meta& m) {
  const std::size_t planes_at = r.offset();
  face.planes.resize(m.curves);
  for (double& x : face.planes)
    x = r.f64("the planes");
  if (!r.ok()) return;
  for (std::size_t j = 0; j < m.curves; ++j) {
    if (!std::isfinite(face.planes[j]))
      r.fail(ErrorCode::NonFinite, fmt::format("plane {} is not finite", j), planes_at + 8 * j);
    else if (j > 0 && !(face.planes[j] > face.planes[j - 1]))
      r.fail(ErrorCode::Malformed, fmt::format("plane {} does not ascend", j), planes_at + 8 * j);
  }
  const std::size_t at = r.offset();
  const std::string_view frame = r.take(r.remaining(), "the samples");
  if (!r.ok()) return;
  const std::optional<std::string> raw = detail::zstd_decompress(frame, m.curves * m.samples * 3 * 8);
  if (!raw) {
    r.fail(ErrorCode::Malformed,
           fmt::format("the samples are not a zstd frame of {} curves x {} samples x 3 float64", m.curves,
                       m.samples),
           at);
    return;
  }
  face.curves.samples.assign(m.curves, pde::Curve(static_cast<Eigen::Index>(m.samples), 3));
  const std::size_t part = m.curves * m.samples * 8;
  for (int d = 0; d < 3; ++d) {
    const std::string values =
        detail::unshuffle(std::string_view(*raw).substr(static_cast<std::size_t>(d) * part, part), 8);
    Reader v(values, 0, {});
    for (std::size_t j = 0; j < m.curves; ++j)
      for (std::size_t k = 0; k < m.samples; ++k) {
        const std::uint64_t bits = v.u64("a sample");
        const double x =
            std::bit_cast<double>(d == 0 ? bits ^ std::bit_cast<std::uint64_t>(face.planes[j]) : bits);
        if (!std::isfinite(x)) {
          r.fail(ErrorCode::NonFinite, fmt::format("sample {} of curve {} is not finite", k, j), at);
          return;
        }
        face.curves.samples[j](static_cast<Eigen::Index>(k), d) = x;
      }
  }
}

void read_lossy_curves(Reader& r, Face& face, const Meta& m) {
  Quantised q;
  q.curves = m.curves;
  q.samples = m.samples;
  q.planes.resize(m.curves);
  for (std::size_t j = 0; j < m.curves && r.ok(); ++j) {
    const std::size_t at = r.offset();
    const std::int64_t v = r.svarint("the planes", 10);
    if (!r.ok()) return;
    if (v > 4 * detail::kMaxQuantised || v < -4 * detail::kMaxQuantised) {
      r.fail(ErrorCode::Malformed, fmt::format("plane {} is beyond the grid's range", j), at);
      return;
    }
    q.planes[j] = j == 0 ? v : j == 1 ? q.planes[0] + v : v + 2 * q.planes[j - 1] - q.planes[j - 2];
    if (q.planes[j] > detail::kMaxQuantised || q.planes[j] < -detail::kMaxQuantised)
      r.fail(ErrorCode::Malformed, fmt::format("plane {} is beyond the grid's range", j), at);
    else if (j > 0 && q.planes[j] <= q.planes[j - 1])
      r.fail(ErrorCode::Malformed, fmt::format("plane {} does not ascend", j), at);
  }
  std::vector<std::uint32_t> symbols(m.curves * m.samples);
  for (const std::size_t c : {0, 1}) {
    std::vector<std::int64_t>* values = c == 0 ? &q.y : &q.z;
    const char* name = c == 0 ? "y" : "z";
    const std::size_t kind_at = r.offset();
    const std::uint8_t kind = r.u8("the prediction's weights");
    if (r.ok() && c == 0 && kind == detail::kHeightsKind) {
      if (!detail::read_heights(r, q.planes, m.samples, m.grid.step, q.heights, q.y)) return;
      face.storage.heights_stride = q.heights.stride;
      face.storage.heights_bits = q.heights.bits;
      continue;
    }
    if (r.ok() && kind > 1)
      r.fail(ErrorCode::Malformed,
             fmt::format("unknown {} kind {} (0: default weights, 1: stored weights{})", name, kind,
                         c == 0 ? ", 2: heights" : ""),
             kind_at);
    detail::Weights weights = detail::kDefaultWeights[c];
    for (std::int32_t& weight : weights) {
      if (kind != 1) break;
      const std::size_t at = r.offset();
      const std::int64_t v = r.svarint("a prediction weight");
      if (r.ok() && (v > detail::kMaxWeight || v < -detail::kMaxWeight))
        r.fail(ErrorCode::Malformed,
               fmt::format("a prediction weight of {} (at most {})", v, detail::kMaxWeight), at);
      weight = static_cast<std::int32_t>(v);
    }
    if (!r.ok()) return;
    const std::size_t at = r.offset();
    const std::optional<std::size_t> used = detail::decode_classes(r.rest(), symbols);
    values->resize(symbols.size());
    if (!used || !detail::from_symbols(symbols, q.planes, m.samples, weights, *values)) {
      r.fail(ErrorCode::Malformed, fmt::format("the {} samples do not decode", name), at);
      return;
    }
    r.take(*used, "the samples");
  }
  if (!r.at_end()) {
    r.fail_here(ErrorCode::Malformed, "bytes left over at the end of the curves section");
    return;
  }
  detail::dequantise(q, m.grid, face);
}

void read_landmarks(Reader& r, Face& face, const Meta& m, bool lossless) {
  const std::size_t at = r.offset();
  const std::uint64_t count = r.varint("the landmark count");
  if (!r.ok()) return;
  const std::size_t least = lossless ? 2 + 24 : 2 + 3;
  if (count > kMaxLandmarks || count * least > r.remaining()) {
    r.fail(ErrorCode::CountTooLarge,
           fmt::format("{} landmarks: at most {} (and at most {} in the bytes left)", count, kMaxLandmarks,
                       r.remaining() / least),
           at);
    return;
  }
  face.landmarks.resize(static_cast<std::size_t>(count));
  for (Landmark& l : face.landmarks) {
    const std::size_t name_at = r.offset();
    const std::uint64_t size = r.varint("a landmark's name length");
    if (r.ok() && (size == 0 || size > kMaxLandmarkName)) {
      r.fail(ErrorCode::Malformed,
             fmt::format("a landmark name of {} bytes (1 to {})", size, kMaxLandmarkName), name_at);
      return;
    }
    l.name = r.take(static_cast<std::size_t>(size), "a landmark's name");
    if (r.ok() && !printable(l.name))
      r.fail(ErrorCode::Malformed, "a landmark name with control characters", name_at);
    const std::size_t pos_at = r.offset();
    for (int i = 0; i < 3; ++i)
      l.position(i) = lossless
                          ? r.f64("a landmark's position")
                          : static_cast<double>(r.svarint("a landmark's position", 10)) * m.grid.step_mm();
    if (r.ok() && !l.position.allFinite())
      r.fail(ErrorCode::NonFinite, fmt::format("landmark {} is not finite", l.name), pos_at);
    if (!r.ok()) return;
  }
  if (!r.at_end()) r.fail_here(ErrorCode::Malformed, "bytes left over at the end of the landmarks section");
}

// The texture layer: a codec byte (1: JPEG) and the image file, whose header must say JPEG and at most
// `kMaxImagePixels` (the pixels themselves are never decoded here).
void read_texture(Reader& r, Face& face, std::size_t size) {
  const std::size_t at = r.offset();
  const std::uint8_t codec = r.u8("the texture's codec");
  if (!r.ok()) return;
  if (codec != detail::kTextureJpeg) {
    r.fail(ErrorCode::Malformed, fmt::format("texture codec {} (1: JPEG)", codec), at);
    return;
  }
  std::string bytes(r.take(size - 1, "the texture's image"));
  if (!r.ok()) return;
  const Result<ImageInfo> info = inspect_image(bytes, r.source());
  if (!info) {
    r.fail(info.error().code, "the texture's image: " + info.error().message,
           at + 1 + info.error().where.byte.value_or(0));
    return;
  }
  if (info->mime_type != "image/jpeg") {
    r.fail(ErrorCode::Malformed, "the texture's image is not a JPEG image", at + 1);
    return;
  }
  face.texture = Image{std::move(bytes), "image/jpeg", {}};
}

std::string section_name(std::uint8_t tag) {
  switch (tag) {
  case detail::kTagFace: return "face";
  case detail::kTagCurves: return "curves";
  case detail::kTagLandmarks: return "landmarks";
  case detail::kTagName: return "name";
  case detail::kTagTexture: return "texture";
  default: return fmt::format("ancillary 0x{:02x}", tag);
  }
}

} // namespace

// ---------------------------------------------------------------------------------------------------------

// A file may describe at most `sample_limit` of its length in samples (docs/pdef-format.md, "Limits"): one
// whose curves code to less (a thousand samples of one straight line) is refused, never written.
std::optional<Error> too_regular(const Face& face, std::size_t file_bytes) {
  const std::size_t limit = sample_limit(file_bytes);
  if (face.curve_count() * face.sample_count() <= limit) return std::nullopt;
  return invalid(
      fmt::format("{} samples in {} bytes: more than a file of that size may hold ({}); the curves "
                  "are too regular to store",
                  face.curve_count() * face.sample_count(), file_bytes, limit));
}

Result<Encoded> encode(const Face& face, const EncodeOptions& options) {
  if (std::optional<Error> e = check_face(face, options)) return *e;
  if (options.lossless) {
    Encoded out{write_file(face, nullptr, {}, true), 0, 0, 0, 0};
    if (std::optional<Error> e = too_regular(face, out.bytes.size())) return *e;
    return out;
  }
  Result<detail::LossyPlan> plan = detail::plan_lossy(face, options);
  if (!plan) return std::move(plan).error();
  Encoded out;
  out.bytes = write_file(face, &plan->quantised, plan->grid, plan->frame64);
  if (std::optional<Error> e = too_regular(face, out.bytes.size())) return *e;
  // The file must decode to exactly the samples the plan checked (a cheap guard against a writer bug).
  Face expected;
  detail::dequantise(plan->quantised, plan->grid, expected);
  const Result<Face> back = decode(out.bytes);
  if (!back || back->planes != expected.planes || back->curves.samples != expected.curves.samples)
    throw std::logic_error("pdef::encode: the file does not decode to what was encoded" +
                           (back ? std::string() : ": " + back.error().to_string()));
  out.step_mm = plan->grid.step_mm();
  out.max_sample_error = plan->max_sample_error;
  out.max_surface_error = plan->max_surface_error;
  out.tightenings = plan->tightenings;
  return out;
}

Result<std::string> with_texture(std::string_view file, const Image& texture) {
  const Result<ImageInfo> info = inspect_image(texture.bytes, "the texture");
  if (!info || info->mime_type != "image/jpeg")
    return invalid("the texture must be one JPEG image" +
                   (info ? std::string() : ": " + info.error().message));
  const Result<Container> container = read_container(file, "the file");
  if (!container || container->residual)
    return invalid("a texture layer goes into a version 2 file" +
                   (container ? std::string() : ": " + container.error().message));
  for (const Container::Part& part : container->parts)
    if (part.tag == detail::kTagTexture) return invalid("the file has a texture layer already");
  Writer section;
  append_section(section, detail::kTagTexture,
                 std::string(1, static_cast<char>(detail::kTextureJpeg)) + texture.bytes);
  std::string out(file.substr(0, file.size() - detail::kChecksumBytes));
  out += section.str();
  const auto length = static_cast<std::uint32_t>(out.size() + detail::kChecksumBytes);
  if (length > kMaxFileBytes) return invalid("the file with its texture is above the largest file");
  for (int i = 0; i < 4; ++i)
    out[6 + static_cast<std::size_t>(i)] = static_cast<char>(length >> (8 * i));
  const std::uint32_t crc = detail::crc32(out);
  for (int i = 0; i < 4; ++i)
    out += static_cast<char>(crc >> (8 * i));
  return out;
}

Result<Face> decode(std::string_view bytes, std::string_view source, const DecodeOptions& options) {
  Result<Container> container = read_container(bytes, source);
  if (!container) return std::move(container).error();
  Face face;
  face.curves.units = Units::Millimetres;
  face.storage.lossless = container->lossless;
  Meta meta;
  std::size_t textures = 0;
  for (const Container::Part& part : container->parts) {
    Reader r(bytes.substr(part.content, part.size), part.content, source);
    switch (part.tag) {
    case detail::kTagFace: meta = read_face_section(r, face, container->lossless, container->length); break;
    case detail::kTagCurves:
      read_runs(r, face, meta);
      if (r.ok())
        container->lossless ? read_lossless_curves(r, face, meta) : read_lossy_curves(r, face, meta);
      if (r.ok() && container->lossless && !r.at_end())
        r.fail_here(ErrorCode::Malformed, "bytes left over at the end of the curves section");
      break;
    case detail::kTagLandmarks: read_landmarks(r, face, meta, container->lossless); break;
    case detail::kTagName:
      face.name = r.take(part.size, "the name");
      if (part.size == 0 || part.size > kMaxName || !printable(face.name))
        r.fail(ErrorCode::Malformed,
               fmt::format("a name of {} bytes (1 to {} printable)", part.size, kMaxName), part.content);
      break;
    case detail::kTagTexture:
      if (textures++ > 0)
        r.fail(ErrorCode::Malformed, "a second texture section", part.offset);
      else if (part.size == 0)
        r.fail(ErrorCode::Malformed, "an empty texture section", part.offset);
      else if (options.texture)
        read_texture(r, face, part.size);
      break;
    default: break; // ancillary: skipped
    }
    if (!r.ok()) return r.error();
  }
  if (container->residual) {
    Result<Residual> layer = detail::read_residual(bytes, container->length, source);
    if (!layer) return std::move(layer).error();
    face.residual = *std::move(layer);
  }
  face.storage.frame_float64 = meta.frame64;
  if (!container->lossless) {
    face.storage.step_mm = meta.grid.step_mm();
    face.storage.plane_step_mm = meta.grid.plane_step_mm();
  }
  return face;
}

Result<std::vector<Section>> sections(std::string_view bytes, std::string_view source) {
  Result<Container> container = read_container(bytes, source);
  if (!container) return std::move(container).error();
  std::vector<Section> out{{"header", 0, detail::kHeaderBytes}};
  for (const Container::Part& part : container->parts)
    out.push_back({section_name(part.tag), part.offset, part.content + part.size - part.offset});
  out.push_back({"checksum", container->length - detail::kChecksumBytes, detail::kChecksumBytes});
  if (container->residual) {
    Result<Residual> layer = detail::read_residual(bytes, container->length, source);
    if (!layer) return std::move(layer).error();
    if (layer->header_bytes > 0) {
      out.push_back({"residual header", layer->offset, layer->header_bytes});
      const std::size_t trim_at = layer->offset + layer->header_bytes;
      if (layer->trim_bytes > 0) out.push_back({"residual trim", trim_at, layer->trim_bytes_read});
      out.push_back({"residual stream", trim_at + layer->trim_bytes, layer->bytes_read});
    } else {
      out.push_back({"residual (cut inside its header)", layer->offset, bytes.size() - layer->offset});
    }
  }
  return out;
}

} // namespace pdeface::pdef
