#include "pdeface/slice/profiles.hpp"

#include "detail.hpp"
#include "evaluation.hpp"
#include "extents.hpp"
#include "fill.hpp"
#include "sampling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::slice {
namespace {

using align::Landmark;

std::size_t median(std::vector<std::size_t> v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

} // namespace

std::string_view to_string(Fit fit) noexcept { return name_of<Fit>(kFitNames, fit); }

std::string_view to_string(Sampling sampling) noexcept { return name_of<Sampling>(kSamplingNames, sampling); }

Result<ProfileSet> extract_profiles(const Mesh& canonical, const align::Landmarks& landmarks,
                                    const align::FaceFrame& frame, const ProfileOptions& options) {
  if (options.points) {
    if (*options.points < 4)
      return make_error(ErrorCode::InvalidArgument,
                        fmt::format("{} points per curve: a cubic spline needs at least 4", *options.points));
  } else if (!(options.ratio >= kMinRatio && options.ratio <= kMaxRatio)) {
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("sampling ratio {:g} % is outside the paper's range, 5 % to 60 %",
                                  100.0 * options.ratio));
  }
  if (auto ok = detail::require_landmarks(landmarks,
                                          {Landmark::NoseTip, Landmark::EyeInnerLeft, Landmark::EyeInnerRight,
                                           Landmark::EyeOuterLeft, Landmark::EyeOuterRight, Landmark::FaceTop,
                                           Landmark::FaceBottom},
                                          "slicing the face into profiles");
      !ok)
    return ok.error();
  Result<FaceMask> mask = face_mask(landmarks, options.planes.mask);
  if (!mask) return mask.error();

  ProfileSet set;
  set.frame = frame;
  set.parameter = options.parameter;
  set.point_cloud = canonical.is_point_cloud();
  set.mask = *mask;
  SectionOptions section = options.section;
  if (set.point_cloud && section.spacing_mm <= 0.0) section.spacing_mm = point_spacing(canonical.positions);
  set.max_hole_mm = options.max_hole_mm.value_or(options.hole_fraction * 2.0 * mask->half_height);
  section.max_gap_mm = set.max_hole_mm;

  auto mostly_missing = [&](double coverage) {
    return make_error(
        ErrorCode::NoFace,
        fmt::format("most of the face is missing: the scan has surface on {:.0f} % of the face its "
                    "landmarks outline (at least {:.0f} % is needed)",
                    100.0 * coverage, 100.0 * options.min_mask_coverage));
  };
  Result<PlaneLayout> layout = profile_planes(canonical, landmarks, options.planes, section);
  if (!layout) {
    // A face mostly missing fails somewhere in the layout: then that is the answer, not where.
    const double coverage = detail::mask_coverage(canonical, *mask, section);
    return coverage < options.min_mask_coverage ? mostly_missing(coverage) : layout.error();
  }
  // The mask as the layout drew it: across the cheeks to the face's silhouette where that is nearer.
  *mask = layout->mask;
  set.mask = *mask;
  const std::vector<ProfilePlane>& planes = layout->planes;
  set.border = layout->border;
  set.border_mm = layout->border_mm;
  set.central_width_mm = layout->central_width_mm;
  // The evaluation profile through the eyes: at the mean height of the four eye corners.
  set.eye_height_mm = 0.0;
  for (Landmark corner :
       {Landmark::EyeInnerLeft, Landmark::EyeInnerRight, Landmark::EyeOuterLeft, Landmark::EyeOuterRight})
    set.eye_height_mm += 0.25 * landmarks[corner]->y();

  // One pass over the scan for every plane: the curves' and the evaluation profiles'.
  const auto specs = detail::evaluation_specs(set.eye_height_mm);
  std::vector<Plane> all;
  std::vector<ProfileAxes> all_axes;
  for (const ProfilePlane& p : planes) {
    all.push_back({Vec3::UnitX(), p.x});
    all_axes.push_back({});
  }
  for (const detail::EvaluationSpec& spec : specs) {
    all.push_back(spec.plane);
    all_axes.push_back(spec.axes);
  }
  const std::vector<Section> cuts = sections(canonical, all, all_axes, section);
  const std::span<const Section> curve_cuts(cuts.data(), planes.size());
  const ProfileAxes axes;
  set.mask_coverage = detail::mask_coverage(curve_cuts, planes, *mask);
  if (set.mask_coverage < options.min_mask_coverage) return mostly_missing(set.mask_coverage);

