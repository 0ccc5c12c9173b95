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

// tests/data/pdef/sample_residual.pdef: the built-in sample face, `pdeface encode --size 1600` (777 bytes
// of curves, 823 of layer). Cut at every byte of its layer, it decodes to a surface that comes closer to
// the whole file's as bytes are added.
TEST(PdefResidual, EveryPrefixOfAFileDecodesToASurfaceThatImproves) {
  const std::string file = test::slurp(test::fixtures() / "pdef" / "sample_residual.pdef");
  const pdef::Face whole = pdef::decode(file, "sample_residual.pdef").value();
  ASSERT_TRUE(whole.residual && whole.residual->complete);
  const pdef::Resolution grid{40, 50};
  const Mesh target = pdef::to_mesh(whole, grid).value();
  auto distance = [&](const Mesh& m) {
    double s = 0;
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
      s += (m.positions[v] - target.positions[v]).squaredNorm();
    return std::sqrt(s / static_cast<double>(m.vertex_count()));
  };
  double best =
      distance(pdef::to_mesh(pdef::decode(file.substr(0, whole.residual->offset)).value(), grid).value());
  const double curves_only = best;
  for (std::size_t n = whole.residual->offset; n <= file.size(); ++n) {
    const Result<pdef::Face> face = pdef::decode(std::string_view(file).substr(0, n), "cut");
    ASSERT_TRUE(face) << n << ": " << face.error().to_string();
    const Result<Mesh> mesh = pdef::to_mesh(*face, grid);
    ASSERT_TRUE(mesh) << n;
    const double d = distance(*mesh);
    EXPECT_LE(d, best * 1.05 + 1e-9) << n;
    best = std::min(best, d);
  }
  EXPECT_EQ(best, 0.0);
  EXPECT_GT(curves_only, 0.01); // the layer moves the surface (scan units: mm)
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

TEST(PdefResidual, EncodingRefusesBadFields) {
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{1, 5, std::vector<double>(5)}));
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{600, 600, std::vector<double>(360000)}));
  EXPECT_FALSE(pdef::code_residual(pde::Displacement{4, 4, std::vector<double>(15)}));
  pde::Displacement nan{4, 4, std::vector<double>(16)};
  nan.values[3] = std::nan("");
  EXPECT_EQ(pdef::code_residual(nan).error().code, ErrorCode::NonFinite);
  EXPECT_FALSE(pdef::code_residual(test_field(), {.step_mm = 0}));
}

} // namespace
} // namespace pdeface
