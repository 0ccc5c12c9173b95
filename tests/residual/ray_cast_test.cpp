// RayCaster against testing every triangle, and the offsets it gives in a fold that stepping towards the
// nearest point did not find.

#include "pdeface/residual/measure.hpp"
#include "pdeface/residual/ray_cast.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

namespace pdeface {
namespace {

// A bumpy sheet folded back on itself: z = sin terms over x, y in [0, 20], then the same sheet 3 mm
// behind, turned over, so that many lines cross it two to four times.
Mesh folded_sheet() {
  Mesh m;
  constexpr int n = 30;
  for (int layer = 0; layer < 2; ++layer)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = 20.0 * i / n, y = 20.0 * j / n;
        const double z =
            std::sin(0.7 * x) * std::cos(0.5 * y) - 3.0 * layer + 0.4 * std::sin(1.3 * x * layer);
        m.positions.emplace_back(x, y, z);
      }
  const auto at = [&](int layer, int i, int j) {
    return static_cast<std::uint32_t>(layer * (n + 1) * (n + 1) + j * (n + 1) + i);
  };
  for (int layer = 0; layer < 2; ++layer)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.triangles.push_back({at(layer, i, j), at(layer, i + 1, j), at(layer, i + 1, j + 1)});
        m.triangles.push_back({at(layer, i, j), at(layer, i + 1, j + 1), at(layer, i, j + 1)});
      }
  return m;
}

// Every crossing, by testing each triangle (the same Möller–Trumbore test, written out again).
std::vector<double> brute_force(const Mesh& m, const Vec3& x, const Vec3& d, double reach) {
  std::vector<double> out;
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-12) continue;
    const Vec3 s = x - a, q = s.cross(e1);
    const double u = s.dot(p) / det, v = d.dot(q) / det, at = e2.dot(q) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && std::abs(at) <= reach) out.push_back(at);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RayCaster, FindsEveryCrossingAndTheNearestAsTestingEveryTriangleDoes) {
  const Mesh m = folded_sheet();
  const residual::RayCaster caster(m);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> in(1.0, 19.0), tilt(-0.6, 0.6), depth(-4.0, 2.0);
  std::size_t crossed = 0, twice = 0;
  for (int q = 0; q < 400; ++q) {
    const Vec3 x(in(random), in(random), depth(random));
    const Vec3 d = Vec3(tilt(random), tilt(random), 1.0).normalized();
    const double reach = 5.0;
    const std::vector<double> expected = brute_force(m, x, d, reach);
    const std::vector<residual::RayHit> all = caster.all(x, d, reach);
    // A line through a shared edge crosses both triangles: compare the distinct crossings.
    std::vector<double> got;
    for (const residual::RayHit& h : all)
      if (got.empty() || std::abs(h.t - got.back()) > 1e-9) got.push_back(h.t);
    std::vector<double> want;
    for (const double t : expected)
      if (want.empty() || std::abs(t - want.back()) > 1e-9) want.push_back(t);
    ASSERT_EQ(got.size(), want.size()) << q;
    for (std::size_t i = 0; i < got.size(); ++i)
      EXPECT_NEAR(got[i], want[i], 1e-9) << q;
    const std::optional<residual::RayHit> nearest = caster.nearest(x, d, reach);
    ASSERT_EQ(nearest.has_value(), !want.empty()) << q;
    if (!nearest) continue;
    ++crossed;
    twice += want.size() >= 2;
    double best = want[0];
    for (const double t : want)
      if (std::abs(t) < std::abs(best)) best = t;
    EXPECT_NEAR(nearest->t, best, 1e-9) << q;
    const Triangle& t = m.triangles[nearest->triangle];
    const Vec3 p = x + nearest->t * d;
    const Vec3 n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    EXPECT_NEAR(n.normalized().dot(p - m.positions[t[0]]), 0.0, 1e-9)
        << "the point lies in its triangle's plane";
  }
  EXPECT_GT(crossed, 300u);
  EXPECT_GT(twice, 100u) << "lines that cross both layers";
  EXPECT_FALSE(caster.nearest(Vec3(50, 50, 0), Vec3::UnitZ(), 5.0)) << "beyond the sheet";
  EXPECT_FALSE(caster.nearest(Vec3(10, 10, 20), Vec3::UnitZ(), 5.0)) << "out of reach";
}

TEST(RayCaster, APointCloudHasNoTriangles) {
  Mesh cloud;
  cloud.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const residual::RayCaster caster(cloud);
  EXPECT_FALSE(caster.nearest(Vec3(0.2, 0.2, 1), -Vec3::UnitZ(), 5.0));
}

} // namespace
} // namespace pdeface
