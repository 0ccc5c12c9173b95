#include "pdeface/compare/fidelity.hpp"

#include "pdeface/metrics/profile_error.hpp"
#include "pdeface/slice/profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace pdeface::compare {

namespace {

bool in_any(const std::vector<std::array<double, 2>>& gaps, double t) {
  return std::ranges::any_of(gaps, [&](const auto& g) { return t > g[0] && t < g[1]; });
}

// The points of a section whose position along `along` lies in [lo, hi] and outside the gaps.
metrics::Polyline within(const std::vector<Vec3>& points, const Vec3& along, double lo, double hi,
                         const std::vector<std::array<double, 2>>& gaps = {}) {
  metrics::Polyline out;
  std::ranges::copy_if(points, std::back_inserter(out), [&](const Vec3& q) {
    const double t = along.dot(q);
    return t >= lo && t <= hi && !in_any(gaps, t);
  });
  return out;
}

// A polyline cut into pieces at its gaps (no segment joins points across a hole); points inside a gap go.
std::vector<metrics::Polyline> pieces(const std::vector<Vec3>& points, const Vec3& along,
                                      const std::vector<std::array<double, 2>>& gaps) {
  std::vector<metrics::Polyline> out(1);
  std::size_t gap = 0;
  for (const Vec3& p : points) {
    const double t = along.dot(p);
    if (in_any(gaps, t)) continue;
    while (gap < gaps.size() && t >= gaps[gap][1]) {
      if (!out.back().empty()) out.emplace_back();
      ++gap;
    }
    out.back().push_back(p);
  }
  if (out.back().empty()) out.pop_back();
  return out;
}

// The scan seen from the front: its sections every `step` mm across |x| <= half_width, each the front-most
// surface along the height.
struct FrontView {
  double x0 = 0.0, step = 1.0;
  std::vector<slice::Section> columns;
  [[nodiscard]] double x_of(std::size_t column) const { return x0 + static_cast<double>(column) * step; }
  //! The front-most surface point at (x, y), if the scan has surface there.
  [[nodiscard]] std::optional<Vec3> front(double x, double y) const {
    const double k = std::round((x - x0) / step);
    if (k < 0 || k >= static_cast<double>(columns.size())) return std::nullopt;
    return slice::section_at(columns[static_cast<std::size_t>(k)], {}, y);
  }
  //! Behind the front-most surface by more than `tolerance` (the inside of the mouth, of a nostril).
  [[nodiscard]] bool hidden(const Vec3& p, double tolerance) const {
    const std::optional<Vec3> f = front(p.x(), p.y());
    return f && p.z() < f->z() - tolerance;
  }
};

FrontView front_view(const Mesh& scan, double half_width, double step) {
  FrontView view{-half_width, step, {}};
  std::vector<double> offsets;
  for (std::size_t k = 0; view.x_of(k) <= half_width + 0.5 * step; ++k)
    offsets.push_back(view.x_of(k));
  view.columns = slice::sections(scan, Vec3::UnitX(), offsets, {});
  return view;
}

} // namespace

FaceRegion face_region(const slice::ProfileSet& profiles, double depth_margin_mm) {
  double deepest = std::numeric_limits<double>::infinity();
  for (const slice::ProfileCurve& c : profiles.curves)
    for (const Vec3& p : c.raw)
      deepest = std::min(deepest, p.z());
  return {profiles.region(), deepest - depth_margin_mm};
}

namespace {

Result<Coverage> coverage_of(const slice::FaceMask& mask, const Mesh& reconstruction, const FrontView& view,
                             const FidelityOptions& options) {
  if (view.columns.empty() || reconstruction.positions.empty())
    return make_error(ErrorCode::InvalidArgument, "coverage: a mesh is empty");
  // The mask is a region of the front view, so its share is measured per unit of that view's area: the
  // scan's front-most surface at every cell of a grid over the mask. Surface that turns away from the
  // viewer (the cheeks' sides, under the chin) counts for the area it shows, not for its own area, and
  // what the front hides (the inside of the mouth and nostrils) is not the face.
  const metrics::SurfaceDistance to_reconstruction(reconstruction);
  const double step = view.step;
  std::vector<double> distances;
  std::size_t near = 0;
  for (std::size_t k = 0; k < view.columns.size(); ++k) {
    const double x = view.x_of(k);
    const std::optional<std::array<double, 2>> h = mask.heights_at(x);
    if (!h) continue;
    for (double y = std::ceil((*h)[0] / step) * step; y <= (*h)[1]; y += step) {
      const std::optional<Vec3> p = slice::section_at(view.columns[k], {}, y);
      if (!p || !mask.contains(*p)) continue;
      const double d = to_reconstruction.distance(*p);
      distances.push_back(d);
      if (d <= options.covered_within_mm) ++near;
    }
  }
  if (distances.empty())
    return make_error(ErrorCode::InvalidArgument, "coverage: the scan has no surface in the face mask");
  Coverage c;
  c.share = static_cast<double>(near) / static_cast<double>(distances.size());
  c.distance = metrics::statistics(std::move(distances));
  return c;
}

} // namespace

