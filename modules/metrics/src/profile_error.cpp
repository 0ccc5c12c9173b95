#include "pdeface/metrics/profile_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::metrics {

double distance_to_polylines(const Vec3& p, std::span<const Polyline> lines) {
  double best = std::numeric_limits<double>::infinity();
  for (const Polyline& line : lines) {
    if (line.size() == 1) best = std::min(best, (p - line[0]).norm());
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Vec3 ab = line[i + 1] - line[i];
      const double length2 = ab.squaredNorm();
      const double t = length2 > 0.0 ? std::clamp((p - line[i]).dot(ab) / length2, 0.0, 1.0) : 0.0;
      best = std::min(best, (p - (line[i] + t * ab)).norm());
    }
  }
  return best;
}

double profile_error(std::span<const Polyline> reconstructed, std::span<const Polyline> original) {
  double sum = 0.0;
  std::size_t n = 0;
  for (const Polyline& line : reconstructed)
    for (const Vec3& p : line) {
      sum += distance_to_polylines(p, original);
      ++n;
    }
  if (n == 0 || original.empty()) return std::numeric_limits<double>::quiet_NaN();
  return sum / static_cast<double>(n);
}

} // namespace pdeface::metrics
