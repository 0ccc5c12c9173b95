// The residual layer (version 3): its codec round trip, every prefix of a file, hostile layers.

#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/pdef/residual.hpp"

#include "pdef_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace pdeface {
namespace {

// Offsets like a face's: smooth, a few sharp creases and bumps, some noise (mm).
pde::Displacement test_field(std::size_t w = 90, std::size_t h = 130) {
  pde::Displacement f{w, h, std::vector<double>(w * h)};
  unsigned seed = 7;
  for (std::size_t k = 0; k < h; ++k)
    for (std::size_t i = 0; i < w; ++i) {
      const double x = static_cast<double>(i) / static_cast<double>(w - 1);
      const double y = static_cast<double>(k) / static_cast<double>(h - 1);
      seed = seed * 1103515245u + 12345u;
      const double noise = (static_cast<double>((seed >> 8) % 1000) / 1000.0 - 0.5) * 0.01;
      f.values[k * w + i] = 0.2 * std::sin(6 * x) * std::cos(4 * y) +
                            1.5 * std::exp(-((x - 0.3) * (x - 0.3) + (y - 0.6) * (y - 0.6)) / 0.002) -
                            0.8 * std::max(0.0, 0.05 - std::abs(y - 0.4 - 0.1 * x)) / 0.05 + noise;
    }
  return f;
}

double rms(const pde::Displacement& a, const pde::Displacement& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    s += (a.values[i] - b.values[i]) * (a.values[i] - b.values[i]);
  return std::sqrt(s / static_cast<double>(a.values.size()));
}

std::string curves_file() { return pdef::encode(test::synthetic_face()).value().bytes; }

void expect_error(std::string_view bytes, ErrorCode code, std::size_t offset, const std::string& what = {}) {
  const Result<pdef::Face> face = pdef::decode(bytes, "t.pdef");
  ASSERT_FALSE(face) << what;
  EXPECT_EQ(face.error().code, code) << what << ": " << face.error().to_string();
  EXPECT_EQ(face.error().where.byte, offset) << what << ": " << face.error().to_string();
}

TEST(PdefResidual, TheWholeStreamDecodesWithinItsStep) {
  const pde::Displacement field = test_field();
  const pdef::CodedResidual coded = pdef::code_residual(field, {.step_mm = 1.0 / 1024}).value();
  const pde::Displacement back = pdef::decode_residual(coded, coded.stream.size());
  ASSERT_EQ(back.values.size(), field.values.size());
  double worst = 0;
  for (std::size_t i = 0; i < field.values.size(); ++i)
    worst = std::max(worst, std::abs(back.values[i] - field.values[i]));
  // Coefficients within half a step (about orthonormal transform): offsets within a few steps.
  EXPECT_LT(worst, 4.0 / 1024);
  EXPECT_LT(rms(back, field), 0.5 / 1024);
}

TEST(PdefResidual, MoreOfTheStreamNeverMakesItWorse) {
  const pde::Displacement field = test_field();
  const pdef::CodedResidual coded = pdef::code_residual(field).value();
  double previous =
      rms(pde::Displacement{field.width, field.height, std::vector<double>(field.values.size())}, field);
  for (std::size_t bytes = 64; bytes <= coded.stream.size(); bytes *= 2) {
    const double e = rms(pdef::decode_residual(coded, bytes), field);
    EXPECT_LT(e, previous) << bytes << " bytes";
    previous = e;
  }
}

TEST(PdefResidual, CurveOnlyFilesStayVersion2AndALayerMakesVersion3) {
  const std::string curves = curves_file();
  EXPECT_EQ(curves[4], 2);
  const pdef::CodedResidual coded = pdef::code_residual(test_field()).value();
  const std::string file = pdef::with_residual(curves, coded, curves.size() + 600).value();
  EXPECT_EQ(file.size(), curves.size() + 600);
  EXPECT_EQ(file[4], 3);
  const pdef::Face face = pdef::decode(file).value();
  ASSERT_TRUE(face.residual);
  EXPECT_TRUE(face.residual->complete);
  EXPECT_EQ(face.residual->offset, curves.size());
  EXPECT_EQ(face.residual->header_bytes + face.residual->bytes_read, 600u);
  const pde::Displacement expected = pdef::decode_residual(coded, face.residual->bytes_read);
  EXPECT_EQ(face.residual->field.values, expected.values);
  // The curves are those of the curve-only file.
  const pdef::Face plain = pdef::decode(curves).value();
  EXPECT_EQ(face.curves.samples, plain.curves.samples);
  EXPECT_FALSE(plain.residual);
  // Too small a budget for the header: refused.
  EXPECT_FALSE(pdef::with_residual(curves, coded, curves.size() + 5));
  EXPECT_FALSE(pdef::with_residual(file, coded, 100000)); // only after a version 2 file
}

TEST(PdefResidual, EveryPrefixOfTheLayerDecodesAndImproves) {
  const std::string curves = curves_file();
  const pde::Displacement field = test_field(40, 60);
  const pdef::CodedResidual coded = pdef::code_residual(field).value();
  const std::string file = pdef::with_residual(curves, coded, curves.size() + 900).value();
  const pde::Displacement zero{field.width, field.height, std::vector<double>(field.values.size())};
  double best = rms(zero, field);
  const double start = best;
  std::size_t improved = 0;
  for (std::size_t n = curves.size(); n <= file.size(); ++n) {
    const Result<pdef::Face> face = pdef::decode(std::string_view(file).substr(0, n));
    ASSERT_TRUE(face) << n << ": " << face.error().to_string();
    ASSERT_TRUE(face->residual) << n;
    const pde::Displacement& got = face->residual->field;
    if (got.empty()) { // cut inside the layer's header: the curves' surface alone
      EXPECT_LT(n, curves.size() + face->residual->header_bytes + 30);
      continue;
    }
    EXPECT_EQ(face->residual->complete, n == file.size()) << n;
    const double e = rms(got, field);
    EXPECT_LE(e, best * 1.02 + 1e-9) << n << " bytes";
    if (e < best) ++improved;
    best = std::min(best, e);
    if (n % 97 == 0) {
      EXPECT_TRUE(pdef::to_mesh(*face, pdef::Resolution{30, 40})) << n;
    }
  }
  EXPECT_LT(best, start / 10);
  EXPECT_GT(improved, 100u);
}

// tests/data/pdef/sample_residual.pdef: the built-in sample face, `pdeface encode --size 1600 --ratio 0.1`
// (777 bytes of curves, 823 of layer: 24 of header, 73 of trim, 726 of stream). Cut at every byte of its
// layer, it decodes to a surface that comes closer to the whole file's as bytes are added, and trims more of
// it, never a cell the whole file keeps. sample_residual_offsets.pdef, made the same way by the first version
// 3 writer (no trim), too.
TEST(PdefResidual, EveryPrefixOfAFileDecodesToASurfaceThatImproves) {
  for (const char* name : {"sample_residual.pdef", "sample_residual_offsets.pdef"}) {
    const std::string file = test::slurp(test::fixtures() / "pdef" / name);
    const pdef::Face whole = pdef::decode(file, name).value();
    ASSERT_TRUE(whole.residual && whole.residual->complete) << name;
    const pdef::Resolution grid{40, 50};
    // The surface on one grid whatever the trim (its vertices in the same order), and the trim apart.
    const auto untrimmed = [&](pdef::Face face) {
      if (face.residual) face.residual->trimmed.clear();
      return pdef::to_mesh(face, grid).value();
    };
    const Mesh target = untrimmed(whole);
    auto distance = [&](const Mesh& m) {
      double s = 0;
      for (std::size_t v = 0; v < m.vertex_count(); ++v)
        s += (m.positions[v] - target.positions[v]).squaredNorm();
      return std::sqrt(s / static_cast<double>(m.vertex_count()));
    };
    double best = distance(untrimmed(pdef::decode(file.substr(0, whole.residual->offset)).value()));
    const double curves_only = best;
    std::size_t trimmed = 0;
    const std::vector<std::uint8_t>& all = whole.residual->trimmed;
    const std::size_t all_trimmed = static_cast<std::size_t>(std::ranges::count(all, 1));
    for (std::size_t n = whole.residual->offset; n <= file.size(); ++n) {
      const Result<pdef::Face> face = pdef::decode(std::string_view(file).substr(0, n), "cut");
      ASSERT_TRUE(face) << name << " " << n << ": " << face.error().to_string();
      const Result<Mesh> mesh = pdef::to_mesh(*face, grid);
      ASSERT_TRUE(mesh) << name << " " << n;
      const double d = distance(untrimmed(*face));
      EXPECT_LE(d, best * 1.05 + 1e-9) << name << " " << n;
      best = std::min(best, d);
      const std::vector<std::uint8_t>& cut = face->residual->trimmed;
      const std::size_t now = static_cast<std::size_t>(std::ranges::count(cut, 1));
      EXPECT_GE(now, trimmed) << name << " " << n << ": a prefix one byte longer trims no less";
      trimmed = now;
      for (std::size_t c = 0; c < cut.size(); ++c)
        ASSERT_TRUE(cut[c] == 0 || all[c] != 0)
            << name << " " << n << ": cell " << c << " kept by the whole file";
    }
    EXPECT_EQ(best, 0.0) << name;
    EXPECT_EQ(trimmed, all_trimmed) << name;
    EXPECT_GT(curves_only, 0.01) << name; // the layer moves the surface (scan units: mm)
    if (std::string_view(name) == "sample_residual.pdef")
      EXPECT_GT(all_trimmed, 100u) << "the sample face's holes: no scan under them";
    else
      EXPECT_EQ(all_trimmed, 0u);
  }
}

TEST(PdefResidual, TheMeshMovesAlongItsNormalsByTheOffsets) {
  pdef::Face face = test::synthetic_face();
  const std::string curves = pdef::encode(face).value().bytes;
  pde::Displacement flat{20, 30, std::vector<double>(600, 0.5)}; // 0.5 mm everywhere
  const pdef::CodedResidual coded = pdef::code_residual(flat).value();
  const pdef::Face with = pdef::decode(pdef::with_residual(curves, coded, 100000).value()).value();
  const pdef::Face without = pdef::decode(curves).value();
  const Mesh moved = pdef::to_mesh(with).value(),
             plain = pdef::to_mesh(without, pdef::Resolution{20, 30}).value();
  ASSERT_EQ(moved.vertex_count(), 600u); // the layer's grid by default
  for (std::size_t v = 0; v < moved.vertex_count(); v += 37) {
    const Vec3 step = (moved.positions[v] - plain.positions[v]) * with.frame.scale; // mm
    EXPECT_NEAR(step.norm(), 0.5, 2e-3) << v;
    EXPECT_GT(step.normalized().dot(plain.normals[v].cast<double>()), 0.999) << v;
  }
}

TEST(PdefResidual, HostileLayersAreRefusedWithTheirOffsets) {
  const std::string curves = curves_file();
  const pdef::CodedResidual coded = pdef::code_residual(test_field(40, 60)).value();
  const std::string good = pdef::with_residual(curves, coded, curves.size() + 400).value();
  const std::size_t at = curves.size();
  const std::size_t stream = coded.stream.size();
  auto file_with = [&](pdef::CodedResidual layer, std::size_t n = 300) {
    std::string f = good.substr(0, at) + pdef::residual_header(layer, n);
    return f + layer.stream.substr(0, std::min(n, layer.stream.size()));
  };
  // field by field (offsets: transform 0, width 1, height 2, levels 3, step 4-5, ...)
  pdef::CodedResidual bad = coded;
  bad.width = 1;
  expect_error(file_with(bad), ErrorCode::Malformed, at + 1, "width 1");
  bad = coded;
  bad.width = 3000;
  bad.height = 3000;
  expect_error(file_with(bad), ErrorCode::CountTooLarge, at + 1, "9 M nodes");
  bad = coded;
  bad.levels = 7;
  expect_error(file_with(bad), ErrorCode::Malformed, at + 3, "levels");
  bad = coded;
  bad.planes = 0;
  expect_error(file_with(bad), ErrorCode::Malformed, at + 6, "planes");
  bad = coded;
  bad.planes = 41;
  expect_error(file_with(bad), ErrorCode::Malformed, at + 6, "planes");
  std::string transform = good;
  transform[at] = 9;
  expect_error(transform, ErrorCode::UnsupportedFormat, at, "transform");
  // A damaged header, a damaged whole stream, bytes after the stream.
  const std::size_t header = pdef::residual_header(coded, 400).size();
  std::string damaged = good;
  damaged[at + 3] = static_cast<char>(damaged[at + 3] ^ 1);
  expect_error(damaged, ErrorCode::ChecksumMismatch, at + header - 4, "header bit");
  damaged = good;
  damaged[good.size() - 1] = static_cast<char>(damaged[good.size() - 1] ^ 0x10);
  expect_error(damaged, ErrorCode::ChecksumMismatch, at + header - 8, "stream bit");
  expect_error(good + "x", ErrorCode::Malformed, good.size(), "trailing");
  // A version 3 base cut before its end is truncated as any file; the base's own checks still hold.
  expect_error(std::string_view(good).substr(0, at - 1), ErrorCode::Truncated, at - 1, "base cut");
  (void)stream;
}

// A trim like a face's: two eye holes, a thin slit, a ragged border row and a few lone cells.
std::vector<std::uint8_t> test_trim(std::size_t w, std::size_t h) {
  std::vector<std::uint8_t> t((w - 1) * (h - 1), 0);
  for (std::size_t k = 0; k + 1 < h; ++k)
    for (std::size_t i = 0; i + 1 < w; ++i) {
      const double x = static_cast<double>(i) / static_cast<double>(w - 2);
      const double y = static_cast<double>(k) / static_cast<double>(h - 2);
      const bool eye = std::pow((x - 0.3) / 0.12, 2) + std::pow((y - 0.65) / 0.05, 2) < 1 ||
                       std::pow((x - 0.7) / 0.12, 2) + std::pow((y - 0.65) / 0.05, 2) < 1;
      const bool slit = std::abs(y - 0.25 - 0.03 * std::sin(9 * x)) < 0.008 && x > 0.35 && x < 0.65;
      const bool border = k == 0 && (i * 7) % 5 < 2;
      const bool lone = (i * 31 + k * 17) % 997 == 0;
      t[k * (w - 1) + i] = eye || slit || border || lone ? 1 : 0;
    }
  return t;
}

TEST(PdefResidual, TheTrimDecodesWholeAndEveryPrefixTrimsASubsetOfIt) {
  const std::size_t w = 90, h = 130;
  const std::vector<std::uint8_t> trim = test_trim(w, h);
  const std::size_t trimmed = static_cast<std::size_t>(std::ranges::count(trim, 1));
  ASSERT_GT(trimmed, 300u);
  pdef::CodedResidual coded = pdef::code_residual(test_field(w, h)).value();
  coded.trim = pdef::code_trim(trim, w, h);
  ASSERT_FALSE(coded.trim.empty());
  EXPECT_LT(coded.trim.size(), trimmed / 2) << "fewer than 4 bits a trimmed cell";
  EXPECT_TRUE(pdef::code_trim(std::vector<std::uint8_t>(trim.size(), 0), w, h).empty()) << "nothing trimmed";
  const std::string curves = curves_file();
  const std::string file = pdef::with_residual(curves, coded, curves.size() + 2000).value();
  const pdef::Face whole = pdef::decode(file).value();
  ASSERT_TRUE(whole.residual->trim_complete);
  EXPECT_EQ(whole.residual->trim_bytes, coded.trim.size());
  EXPECT_EQ(whole.residual->trimmed, trim) << "the whole trim, cell for cell";
  // Every prefix: only cells the whole trim has, more of them with every byte.
  std::size_t before = 0;
  const std::size_t from = whole.residual->offset + whole.residual->header_bytes;
  for (std::size_t n = from; n <= from + coded.trim.size(); ++n) {
    const pdef::Face cut = pdef::decode(std::string_view(file).substr(0, n)).value();
    const std::vector<std::uint8_t>& got = cut.residual->trimmed;
    const std::size_t now = static_cast<std::size_t>(std::ranges::count(got, 1));
    EXPECT_GE(now, before) << n;
    before = now;
    for (std::size_t c = 0; c < got.size(); ++c)
      ASSERT_TRUE(got[c] == 0 || trim[c] != 0) << n << ": cell " << c;
    EXPECT_EQ(cut.residual->trim_complete, n == from + coded.trim.size()) << n;
  }
  EXPECT_EQ(before, trimmed);
  // A writer may keep less of the trim: the prefix of its stream, a layer of offsets alone for none.
  const pdef::Face less =
      pdef::decode(pdef::with_residual(curves, coded, curves.size() + 2000, {.trim_bytes = 20}).value())
          .value();
  EXPECT_EQ(less.residual->trim_bytes, 20u);
  EXPECT_LT(std::ranges::count(less.residual->trimmed, 1), static_cast<std::ptrdiff_t>(trimmed));
  const std::string none =
      pdef::with_residual(curves, coded, curves.size() + 2000, {.trim_bytes = 0}).value();
  EXPECT_EQ(static_cast<std::uint8_t>(none[curves.size()]), 1) << "kind 1";
  EXPECT_TRUE(pdef::decode(none).value().residual->trimmed.empty());
}

TEST(PdefResidual, TheMeshLeavesOutTrimmedCellsAndTheirLoneVertices) {
  const pdef::Face face = test::synthetic_face();
  const std::string curves = pdef::encode(face).value().bytes;
  pdef::CodedResidual coded =
      pdef::code_residual(pde::Displacement{20, 30, std::vector<double>(600, 0.5)}).value();
  std::vector<std::uint8_t> trim(19 * 29, 0);
  for (std::size_t k = 10; k < 15; ++k) // a 4 × 5 block of cells: 3 × 4 of its nodes lose every triangle
    for (std::size_t i = 5; i < 9; ++i)
      trim[k * 19 + i] = 1;
  coded.trim = pdef::code_trim(trim, 20, 30);
  const pdef::Face with = pdef::decode(pdef::with_residual(curves, coded, 100000).value()).value();
  pdef::Face untrimmed = with;
  untrimmed.residual->trimmed.clear();
  const Mesh full = pdef::to_mesh(untrimmed).value(), cut = pdef::to_mesh(with).value();
  ASSERT_EQ(full.vertex_count(), 600u);
  EXPECT_EQ(cut.triangle_count(), full.triangle_count() - 2 * 20);
  EXPECT_EQ(cut.vertex_count(), 600u - 3 * 4);
  EXPECT_EQ(cut.normals.size(), cut.vertex_count());
  // The vertices kept are the grid's in order, moved as before; the triangles kept are the grid's, in order.
  std::vector<std::uint32_t> grid_index;
  for (std::uint32_t g = 0; g < 600; ++g) {
    const std::size_t i = g % 20, k = g / 20;
    if (i >= 6 && i <= 8 && k >= 11 && k <= 14) continue;
    ASSERT_EQ(cut.positions[grid_index.size()], full.positions[g]) << g;
    ASSERT_EQ(cut.normals[grid_index.size()], full.normals[g]) << g;
    grid_index.push_back(g);
  }
  std::size_t t = 0;
  for (std::size_t c = 0; c < trim.size(); ++c) {
    if (trim[c] != 0) continue;
    for (std::size_t n = 2 * c; n < 2 * c + 2; ++n, ++t)
      for (int corner = 0; corner < 3; ++corner)
        ASSERT_EQ(grid_index[cut.triangles[t][corner]], full.triangles[n][corner]) << "cell " << c;
  }
  EXPECT_EQ(t, cut.triangle_count());
  // On another grid a cell is trimmed where the layer's cell holding its centre is.
  const Mesh finer = pdef::to_mesh(with, pdef::Resolution{39, 59}).value(); // two cells a side per cell
  EXPECT_EQ(finer.triangle_count(), 2u * 38 * 58 - 2 * 4 * 20);
  // A trim of every cell leaves no surface: no mesh.
  coded.trim = pdef::code_trim(std::vector<std::uint8_t>(19 * 29, 1), 20, 30);
  const Result<Mesh> nothing =
      pdef::to_mesh(pdef::decode(pdef::with_residual(curves, coded, 100000).value()).value());
  ASSERT_FALSE(nothing);
  EXPECT_EQ(nothing.error().code, ErrorCode::Empty);
}

TEST(PdefResidual, HostileTrimsAreRefusedWithTheirOffsets) {
  const std::string curves = curves_file();
  pdef::CodedResidual coded = pdef::code_residual(test_field(40, 60)).value();
  coded.trim = pdef::code_trim(test_trim(40, 60), 40, 60);
  ASSERT_GT(coded.trim.size(), 8u);
  const std::string good = pdef::with_residual(curves, coded, curves.size() + 400).value();
  const std::size_t at = curves.size();
  const pdef::Face face = pdef::decode(good).value();
  const std::size_t header = face.residual->header_bytes, trim = coded.trim.size();
  ASSERT_EQ(static_cast<std::uint8_t>(good[at]), 2) << "kind 2";
  // kind 2, width 1, height 2, levels 3, step 4-5, planes 6, T 7, its CRC 8-11, S 12-13, ...
  const std::size_t trim_at = at + 7, trim_crc_at = at + 8;
  std::string kind = good;
  kind[at] = 3;
  expect_error(kind, ErrorCode::UnsupportedFormat, at, "kind 3");
  // T too large: the header rewritten (its CRC too), so that only T is wrong.
  auto with_trim_length = [&](std::uint64_t t) {
    std::string h = good.substr(at, 7);
    for (std::uint64_t v = t;; v >>= 7) { // varint
      h += static_cast<char>((v & 0x7f) | (v >= 0x80 ? 0x80 : 0));
      if (v < 0x80) break;
    }
    h += good.substr(trim_crc_at, header - 4 - (trim_crc_at - at));
    std::uint32_t crc = 0xFFFFFFFFu; // CRC-32 (zlib's)
    for (const char c : h) {
      crc ^= static_cast<std::uint8_t>(c);
      for (int b = 0; b < 8; ++b)
        crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xFFFFFFFFu;
    for (int i = 0; i < 4; ++i)
      h += static_cast<char>(crc >> (8 * i));
    return good.substr(0, at) + h + good.substr(at + header);
  };
  expect_error(with_trim_length((std::uint64_t{1} << 26) + 1), ErrorCode::CountTooLarge, trim_at, "T > 2^26");
  // A damaged header, a damaged whole trim, bytes after the stream.
  std::string damaged = good;
  damaged[trim_at] = static_cast<char>(damaged[trim_at] ^ 1);
  expect_error(damaged, ErrorCode::ChecksumMismatch, at + header - 4, "T's bit");
  damaged = good;
  damaged[at + header + trim / 2] = static_cast<char>(damaged[at + header + trim / 2] ^ 0x10);
  expect_error(damaged, ErrorCode::ChecksumMismatch, trim_crc_at, "a trim bit");
  // ... but a prefix cut inside the trim is not checked against the CRC: it decodes, trimming what it says.
  EXPECT_TRUE(pdef::decode(std::string_view(damaged).substr(0, at + header + trim - 1)));
  expect_error(good + "x", ErrorCode::Malformed, good.size(), "trailing");
  // Shorter T, same bytes: what was the trim's end is the stream's, too many bytes for T + S.
  const std::string shorter = with_trim_length(trim - 1);
  expect_error(shorter, ErrorCode::Malformed, shorter.size() - 1, "a byte more than T + S");
  // A trim stream of noise (its CRC right) decodes to some trim and never fails.
  std::string noise = coded.trim;
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<char>((i * 151 + 7) & 0xff);
  pdef::CodedResidual noisy = coded;
  noisy.trim = noise;
  const Result<pdef::Face> odd =
      pdef::decode(pdef::with_residual(curves, noisy, curves.size() + 400).value());
  ASSERT_TRUE(odd) << odd.error().to_string();
  EXPECT_EQ(odd->residual->trimmed.empty() ? 39u * 59 : odd->residual->trimmed.size(), 39u * 59);
}

TEST(PdefResidual, EncodingRefusesBadFields) {
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{1, 5, std::vector<double>(5)}));
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{600, 600, std::vector<double>(360000)}));
  // ... unless asked to allow more; after curves too short to justify them, a reader refuses the file.
  const std::string curves = curves_file();
  ASSERT_LT(pdef::max_residual_nodes(curves.size()), 360000u);
  const pdef::CodedResidual big =
      pdef::code_residual(pde::Displacement{600, 600, std::vector<double>(360000, 0.25)},
                          {.max_nodes = 360000})
          .value();
  const Result<pdef::Face> refused =
      pdef::decode(pdef::with_residual(curves, big, curves.size() + 100).value());
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::CountTooLarge);
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{4, 4, std::vector<double>(15)}));
  pde::Displacement nan{4, 4, std::vector<double>(16)};
  nan.values[3] = std::nan("");
  EXPECT_EQ(pdef::code_residual(nan).error().code, ErrorCode::NonFinite);
  EXPECT_FALSE(pdef::code_residual(test_field(), {.step_mm = 0}));
}

} // namespace
} // namespace pdeface
