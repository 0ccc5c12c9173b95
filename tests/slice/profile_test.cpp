// Profiles of one plane: height fields, front-most layers, holes, point clouds.

#include "meshes.hpp"
#include "pdeface/slice/profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pdeface::slice {
namespace {

// A smooth face-like height field (mm): |f_yy| <= 12/400 + ..., well inside a 120 x 160 mm box.
double f(double x, double y) { return 12.0 * std::cos(x / 25.0) * std::sin(y / 20.0) - 0.004 * x * x; }

Result<Profile> profile_at(const Mesh& m, double c, double lo, double hi, const SectionOptions& o = {}) {
  const auto cut = intersect(m, Plane{Vec3::UnitX(), c});
  return clip(mesh_section(cut, {}), {}, lo, hi, o);
}

TEST(Profile, HeightFieldSliceReproducesTheFunction) {
  // Sliced between grid lines, each point is on a triangle edge: off f by at most the linear
  // interpolation error h²/8 · max|f''| along that edge (diagonals: twice the squared step).
  for (double h : {2.0, 1.0, 0.5}) {
    const Mesh m = test::height_field(f, -60, 60, -80, 80, h);
    const double c = 13.3;
    Result<Profile> p = profile_at(m, c, -70.0, 70.0);
    ASSERT_TRUE(p) << p.error().message;
    const double second = 12.0 / 400.0 + 12.0 / 625.0 + 0.008 + 2 * 12.0 / 500.0; // bound on |f''| any way
    const double bound = 2.0 * h * h / 8.0 * second;
    double worst = 0.0;
    for (const Vec3& q : p->points) {
      EXPECT_EQ(q.x(), c);
      worst = std::max(worst, std::abs(q.z() - f(c, q.y())));
    }
    EXPECT_LE(worst, bound) << "h = " << h;
    EXPECT_GT(worst, bound / 100.0) << "h = " << h; // it is the triangulation error, not zero
    EXPECT_EQ(p->points.front().y(), -70.0);
    EXPECT_EQ(p->points.back().y(), 70.0);
    for (std::size_t i = 1; i < p->points.size(); ++i)
      EXPECT_LT(p->points[i - 1].y(), p->points[i].y());
    EXPECT_EQ(p->bridged, 0U);
  }
}

TEST(Profile, KeepsTheFrontLayer) {
  // The face and, 60 mm behind it, a second sheet (an ear, the back of the head) over part of the range.
  Mesh m = test::height_field(f, -60, 60, -80, 80, 1.0);
  const Mesh back = test::height_field([](double, double) { return -60.0; }, -20, 20, -30, 30, 1.0);
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), back.positions.begin(), back.positions.end());
  for (Triangle t : back.triangles)
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  Result<Profile> p = profile_at(m, 5.0, -70.0, 70.0);
  ASSERT_TRUE(p);
  for (const Vec3& q : p->points)
    EXPECT_GT(q.z(), -30.0);
}

TEST(Profile, SmallHolesAreBridgedLongOnesNamed) {
  auto hole = [](double r) { return [r](double x, double y) { return std::hypot(x - 10.0, y - 30.0) > r; }; };
  const Mesh small = test::height_field(f, -60, 60, -80, 80, 1.0, hole(2.5));
  Result<Profile> bridged = profile_at(small, 10.2, -70.0, 70.0);
  ASSERT_TRUE(bridged) << bridged.error().message;
  EXPECT_EQ(bridged->bridged, 1U);
  EXPECT_GT(bridged->longest_bridge, 3.0);
  EXPECT_LT(bridged->longest_bridge, 8.0);

  const Mesh big = test::height_field(f, -60, 60, -80, 80, 1.0, hole(10.0));
  Result<Profile> broken = profile_at(big, 10.2, -70.0, 70.0);
  ASSERT_FALSE(broken);
  EXPECT_EQ(broken.error().code, ErrorCode::NoFace);
  EXPECT_NE(broken.error().message.find("hole 2"), std::string::npos) << broken.error().message; // ~20 mm
  EXPECT_NE(broken.error().message.find("at y = 3"), std::string::npos) << broken.error().message;
  // A longer bridge is an option away.
  EXPECT_TRUE(profile_at(big, 10.2, -70.0, 70.0, {.max_gap_mm = 25.0}));

  Result<Profile> beyond = profile_at(small, 10.2, -70.0, 95.0);
  ASSERT_FALSE(beyond);
  EXPECT_NE(beyond.error().message.find("the surface ends at y = 80.0"), std::string::npos)
      << beyond.error().message;
}

