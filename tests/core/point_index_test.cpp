#include "pdeface/core/point_index.hpp"

#include "pdeface/core/sample_face.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace pdeface {
namespace {

// Brute force, the definition the index must agree with.
std::vector<std::size_t> brute_within(const std::vector<Vec3>& points, const Vec3& q, double r) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < points.size(); ++i)
    if ((points[i] - q).norm() <= r) out.push_back(i);
  return out;
}

TEST(PointIndex, AgreesWithBruteForce) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const PointIndex index(face.positions);
  ASSERT_EQ(index.size(), face.vertex_count());
  for (const Vec3& q : {Vec3(0, 0, 30), Vec3(-31.3, 27.1, -5), Vec3(70, -90, -40), Vec3(500, 0, 0)}) {
    const auto nearest = index.nearest(q);
    double best = 1e300;
    for (const Vec3& p : face.positions)
      best = std::min(best, (p - q).norm());
    EXPECT_DOUBLE_EQ(nearest.distance, best);

    const auto five = index.nearest(q, 5);
    ASSERT_EQ(five.size(), 5U);
    EXPECT_TRUE(std::ranges::is_sorted(five, {}, &PointIndex::Neighbour::distance));
    EXPECT_EQ(five.front().index, nearest.index);

    auto found = index.within(q, 12.0);
    std::vector<std::size_t> ids;
    for (const auto& n : found)
      ids.push_back(n.index);
    std::ranges::sort(ids);
    EXPECT_EQ(ids, brute_within(face.positions, q, 12.0));
  }
}

// Visiting the points within a radius visits within's points, each once, with the squared distance whose
// root within gives.
TEST(PointIndex, VisitWithinVisitsWithinsPoints) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const PointIndex index(face.positions);
  for (const Vec3& q : {Vec3(0, 0, 30), Vec3(-31.3, 27.1, -5), Vec3(500, 0, 0)}) {
    std::vector<std::pair<std::size_t, double>> visited, listed;
    index.visit_within(q, 25.0,
                       [&](std::size_t i, double squared) { visited.emplace_back(i, std::sqrt(squared)); });
    for (const auto& n : index.within(q, 25.0))
      listed.emplace_back(n.index, n.distance);
    std::ranges::sort(visited);
    std::ranges::sort(listed);
    EXPECT_EQ(visited, listed);
  }
  std::size_t all = 0;
  index.visit_within(Vec3::Zero(), 1e6, [&](std::size_t, double) { ++all; });
  EXPECT_EQ(all, face.vertex_count());
}

// The k nearest into a buffer a loop re-uses are the k nearest returned, to the bit, for a few (found on
// the stack) and for many (more than the stack holds), and the buffer is replaced, not appended to.
TEST(PointIndex, NearestIntoABufferIsTheNearestReturned) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const PointIndex index(face.positions);
  std::vector<PointIndex::Neighbour> buffer(100, {7, 7.0});
  for (const Vec3& q : {Vec3(0, 0, 30), Vec3(-31.3, 27.1, -5), Vec3(500, 0, 0)})
    for (const std::size_t k : {1U, 2U, 8U, 16U, 17U, 40U}) {
      const std::vector<PointIndex::Neighbour> returned = index.nearest(q, k);
      index.nearest(q, k, buffer);
      ASSERT_EQ(buffer.size(), k);
      ASSERT_EQ(returned.size(), k);
      for (std::size_t i = 0; i < k; ++i) {
        EXPECT_EQ(buffer[i].index, returned[i].index) << "k " << k;
        EXPECT_EQ(buffer[i].distance, returned[i].distance) << "k " << k;
      }
      // The k-th nearest is no nearer than any point left out.
      std::vector<double> all;
      for (const Vec3& p : face.positions)
        all.push_back((p - q).norm());
      std::ranges::nth_element(all, all.begin() + static_cast<std::ptrdiff_t>(k - 1));
      EXPECT_DOUBLE_EQ(buffer.back().distance, all[k - 1]) << "k " << k;
    }
  index.nearest(Vec3(0, 0, 30), 3 * face.vertex_count(), buffer); // more than it holds: all of them
  EXPECT_EQ(buffer.size(), face.vertex_count());
}

// A search from a guess and a bounded one give what a full search gives, to the bit: the symmetry search
// relies on it to stay bit-exact (docs/performance.md).
TEST(PointIndex, SearchFromAGuessOrWithinABoundIsTheFullSearch) {
  const Mesh face = sample_face({.spacing_mm = 3.0});
  const PointIndex index(face.positions);
  const std::size_t far_guess = face.vertex_count() - 1;
  for (const Vec3& q : {Vec3(0, 0, 30), Vec3(-31.3, 27.1, -5), Vec3(70, -90, -40), Vec3(500, 0, 0)}) {
    const auto full = index.nearest(q);
    for (const std::size_t guess : {std::size_t{0}, far_guess, full.index}) {
      const auto from = index.nearest_from(q, guess);
      EXPECT_EQ(from.index, full.index);
      EXPECT_EQ(from.distance, full.distance); // the same bits, whichever search found it
    }
    EXPECT_FALSE(index.nearest_within(q, full.distance).has_value()); // "nearer than": not as near
    const auto within = index.nearest_within(q, full.distance * 1.01 + 1e-9);
    ASSERT_TRUE(within.has_value());
    EXPECT_EQ(within->index, full.index);
    EXPECT_EQ(within->distance, full.distance);
    EXPECT_EQ(index.nearest_within(q, std::numeric_limits<double>::infinity())->index, full.index);
  }
}

TEST(PointIndex, AskingForMoreNeighboursThanPoints) {
  const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}};
  const PointIndex index(points);
  EXPECT_EQ(index.nearest(Vec3(0.9, 0, 0), 10).size(), 2U);
}

} // namespace
} // namespace pdeface
