#include "pdeface/compare/fidelity.hpp"

#include "pdeface/metrics/profile_error.hpp"
#include "pdeface/slice/profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <limits>

namespace pdeface::compare {

namespace {

// The points of a section whose position along `along` lies in [lo, hi].
metrics::Polyline within(const std::vector<Vec3>& points, const Vec3& along, double lo, double hi) {
  metrics::Polyline out;
  std::ranges::copy_if(points, std::back_inserter(out), [&](const Vec3& q) {
    const double t = along.dot(q);
    return t >= lo && t <= hi;
  });
  return out;
}

} // namespace

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
  if (profiles.evaluation.size() != 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("expected 4 evaluation profiles, got {}", profiles.evaluation.size()));
  // The reconstruction cut by the same 4 planes, its front-most part within each original's extent. A
  // reconstruction that falls short of the range is measured where it exists (the surface distance sees
  // what is missing).
  std::vector<slice::Plane> planes;
  std::vector<slice::ProfileAxes> axes;
  for (const slice::EvaluationProfile& e : profiles.evaluation) {
    planes.push_back(e.plane);
    axes.push_back({e.along, Vec3::UnitZ()});
  }
  const std::vector<slice::Section> evaluation = slice::sections(reconstruction, planes, axes);
  Fidelity f;
  for (std::size_t i = 0; i < 4; ++i) {
    const slice::EvaluationProfile& e = profiles.evaluation[i];
    if (e.points.empty())
      return make_error(ErrorCode::InvalidArgument, fmt::format("the {} profile is empty", e.name));
    const double lo = e.along.dot(e.points.front()), hi = e.along.dot(e.points.back());
    const metrics::Polyline rebuilt = within(evaluation[i].points, e.along, lo, hi);
    if (rebuilt.empty())
      return make_error(
          ErrorCode::NoFace,
          fmt::format("the reconstruction has no surface on the {} evaluation profile", e.name));
    const metrics::Polyline original[] = {e.points};
    f.profile_error[i] = metrics::profile_error(std::span(&rebuilt, 1), original);
    f.mean_profile_error += f.profile_error[i] / 4.0;
  }

  // The reconstruction cut by the curves' planes (its front-most part within the height range), against
  // each raw profile.
  // The border curves lie on the reconstruction's edge: they are cut 1 µm inside it, where it surely is.
  std::vector<double> offsets;
  for (const slice::ProfileCurve& c : profiles.curves)
    offsets.push_back(std::clamp(c.x, -profiles.border_mm + 1e-3, profiles.border_mm - 1e-3));
  const std::vector<slice::Section> cuts = slice::sections(reconstruction, Vec3::UnitX(), offsets, {});
  const auto [lo, hi] = profiles.height_range;
  for (std::size_t j = 0; j < profiles.curves.size(); ++j) {
    const metrics::Polyline rebuilt = within(cuts[j].points, Vec3::UnitY(), lo, hi);
    const metrics::Polyline original[] = {profiles.curves[j].raw};
    f.curve_error += metrics::profile_error(std::span(&rebuilt, 1), original) /
                     static_cast<double>(profiles.curves.size());
  }

  Result<metrics::TwoSidedDistance> distance = metrics::surface_distance(
      scan, reconstruction,
      {.spacing = options.sample_spacing_mm, .region = face_region(profiles, options.depth_margin_mm)});
  if (!distance) return std::move(distance).error();
  f.surface = *distance;
  return f;
}

} // namespace pdeface::compare
