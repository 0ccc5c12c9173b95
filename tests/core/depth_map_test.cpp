// The depth map bounded whatever the coordinates and radii (they come from files): a splat or a blur wider
// than the grid costs at most the grid, coordinates beyond int's range are outside it.
#include "pdeface/core/depth_map.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

#include <cfloat>
#include <cmath>
#include <limits>
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

// A mesh's depth map the plain way: each triangle's cells from its own extreme coordinates (its box),
// each cell of the box whose centre it holds (barycentric coordinates above -1e-9) given the front-most
// depth. The map finds the boxes from bounds per vertex; it must be the same bits.
TEST(DepthMap, AMeshsMapIsEachTrianglesBoxTriedCellByCell) {
  const Mesh face = sample_face({.spacing_mm = 7.0});
  for (const double cell : {2.5, 1.3, 0.7}) {
    DepthMap map(-80.3, 79.1, -100.7, 90.2, cell);
    map.rasterise(face.positions, face.triangles, 1.0);
    Eigen::MatrixXd plain = Eigen::MatrixXd::Constant(map.rows(), map.cols(), std::nan(""));
    for (const Triangle& t : face.triangles) {
      const Vec3 &a = face.positions[t[0]], &b = face.positions[t[1]], &c = face.positions[t[2]];
      const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
      if (!(std::abs(area) >= 1e-12)) continue;
      const auto first = [&](double v, double origin) {
        return static_cast<int>(std::ceil((v - origin) / cell));
      };
      const auto last = [&](double v, double origin) {
        return static_cast<int>(std::floor((v - origin) / cell));
      };
      const int c0 = std::max(0, first(std::min({a.x(), b.x(), c.x()}), -80.3));
      const int c1 = std::min(map.cols() - 1, last(std::max({a.x(), b.x(), c.x()}), -80.3));
      const int r0 = std::max(0, first(std::min({a.y(), b.y(), c.y()}), -100.7));
      const int r1 = std::min(map.rows() - 1, last(std::max({a.y(), b.y(), c.y()}), -100.7));
      for (int r = r0; r <= r1; ++r)
        for (int col = c0; col <= c1; ++col) {
          const double x = map.x_of(col), y = map.y_of(r);
          const double wa = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) / area;
          const double wb = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) / area;
          const double wc = 1.0 - wa - wb;
          if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
          const double z = wa * a.z() + wb * b.z() + wc * c.z();
          if (std::isnan(plain(r, col)) || z > plain(r, col)) plain(r, col) = z;
        }
    }
    std::size_t covered = 0;
    for (int r = 0; r < map.rows(); ++r)
      for (int col = 0; col < map.cols(); ++col) {
        ASSERT_EQ(map.known(r, col), !std::isnan(plain(r, col))) << "cell " << r << ", " << col;
        if (!map.known(r, col)) continue;
        ++covered;
        ASSERT_EQ(map.z(r, col), plain(r, col)) << "cell " << r << ", " << col;
      }
    EXPECT_GT(covered, 1000U) << "cell " << cell;
  }
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

// Dropping the cells seen through holes the plain way: a known cell goes when the front-most known cell
// within the reach on both sides of it, along its row or along its column, lies more than `depth` in front
// of it. The map finds those fronts by sliding maxima; it must drop the same cells.
TEST(DepthMap, DropsTheCellsWithAFrontInReachOnBothSides) {
  for (const double cell : {1.0, 0.7}) {
    DepthMap map(-30.0, 32.0, -25.0, 21.0, cell);
    // One point per cell centre (a splat smaller than a cell: each cell its own point's depth): a wavy
    // surface, deep pits in a pattern no line of cells repeats, a few unknown cells.
    std::vector<Vec3> points;
    for (int r = 0; r < map.rows(); ++r)
      for (int c = 0; c < map.cols(); ++c) {
        if ((r * 7 + c * 3) % 17 == 0) continue;
        const bool pit = (r * 13 + c * 5) % 11 < 3 || (r / 9 + c / 7) % 5 == 0;
        const double z = 4.0 * std::sin(0.3 * r) + 3.0 * std::cos(0.2 * c) - (pit ? 6.0 + (r + c) % 4 : 0.0);
        points.emplace_back(map.x_of(c), map.y_of(r), z);
      }
    map.rasterise(points, {}, 0.4 * cell);
    const DepthMap before = map;
    constexpr double kDepth = 5.0, kReach = 6.0;
    map.drop_pits(kDepth, kReach);
    const int n = static_cast<int>(std::ceil(kReach / cell));
    const auto front = [&](int r, int c, int dr, int dc) {
      double best = -std::numeric_limits<double>::infinity();
      for (int k = 1; k <= n; ++k) {
        const int rr = r + k * dr, cc = c + k * dc;
        if (rr >= 0 && cc >= 0 && rr < before.rows() && cc < before.cols() && before.known(rr, cc))
          best = std::max(best, before.z(rr, cc));
      }
      return best;
    };
    int dropped = 0, kept = 0;
    for (int r = 0; r < map.rows(); ++r)
      for (int c = 0; c < map.cols(); ++c) {
        if (!before.known(r, c)) {
          ASSERT_FALSE(map.known(r, c));
          continue;
        }
        const double floor = before.z(r, c) + kDepth;
        const bool drop = (front(r, c, 0, -1) > floor && front(r, c, 0, 1) > floor) ||
                          (front(r, c, -1, 0) > floor && front(r, c, 1, 0) > floor);
        ASSERT_EQ(map.known(r, c), !drop) << "cell " << r << ", " << c;
        if (drop) {
          ++dropped;
        } else {
          ++kept;
          ASSERT_EQ(map.z(r, c), before.z(r, c));
        }
      }
    EXPECT_GT(dropped, 100) << "cell " << cell;
    EXPECT_GT(kept, 1000) << "cell " << cell;
  }
}

} // namespace
} // namespace pdeface
