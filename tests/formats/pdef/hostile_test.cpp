// Hostile and damaged .pdef files: every truncation, every bit of the header flipped, bytes after the end,
// wrong magic, version and flags, a damaged checksum, absurd counts and lengths (made to pass the
// checksum). Each is one specific error with its byte offset; nothing crashes, hangs or allocates beyond
// what the file's size allows.

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include "pdef_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>
#include <utility>

namespace pdeface::pdef {
namespace {

using test::synthetic_face;
using test::with_checksum;

std::string lossy_file() {
  Face face = synthetic_face();
  face.landmarks = {{"nose_tip", Vec3(0.1, 0.2, 18.3)}};
  face.name = "hostile";
  return encode(face).value().bytes;
}

std::uint32_t declared_length(std::string_view bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= std::uint32_t{static_cast<std::uint8_t>(bytes[6 + static_cast<std::size_t>(i)])} << (8 * i);
  return v;
}

void set_length(std::string& bytes) {
  const auto n = static_cast<std::uint32_t>(bytes.size());
  for (int i = 0; i < 4; ++i)
    bytes[6 + static_cast<std::size_t>(i)] = static_cast<char>(n >> (8 * i));
}

std::string varint(std::uint64_t v) {
  std::string out;
  do {
    out.push_back(static_cast<char>((v & 0x7f) | (v >= 0x80 ? 0x80 : 0)));
    v >>= 7;
  } while (v != 0);
  return out;
}

// The bytes [at, at + old) of the section whose tag is at `section` replaced by `with` (the section's
// length and the file's fixed up, the checksum recomputed): a file a hostile writer could make.
std::string splice(std::string bytes, std::size_t section, std::size_t at, std::size_t old,
                   std::string_view with) {
  const auto length = static_cast<std::size_t>(static_cast<std::uint8_t>(bytes[section + 1]));
  EXPECT_LT(length, 0x80U) << "the test assumes a one-byte section length";
  const std::size_t new_length = length - old + with.size();
  EXPECT_LT(new_length, 0x80U);
  bytes.replace(at, old, with);
  bytes[section + 1] = static_cast<char>(new_length);
  set_length(bytes);
  return with_checksum(bytes);
}

// A section inserted before the checksum.
std::string append_section(std::string bytes, std::uint8_t tag, std::string_view content) {
  const std::string section =
      std::string(1, static_cast<char>(tag)) + varint(content.size()) + std::string(content);
  bytes.insert(bytes.size() - 4, section);
  set_length(bytes);
  return with_checksum(bytes);
}

void expect_error(const std::string& bytes, ErrorCode code, std::uint64_t offset,
                  std::string_view what = {}) {
  const Result<Face> r = decode(bytes, "hostile.pdef");
  ASSERT_FALSE(r) << what;
  EXPECT_EQ(r.error().code, code) << what << ": " << r.error().to_string();
  EXPECT_EQ(r.error().where.byte, offset) << what << ": " << r.error().to_string();
  EXPECT_EQ(r.error().source, "hostile.pdef");
}

// Where the face section's fields are in a lossy file with a float32 frame (docs/pdef-format.md).
struct FaceFields {
  std::size_t section = 10; // its tag
  std::size_t content = 12;
  std::size_t units = 12, precision = 13, frame = 14, scheme = 42, smoothing = 43, curves = 51, samples = 52,
              modes = 53;
};

TEST(PdefHostile, EveryTruncationIsTruncatedAtItsLength) {
  const std::string bytes = lossy_file();
  expect_error("", ErrorCode::Empty, 0);
  for (std::size_t n = 1; n < bytes.size(); ++n)
    expect_error(bytes.substr(0, n), ErrorCode::Truncated, n, std::to_string(n));
}

TEST(PdefHostile, EveryBitOfTheHeaderFlippedIsItsOwnError) {
  const std::string bytes = lossy_file();
  const std::size_t length = bytes.size(), checksum_at = length - 4;
  for (std::size_t byte = 0; byte < 10; ++byte)
    for (int bit = 0; bit < 8; ++bit) {
      std::string damaged = bytes;
      damaged[byte] = static_cast<char>(damaged[byte] ^ (1 << bit));
      const std::string what = std::to_string(byte) + "." + std::to_string(bit);
      if (byte < 4) {
        expect_error(damaged, ErrorCode::BadMagic, 0, what);
      } else if (byte == 4) {
        // 2 ^ 1 = 3, the version with a residual layer: known, so the checksum (which covers it) catches it
        expect_error(damaged, bit == 0 ? ErrorCode::ChecksumMismatch : ErrorCode::UnsupportedVersion,
                     bit == 0 ? checksum_at : 4, what);
      } else if (byte == 5) {
        // bit 0 is the lossless flag (known: the checksum catches it), the others are unknown and required
        expect_error(damaged, bit == 0 ? ErrorCode::ChecksumMismatch : ErrorCode::UnsupportedFormat,
                     bit == 0 ? checksum_at : 5, what);
      } else {
        const std::uint32_t claimed = declared_length(damaged);
        if (claimed > kMaxFileBytes)
          expect_error(damaged, ErrorCode::CountTooLarge, 6, what);
        else if (claimed < 14)
          expect_error(damaged, ErrorCode::Malformed, 6, what);
        else if (claimed > length)
          expect_error(damaged, ErrorCode::Truncated, length, what);
        else
          expect_error(damaged, ErrorCode::Malformed, claimed, what); // bytes after its stated end
      }
    }
}

TEST(PdefHostile, EveryBitOfTheBodyFlippedFailsTheChecksum) {
  const std::string bytes = lossy_file();
  for (std::size_t byte = 10; byte < bytes.size(); ++byte) {
    std::string damaged = bytes;
    damaged[byte] = static_cast<char>(damaged[byte] ^ (1 << (byte % 8)));
    expect_error(damaged, ErrorCode::ChecksumMismatch, bytes.size() - 4, std::to_string(byte));
  }
}

TEST(PdefHostile, MagicVersionFlagsAndTrailingBytes) {
  const std::string bytes = lossy_file();
  expect_error("PLY\n", ErrorCode::BadMagic, 0);
  expect_error("glTF\x02\x00\x00\x00", ErrorCode::BadMagic, 0);
  for (const char version :
       {char{1}, char{4}}) { // 1: the development format of 2026-12-01, never released; 3: a layer
    std::string other = bytes;
    other[4] = version;
    expect_error(other, ErrorCode::UnsupportedVersion, 4);
  }
  std::string flags = bytes;
  flags[5] = static_cast<char>(0x40);
  expect_error(flags, ErrorCode::UnsupportedFormat, 5);
  expect_error(bytes + "x", ErrorCode::Malformed, bytes.size());
  expect_error(bytes + bytes, ErrorCode::Malformed, bytes.size());
}

TEST(PdefHostile, AbsurdCountsAreRefusedBeforeAnythingIsAllocated) {
  const std::string bytes = lossy_file();
  const FaceFields f;
  ASSERT_EQ(static_cast<std::uint8_t>(bytes[f.precision]), 4); // the layout this test assumes
  ASSERT_EQ(static_cast<std::uint8_t>(bytes[f.curves]), 10);
  ASSERT_EQ(static_cast<std::uint8_t>(bytes[f.samples]), 12);
  expect_error(splice(bytes, f.section, f.curves, 1, varint(2000)), ErrorCode::CountTooLarge, f.curves, "J");
  expect_error(splice(bytes, f.section, f.samples, 1, varint(5000)), ErrorCode::CountTooLarge, f.curves, "K");
  // Within each limit, but more samples than a file of this size may hold: no 4 M-sample allocation.
  expect_error(splice(bytes, f.section, f.curves, 2, varint(1000) + varint(4000)), ErrorCode::CountTooLarge,
               f.curves, "J x K");
  expect_error(splice(bytes, f.section, f.curves, 1, varint(3)), ErrorCode::Malformed, f.curves, "J = 3");
  expect_error(splice(bytes, f.section, f.modes, 1, varint(12)), ErrorCode::Malformed, f.modes, "N = K");
  expect_error(splice(bytes, f.section, f.curves, 1, varint(std::uint64_t{1} << 35)), ErrorCode::Malformed,
               f.curves, "a varint above 32 bits");
  expect_error(splice(bytes, f.section, f.curves, 1, std::string("\x8a\x00", 2)), ErrorCode::Malformed,
               f.curves, "a varint not in its shortest form");

  // The curves section: its runs of filled samples.
  const std::size_t curves = f.content + static_cast<std::uint8_t>(bytes[f.section + 1]);
  ASSERT_EQ(static_cast<std::uint8_t>(bytes[curves]), 2); // its tag
  const std::size_t length_bytes = static_cast<std::uint8_t>(bytes[curves + 1]) >= 0x80 ? 2 : 1;
  const std::size_t runs = curves + 1 + length_bytes;
  std::uint64_t old_length = static_cast<std::uint8_t>(bytes[curves + 1]) & 0x7fU;
  if (length_bytes == 2) old_length |= std::uint64_t{static_cast<std::uint8_t>(bytes[curves + 2])} << 7;
  const std::string huge = varint(1'000'000);
  const std::string new_length = varint(old_length + huge.size() - 1);
  ASSERT_EQ(new_length.size(), length_bytes);
  std::string many_runs = bytes;
  many_runs.replace(runs, 1, huge);
  many_runs.replace(curves + 1, length_bytes, new_length);
  set_length(many_runs);
  expect_error(with_checksum(many_runs), ErrorCode::CountTooLarge, runs, "runs");
}

TEST(PdefHostile, FieldValuesOutsideTheirRange) {
  const std::string bytes = lossy_file();
  const FaceFields f;
  expect_error(splice(bytes, f.section, f.units, 1, "\x09"), ErrorCode::Malformed, f.units, "units");
  expect_error(splice(bytes, f.section, f.precision, 1, "\x05"), ErrorCode::Malformed, f.precision,
               "precision");
  expect_error(splice(bytes, f.section, f.scheme, 1, "\x03"), ErrorCode::Malformed, f.scheme, "scheme 3");
  expect_error(splice(bytes, f.section, f.scheme, 1, "\x14"), ErrorCode::Malformed, f.scheme,
               "reserved bits");
  const double nan = std::nan(""), negative = -1.0;
  expect_error(
      splice(bytes, f.section, f.smoothing, 8, std::string_view(reinterpret_cast<const char*>(&nan), 8)),
      ErrorCode::NonFinite, f.smoothing, "a = NaN");
  expect_error(
      splice(bytes, f.section, f.smoothing, 8, std::string_view(reinterpret_cast<const char*>(&negative), 8)),
      ErrorCode::Malformed, f.smoothing, "a < 0");
  const float two = 2.0F; // a quaternion component of 2: no rotation
  expect_error(splice(bytes, f.section, f.frame, 4, std::string_view(reinterpret_cast<const char*>(&two), 4)),
               ErrorCode::Malformed, f.frame, "rotation");
  // The paper's scheme with 11 curves (not 3p + 1).
  expect_error(splice(splice(bytes, f.section, f.scheme, 1, "\x0d"), f.section, f.curves, 1, varint(11)),
               ErrorCode::Malformed, f.curves, "paper with 11 curves");
}

// The fields of a file whose y is stored as heights (docs/pdef-format.md, "Heights"): where its anchor
// stride, grid and flags are.
struct HeightsFields {
  std::string bytes;
  std::size_t kind = 0; // the y kind (2); then the stride (1 byte here), the grid's bits, the flags
};
HeightsFields heights_file() {
  Face face = synthetic_face(28, 30);
  // The heights of a slicer's anchors: each curve's y at shared relative heights, so y costs only them.
  for (std::size_t j = 0; j < face.curve_count(); ++j) {
    pde::Curve& c = face.curves.samples[j];
    const double bottom = c(0, 1), top = c(c.rows() - 1, 1);
    for (Eigen::Index k = 0; k < c.rows(); ++k)
      c(k, 1) =
          bottom + (top - bottom) * std::ldexp(std::round(std::ldexp(static_cast<double>(k) / 29.0, 9)), -9);
  }
  HeightsFields out{encode(face).value().bytes};
  const Face back = decode(out.bytes).value();
  EXPECT_GT(back.storage.heights_stride, 0U) << "the file stores y as heights";
  // The curves section: its tag and length, the runs, then 28 planes (svarints), then y's kind.
  const std::vector<Section> parts = sections(out.bytes).value();
  std::size_t at = parts[2].offset + 1;
  const auto skip_varint = [&] {
    while ((static_cast<std::uint8_t>(out.bytes[at++]) & 0x80) != 0) {
    }
  };
  skip_varint(); // the section's length
  const std::uint8_t runs = static_cast<std::uint8_t>(out.bytes[at]);
  skip_varint();
  for (std::size_t i = 0; i < runs + face.curve_count(); ++i)
    skip_varint();
  out.kind = at;
  EXPECT_EQ(out.bytes[at], 2) << "y's kind: heights";
  return out;
}

TEST(PdefHostile, HeightsLayoutOutsideItsRange) {
  const HeightsFields h = heights_file();
  const auto with = [&](std::size_t at, char value) {
    std::string damaged = h.bytes;
    damaged[at] = value;
    return with_checksum(damaged);
  };
  ASSERT_TRUE(decode(h.bytes));
  expect_error(with(h.kind, 3), ErrorCode::Malformed, h.kind, "y kind 3");
  expect_error(with(h.kind + 1, 0), ErrorCode::Malformed, h.kind + 1, "anchor stride 0");
  expect_error(with(h.kind + 1, 4), ErrorCode::Malformed, h.kind + 1, "a stride that does not divide 27");
  expect_error(with(h.kind + 2, 0), ErrorCode::Malformed, h.kind + 2, "a grid of 2^-0");
  expect_error(with(h.kind + 2, 17), ErrorCode::Malformed, h.kind + 2, "a grid of 2^-17");
  expect_error(with(h.kind + 3, 2), ErrorCode::Malformed, h.kind + 3, "unknown flags");
}

TEST(PdefHostile, SectionsUnknownOutOfOrderOrTooLong) {
  const std::string bytes = lossy_file();
  const std::size_t end = bytes.size() - 4;
  // Ancillary sections (tag 0x80 and up) are skipped; unknown required ones are refused.
  const std::string ancillary = append_section(bytes, 0x90, "future data");
  const Result<Face> skipped = decode(ancillary);
  ASSERT_TRUE(skipped) << skipped.error().to_string();
  EXPECT_EQ(skipped->name, "hostile");
  EXPECT_EQ(sections(ancillary).value()[5].name, "ancillary 0x90");
  expect_error(append_section(bytes, 0x05, "x"), ErrorCode::UnsupportedFormat, end, "tag 5");
  expect_error(append_section(bytes, 0x00, "x"), ErrorCode::UnsupportedFormat, end, "tag 0");
  expect_error(append_section(bytes, 0x03, ""), ErrorCode::Malformed, end, "landmarks after the name");
  expect_error(append_section(bytes, 0x01, ""), ErrorCode::Malformed, end, "a second face section");
  // A section claiming more bytes than remain before the checksum.
  std::string too_long = bytes;
  too_long.replace(11, 1, varint(60000));
  set_length(too_long);
  expect_error(with_checksum(too_long), ErrorCode::Truncated, 10, "length");
  // Only a header and a checksum.
  std::string empty = bytes.substr(0, 10) + "0000";
  set_length(empty);
  expect_error(with_checksum(empty), ErrorCode::Malformed, 10, "no sections");
}

TEST(PdefHostile, RandomDamageNeverCrashes) {
  Face face = synthetic_face();
  face.landmarks = {{"nose_tip", Vec3(0.1, 0.2, 18.3)}};
  const std::array<std::string, 2> files{encode(face).value().bytes,
                                         encode(face, {.lossless = true}).value().bytes};
  std::mt19937 rng(12345);
  std::size_t decoded = 0, refused = 0;
  for (const std::string& file : files)
    for (int i = 0; i < 4000; ++i) {
      std::string damaged = file;
      const int changes = 1 + static_cast<int>(rng() % 4);
      for (int c = 0; c < changes; ++c) {
        const std::size_t at = 10 + rng() % (damaged.size() - 14);
        damaged[at] = static_cast<char>(rng() % 2 == 0 ? static_cast<int>(rng() % 256)
                                                       : damaged[at] ^ (1 << (rng() % 8)));
      }
      const Result<Face> r = decode(with_checksum(damaged), "fuzz.pdef");
      if (!r) {
        ++refused;
        EXPECT_TRUE(r.error().where.byte.has_value());
        EXPECT_LE(*r.error().where.byte, damaged.size());
        continue;
      }
      ++decoded;
      (void)to_mesh(*r, Resolution{8, 8}); // may fail (a surface that cannot be built), must not crash
    }
  EXPECT_GT(refused, 1000U);
  std::printf("random damage: %zu decoded, %zu refused\n", decoded, refused);
}

// Found by pdef_fuzz: a lossy file whose heights' residuals on an anchor curve are far from what the
// encoder writes (a table the encoder would round otherwise). Encoding the decoded face again cannot keep
// its grid (the anchors' heights fitted again differ); it is encoded afresh, within the error asked for.
TEST(PdefHostile, HeightsTheEncoderNeverWritesAreEncodedAgainWithinTheError) {
  const std::string file = test::slurp(test::fixtures() / "pdef" / "fuzz_heights_off_grid.pdef");
  const Result<Face> face = decode(file, "fuzz_heights_off_grid.pdef");
  ASSERT_TRUE(face.ok()) << face.error().to_string();
  ASSERT_GT(face->storage.heights_stride, 0U);
  const double error = face->storage.step_mm;
  const Result<Encoded> again = encode(*face, {.max_error_mm = error});
  ASSERT_TRUE(again.ok()) << again.error().to_string();
  const Result<Face> back = decode(again->bytes, "again");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  ASSERT_EQ(back->curve_count(), face->curve_count());
  EXPECT_EQ(back->filled, face->filled);
  for (std::size_t j = 0; j < face->curve_count(); ++j) {
    EXPECT_LE(std::abs(back->planes[j] - face->planes[j]), error) << "plane " << j;
    EXPECT_LE((back->curves.samples[j] - face->curves.samples[j]).rowwise().norm().maxCoeff(), error)
        << "curve " << j;
  }
}

// Every curve the same straight line, `curves` × `samples`: it codes to almost nothing.
Face flat_face(std::size_t curves, std::size_t samples) {
  Face face = synthetic_face(curves, 4);
  for (std::size_t j = 0; j < curves; ++j) {
    pde::Curve c(static_cast<Eigen::Index>(samples), 3);
    for (std::size_t k = 0; k < samples; ++k)
      c.row(static_cast<Eigen::Index>(k)) << face.planes[j], 0.1 * static_cast<double>(k), 0.0;
    face.curves.samples[j] = c;
    face.filled[j].assign(samples, false);
  }
  face.pde.modes = 3;
  return face;
}

// A file may describe at most 4096 + 256 × its length in samples: a face whose curves code to less is
// refused, never written as a file its own decoder refuses (encode threw std::logic_error on it).
TEST(PdefHostile, AFaceTooRegularForItsFileIsRefusedNotWritten) {
  const Result<Encoded> encoded = encode(flat_face(200, 500));
  ASSERT_FALSE(encoded);
  EXPECT_EQ(encoded.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(encoded.error().message.find("too regular to store"), std::string::npos)
      << encoded.error().message;
}

// Whatever a face's size, encoding it either refuses it or writes a file that decodes to it; the lossy
// checks are bounded in work (a flat face of 16 × 300 samples took 1.7 s and one of 4 × 4097 samples 107 s
// before): a document too large to check is refused lossy, and kept lossless.
TEST(PdefHostile, LargeDocumentsAreEncodedWithinBoundedChecksOrRefused) {
  for (const auto& [curves, samples] : {std::pair<std::size_t, std::size_t>{16, 300}, {4, 4097}}) {
    const Face face = flat_face(curves, samples);
    for (const bool lossless : {false, true}) {
      const Result<Encoded> encoded = encode(face, {.lossless = lossless});
      const std::string what = fmt::format("{} × {} {}", curves, samples, lossless ? "lossless" : "lossy");
      if (!encoded) {
        EXPECT_FALSE(lossless) << what << ": " << encoded.error().to_string();
        EXPECT_EQ(encoded.error().code, ErrorCode::InvalidArgument) << what;
        continue;
      }
      const Result<Face> back = decode(encoded->bytes, "again");
      ASSERT_TRUE(back.ok()) << what << ": " << back.error().to_string();
      EXPECT_EQ(back->sample_count(), samples) << what;
    }
  }
  const Result<Encoded> refused = encode(flat_face(4, 4097));
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("more than a lossy encoding can check"), std::string::npos)
      << refused.error().message;
}

} // namespace
} // namespace pdeface::pdef
