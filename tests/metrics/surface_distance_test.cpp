#include "pdeface/metrics/surface_distance.hpp"

#include "pdeface/core/sample_face.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <random>

namespace pdeface::metrics {
namespace {

// The definition: the nearest of a dense set of points of the triangle, refined (used only as a check).
double brute_distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  double best = 1e300;
  constexpr int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const Vec3 q = a + (b - a) * (i / double(n)) + (c - a) * (j / double(n));
      best = std::min(best, (q - p).norm());
    }
  return best;
}

// The distance to the mesh by testing every triangle.
double nearest_by_every_triangle(const Mesh& mesh, const Vec3& p) {
  double best = 1e300;
  for (const Triangle& t : mesh.triangles)
    best = std::min(
        best,
        (closest_point_on_triangle(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]) - p)
            .norm());
  return best;
}

TEST(ClosestPoint, EveryVoronoiRegion) {
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(1, 3, 0);
  // Inside the face, near each vertex, near each edge, above and below.
  for (const Vec3& p : {Vec3(1.5, 1, 2), Vec3(-1, -1, 0.5), Vec3(5, -1, 0), Vec3(1, 4, -1), Vec3(2, -1, 0.3),
                        Vec3(3.5, 2, 1), Vec3(-0.5, 1.5, 0), Vec3(1.4, 0.9, -0.7)}) {
    const Vec3 q = closest_point_on_triangle(p, a, b, c);
    EXPECT_NEAR((q - p).norm(), brute_distance_to_triangle(p, a, b, c), 2e-2) << p.transpose();
    // The result lies on the triangle: its barycentric coordinates are in [0, 1].
    Eigen::Matrix<double, 3, 2> m;
    m << b - a, c - a;
    const Eigen::Vector2d uv = m.colPivHouseholderQr().solve(q - a);
    EXPECT_GE(uv.minCoeff(), -1e-12);
    EXPECT_LE(uv.sum(), 1.0 + 1e-12);
  }
  EXPECT_EQ(closest_point_on_triangle(Vec3(1.5, 1, 2), a, b, c), Vec3(1.5, 1, 0)); // straight above: exact
}

TEST(SurfaceDistance, AgreesWithTestingEveryTriangle) {
  const Mesh face = sample_face({.spacing_mm = 4.0});
  const SurfaceDistance distance(face);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 300; ++k) {
    const Vec3 p(80 * u(rng), 110 * u(rng), 40 * u(rng));
    const double best = nearest_by_every_triangle(face, p);
    const auto n = distance.nearest(p);
    EXPECT_NEAR(n.distance, best, 1e-12 * (1.0 + best));
    EXPECT_NEAR((n.point - p).norm(), n.distance, 1e-12 * (1.0 + best));
  }
}

// Built on several threads, the hierarchy is the same: every answer the same to the bit, the triangle
// included where several are equally near (a query at a vertex is nearest to all its triangles, and the
// one the search meets first says which order the tree holds them in).
TEST(SurfaceDistance, BuiltOnThreadsIsTheSameHierarchy) {
  const Mesh face = sample_face({.spacing_mm = 0.8});
  ASSERT_GT(face.triangles.size(), 4U * 16384U); // split on threads at the root and below it
  const SurfaceDistance one(face);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> queries;
  for (std::size_t k = 0; k < 2000; ++k) {
    queries.push_back(face.positions[(k * 7919) % face.positions.size()]);
    queries.emplace_back(80 * u(rng), 110 * u(rng), 40 * u(rng));
  }
  for (const unsigned threads : {2U, 3U, 4U, 0U}) {
    const SurfaceDistance many(face, threads);
    for (const Vec3& q : queries) {
      const SurfaceDistance::Nearest a = one.nearest(q), b = many.nearest(q);
      ASSERT_EQ(a.triangle, b.triangle) << threads << " threads, " << q.transpose();
      ASSERT_EQ(a.point, b.point);
      ASSERT_EQ(a.distance, b.distance);
    }
  }
  for (std::size_t k = 0; k < 50; ++k)
    EXPECT_NEAR(one.distance(queries[2 * k + 1]), nearest_by_every_triangle(face, queries[2 * k + 1]), 1e-12);
}

