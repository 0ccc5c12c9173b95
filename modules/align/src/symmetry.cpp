#include "symmetry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

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

NearGrid::NearGrid(std::span<const Vec3> points, double cell) : points_(points), cell_(cell) {
  if (points.empty() || !(cell > 0.0)) throw std::invalid_argument("NearGrid: no points, or a cell <= 0");
  Vec3 lo = points.front(), hi = lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  constexpr int kMargin = 2;
  constexpr double kMostCells = 2e6;
  const auto dims_for = [&](double c) {
    std::array<int, 3> d{};
    for (int k = 0; k < 3; ++k)
      d[static_cast<std::size_t>(k)] = static_cast<int>(std::ceil((hi[k] - lo[k]) / c)) + 1 + 2 * kMargin;
    return d;
  };
  const auto cells = [](const std::array<int, 3>& d) { return double(d[0]) * double(d[1]) * double(d[2]); };
  dims_ = dims_for(cell_);
  while (cells(dims_) > kMostCells) {
    cell_ *= std::cbrt(cells(dims_) / kMostCells) * 1.01;
    dims_ = dims_for(cell_);
  }
  origin_ = lo - Vec3::Constant(kMargin * cell_);
  const int nx = dims_[0], ny = dims_[1], nz = dims_[2];
  const std::size_t total =
      static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  constexpr float kNone = std::numeric_limits<float>::infinity();
  site_.assign(total, Eigen::Vector3f::Constant(kNone));
  std::vector<float> d2(total, kNone);
  const auto centre = [&](int x, int y, int z) {
    return Eigen::Vector3f(static_cast<float>(x * cell_), static_cast<float>(y * cell_),
                           static_cast<float>(z * cell_));
  };
  const auto at = [&](int x, int y, int z) {
    return (static_cast<std::size_t>(z) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(x);
  };
  for (const Vec3& p : points) {
    const Vec3 u = (p - origin_) / cell_;
    const int x = static_cast<int>(std::lround(u.x())), y = static_cast<int>(std::lround(u.y())),
              z = static_cast<int>(std::lround(u.z()));
    const Eigen::Vector3f f = (p - origin_).cast<float>();
    const std::size_t i = at(x, y, z);
    if (const float e = (f - centre(x, y, z)).squaredNorm(); e < d2[i]) {
      d2[i] = e;
      site_[i] = f;
    }
  }
  // The 13 neighbours before a cell in raster order (z, then y, then x); the pass back uses their opposites.
  std::array<std::array<int, 3>, 13> before{};
  std::size_t n = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dz < 0 || (dz == 0 && (dy < 0 || (dy == 0 && dx < 0)))) before[n++] = {dx, dy, dz};
  std::array<std::ptrdiff_t, 13> step{}; // the same neighbours as offsets in site_
  for (std::size_t k = 0; k < before.size(); ++k)
    step[k] = (static_cast<std::ptrdiff_t>(before[k][2]) * ny + before[k][1]) * nx + before[k][0];
  const auto visit = [&](int x, int y, int z, int sign) {
    const std::size_t i = at(x, y, z);
    const Eigen::Vector3f c = centre(x, y, z);
    const auto offer = [&](std::size_t j) {
      const Eigen::Vector3f& s = site_[j];
      if (const float e = (s - c).squaredNorm(); e < d2[i]) { // an empty cell's inf never wins
        d2[i] = e;
        site_[i] = s;
      }
    };
    if (x > 0 && y > 0 && z > 0 && x + 1 < nx && y + 1 < ny && z + 1 < nz) {
      for (const std::ptrdiff_t o : step)
        offer(static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + sign * o));
      return;
    }
    for (const auto& o : before) {
      const int ax = x + sign * o[0], ay = y + sign * o[1], az = z + sign * o[2];
      if (ax < 0 || ay < 0 || az < 0 || ax >= nx || ay >= ny || az >= nz) continue;
      offer(at(ax, ay, az));
    }
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        visit(x, y, z, 1);
  for (int z = nz - 1; z >= 0; --z)
    for (int y = ny - 1; y >= 0; --y)
      for (int x = nx - 1; x >= 0; --x)
        visit(x, y, z, -1);
}

