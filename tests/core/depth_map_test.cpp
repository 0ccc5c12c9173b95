// The depth map bounded whatever the coordinates and radii (they come from files): a splat or a blur wider
// than the grid costs at most the grid, coordinates beyond int's range are outside it.
#include "pdeface/core/depth_map.hpp"

#include "pdeface_test.hpp"

#include <cfloat>
#include <vector>

namespace pdeface {
namespace {

TEST(DepthMap, AHugeSplatCoversTheGridOnce) {
  DepthMap map(-10.0, 10.0, -10.0, 10.0, 1.0);
  const std::vector<Vec3> points{{0.0, 0.0, 5.0}};
  map.rasterise(points, {}, 1e12); // was (2e12)^2 cells visited
  EXPECT_EQ(map.at(-10.0, -10.0), 5.0);
  EXPECT_EQ(map.at(10.0, 10.0), 5.0);
}

TEST(DepthMap, PointsAndTrianglesFarOutsideTheGridAreIgnored) {
  DepthMap map(-10.0, 10.0, -10.0, 10.0, 1.0);
  const std::vector<Vec3> points{{1e300, -1e300, 1.0}, {-DBL_MAX, DBL_MAX, 1.0}, {1e12, 0.0, 1.0}};
  map.rasterise(points, {}, 2.0);
  const std::vector<Triangle> triangles{{0, 1, 2}};
  map.rasterise(points, triangles, 2.0);
  EXPECT_FALSE(map.at(0.0, 0.0));
  EXPECT_FALSE(map.at(1e300, 0.0));
  EXPECT_FALSE(map.relief(-1e300, 0.0, 1e300));
}

TEST(DepthMap, ABlurWiderThanTheGridIsTheMean) {
  DepthMap map(-10.0, 10.0, -10.0, 10.0, 1.0);
  const std::vector<Vec3> points{{-5.0, 0.0, 0.0}, {5.0, 0.0, 2.0}};
  map.rasterise(points, {}, 1.0);
  const DepthMap blurred = map.smoothed(1e15); // was a kernel of 6e15 taps
  ASSERT_TRUE(blurred.at(-5.0, 0.0));
  EXPECT_NEAR(*blurred.at(-5.0, 0.0), 1.0, 1e-9);
  EXPECT_NEAR(*blurred.at(5.0, 0.0), 1.0, 1e-9);
}

} // namespace
} // namespace pdeface
