#include "encode_check.hpp"

#include "pdeface/metrics/front_view.hpp"
#include "pdeface/metrics/surface_distance.hpp"

#include <fmt/format.h>

#include <limits>
#include <string>

namespace pdeface::pipeline {

Result<metrics::SelfCheck> encode_check(const Mesh& scan, const slice::ProfileSet& profiles,
                                        const Mesh& result, const metrics::CheckLimits& limits, bool force,
                                        std::string_view source) {
  const auto refused = [&](const std::string& why) -> Result<metrics::SelfCheck> {
    if (force) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return metrics::SelfCheck{nan, nan, nan, {why}};
    }
    return make_error(
        ErrorCode::SelfCheck,
        fmt::format("the result is off, so it was not written: {} (--force writes it anyway)", why),
        std::string(source));
  };
  if (scan.positions.empty()) return refused("the scan is empty");
  if (result.positions.empty()) return refused("coverage: a mesh is empty");
  // What `metrics::FaceYardstick` measures, on a coarser grid: the scan's front-most surface inside the
  // mask (one sample per cell of its front view) → the result, and the result's vertices and area samples
  // inside the mask where the scan shows surface → the scan.
  const slice::FaceMask& mask = profiles.mask;
  constexpr double step = kEncodeCheckSpacingMm;
  const double half_width = mask.half_width + 1.0;
  const metrics::FrontView view(scan, -half_width, half_width, mask.centre_y - mask.half_height - step,
                                mask.centre_y + mask.half_height + step, step);
  const std::vector<Vec3> samples = view.samples([&](const Vec3& p) { return mask.contains(p); });
  if (samples.empty()) return refused("coverage: no sample of the scan lies in the face mask");
  const double covered_within = metrics::FidelityOptions{}.covered_within_mm;

  // The hierarchies are built on every core, as an encode detects its landmarks (the same either way).
  metrics::MeshFidelity fidelity;
  {
    const metrics::SurfaceDistance to_result(result, 0);
    std::size_t near = 0;
    for (const Vec3& p : samples)
      if (to_result.distance(p) <= covered_within) ++near;
    fidelity.coverage.share = static_cast<double>(near) / static_cast<double>(samples.size());
  }
  {
    const metrics::SurfaceDistance to_scan(scan, 0);
    double sum = 0.0;
    std::size_t count = 0;
    for (const Vec3& p : metrics::sample_surface(result, step, mask.box()))
      if (mask.contains(p) && view.sees_surface(p.x(), p.y())) {
        sum += to_scan.distance(p);
        ++count;
      }
    fidelity.to_scan.samples = count;
    fidelity.to_scan.mean =
        count > 0 ? sum / static_cast<double>(count) : std::numeric_limits<double>::quiet_NaN();
  }
  metrics::SelfCheck check = metrics::self_check(fidelity, metrics::facing_away(result, mask), limits);
  if (!check.passed() && !force) return refused(check.summary());
  return check;
}

} // namespace pdeface::pipeline