double NearGrid::distance(const Vec3& q) const {
  const Vec3 local = q - origin_;
  const Vec3 u = local / cell_;
  std::array<int, 3> i0{};
  for (int k = 0; k < 3; ++k) {
    const int top = dims_[static_cast<std::size_t>(k)] - 2;
    const double f = std::floor(std::clamp(u[k], 0.0, static_cast<double>(top)));
    i0[static_cast<std::size_t>(k)] = static_cast<int>(f);
  }
  const auto nx = static_cast<std::size_t>(dims_[0]), ny = static_cast<std::size_t>(dims_[1]);
  double best = std::numeric_limits<double>::infinity();
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy) {
      const std::size_t row =
          (static_cast<std::size_t>(i0[2] + dz) * ny + static_cast<std::size_t>(i0[1] + dy)) * nx +
          static_cast<std::size_t>(i0[0]);
      for (std::size_t dx = 0; dx < 2; ++dx)
        best = std::min(best, (site_[row + dx].cast<double>() - local).squaredNorm());
    }
  return std::sqrt(best);
}

double mirror_rms(const Mirror& m, std::span<const Vec3> points, const NearGrid& grid, double keep) {
  if (points.empty()) return std::numeric_limits<double>::infinity();
  const auto n =
      std::max<std::size_t>(1, static_cast<std::size_t>(keep * static_cast<double>(points.size())));
  std::vector<double> d;
  d.reserve(points.size());
  for (const Vec3& p : points)
    d.push_back(grid.distance(m(p)));
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(n - 1));
  std::sort(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n));
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum += d[i] * d[i];
  return std::sqrt(sum / static_cast<double>(n));
}

namespace {

// The squared distance as nanoflann measures it (the same sum in the same order), so that an answer
// found among cached neighbours has the same bits as one the tree found.
double squared_as_the_tree(const Vec3& q, const Vec3& p) {
  double result = 0.0;
  for (Eigen::Index i = 0; i < 3; ++i) {
    const double diff = q[i] - p[i];
    result += diff * diff;
  }
  return result;
}

} // namespace

Mirror refine(Mirror m, std::span<const Vec3> points, std::span<const Vec3> all, const PointIndex& index,
              double keep, int iterations, double still) {
  const auto n = points.size();
  if (n < 3) return m;
  Eigen::Matrix3Xd src(3, static_cast<Eigen::Index>(n)), dst(3, static_cast<Eigen::Index>(n));
  std::vector<std::pair<double, std::size_t>> order(n);
  std::vector<Vec3> moved(n), target(n);
  // A step moves the points little (but for the first). At the second step each point keeps the kCached
  // points nearest to it
  // (`from`: where it was then), and the distance of the farthest of them (`reach`): every other point is
  // at least reach - |q - from| from the point's new place q, so when the nearest cached one is nearer
  // than that, it is the nearest of all (the same answer as a search, with its bits), found with kCached
  // subtractions instead of a search (~90 % of the later steps' queries on facefuns_f18). Else the tree is
  // searched from the last answer (a search for the cache costs several of those: it is not renewed).
  constexpr std::size_t kCached = 8;
  const std::size_t cached = std::min(kCached, all.size());
  std::vector<std::size_t> near(n * cached);
  std::vector<double> reach(n);
  std::vector<Vec3> from(n);
  std::vector<std::size_t> last(n);
  std::vector<PointIndex::Neighbour> found;
  const auto search = [&](std::size_t i) {
    index.nearest(moved[i], cached, found);
    for (std::size_t k = 0; k < cached; ++k)
      near[i * cached + k] = found[std::min(k, found.size() - 1)].index;
    reach[i] = found.back().distance;
    from[i] = moved[i];
    return found.front();
  };
  for (int iteration = 0; iteration < iterations; ++iteration) {
    for (std::size_t i = 0; i < n; ++i) {
      moved[i] = m(points[i]);
      PointIndex::Neighbour nn{};
      bool known = false;
      if (iteration > 1) {
        // The last answer first: it wins a tie, as in a search from it.
        std::size_t best = last[i];
        double best2 = squared_as_the_tree(moved[i], all[best]);
        for (std::size_t k = 0; k < cached; ++k) {
          const std::size_t j = near[i * cached + k];
          if (const double d2 = squared_as_the_tree(moved[i], all[j]); d2 < best2) {
            best2 = d2;
            best = j;
          }
        }
        // (less a hair, so that rounding never lets a point beyond the cached ones tie or win)
        const double margin = (reach[i] - (moved[i] - from[i]).norm()) * (1.0 - 1e-9);
        if (margin > 0.0 && best2 < margin * margin) {
          nn = {best, std::sqrt(best2)};
          known = true;
        }
      }
      if (!known)
        nn = iteration == 0   ? index.nearest(moved[i])
             : iteration == 1 ? search(i)
                              : index.nearest_from(moved[i], last[i]);
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

namespace {

// A voxel's key: 21 bits an axis, never all ones (the tables' empty slot).
constexpr std::uint64_t kNoVoxel = ~std::uint64_t{0};
std::uint64_t voxel_key(const Vec3& p, double cell) {
  const Eigen::Vector3d k = (p / cell).array().floor();
  return (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.x()) & 0x1FFFFF) << 42U) |
         (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.y()) & 0x1FFFFF) << 21U) |
         (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.z()) & 0x1FFFFF));
}
// Its slot in an open-addressing table of 2^bits slots (Fibonacci hashing, then the next free one).
std::size_t voxel_slot(const std::vector<std::uint64_t>& keys, std::uint64_t key, unsigned bits) {
  auto slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> (64U - bits));
  while (keys[slot] != kNoVoxel && keys[slot] != key)
    slot = (slot + 1) & (keys.size() - 1);
  return slot;
}

} // namespace

