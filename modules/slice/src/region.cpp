#include "pdeface/slice/profiles.hpp"

#include <algorithm>

namespace pdeface::slice {

std::optional<std::array<double, 2>> CurveRegion::heights_at(double at) const {
  if (xs.empty() || at < xs.front() || at > xs.back()) return std::nullopt;
  const auto hi = std::upper_bound(xs.begin(), xs.end(), at);
  const auto j = hi == xs.end() ? xs.size() - 1 : static_cast<std::size_t>(hi - xs.begin());
  if (j == 0) return extents.front();
  const double span = xs[j] - xs[j - 1];
  const double w = span > 0.0 ? (at - xs[j - 1]) / span : 1.0;
  return std::array<double, 2>{extents[j - 1][0] + w * (extents[j][0] - extents[j - 1][0]),
                               extents[j - 1][1] + w * (extents[j][1] - extents[j - 1][1])};
}

bool CurveRegion::filled_at(double at, double y) const {
  if (xs.empty() || holes.size() != xs.size() || at < xs.front() || at > xs.back()) return false;
  const auto hi = std::upper_bound(xs.begin(), xs.end(), at);
  const auto j =
      hi == xs.end() ? xs.size() - 1 : std::max<std::size_t>(1, static_cast<std::size_t>(hi - xs.begin()));
  const double span = xs[j] - xs[j - 1];
  const double w = span > 0.0 ? (at - xs[j - 1]) / span : 1.0;
  auto in = [&](std::size_t k) {
    return std::ranges::any_of(holes[k], [&](const auto& h) { return y > h[0] && y < h[1]; }) ? 1.0 : 0.0;
  };
  return (1.0 - w) * in(j - 1) + w * in(j) >= 0.5;
}

std::array<double, 2> CurveRegion::span_along(const Eigen::Vector2d& o, const Eigen::Vector2d& d) const {
  auto inside = [&](double t) { return contains(o.x() + t * d.x(), o.y() + t * d.y()); };
  if (!inside(0.0)) return {1.0, 0.0};
  std::array<double, 2> out{};
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;
    double in = 0.0, step = 0.5;
    while (inside(sign * (in + step)) && in < 1000.0)
      in += step;
    double out_t = in + step; // inside at `in`, outside at `out_t`: bisect
    for (int k = 0; k < 30; ++k) {
      const double mid = 0.5 * (in + out_t);
      (inside(sign * mid) ? in : out_t) = mid;
    }
    out[side] = sign * in;
  }
  return out;
}

CurveRegion ProfileSet::region() const {
  CurveRegion r;
  for (const ProfileCurve& c : curves) {
    r.xs.push_back(c.x);
    r.extents.push_back(c.extent);
    r.holes.push_back(c.holes);
  }
  return r;
}

std::size_t ProfileSet::holes() const {
  std::size_t n = 0;
  for (const ProfileCurve& c : curves)
    n += c.holes.size();
  return n;
}

double ProfileSet::longest_hole_mm() const {
  double longest = 0.0;
  for (const ProfileCurve& c : curves)
    longest = std::max(longest, c.longest_bridge_mm);
  return longest;
}

} // namespace pdeface::slice