TEST(Profile, PointCloudSlabFollowsTheSurface) {
  Mesh cloud = test::height_field(f, -60, 60, -80, 80, 0.7);
  cloud.triangles.clear();
  const double spacing = point_spacing(cloud.positions);
  EXPECT_NEAR(spacing, 0.7, 0.01); // the grid step, a little more where the surface slopes
  const Section s = cloud_section(cloud.positions, Plane{Vec3::UnitX(), 13.3}, {}, spacing);
  Result<Profile> p = clip(s, {}, -70.0, 70.0);
  ASSERT_TRUE(p) << p.error().message;
  double worst = 0.0;
  for (const Vec3& q : p->points) {
    EXPECT_EQ(q.x(), 13.3);
    worst = std::max(worst, std::abs(q.z() - f(13.3, q.y())));
  }
  EXPECT_LT(worst, 0.05); // a local linear fit on the slab: second order in the spacing
  EXPECT_GT(p->points.size(), 140.0 / 0.7 / 2);
}

TEST(Profile, PointCloudHolesAreRealHolesOnly) {
  // A scanner's cloud is not a grid: points jittered by up to 0.4 of the step, so that neighbouring
  // points of a section are often more than a spacing apart. A cloud without holes has none to bridge
  // (the first version counted every gap between one slab bin's point and the next: ~100 "holes" per
  // profile of facefuns_f56_points.ply), and a real hole is one bridge about as long as the hole.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  auto cloud = [&](double hole_radius) {
    Mesh m;
    for (double y = -80.0; y <= 80.0; y += 0.7)
      for (double x = -60.0; x <= 60.0; x += 0.7) {
        const double px = x + 0.7 * jitter(random), py = y + 0.7 * jitter(random);
        if (std::hypot(px - 10.0, py - 30.0) > hole_radius) m.positions.push_back({px, py, f(px, py)});
      }
    return m;
  };
  for (const Mesh& whole : {cloud(0.0), test::height_field(f, -60, 60, -80, 80, 0.7)}) {
    const double spacing = point_spacing(whole.positions);
    for (double c : {-41.3, 0.0, 13.3, 52.9}) {
      Result<Profile> p =
          clip(cloud_section(whole.positions, Plane{Vec3::UnitX(), c}, {}, spacing), {}, -70.0, 70.0);
      ASSERT_TRUE(p) << p.error().message;
      EXPECT_EQ(p->bridged, 0U) << "x = " << c << ", longest " << p->longest_bridge;
    }
  }
  const Mesh holed = cloud(3.0);
  Result<Profile> p =
      clip(cloud_section(holed.positions, Plane{Vec3::UnitX(), 10.2}, {}, point_spacing(holed.positions)), {},
           -70.0, 70.0);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->bridged, 1U);
  EXPECT_GT(p->longest_bridge, 3.0); // the chord is 6 mm, less the slab's half-width at its ends
  EXPECT_LT(p->longest_bridge, 7.0);
}

TEST(Profile, PointCloudLayerBehindAGapIsHidden) {
  // A sparse cloud whose front surface has no points in the slab over 10 mm of height (a scanner's gap,
  // or a side of the face sampled more coarsely than the median), with another layer 100 mm behind it
  // everywhere (the far side of a head): there the section has a gap, not the layer behind.
  Mesh cloud;
  for (double y = -60.0; y <= 60.0; y += 1.0)
    for (double x = -20.0; x <= 20.0; x += 1.0) {
      if (!(std::abs(x - 5.0) < 4.0 && y > 0.0 && y < 10.0)) cloud.positions.push_back({x, y, f(x, y)});
      cloud.positions.push_back({x, y, f(x, y) - 100.0});
    }
  const Section s = cloud_section(cloud.positions, Plane{Vec3::UnitX(), 5.0}, {}, 1.0);
  for (const Vec3& q : s.points)
    EXPECT_NEAR(q.z(), f(5.0, q.y()), 0.5) << "y = " << q.y(); // only the front layer
  Result<Profile> p = clip(s, {}, -50.0, 50.0, {.max_gap_mm = 20.0});
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->bridged, 1U);
  EXPECT_GT(p->longest_bridge, 6.0);
  // Nearer than the hidden depth (20 mm), a recess between two fronts is surface: an eye socket.
  Mesh socket;
  for (double y = -60.0; y <= 60.0; y += 1.0)
    for (double x = -20.0; x <= 20.0; x += 1.0)
      socket.positions.push_back({x, y, f(x, y) - (std::abs(y - 5.0) < 5.0 ? 12.0 : 0.0)});
  const Section eye = cloud_section(socket.positions, Plane{Vec3::UnitX(), 5.0}, {}, 1.0);
  EXPECT_TRUE(std::ranges::any_of(eye.points, [](const Vec3& q) { return q.z() < f(5.0, q.y()) - 11.0; }));
}

TEST(Profile, CoveredExtentBridgesShortGaps) {
  Section s;
  s.cover = {{-50, -20}, {-15, 10}, {30, 60}};
  EXPECT_EQ(covered_extent(s, 0.0, 8.0), (std::array<double, 2>{-50, 10}));
  EXPECT_EQ(covered_extent(s, 0.0, 25.0), (std::array<double, 2>{-50, 60}));
  EXPECT_EQ(covered_extent(s, 40.0, 8.0), (std::array<double, 2>{30, 60}));
}

} // namespace
} // namespace pdeface::slice