std::vector<Vec3> voxel_subsample(std::span<const Vec3> points, double cell) {
  // The voxels seen so far in a table at most half full: no allocation a point.
  unsigned bits = 4;
  while ((std::size_t{1} << bits) < 2 * points.size())
    ++bits;
  std::vector<std::uint64_t> seen(std::size_t{1} << bits, kNoVoxel);
  std::vector<Vec3> out;
  for (const Vec3& p : points) {
    const std::uint64_t key = voxel_key(p, cell);
    const std::size_t slot = voxel_slot(seen, key, bits);
    if (seen[slot] == kNoVoxel) {
      seen[slot] = key;
      out.push_back(p);
    }
  }
  return out;
}

std::vector<Vec3> voxel_subsample_within(const PointIndex& index, std::span<const Vec3> positions,
                                         const Vec3& centre, double radius, double cell) {
  // Each voxel's point nearest the centre (the first of it in nearest-first order; of equally near ones
  // the first indexed), in a table kept at most half full, grown as voxels come.
  struct Pick {
    double squared;
    std::size_t index;
    bool operator<(const Pick& o) const {
      return squared < o.squared || (squared == o.squared && index < o.index);
    }
  };
  unsigned bits = 10;
  std::vector<std::uint64_t> keys(std::size_t{1} << bits, kNoVoxel);
  std::vector<Pick> picks(keys.size());
  std::size_t used = 0;
  index.visit_within(centre, radius, [&](std::size_t i, double squared) {
    const std::uint64_t key = voxel_key(positions[i], cell);
    std::size_t slot = voxel_slot(keys, key, bits);
    if (keys[slot] == key) {
      picks[slot] = std::min(picks[slot], Pick{squared, i});
      return;
    }
    if (2 * (used + 1) > keys.size()) { // grow: every key to its slot in a table twice as large
      std::vector<std::uint64_t> old_keys(std::size_t{1} << (bits + 1), kNoVoxel);
      std::vector<Pick> old_picks(old_keys.size());
      old_keys.swap(keys);
      old_picks.swap(picks);
      ++bits;
      for (std::size_t k = 0; k < old_keys.size(); ++k)
        if (old_keys[k] != kNoVoxel) {
          const std::size_t to = voxel_slot(keys, old_keys[k], bits);
          keys[to] = old_keys[k];
          picks[to] = old_picks[k];
        }
      slot = voxel_slot(keys, key, bits);
    }
    keys[slot] = key;
    picks[slot] = {squared, i};
    ++used;
  });
  std::vector<Pick> chosen;
  chosen.reserve(used);
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (keys[k] != kNoVoxel) chosen.push_back(picks[k]);
  std::sort(chosen.begin(), chosen.end());
  std::vector<Vec3> out;
  out.reserve(chosen.size());
  for (const Pick& c : chosen)
    out.push_back(positions[c.index]);
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
  std::vector<PointIndex::Neighbour> found;
  for (const Vec3& p : thin(points, 400)) {
    index.nearest(p, 2, found);
    d.push_back(found.back().distance);
  }
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2));
  return d[d.size() / 2];
}

} // namespace pdeface::align::detail