  const FaceMask region = mask->grown(options.region_across, options.region_along);
  const detail::Extents extents =
      detail::curve_extents(curve_cuts, planes, region, landmarks, options, set.max_hole_mm);
  std::vector<detail::FillColumn> columns;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const auto [lo, hi] = extents.extent[j];
    if (!(hi - lo >= 4.0 * options.fill_step_mm))
      return make_error(ErrorCode::NoFace,
                        fmt::format("{}: the scan has almost no surface on it (from y = {:.1f} to {:.1f} mm)",
                                    detail::describe_plane(j, planes[j].x, planes[j].feature), lo, hi));
    // Only the curve's own stretch of surface is known; beyond it (a closed notch) is filled.
    columns.push_back({planes[j].x, extents.extent[j],
                       [&cut = cuts[j], &axes, own = extents.surface[j]](double y) -> std::optional<double> {
                         if (y < own[0] || y > own[1]) return std::nullopt;
                         const std::optional<Vec3> p = section_at(cut, axes, y);
                         return p ? std::optional<double>(p->z()) : std::nullopt;
                       }});
  }
  const auto fills = detail::fill_holes(columns, options.fill_step_mm);

  std::vector<std::size_t> counts;
  double curve_length = 0.0, filled_length = 0.0;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const auto [lo, hi] = extents.extent[j];
    ProfileCurve c;
    c.index = j;
    c.x = planes[j].x;
    c.role = planes[j].role;
    c.feature = planes[j].feature;
    c.ends = extents.ends[j];
    // The curve's own surface within the extent, its holes, and the stretches beyond it that were closed.
    const double from = std::max(lo, extents.surface[j][0]), to = std::min(hi, extents.surface[j][1]);
    if (lo < from) c.holes.push_back({lo, from});
    for (const auto& h : holes_within(cuts[j], from, to))
      c.holes.push_back(h);
    if (to < hi) c.holes.push_back({to, hi});
    c.raw.push_back(*section_at(cuts[j], axes, from));
    for (const Vec3& p : cuts[j].points)
      if (p.y() > from && p.y() < to) c.raw.push_back(p);
    c.raw.push_back(*section_at(cuts[j], axes, to));
    c.surface_points = c.raw.size();
    for (const auto& [y, z] : fills[j])
      c.raw.emplace_back(c.x, y, z);
    std::stable_sort(c.raw.begin(), c.raw.end(), [](const Vec3& a, const Vec3& b) { return a.y() < b.y(); });
    c.extent = {c.raw.front().y(), c.raw.back().y()};
    for (auto& h : c.holes)
      h = {std::max(h[0], c.extent[0]), std::min(h[1], c.extent[1])};
    std::erase_if(c.holes, [](const auto& h) { return !(h[1] - h[0] > 1e-6); });
    c.bridged = c.holes.size();
    double hole_length = 0.0;
    for (const auto& h : c.holes) {
      c.longest_bridge_mm = std::max(c.longest_bridge_mm, h[1] - h[0]);
      hole_length += h[1] - h[0];
    }
    curve_length += hi - lo;
    filled_length += hole_length;
    // The scan's own density counts, not the fill grid's: a filled hole counts as the points the scan would
    // have had there.
    const double spacing =
        (hi - lo - hole_length) / static_cast<double>(std::max<std::size_t>(1, c.surface_points - 1));
    counts.push_back(c.surface_points +
                     static_cast<std::size_t>(std::lround(hole_length / std::max(spacing, 1e-6))));
    set.curves.push_back(std::move(c));
  }
  set.filled_fraction = curve_length > 0.0 ? filled_length / curve_length : 0.0;
  set.height_range = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const ProfileCurve& c : set.curves) {
    set.height_range[0] = std::min(set.height_range[0], c.extent[0]);
    set.height_range[1] = std::max(set.height_range[1], c.extent[1]);
  }

  set.raw_points = median(counts);
  set.reference_points = options.reference_points;
  set.k =
      options.points
          ? *options.points
          : static_cast<std::size_t>(std::lround(options.ratio * static_cast<double>(set.reference_points)));
  set.ratio = static_cast<double>(set.k) / static_cast<double>(set.reference_points);
  if (set.k < 4)
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("a ratio of {:g} % of {} reference points leaves {} points per curve; a cubic spline "
                    "needs at least 4",
                    100.0 * options.ratio, set.reference_points, set.k));
  Result<detail::CurveSamples> samples = detail::sample_curves(set.curves, set.k, options);
  if (!samples) return samples.error();
  set.sampling = options.sampling;
  set.fit = options.fit;
  set.heights = std::move(samples->heights);
  for (std::size_t j = 0; j < set.curves.size(); ++j)
    set.curves[j].points = std::move(samples->points[j]);
  for (ProfileCurve& curve : set.curves)
    for (const Vec3& p : curve.points)
      curve.filled.push_back(
          std::ranges::any_of(curve.holes, [&](const auto& h) { return p.y() > h[0] && p.y() < h[1]; }));

  Result<std::vector<EvaluationProfile>> evaluation =
      detail::evaluation_from(specs, std::span(cuts).subspan(planes.size()), set.region());
  if (!evaluation) return evaluation.error();
  set.evaluation = std::move(evaluation).value();
  set.spacing_mm = set.point_cloud ? section.spacing_mm : 0.0;
  set.missing = detail::missing_parts(set, *layout);
  return set;
}

} // namespace pdeface::slice
