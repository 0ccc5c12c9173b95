// The mirror-symmetry measures inside align (modules/align/src/symmetry.hpp) against their definitions:
// the trimmed mirror RMS searches most points only within a bound (docs/performance.md), which must not
// change what it measures.

#include "symmetry.hpp"

#include "pdeface/core/point_index.hpp"
#include "pdeface/core/sample_face.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

namespace pdeface::align::detail {
namespace {

// The definition: every point's distance to the nearest indexed point, the smallest share `keep` of them.
double brute_mirror_rms(const Mirror& m, const std::vector<Vec3>& points, const std::vector<Vec3>& all,
                        double keep) {
  std::vector<double> d;
  for (const Vec3& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& q : all)
      best = std::min(best, (m(p) - q).norm());
    d.push_back(best);
  }
  std::ranges::sort(d);
  const auto n = std::max<std::size_t>(1, static_cast<std::size_t>(keep * static_cast<double>(d.size())));
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum += d[i] * d[i];
  return std::sqrt(sum / static_cast<double>(n));
}

TEST(Symmetry, TrimmedMirrorRmsIsItsDefinitionOnGoodAndBadPlanes) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const PointIndex index(face.positions);
  const std::vector<Vec3> probe = thin(face.positions, 300);
  // The face's own plane (x = 0), planes a little and far off it, and one that mirrors the face into the
  // air, where every search would run long unbounded.
  const std::vector<Plane> planes{{Vec3::UnitX(), 0.0},
                                  {Vec3(1.0, 0.1, 0.0).normalized(), 2.0},
                                  {Vec3(0.3, 1.0, 0.2).normalized(), -10.0},
                                  {Vec3::UnitZ(), 300.0}};
  for (const Plane& plane : planes)
    for (const double keep : {0.7, 0.8, 0.95, 1.0, 0.001}) {
      const double rms = mirror_rms(mirror_of(plane), probe, index, keep);
      const double expected = brute_mirror_rms(mirror_of(plane), probe, face.positions, keep);
      EXPECT_NEAR(rms, expected, 1e-12 * std::max(1.0, expected))
          << "plane offset " << plane.offset << ", keep " << keep;
    }
  // A few points far out among near ones, none of them among the points that set the first bound (every
  // 16th): with keep 1 they count, however many times the bound must grow.
  std::vector<Vec3> outliers = probe;
  for (std::size_t i = 5; i < outliers.size(); i += 50)
    outliers[i] = Vec3(1e7, 0.0, 0.0);
  for (const double keep : {1.0, 0.99, 0.7}) {
    const double rms = mirror_rms(mirror_of(planes[0]), outliers, index, keep);
    const double expected = brute_mirror_rms(mirror_of(planes[0]), outliers, face.positions, keep);
    EXPECT_NEAR(rms, expected, 1e-12 * std::max(1.0, expected)) << "outliers, keep " << keep;
  }
  EXPECT_TRUE(std::isinf(mirror_rms(mirror_of(planes[0]), {}, index, 0.7)));
}

// One point per occupied voxel: the first of each, in the order the points come (its plain definition, with
// a set of voxels), on points on both sides of every axis (negative voxel coordinates) and repeated ones.
TEST(Symmetry, VoxelSubsampleKeepsTheFirstPointOfEachVoxel) {
  Mesh face = sample_face({.spacing_mm = 1.0});
  for (std::size_t i = 0; i < face.positions.size(); i += 5)
    face.positions.push_back(-face.positions[i]);   // the other octants
  face.positions.push_back(face.positions.front()); // a repeat
  for (const double cell : {0.7, 3.0, 25.0}) {
    std::set<std::array<std::int64_t, 3>> seen;
    std::vector<Vec3> want;
    for (const Vec3& p : face.positions) {
      const Eigen::Vector3d k = (p / cell).array().floor();
      if (seen.insert({static_cast<std::int64_t>(k.x()), static_cast<std::int64_t>(k.y()),
                       static_cast<std::int64_t>(k.z())})
              .second)
        want.push_back(p);
    }
    const std::vector<Vec3> got = voxel_subsample(face.positions, cell);
    ASSERT_EQ(got.size(), want.size()) << "cell " << cell;
    for (std::size_t i = 0; i < got.size(); ++i)
      ASSERT_EQ(got[i], want[i]) << "cell " << cell << ", point " << i;
  }
  EXPECT_TRUE(voxel_subsample({}, 1.0).empty());
}

// A patch subsampled without listing its points is the subsample of the listed points, nearest first.
TEST(Symmetry, VoxelSubsampleWithinIsTheSubsampleOfThePointsWithin) {
  const Mesh face = sample_face({.spacing_mm = 1.5});
  const PointIndex index(face.positions);
  for (const double cell : {0.7, 3.0, 25.0})
    for (const Vec3& centre : {Vec3(3.3, 1.7, 30), Vec3(-20.1, 35.3, 10.7)}) { // no two points equally near
      std::vector<Vec3> listed;
      for (const auto& n : index.within(centre, 60.0))
        listed.push_back(face.positions[n.index]);
      const std::vector<Vec3> want = voxel_subsample(listed, cell);
      const std::vector<Vec3> got = voxel_subsample_within(index, face.positions, centre, 60.0, cell);
      ASSERT_GT(want.size(), 1U);
      EXPECT_EQ(got, want) << "cell " << cell;
    }
  EXPECT_TRUE(voxel_subsample_within(index, face.positions, Vec3(1e4, 0, 0), 1.0, 1.0).empty());
}

// The grid's distance is a point's distance (never less than the nearest's), the nearest's for queries near
// the set (within a cell: what ranks good planes), and close to it far away (where only "far" matters).
TEST(Symmetry, NearGridDistancesAreTheNearestPointsNearTheSet) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const std::vector<Vec3> sample = voxel_subsample(face.positions, 3.0);
  const PointIndex index(sample);
  const NearGrid grid(sample, 3.0);
  std::size_t near = 0, exact = 0;
  for (std::size_t i = 0; i < face.positions.size(); i += 7)
    for (const Vec3& shift :
         {Vec3(0.4, -0.7, 1.1), Vec3(-2.0, 1.5, 0.5), Vec3(15.0, -20.0, 30.0), Vec3(0.0, 0.0, 400.0)}) {
      const Vec3 q = face.positions[i] + shift;
      const double want = index.nearest(q).distance;
      const double got = grid.distance(q);
      EXPECT_GE(got, want - 1e-3);
      if (shift.norm() < 3.0) {
        ++near;
        if (got - want < 1e-3) ++exact;
        EXPECT_LT(got - want, 0.5 * grid.cell());
      } else {
        EXPECT_LT(got, want + 0.25 * want + grid.cell());
      }
    }
  EXPECT_GT(static_cast<double>(exact), 0.95 * static_cast<double>(near));
  const Mirror off = mirror_of({Vec3(1.0, 0.1, 0.0).normalized(), 2.0});
  const std::vector<Vec3> probe = thin(sample, 300);
  EXPECT_NEAR(mirror_rms(off, probe, grid), mirror_rms(off, probe, index), 0.05);
}

} // namespace
} // namespace pdeface::align::detail
