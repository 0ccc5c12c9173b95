// A surface's colour at a point (texture or vertex colours), CIELAB and CIEDE2000, PSNR of two surfaces.

#include "pdeface/metrics/colour.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdeface::metrics {
namespace {

// Sharma, Wu and Dalal (2005), "The CIEDE2000 color-difference formula": test data pairs 1, 7, 13, 17, 19,
// 25 and 34 (L, a, b of each and the difference).
TEST(Colour, DeltaE2000MatchesSharmasTestData) {
  struct Pair {
    Eigen::Vector3d a, b;
    double expected;
  };
  const Pair pairs[] = {
      {{50.0, 2.6772, -79.7751}, {50.0, 0.0, -82.7485}, 2.0425},
      {{50.0, 0.0, 0.0}, {50.0, -1.0, 2.0}, 2.3669},
      {{50.0, 2.49, -0.001}, {50.0, -2.49, 0.0011}, 7.2195},
      {{50.0, 2.5, 0.0}, {73.0, 25.0, -18.0}, 27.1492},
      {{50.0, 2.5, 0.0}, {50.0, 3.1736, 0.5854}, 1.0},
      {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
      {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
  };
  for (const Pair& p : pairs) {
    EXPECT_NEAR(delta_e2000(p.a, p.b), p.expected, 1e-4);
    EXPECT_NEAR(delta_e2000(p.b, p.a), p.expected, 1e-4) << "symmetric";
  }
  EXPECT_EQ(delta_e2000(pairs[0].a, pairs[0].a), 0.0);
}

TEST(Colour, LabOfWhiteBlackAndGrey) {
  EXPECT_TRUE(srgb_to_lab({1, 1, 1}).isApprox(Eigen::Vector3d(100, 0, 0), 1e-3));
  EXPECT_NEAR(srgb_to_lab({0, 0, 0}).norm(), 0.0, 1e-9);
  const Eigen::Vector3d grey = srgb_to_lab({0.5f, 0.5f, 0.5f});
  EXPECT_NEAR(grey.x(), 53.39, 0.01);
  EXPECT_NEAR(grey.y(), 0.0, 1e-3);
}

Mesh coloured_square() {
  Mesh m;
  m.positions = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
  return m;
}

TEST(Colour, VertexColoursInterpolatedAndTurnedIntoSrgb) {
  const Mesh m = coloured_square();
  const Result<SurfaceColour> c = SurfaceColour::of(m, "square");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->source(), ColourSource::VertexColours);
  EXPECT_TRUE(c->at({0, 0, 0}, 0)->isApprox(Eigen::Vector3f(1, 0, 0)));
  const Eigen::Vector3f mid = *c->at({5, 0, 0}, 0); // half red, half green, linear: 0.5 each
  EXPECT_NEAR(mid.x(), image::to_srgb(0.5f), 1e-5f);
  EXPECT_NEAR(mid.y(), image::to_srgb(0.5f), 1e-5f);
  EXPECT_FALSE(SurfaceColour::of(Mesh{m.positions, m.triangles}, "plain")->at({0, 0, 0}, 0));
}

TEST(Colour, TextureColoursThroughTheCornersCoordinates) {
  Mesh m = coloured_square();
  m.colors.clear();
  image::Pixels p{2, 1, {255, 0, 0, 0, 0, 255}}; // red on the left, blue on the right
  m.material = Material{"m", Vec4f::Ones(),
                        Image{image::encode_jpeg(p, {.quality = 100, .subsample = false}), "image/jpeg", {}}};
  m.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Result<SurfaceColour> c = SurfaceColour::of(m, "textured");
  ASSERT_TRUE(c.ok()) << c.error().to_string();
  EXPECT_EQ(c->source(), ColourSource::Texture);
  const Eigen::Vector3f left = *c->at({0, 5, 0}, 1), right = *c->at({10, 5, 0}, 0);
  EXPECT_GT(left.x(), 0.8f);
  EXPECT_GT(right.z(), 0.8f);
  m.material->base_color_image->bytes.resize(20); // a corrupt photograph
  EXPECT_FALSE(SurfaceColour::of(m, "corrupt").ok());
}

TEST(Colour, ASurfaceAgainstItselfIsExactAndAgainstOtherColoursIsNot) {
  const Mesh m = coloured_square();
  Mesh other = m;
  for (Vec4f& c : other.colors)
    c.head<3>() *= 0.8f;
  const SurfaceColour a = SurfaceColour::of(m, "a").value(), b = SurfaceColour::of(other, "b").value();
  const SurfaceDistance da(m), db(other);
  const std::vector<Vec3> points = sample_surface(m, 1.0);
  const ColourError same = colour_error(a, da, a, da, points);
  EXPECT_TRUE(std::isinf(same.psnr_db));
  EXPECT_EQ(same.mean_delta_e, 0.0);
  EXPECT_EQ(same.samples, points.size());
  const ColourError darker = colour_error(a, da, b, db, points);
  EXPECT_LT(darker.psnr_db, 30.0);
  EXPECT_GT(darker.mean_delta_e, 2.0);
  EXPECT_GE(darker.p95_delta_e, darker.mean_delta_e * 0.5);
  const Mesh plain{m.positions, m.triangles};
  const ColourError none = colour_error(a, da, SurfaceColour::of(plain, "p").value(), da, points);
  EXPECT_EQ(none.uncoloured, points.size());
}

} // namespace
} // namespace pdeface::metrics
