#include "pdeface/metrics/profile_error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pdeface::metrics {
namespace {

TEST(ProfileError, DistanceToSegmentsAndPoints) {
  const std::vector<Polyline> lines{{Vec3(0, 0, 0), Vec3(10, 0, 0)}, {Vec3(20, 5, 0)}};
  EXPECT_DOUBLE_EQ(distance_to_polylines(Vec3(3, 4, 0), lines), 4.0);  // above the segment's interior
  EXPECT_DOUBLE_EQ(distance_to_polylines(Vec3(-3, 4, 0), lines), 5.0); // beyond its end: to the end point
  EXPECT_DOUBLE_EQ(distance_to_polylines(Vec3(20, 8, 0), lines), 3.0); // to the lone point
  EXPECT_TRUE(std::isinf(distance_to_polylines(Vec3(0, 0, 0), {})));
}

TEST(ProfileError, MeanOverTheReconstructedPoints) {
  // An original profile along y, and a reconstruction offset by 1 mm then 3 mm in z.
  const std::vector<Polyline> original{{Vec3(0, -50, 0), Vec3(0, 0, 0), Vec3(0, 50, 0)}};
  const std::vector<Polyline> rebuilt{{Vec3(0, -40, 1), Vec3(0, -10, 1), Vec3(0, 20, 3), Vec3(0, 40, 3)}};
  EXPECT_DOUBLE_EQ(profile_error(rebuilt, original), 2.0);
  EXPECT_TRUE(std::isnan(profile_error({}, original)));
  EXPECT_TRUE(std::isnan(profile_error(rebuilt, {})));
}

} // namespace
} // namespace pdeface::metrics
