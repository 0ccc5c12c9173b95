#include "pdeface/compare/fidelity.hpp"

#include "pdeface/metrics/profile_error.hpp"

#include <fmt/format.h>

#include <limits>

namespace pdeface::compare {

Box face_region(const slice::ProfileSet& profiles, double depth_margin_mm) {
  double deepest = std::numeric_limits<double>::infinity();
  for (const slice::ProfileCurve& c : profiles.curves)
    for (const Vec3& p : c.raw)
      deepest = std::min(deepest, p.z());
  Box region;
  region.min = Vec3(-profiles.border_mm, profiles.height_range[0], deepest - depth_margin_mm);
  region.max = Vec3(profiles.border_mm, profiles.height_range[1], std::numeric_limits<double>::infinity());
  return region;
}

Result<Fidelity> measure_fidelity(const Mesh& scan, const slice::ProfileSet& profiles,
                                  const Mesh& reconstruction, const FidelityOptions& options) {
  // The reconstruction cut by the same 4 planes, within the same rectangle as the originals.
  Result<std::vector<slice::EvaluationProfile>> cut = slice::evaluation_profiles(
      reconstruction, profiles.height_range, profiles.border_mm, profiles.eye_height_mm);
  if (!cut) {
    Error e = std::move(cut).error();
    e.message = "the reconstruction: " + e.message;
    return e;
  }
  if (cut->size() != profiles.evaluation.size() || profiles.evaluation.size() != 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("expected 4 evaluation profiles, got {} of the scan and {} of the "
                                  "reconstruction",
                                  profiles.evaluation.size(), cut->size()));
  Fidelity f;
  for (std::size_t i = 0; i < 4; ++i) {
    const metrics::Polyline original[] = {profiles.evaluation[i].points};
    const metrics::Polyline rebuilt[] = {(*cut)[i].points};
    f.profile_error[i] = metrics::profile_error(rebuilt, original);
    f.mean_profile_error += f.profile_error[i] / 4.0;
  }

  Result<metrics::TwoSidedDistance> distance = metrics::surface_distance(
      scan, reconstruction,
      {.spacing = options.sample_spacing_mm, .region = face_region(profiles, options.depth_margin_mm)});
  if (!distance) return std::move(distance).error();
  f.surface = *distance;
  return f;
}

} // namespace pdeface::compare