// The hierarchy's boxes are float, rounded outwards: far from the origin, where a float's step (0.06 mm at
// 10^6) is larger than the queries' distances, every distance is still the exact one, to the bit of the
// brute force's. The queries lie just inside a triangle's edge, a hair above it: its neighbour across the
// edge is nearly as near, and a box rounded inwards would lose the triangle to it.
TEST(SurfaceDistance, ExactWhereItsFloatBoxesRound) {
  Mesh face = sample_face({.spacing_mm = 4.0});
  const Vec3 far(1.0e6, -3.3e5, 7.0e4);
  for (Vec3& p : face.positions)
    p += far;
  const SurfaceDistance distance(face);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t k = 0; k < 3000; ++k) {
    const Triangle& t = face.triangles[(k * 7919) % face.triangles.size()];
    const Vec3 &a = face.positions[t[k % 3]], &b = face.positions[t[(k + 1) % 3]],
               &c = face.positions[t[(k + 2) % 3]];
    const Vec3 on_edge = a + u(rng) * (b - a);
    const Vec3 inwards = (c - on_edge).normalized(), normal = (b - a).cross(c - a).normalized();
    const Vec3 p = on_edge + 0.002 * inwards + (k % 2 == 0 ? 0.0 : 0.001) * normal;
    const double best = nearest_by_every_triangle(face, p);
    ASSERT_EQ(distance.distance(p), best) << k;
  }
}

TEST(SurfaceDistance, PointCloudsMeasureToTheirPoints) {
  Mesh cloud;
  cloud.positions = {{0, 0, 0}, {10, 0, 0}};
  const SurfaceDistance distance(cloud);
  EXPECT_DOUBLE_EQ(distance.distance(Vec3(3, 4, 0)), 5.0); // too few points for a plane: to the point
  EXPECT_THROW(SurfaceDistance(Mesh{}), std::invalid_argument);
}

// A cloud sampled every 2 mm from the plane z = 0 is the plane: a query 0.1 mm above it between its
// points is 0.1 mm away (not the ~1.4 mm to the nearest point), a point of the cloud is at 0, and a
// query beyond the cloud's edge is measured to its nearest point.
TEST(SurfaceDistance, PointCloudsMeasureToTheirTangentPlanes) {
  Mesh cloud;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i)
      cloud.positions.emplace_back(2.0 * i, 2.0 * j, 0.0);
  const SurfaceDistance distance(cloud);
  EXPECT_NEAR(distance.distance(Vec3(11, 11, 0.1)), 0.1, 1e-9);
  EXPECT_NEAR(distance.distance(Vec3(11, 11, -0.3)), 0.3, 1e-9);
  EXPECT_NEAR((distance.nearest(Vec3(11, 11, 0.1)).point - Vec3(11, 11, 0)).norm(), 0.0, 1e-9);
  EXPECT_EQ(distance.distance(cloud.positions[200]), 0.0);
  EXPECT_NEAR(distance.distance(Vec3(60, 20, 0.1)), std::hypot(20.0, 0.1), 1e-9);
}

Mesh grid(int n, double step, double z) {
  Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.emplace_back(i * step, j * step, z);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto v = static_cast<std::uint32_t>(j * (n + 1) + i);
      const auto w = static_cast<std::uint32_t>(n + 1);
      m.triangles.push_back({v, v + 1, v + w + 1});
      m.triangles.push_back({v, v + w + 1, v + w});
    }
  return m;
}

TEST(SurfaceDistanceTwoSided, ParallelPlanesAreTheirGapApart) {
  const Mesh a = grid(20, 1.0, 0.0), b = grid(20, 1.0, 0.25);
  auto d = surface_distance(a, b, {.spacing = 0.3});
  ASSERT_TRUE(d.ok()) << d.error().to_string();
  for (const DistanceStats& s : {d->a_to_b, d->b_to_a, d->both}) {
    EXPECT_NEAR(s.mean, 0.25, 1e-12);
    EXPECT_NEAR(s.rms, 0.25, 1e-12);
    EXPECT_NEAR(s.p95, 0.25, 1e-12);
    EXPECT_NEAR(s.max, 0.25, 1e-12);
    EXPECT_GT(s.samples, 4000U); // 400 mm² at 0.3 mm spacing
  }
  EXPECT_NEAR(d->diagonal, std::sqrt(800.0), 1e-12);
  auto self = surface_distance(a, a);
  ASSERT_TRUE(self.ok());
  EXPECT_LT(self->both.max, 1e-12);
}

