// Plane-mesh intersection on meshes whose sections are known exactly.

#include "meshes.hpp"
#include "pdeface/slice/intersect.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace pdeface::slice {
namespace {

std::size_t distinct(const std::vector<Vec3>& points) {
  std::set<std::array<double, 3>> seen;
  for (const Vec3& p : points)
    seen.insert({p.x(), p.y(), p.z()});
  return seen.size();
}

double longest_edge(const Mesh& m) {
  double e = 0.0;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      e = std::max(e, (m.positions[t[k]] - m.positions[t[(k + 1) % 3]]).norm());
  return e;
}

TEST(Intersect, SphereThroughAVertexRingIsThatRing) {
  const Mesh sphere = test::uv_sphere(50.0, 15, 48);
  const std::size_t first = 1 + 7 * 48; // ring 7: the equator
  const double z = sphere.positions[first].z();
  const auto cut = intersect(sphere, Plane{Vec3::UnitZ(), z});
  ASSERT_EQ(cut.size(), 1U);
  EXPECT_TRUE(cut[0].closed);
  ASSERT_EQ(cut[0].points.size(), 48U); // each vertex once, no crossings added
  EXPECT_EQ(distinct(cut[0].points), 48U);
  for (const Vec3& p : cut[0].points) {
    EXPECT_EQ(p.z(), z);
    EXPECT_NEAR(p.head<2>().norm(), 50.0, 50.0 * 1e-9);
    EXPECT_NE(std::find(sphere.positions.begin(), sphere.positions.end(), p), sphere.positions.end());
  }
}

TEST(Intersect, SphereByAnyPlaneIsACircleWithinTheChords) {
  const Mesh sphere = test::uv_sphere(50.0, 40, 80);
  const double sagitta = std::pow(longest_edge(sphere), 2) / (4.0 * 50.0);
  for (const Plane& plane :
       {Plane{Vec3(1, 2, 2) / 3.0, 10.0}, Plane{Vec3::UnitX(), -31.7}, Plane{Vec3(0.6, 0.0, 0.8), 0.0}}) {
    const auto cut = intersect(sphere, plane);
    ASSERT_EQ(cut.size(), 1U);
    EXPECT_TRUE(cut[0].closed);
    const Vec3 centre = plane.offset * plane.normal;
    const double radius = std::sqrt(50.0 * 50.0 - plane.offset * plane.offset);
    for (const Vec3& p : cut[0].points) {
      EXPECT_NEAR(plane.normal.dot(p), plane.offset, 1e-12 * 50.0);
      EXPECT_LE((p - centre).norm(), radius * (1 + 1e-9)); // chords lie inside
      EXPECT_GE((p - centre).norm(), radius - sagitta);
    }
    EXPECT_EQ(distinct(cut[0].points), cut[0].points.size());
  }
}

TEST(Intersect, CylinderGivesCirclesAcrossAndLinesAlong) {
  const Mesh c = test::cylinder(30.0, 60.0, 6, 24);
  const auto ring = intersect(c, Plane{Vec3::UnitZ(), 20.0}); // through ring 2
  ASSERT_EQ(ring.size(), 1U);
  EXPECT_TRUE(ring[0].closed);
  EXPECT_EQ(ring[0].points.size(), 24U);
  for (const Vec3& p : ring[0].points)
    EXPECT_NEAR(p.head<2>().norm(), 30.0, 30.0 * 1e-9);

  // y = 0 holds the vertical edges at angle 0 exactly (in the plane, shared by two triangles each) and
  // passes within 1e-15 of those at angle π: two straight lines along the axis.
  const auto lines = intersect(c, Plane{Vec3::UnitY(), 0.0});
  ASSERT_EQ(lines.size(), 2U);
  for (const Polyline& line : lines) {
    EXPECT_FALSE(line.closed);
    const double x = line.points.front().x() > 0 ? 30.0 : -30.0;
    double lo = 1e9, hi = -1e9;
    for (const Vec3& p : line.points) {
      EXPECT_NEAR(p.x(), x, 30.0 * 1e-9);
      EXPECT_NEAR(p.y(), 0.0, 30.0 * 1e-9);
      lo = std::min(lo, p.z());
      hi = std::max(hi, p.z());
    }
    EXPECT_NEAR(lo, 0.0, 1e-9);
    EXPECT_NEAR(hi, 60.0, 60.0 * 1e-9);
    EXPECT_EQ(distinct(line.points), line.points.size());
    if (x > 0) {
      EXPECT_EQ(line.points.size(), 7U); // exactly the 7 vertices on the edge line
    }
  }
}

TEST(Intersect, PlaneGivesSegmentsAndVerticesOnThePlaneOnce) {
  const Mesh flat = test::height_field([](double, double) { return 0.0; }, 0.0, 10.0, 0.0, 10.0, 1.0);
  // Between grid lines: a segment from y = 0 to y = 10, every point exactly on x = 3.5, z = 0.
  const auto between = intersect(flat, Plane{Vec3::UnitX(), 3.5});
  ASSERT_EQ(between.size(), 1U);
  EXPECT_FALSE(between[0].closed);
  for (const Vec3& p : between[0].points) {
    EXPECT_EQ(p.x(), 3.5);
    EXPECT_EQ(p.z(), 0.0);
  }
  const auto [lo, hi] = std::minmax(between[0].points.front().y(), between[0].points.back().y());
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 10.0);
  // On a grid line: the 11 vertices, each once, though every edge between them lies in the plane.
  const auto on = intersect(flat, Plane{Vec3::UnitX(), 3.0});
  ASSERT_EQ(on.size(), 1U);
  ASSERT_EQ(on[0].points.size(), 11U);
  for (std::size_t j = 0; j < 11; ++j)
    EXPECT_EQ(on[0].points[j],
              Vec3(3.0, on[0].points.front().y() == 0.0 ? double(j) : 10.0 - double(j), 0.0));
  // Along the split diagonals (x = y): the diagonal vertices, once each.
  const double s = 1.0 / std::sqrt(2.0);
  const auto diagonal = intersect(flat, Plane{Vec3(s, -s, 0.0), 0.0});
  ASSERT_EQ(diagonal.size(), 1U);
  EXPECT_EQ(diagonal[0].points.size(), 11U);
  EXPECT_EQ(distinct(diagonal[0].points), 11U);
}

