#include "pdeface/metrics/front_view.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdeface::metrics {
namespace {

// Two squares seen from the front: a tilted one in front (z = 1 + 0.1 x, 20 × 20 mm, with a 4 × 4 mm hole
// in its middle) and a flat one 10 mm behind it, larger.
Mesh two_layers() {
  Mesh m;
  const auto square = [&](double half, double z0, double slope, double hole) {
    const int n = static_cast<int>(2 * half);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = -half + i, y = -half + j;
        m.positions.emplace_back(x, y, z0 + slope * x);
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double cx = -half + i + 0.5, cy = -half + j + 0.5;
        if (std::abs(cx) < hole / 2 && std::abs(cy) < hole / 2) continue;
        const auto v = base + static_cast<std::uint32_t>(j * (n + 1) + i);
        const auto w = static_cast<std::uint32_t>(n + 1);
        m.triangles.push_back({v, v + 1, v + w + 1});
        m.triangles.push_back({v, v + w + 1, v + w});
      }
  };
  square(10, 1.0, 0.1, 4.0);
  square(15, -10.0, 0.0, 0.0);
  return m;
}

TEST(FrontView, TheFrontMostSurfaceExactlyAndWhatAHoleShows) {
  const Mesh scan = two_layers();
  const FrontView view(scan, -12, 12, -12, 12, 0.5);
  EXPECT_FALSE(view.point_cloud());
  // On the front square: its own plane, exactly.
  const std::optional<Vec3> p = view.front(5.0, -3.0);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->z(), 1.5, 1e-12);
  EXPECT_EQ(p->x(), 5.0);
  // Through the hole: the square behind it.
  ASSERT_TRUE(view.front(0.0, 0.0));
  EXPECT_EQ(view.front(0.0, 0.0)->z(), -10.0);
  EXPECT_TRUE(view.hidden(Vec3(5, -3, -10), 2.0));
  EXPECT_FALSE(view.hidden(Vec3(5, -3, 0.0), 2.0));
  // Every sample of the front square lies on it.
  const std::vector<Vec3> front = view.samples([](const Vec3& q) { return q.z() > -5.0; });
  EXPECT_GT(front.size(), 1000U);
  for (const Vec3& q : front)
    EXPECT_NEAR(q.z(), 1.0 + 0.1 * q.x(), 1e-12);
  // Beyond both squares nothing is seen.
  EXPECT_FALSE(view.sees_surface(11.9, 11.9) && view.front(11.9, 11.9)->z() > -5.0);
  EXPECT_THROW(FrontView(scan, 0, 1, 0, 1, 0.0), std::invalid_argument);
}

TEST(FrontView, APointCloudShowsItsOwnFrontMostPoints) {
  Mesh cloud;
  for (int j = -10; j <= 10; ++j)
    for (int i = -10; i <= 10; ++i) {
      cloud.positions.emplace_back(i, j, 0.0);         // the front, 1 mm apart
      cloud.positions.emplace_back(i + 0.5, j, -30.0); // the far side, behind it
    }
  const FrontView view(cloud, -12, 12, -12, 12, 0.5);
  EXPECT_TRUE(view.point_cloud());
  EXPECT_GE(view.cell(), 1.0); // at least twice the point spacing
  const std::vector<Vec3> seen = view.samples([](const Vec3&) { return true; });
  ASSERT_FALSE(seen.empty());
  for (const Vec3& q : seen) {
    EXPECT_EQ(q.z(), 0.0) << q.transpose(); // the far side never shows
    EXPECT_EQ(q.x(), std::round(q.x()));    // the cloud's own points
  }
}

} // namespace
} // namespace pdeface::metrics
