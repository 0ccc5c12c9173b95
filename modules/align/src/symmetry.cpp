#include "symmetry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

namespace pdeface::align::detail {

Mirror mirror_of(const Plane& plane) {
  return {Eigen::Matrix3d::Identity() - 2.0 * plane.normal * plane.normal.transpose(),
          2.0 * plane.offset * plane.normal};
}

Plane plane_of(const Mirror& m, std::span<const Vec3> points) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (m.a + m.a.transpose()));
  const Vec3 n = eig.eigenvectors().col(0).normalized();
  double offset = 0.0;
  for (const Vec3& p : points)
    offset += n.dot(0.5 * (p + m(p)));
  return {n, offset / static_cast<double>(points.size())};
}

double mirror_rms(const Mirror& m, std::span<const Vec3> points, const PointIndex& index, double keep) {
  if (points.empty()) return std::numeric_limits<double>::infinity();
  const std::size_t count = points.size();
  const auto n = std::max<std::size_t>(1, static_cast<std::size_t>(keep * static_cast<double>(count)));
  // Only the n nearest distances count; a farther point need only be known to be farther, and the search
  // for a far point (a wrong plane mirrors much of the scan into the air) ends early when it is bounded.
  // So every 16th point is searched in full, the bound is a little over the share `keep` of their
  // distances, and the rest are searched within it, those not found within it again with a bound four
  // times larger, until n points are nearer than the bound: then no point left out can be among them.
  constexpr std::size_t kStride = 16;
  constexpr double kMargin = 1.5;
  constexpr double kGrowth = 4.0;
  constexpr int kBoundedPasses = 6; // then unbounded
  std::vector<double> d(count, std::numeric_limits<double>::infinity());
  std::vector<double> first;
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < count; ++i)
    if (i % kStride == 0) {
      d[i] = index.nearest(m(points[i])).distance;
      first.push_back(d[i]);
    } else {
      open.push_back(i);
    }
  const auto at =
      std::min(first.size() - 1, static_cast<std::size_t>(keep * static_cast<double>(first.size())));
  std::ranges::nth_element(first, first.begin() + static_cast<std::ptrdiff_t>(at));
  double bound = first[at] > 0.0 ? kMargin * first[at] : std::numeric_limits<double>::infinity();
  for (int pass = 0; !open.empty(); ++pass) {
    if (pass == kBoundedPasses) bound = std::numeric_limits<double>::infinity();
    std::size_t still_open = 0;
    for (const std::size_t i : open)
      if (const auto nn = index.nearest_within(m(points[i]), bound))
        d[i] = nn->distance;
      else
        open[still_open++] = i;
    open.resize(still_open);
    if (std::ranges::count_if(d, [&](double x) { return x < bound; }) >= static_cast<std::ptrdiff_t>(n))
      break;
    bound *= kGrowth;
  }
  // The n smallest, summed smallest first (whatever order the selection left them in).
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(n - 1));
  std::sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n));
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum += d[i] * d[i];
  return std::sqrt(sum / static_cast<double>(n));
}

Mirror refine(Mirror m, std::span<const Vec3> points, std::span<const Vec3> all, const PointIndex& index,
              double keep, int iterations, double still) {
  const auto n = points.size();
  if (n < 3) return m;
  Eigen::Matrix3Xd src(3, static_cast<Eigen::Index>(n)), dst(3, static_cast<Eigen::Index>(n));
  std::vector<std::pair<double, std::size_t>> order(n);
  std::vector<Vec3> moved(n), target(n);
  // Each point's nearest neighbour in the last step: a step moves the points little, so the search starts
  // from it (the same answer, found sooner).
  std::vector<std::size_t> last(n);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    for (std::size_t i = 0; i < n; ++i) {
      moved[i] = m(points[i]);
      const auto nn = iteration == 0 ? index.nearest(moved[i]) : index.nearest_from(moved[i], last[i]);
      last[i] = nn.index;
      target[i] = all[nn.index];
      order[i] = {nn.distance, i};
    }
    const std::size_t kept =
        std::max<std::size_t>(3, static_cast<std::size_t>(keep * static_cast<double>(n)));
    std::ranges::nth_element(order, order.begin() + static_cast<std::ptrdiff_t>(kept - 1));
    for (std::size_t j = 0; j < kept; ++j) {
      src.col(static_cast<Eigen::Index>(j)) = moved[order[j].second];
      dst.col(static_cast<Eigen::Index>(j)) = target[order[j].second];
    }
    const auto k = static_cast<Eigen::Index>(kept);
    const Eigen::Matrix4d t = Eigen::umeyama(src.leftCols(k), dst.leftCols(k), false);
    const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
    m = {r * m.a, r * m.b + t.topRightCorner<3, 1>()};
    if (Eigen::AngleAxisd(r).angle() < 1e-4 && t.topRightCorner<3, 1>().norm() < still) break;
  }
  return m;
}

std::vector<Vec3> fibonacci_directions(int count, bool whole_sphere) {
  std::vector<Vec3> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double t = (i + 0.5) / count;
    const double z = whole_sphere ? 1.0 - 2.0 * t : 1.0 - t;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

std::vector<Vec3> voxel_subsample(std::span<const Vec3> points, double cell) {
  std::unordered_map<std::uint64_t, std::size_t> seen;
  std::vector<Vec3> out;
  for (const Vec3& p : points) {
    const Eigen::Vector3d k = (p / cell).array().floor();
    const auto key = (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.x()) & 0x1FFFFF) << 42U) |
                     (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.y()) & 0x1FFFFF) << 21U) |
                     (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.z()) & 0x1FFFFF));
    if (seen.emplace(key, out.size()).second) out.push_back(p);
  }
  return out;
}

std::vector<Vec3> thin(std::span<const Vec3> points, std::size_t count) {
  const std::size_t step = std::max<std::size_t>(1, points.size() / std::max<std::size_t>(count, 1));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < points.size(); i += step)
    out.push_back(points[i]);
  return out;
}

double median_spacing(std::span<const Vec3> points, const PointIndex& index) {
  std::vector<double> d;
  for (const Vec3& p : thin(points, 400))
    d.push_back(index.nearest(p, 2).back().distance);
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2));
  return d[d.size() / 2];
}

} // namespace pdeface::align::detail