Result<Coverage> measure_coverage(const Mesh& scan, const slice::FaceMask& mask, const Mesh& reconstruction,
                                  const FidelityOptions& options) {
  if (scan.positions.empty()) return make_error(ErrorCode::InvalidArgument, "coverage: a mesh is empty");
  return coverage_of(mask, reconstruction, front_view(scan, mask.half_width, options.sample_spacing_mm),
                     options);
}

Result<Fidelity> measure_fidelity(const Mesh& scan, const slice::ProfileSet& profiles,
                                  const Mesh& reconstruction, const FidelityOptions& options) {
  if (profiles.evaluation.size() != 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("expected 4 evaluation profiles, got {}", profiles.evaluation.size()));
  // The reconstruction cut by the same 4 planes, its front-most part within each original's extent and
  // outside its gaps. A reconstruction that falls short of the range is measured where it exists (the
  // surface distance sees what is missing).
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
    const metrics::Polyline rebuilt = within(evaluation[i].points, e.along, lo, hi, e.gaps);
    if (rebuilt.empty())
      return make_error(
          ErrorCode::NoFace,
          fmt::format("the reconstruction has no surface on the {} evaluation profile", e.name));
    f.profile_error[i] = metrics::profile_error(std::span(&rebuilt, 1), pieces(e.points, e.along, e.gaps));
    f.mean_profile_error += f.profile_error[i] / 4.0;
  }

  // The reconstruction cut by the curves' planes (its front-most part within each curve's extent, outside
  // its holes), against the scan's part of each raw profile.
  // The border curves lie on the reconstruction's edge: they are cut 1 µm inside it, where it surely is.
  const double x_lo = profiles.curves.front().x + 1e-3, x_hi = profiles.curves.back().x - 1e-3;
  std::vector<double> offsets;
  for (const slice::ProfileCurve& c : profiles.curves)
    offsets.push_back(std::clamp(c.x, x_lo, x_hi));
  const std::vector<slice::Section> cuts = slice::sections(reconstruction, Vec3::UnitX(), offsets, {});
  for (std::size_t j = 0; j < profiles.curves.size(); ++j) {
    const slice::ProfileCurve& c = profiles.curves[j];
    const metrics::Polyline rebuilt =
        within(cuts[j].points, Vec3::UnitY(), c.extent[0], c.extent[1], c.holes);
    f.curve_error += metrics::profile_error(std::span(&rebuilt, 1), pieces(c.raw, Vec3::UnitY(), c.holes)) /
                     static_cast<double>(profiles.curves.size());
  }

  // The scan's side counts what a viewer sees from the front: the inside of the mouth and the nostrils,
  // which no front-most profile holds, are not the face.
  const FaceRegion region = face_region(profiles, options.depth_margin_mm);
  const FrontView view = front_view(scan, std::max(profiles.mask.half_width, profiles.border_mm) + 1.0,
                                    options.sample_spacing_mm);
  Result<metrics::TwoSidedDistance> distance = metrics::surface_distance(
      scan, reconstruction,
      {.spacing = options.sample_spacing_mm,
       .region = std::nullopt,
       .keep_a =
           [&](const Vec3& p) { return region.contains(p) && !view.hidden(p, options.front_tolerance_mm); },
       .keep_b =
           [&](const Vec3& p) { return region.contains(p) && !region.curves.filled_at(p.x(), p.y()); }});
  if (!distance) return std::move(distance).error();
  f.surface = *distance;
  Result<Coverage> coverage = coverage_of(profiles.mask, reconstruction, view, options);
  if (!coverage) return std::move(coverage).error();
  f.coverage = *coverage;
  return f;
}

} // namespace pdeface::compare