TEST(SurfaceDistanceTwoSided, RegionAndOneSidedExcess) {
  // b covers only half of a: from a, the uncovered half is far; from b, everything is close.
  const Mesh a = grid(20, 1.0, 0.0);
  Mesh b = grid(10, 1.0, 0.0);
  auto d = surface_distance(a, b, {.spacing = 0.5});
  ASSERT_TRUE(d.ok());
  EXPECT_LT(d->b_to_a.max, 1e-12);
  EXPECT_NEAR(d->a_to_b.max, std::sqrt(200.0), 1e-9); // the far corner (20, 20) to (10, 10)
  // Restricted to the part both cover, they agree.
  Box region;
  region.min = Vec3(-1, -1, -1);
  region.max = Vec3(10, 10, 1);
  auto r = surface_distance(a, b, {.spacing = 0.5, .region = region});
  ASSERT_TRUE(r.ok());
  EXPECT_LT(r->both.max, 1e-12);
  Box nowhere;
  nowhere.min = Vec3(100, 100, 100);
  nowhere.max = Vec3(101, 101, 101);
  EXPECT_EQ(surface_distance(a, b, {.region = nowhere}).error().code, ErrorCode::InvalidArgument);
}

TEST(Statistics, KnownValues) {
  std::vector<double> d(100);
  for (int i = 0; i < 100; ++i)
    d[static_cast<std::size_t>(i)] = i + 1; // 1..100
  const DistanceStats s = statistics(d);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_DOUBLE_EQ(s.rms, std::sqrt(338350.0 / 100.0));
  EXPECT_DOUBLE_EQ(s.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
  EXPECT_EQ(s.samples, 100U);
}

// Sampling within a box gives the whole sampling's points inside it, in order, whatever the box cuts:
// triangles across its sides, a side through vertices and samples, a box that holds nothing.
TEST(Sampling, WithinABoxIsTheWholeSamplingFiltered) {
  Mesh a = grid(12, 1.0, 0.0);
  for (Vec3& p : a.positions)
    p.z() = 0.3 * std::sin(p.x()) * std::cos(0.7 * p.y()); // no two samples share a depth by accident
  const std::vector<Vec3> all = sample_surface(a, 0.15);
  for (const Box& box :
       {Box{{2.5, 3.25, -1.0}, {7.3, 9.0, 1.0}}, Box{{3.0, 0.0, -0.1}, {6.0, 12.0, 0.1}},
        Box{{-5.0, -5.0, -5.0}, {20.0, 20.0, 5.0}}, Box{{20.0, 20.0, 0.0}, {30.0, 30.0, 1.0}},
        Box{{4.0, 4.0, -std::numeric_limits<double>::infinity()},
            {8.0, 5.0, std::numeric_limits<double>::infinity()}}}) {
    std::vector<Vec3> inside;
    std::ranges::copy_if(all, std::back_inserter(inside), [&](const Vec3& p) {
      return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
    });
    EXPECT_EQ(sample_surface(a, 0.15, box), inside) << box.min.transpose() << " .. " << box.max.transpose();
  }
}

TEST(Sampling, DenseEvenAndDeterministic) {
  const Mesh a = grid(10, 1.0, 0.0);
  const auto p = sample_surface(a, 0.2);
  EXPECT_EQ(p, sample_surface(a, 0.2));
  EXPECT_NEAR(static_cast<double>(p.size() - a.vertex_count()), 100.0 / 0.04,
              200.0 * 1.0); // ~ area / spacing²
  for (const Vec3& q : p) {
    EXPECT_GE(q.x(), 0.0);
    EXPECT_LE(q.x(), 10.0);
    EXPECT_EQ(q.z(), 0.0);
  }
}

} // namespace
} // namespace pdeface::metrics