TEST(Intersect, OnePassEqualsPlaneByPlane) {
  const Mesh sphere = test::uv_sphere(40.0, 20, 36);
  const std::vector<double> offsets{12.5, -30.0, 0.0, 39.9, -45.0, 7.25, 12.5};
  const auto all = intersect(sphere, Vec3::UnitX(), offsets);
  ASSERT_EQ(all.size(), offsets.size());
  for (std::size_t j = 0; j < offsets.size(); ++j) {
    const auto one = intersect(sphere, Plane{Vec3::UnitX(), offsets[j]});
    ASSERT_EQ(all[j].size(), one.size()) << offsets[j];
    for (std::size_t k = 0; k < one.size(); ++k)
      EXPECT_EQ(all[j][k].points, one[k].points);
  }
  EXPECT_TRUE(all[4].empty()); // x = -45 misses the sphere
  // Planes of several orientations in one pass.
  const std::vector<Plane> mixed{{Vec3::UnitZ(), 5.0}, {Vec3::UnitX(), 12.5}, {Vec3::UnitZ(), -5.0}};
  const auto together = intersect(sphere, mixed);
  for (std::size_t j = 0; j < mixed.size(); ++j)
    EXPECT_EQ(together[j][0].points, intersect(sphere, mixed[j])[0].points);
}

TEST(Intersect, BadCallsThrow) {
  const Mesh sphere = test::uv_sphere(40.0, 8, 8);
  EXPECT_THROW((void)intersect(sphere, Plane{Vec3(1, 1, 0), 0.0}), std::invalid_argument);
  const std::vector<double> nan{std::numeric_limits<double>::quiet_NaN()};
  EXPECT_THROW((void)intersect(sphere, Vec3::UnitX(), nan), std::invalid_argument);
  EXPECT_TRUE(intersect(Mesh{}, Plane{Vec3::UnitX(), 0.0}).empty());
}

} // namespace
} // namespace pdeface::slice
