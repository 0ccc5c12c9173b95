#include "pdeface/slice/profiles.hpp"

#include "fill.hpp"
#include "landmark_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::slice {
namespace {

using align::Landmark;

std::string describe(std::size_t index, const ProfilePlane& plane) {
  return fmt::format("plane {} (x = {:.1f} mm, {})", index, plane.x, plane.feature);
}

Error about(std::string_view what, Error error) {
  error.message = fmt::format("{}: {}", what, error.message);
  return error;
}

std::size_t median(std::vector<std::size_t> v) {
  auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// A fitted curve tabulated densely: heights (made non-decreasing) and arc length from its start.
struct HeightTable {
  Spline spline;
  std::vector<double> t, y, length;
};

// Heights relative to the curve's extent (0 at its bottom, 1 at its top), so that curves of different
// extents share the relative heights. The "length" counts each radian the curve turns as `turn_weight` mm:
// samples spaced evenly in it crowd where the profile bends (the lips, the nose), not only where it is long.
HeightTable height_table(Spline spline, std::array<double, 2> extent, double turn_weight) {
  constexpr std::size_t dense = 2048;
  const double span = std::max(extent[1] - extent[0], 1e-9);
  HeightTable table{std::move(spline), {}, {}, {}};
  Vec3 previous = table.spline.evaluate(0.0);
  Vec3 direction = Vec3::Zero();
  for (std::size_t i = 0; i < dense; ++i) {
    const double t = static_cast<double>(i) / (dense - 1);
    const Vec3 p = table.spline.evaluate(t);
    table.t.push_back(t);
    const double y = (p.y() - extent[0]) / span;
    table.y.push_back(i == 0 ? y : std::max(table.y.back(), y));
    const Vec3 step = p - previous;
    double turn = 0.0;
    if (i > 1 && step.norm() > 0 && direction.norm() > 0)
      turn = std::acos(std::clamp(step.normalized().dot(direction), -1.0, 1.0));
    if (step.norm() > 0) direction = step.normalized();
    table.length.push_back(i == 0 ? 0.0 : table.length.back() + step.norm() + turn_weight * turn);
    previous = p;
  }
  return table;
}

// Linear interpolation of `to` at `x` in the non-decreasing `from`.
double interpolate(const std::vector<double>& from, const std::vector<double>& to, double x) {
  const auto hi = std::upper_bound(from.begin(), from.end(), x);
  if (hi == from.begin()) return to.front();
  if (hi == from.end()) return to.back();
  const auto i = static_cast<std::size_t>(hi - from.begin());
  const double span = from[i] - from[i - 1];
  const double w = span > 0 ? (x - from[i - 1]) / span : 0.0;
  return to[i - 1] + w * (to[i] - to[i - 1]);
}

// Each curve's share of its arc length in each of `grid` steps of relative height.
std::vector<std::vector<double>> arc_increments(std::span<const HeightTable> tables, std::size_t grid) {
  std::vector<std::vector<double>> out;
  for (const HeightTable& table : tables) {
    std::vector<double> d(grid, 0.0);
    double previous = 0.0;
    for (std::size_t g = 0; g < grid; ++g) {
      const double h = static_cast<double>(g) / static_cast<double>(grid - 1);
      const double fraction = interpolate(table.y, table.length, h) / table.length.back();
      if (g > 0) d[g] = std::max(0.0, fraction - previous);
      previous = fraction;
    }
    out.push_back(std::move(d));
  }
  return out;
}

// K relative heights from 0 to 1 between which the curves' arc length advances evenly: the root mean square
// of the curves' increments, each curve weighted by `weights`. The root mean square leans towards the curves
// that are long there (the nose, the lips), which the plain mean dilutes by the outer curves: on
// facefuns_f18, m46 and f56 the surface lies 0.190 / 0.108 mm from the scan at 10 / 30 % on average, against
// 0.210 / 0.093 with the plain mean (all curves weighted alike).
std::vector<double> even_heights(const std::vector<std::vector<double>>& increments,
                                 std::span<const double> weights, std::size_t k) {
  const std::size_t grid = increments.front().size();
  std::vector<double> heights(grid), cumulative(grid, 0.0);
  for (std::size_t g = 0; g < grid; ++g)
    heights[g] = static_cast<double>(g) / static_cast<double>(grid - 1);
  for (std::size_t g = 1; g < grid; ++g) {
    double squares = 0.0;
    for (std::size_t i = 0; i < increments.size(); ++i)
      squares += weights[i] * increments[i][g] * increments[i][g];
    cumulative[g] = cumulative[g - 1] + std::sqrt(squares);
  }
  for (double& c : cumulative)
    c /= cumulative.back();
  std::vector<double> out(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = interpolate(cumulative, heights, static_cast<double>(i) / static_cast<double>(k - 1));
  out.front() = 0.0;
  out.back() = 1.0;
  return out;
}

// The spline parameters where the curve is at `heights` (its ends exactly at 0 and 1).
std::vector<double> at_heights(const HeightTable& table, std::span<const double> heights) {
  std::vector<double> ts;
  for (double h : heights)
    ts.push_back(interpolate(table.y, table.t, h));
  ts.front() = 0.0;
  ts.back() = 1.0;
  for (std::size_t i = 1; i < ts.size(); ++i)
    ts[i] = std::max(ts[i], ts[i - 1]);
  return ts;
}

} // namespace

std::string_view to_string(Fit fit) noexcept { return fit == Fit::Spline ? "spline" : "cosine"; }

std::string_view to_string(Sampling sampling) noexcept {
  switch (sampling) {
  case Sampling::SharedHeights: return "shared_heights";
  case Sampling::LocalHeights: return "local_heights";
  case Sampling::Parameter: break;
  }
  return "parameter";
}

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

namespace {

// The planes of the four evaluation profiles, how each is read, and the line in the x–y plane it follows.
struct EvaluationSpec {
  const char* name;
  Plane plane;
  ProfileAxes axes;
  const char* axis;
  Eigen::Vector2d origin, direction;
};

std::array<EvaluationSpec, 4> evaluation_specs(double eye_height) {
  const double s = 1.0 / std::sqrt(2.0);
  return {{
      {"symmetry", {Vec3::UnitX(), 0.0}, {Vec3::UnitY(), Vec3::UnitZ()}, "y", {0, 0}, {0, 1}},
      {"eyes", {Vec3::UnitY(), eye_height}, {Vec3::UnitX(), Vec3::UnitZ()}, "x", {0, eye_height}, {1, 0}},
      {"diagonal_up", {Vec3(-s, s, 0.0), 0.0}, {Vec3(s, s, 0.0), Vec3::UnitZ()}, "u", {0, 0}, {s, s}},
      {"diagonal_down", {Vec3(s, s, 0.0), 0.0}, {Vec3(s, -s, 0.0), Vec3::UnitZ()}, "u", {0, 0}, {s, -s}},
  }};
}

// The profiles from their sections, each over its line's stretch inside the region, trimmed to where the
// scan has surface; holes inside are gaps.
Result<std::vector<EvaluationProfile>> evaluation_from(const std::array<EvaluationSpec, 4>& specs,
                                                       std::span<const Section> cuts,
                                                       const CurveRegion& region) {
  std::vector<EvaluationProfile> out;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const EvaluationSpec& spec = specs[i];
    const Section& cut = cuts[i];
    auto fail = [&](const std::string& why) {
      return make_error(ErrorCode::NoFace, fmt::format("the {} evaluation profile: {}", spec.name, why));
    };
    const auto [t0, t1] = region.span_along(spec.origin, spec.direction);
    if (!(t1 > t0)) return fail("its line misses the face region");
    // Along the axis, the line's parameter t is the coordinate plus the origin's own.
    const double shift = spec.axes.along.dot(Vec3(spec.origin.x(), spec.origin.y(), 0.0));
    double lo = shift + t0, hi = shift + t1;
    const auto first = std::ranges::find_if(cut.cover, [&](const auto& c) { return c[1] > lo; });
    const auto last =
        std::ranges::find_if(cut.cover.rbegin(), cut.cover.rend(), [&](const auto& c) { return c[0] < hi; });
    if (first == cut.cover.end() || last == cut.cover.rend() ||
        !(std::max(lo, (*first)[0]) < std::min(hi, (*last)[1])))
      return fail(fmt::format("the scan has no surface between {0} = {1:.1f} and {0} = {2:.1f} mm", spec.axis,
                              lo, hi));
    lo = std::max(lo, (*first)[0]);
    hi = std::min(hi, (*last)[1]);
    EvaluationProfile e{spec.name, spec.plane, spec.axes.along, {}, holes_within(cut, lo, hi)};
    e.points.push_back(*section_at(cut, spec.axes, lo));
    for (const Vec3& p : cut.points) {
      const double u = spec.axes.along.dot(p);
      if (u > lo && u < hi) e.points.push_back(p);
    }
    e.points.push_back(*section_at(cut, spec.axes, hi));
    if (e.points.size() < 4) return fail("the scan has too little surface on it");
    out.push_back(std::move(e));
  }
  return out;
}

// The heights each curve spans, from the nose tip's height down and up its section within the region.
struct Extents {
  std::vector<std::array<double, 2>> extent;  // what each curve spans
  std::vector<std::array<double, 2>> surface; // the stretch of its own surface that holds the seed
  std::vector<std::array<ReachEnd, 2>> ends;
};

Extents curve_extents(std::span<const Section> cuts, std::span<const ProfilePlane> planes,
                      const FaceMask& region, const align::Landmarks& landmarks,
                      const ProfileOptions& options, double max_hole) {
  const ProfileAxes axes;
  // Turning away counts only at the ends: below the mouth (the chin, the jaw) and above the eyes; the
  // nose's underside and the lips turn as steeply.
  double mouth = std::numeric_limits<double>::infinity(), eyes = -mouth;
  for (Landmark m : {Landmark::MouthLeft, Landmark::MouthRight})
    if (landmarks.has(m)) mouth = std::min(mouth, landmarks[m]->y());
  for (Landmark e :
       {Landmark::EyeInnerLeft, Landmark::EyeInnerRight, Landmark::EyeOuterLeft, Landmark::EyeOuterRight})
    if (landmarks.has(e)) eyes = std::max(eyes, landmarks[e]->y());
  if (!std::isfinite(mouth)) mouth = landmarks[Landmark::NoseTip]->y() - 0.2 * 2.0 * region.half_height;
  const double seed = landmarks[Landmark::NoseTip]->y();

  Extents out;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const auto limits = region.heights_at(planes[j].x).value_or(std::array<double, 2>{seed, seed});
    const double start = std::clamp(seed, limits[0], limits[1]);
    const Reach down = reach(cuts[j], axes, start,
                             {.limit = limits[0],
                              .max_hole_mm = max_hole,
                              .turn_from = mouth,
                              .max_turn_deg = options.max_turn_deg});
    const Reach up = reach(cuts[j], axes, start,
                           {.limit = limits[1],
                            .max_hole_mm = max_hole,
                            .turn_from = eyes,
                            .max_turn_deg = options.max_turn_deg});
    out.extent.push_back({down.end, up.end});
    out.ends.push_back({down.why, up.why});
  }
  out.surface = out.extent;
  // A notch: a curve ending short of curves on both sides of it within `notch` (a capture hole at its end,
  // a turn under the chin its plane meets first) is closed to the shorter of the two sides' reach, within
  // the region; the stretch beyond its own surface is filled from its neighbours.
  const double notch = options.notch_fraction * 2.0 * region.half_height;
  const std::vector<std::array<double, 2>> reached = out.extent;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const auto limits = region.heights_at(planes[j].x);
    if (!limits) continue;
    for (int end = 0; end < 2; ++end) {
      const double sign = end == 0 ? -1.0 : 1.0; // the direction the end reaches in
      std::array<std::optional<std::size_t>, 2> best;
      for (std::size_t i = 0; i < planes.size(); ++i) {
        if (i == j || std::abs(planes[i].x - planes[j].x) > notch) continue;
        auto& b = best[i < j ? 0 : 1];
        if (!b || sign * reached[i][end] > sign * reached[*b][end]) b = i;
      }
      if (!best[0] || !best[1]) continue;
      const std::size_t shorter =
          sign * reached[*best[0]][end] < sign * reached[*best[1]][end] ? *best[0] : *best[1];
      const double target = end == 0 ? std::max(reached[shorter][end], (*limits)[0])
                                     : std::min(reached[shorter][end], (*limits)[1]);
      if (sign * target > sign * out.extent[j][end] && std::abs(target - out.extent[j][end]) <= max_hole) {
        out.extent[j][end] = target;
        out.ends[j][end] = out.ends[shorter][end];
      }
    }
  }
  // Extents may not change across the curves faster than the region's own outline does there (a curve cut
  // short by a hole at its end would shear the surface): the largest envelope within every curve's extent
  // that keeps to that slope.
  double slope = 1.0;
  for (std::size_t j = 1; j < planes.size(); ++j)
    for (double x : {planes[j - 1].x, planes[j].x})
      if (const auto h = region.heights_at(x); h && std::abs(x) > 0.0) {
        const double u = x / region.half_width;
        slope = std::max(slope, 1.25 * region.half_height * std::abs(u) /
                                    (region.half_width * std::sqrt(1 - u * u)));
      }
  auto relax = [&](std::size_t j, std::size_t from) {
    const double allowed = slope * std::abs(planes[j].x - planes[from].x);
    if (out.extent[j][0] < out.extent[from][0] - allowed) {
      out.extent[j][0] = out.extent[from][0] - allowed;
      out.ends[j][0] = out.ends[from][0];
    }
    if (out.extent[j][1] > out.extent[from][1] + allowed) {
      out.extent[j][1] = out.extent[from][1] + allowed;
      out.ends[j][1] = out.ends[from][1];
    }
  };
  for (std::size_t j = 1; j < planes.size(); ++j)
    relax(j, j - 1);
  for (std::size_t j = planes.size() - 1; j-- > 0;)
    relax(j, j + 1);
  // An end moved into a hole of its own surface moves on to the surface beyond it.
  for (std::size_t j = 0; j < planes.size(); ++j) {
    auto& [lo, hi] = out.extent[j];
    if (lo > out.surface[j][0] && !section_at(cuts[j], axes, lo))
      if (const auto next = std::ranges::find_if(cuts[j].cover, [&](const auto& c) { return c[0] > lo; });
          next != cuts[j].cover.end())
        lo = (*next)[0];
    if (hi < out.surface[j][1] && !section_at(cuts[j], axes, hi))
      if (const auto next = std::ranges::find_if(cuts[j].cover.rbegin(), cuts[j].cover.rend(),
                                                 [&](const auto& c) { return c[1] < hi; });
          next != cuts[j].cover.rend())
        hi = (*next)[1];
  }
  return out;
}

// The share of the face mask where the scan has surface: sections across the mask every 4 mm, each
// sampled every 2 mm of height inside it.
double mask_coverage(const Mesh& canonical, const FaceMask& mask, const SectionOptions& section) {
  std::vector<double> xs;
  for (double x = -mask.half_width + 2.0; x < mask.half_width; x += 4.0)
    xs.push_back(x);
  const std::vector<Section> cuts = sections(canonical, Vec3::UnitX(), xs, {}, section);
  std::size_t inside = 0, covered = 0;
  for (std::size_t j = 0; j < xs.size(); ++j) {
    const auto h = mask.heights_at(xs[j]);
    if (!h) continue;
    for (double y = (*h)[0] + 1.0; y < (*h)[1]; y += 2.0) {
      ++inside;
      if (section_at(cuts[j], {}, y)) ++covered;
    }
  }
  return inside == 0 ? 0.0 : static_cast<double>(covered) / static_cast<double>(inside);
}

// What the curves lack of the mask, in words: runs of curves that end short of the mask's outline because
// the surface ends, and sides cut short.
std::vector<std::string> missing_parts(const ProfileSet& set, const PlaneLayout& layout) {
  std::vector<std::string> out;
  for (int end = 0; end < 2; ++end) {
    std::size_t j = 0;
    while (j < set.curves.size()) {
      auto short_by = [&](const ProfileCurve& c) {
        const auto h = set.mask.heights_at(c.x);
        if (!h || c.ends[end] == ReachEnd::Limit) return 0.0;
        return end == 0 ? c.extent[0] - (*h)[0] : (*h)[1] - c.extent[1];
      };
      if (short_by(set.curves[j]) <= 2.0) {
        ++j;
        continue;
      }
      const std::size_t first = j;
      double most = 0.0;
      while (j < set.curves.size() && short_by(set.curves[j]) > 2.0)
        most = std::max(most, short_by(set.curves[j++]));
      out.push_back(
          fmt::format("{}: the scan ends up to {:.1f} mm {} the face's outline between x = {:.1f} and "
                      "{:.1f} mm",
                      end == 0 ? "the chin and jaw" : "the forehead", most, end == 0 ? "above" : "below",
                      set.curves[first].x, set.curves[j - 1].x));
    }
  }
  for (std::size_t side = 0; side < 2; ++side)
    if (layout.border_limited[side] && layout.border[side] < set.mask.half_width - 2.0)
      out.push_back(
          fmt::format("the face's {} side beyond |x| = {:.1f} mm (the face's outline reaches {:.1f} mm): "
                      "the scan {} there",
                      side == 0 ? "right" : "left", layout.border[side], set.mask.half_width,
                      layout.border_limited[side] == ReachEnd::TurnsAway ? "turns away" : "ends"));
  return out;
}

} // namespace

Result<std::vector<EvaluationProfile>> evaluation_profiles(const Mesh& canonical, const CurveRegion& region,
                                                           double eye_height, const SectionOptions& section) {
  const auto specs = evaluation_specs(eye_height);
  std::vector<Plane> planes;
  std::vector<ProfileAxes> axes;
  for (const EvaluationSpec& spec : specs) {
    planes.push_back(spec.plane);
    axes.push_back(spec.axes);
  }
  return evaluation_from(specs, sections(canonical, planes, axes, section), region);
}

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

  set.mask_coverage = mask_coverage(canonical, *mask, section);
  if (set.mask_coverage < options.min_mask_coverage)
    return make_error(
        ErrorCode::NoFace,
        fmt::format("most of the face is missing: the scan has surface on {:.0f} % of the face its "
                    "landmarks outline (at least {:.0f} % is needed)",
                    100.0 * set.mask_coverage, 100.0 * options.min_mask_coverage));

  Result<PlaneLayout> layout = profile_planes(canonical, landmarks, options.planes, section);
  if (!layout) return layout.error();
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
  const auto specs = evaluation_specs(set.eye_height_mm);
  std::vector<Plane> all;
  std::vector<ProfileAxes> all_axes;
  for (const ProfilePlane& p : planes) {
    all.push_back({Vec3::UnitX(), p.x});
    all_axes.push_back({});
  }
  for (const EvaluationSpec& spec : specs) {
    all.push_back(spec.plane);
    all_axes.push_back(spec.axes);
  }
  const std::vector<Section> cuts = sections(canonical, all, all_axes, section);
  const std::span<const Section> curve_cuts(cuts.data(), planes.size());
  const ProfileAxes axes;

  const FaceMask region = mask->grown(options.region_across, options.region_along);
  const Extents extents = curve_extents(curve_cuts, planes, region, landmarks, options, set.max_hole_mm);
  std::vector<detail::FillColumn> columns;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    const auto [lo, hi] = extents.extent[j];
    if (!(hi - lo >= 4.0 * options.fill_step_mm))
      return make_error(ErrorCode::NoFace,
                        fmt::format("{}: the scan has almost no surface on it (from y = {:.1f} to {:.1f} mm)",
                                    describe(j, planes[j]), lo, hi));
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
  // Where each curve's K samples go (spline parameters), then the samples themselves.
  const SplineOptions spline{.parameter = options.parameter, .controls = set.k};
  std::vector<Spline> splines;
  std::vector<std::vector<double>> at(set.curves.size());
  for (ProfileCurve& curve : set.curves) {
    Result<Spline> fitted = fit_spline(curve.raw, spline);
    if (!fitted) return about(describe(curve.index, planes[curve.index]), std::move(fitted).error());
    splines.push_back(*std::move(fitted));
  }
  set.sampling = options.sampling;
  set.fit = options.fit;
  const std::size_t n = set.curves.size();
  if (options.sampling == Sampling::Parameter) {
    for (auto& ts : at)
      for (std::size_t i = 0; i < set.k; ++i)
        ts.push_back(static_cast<double>(i) / static_cast<double>(set.k - 1));
  } else {
    std::vector<HeightTable> tables;
    for (std::size_t j = 0; j < n; ++j)
      tables.push_back(height_table(splines[j], set.curves[j].extent, options.turn_weight_mm));
    const auto increments = arc_increments(tables, 1024);
    for (std::size_t j = 0; j < n; ++j) {
      std::vector<double> weights(n, 1.0);
      if (options.sampling == Sampling::LocalHeights)
        for (std::size_t i = 0; i < n; ++i)
          weights[i] =
              std::exp(-0.5 * std::pow((set.curves[i].x - set.curves[j].x) / options.sampling_window_mm, 2));
      const std::vector<double> heights = options.sampling == Sampling::SharedHeights && j > 0
                                              ? set.heights
                                              : even_heights(increments, weights, set.k);
      at[j] = at_heights(tables[j], heights);
      if (j == 0 || j == n / 2) set.heights = heights;
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    ProfileCurve& curve = set.curves[j];
    if (options.fit == Fit::Spline) {
      for (double t : at[j])
        curve.points.push_back(splines[j].evaluate(t));
      continue;
    }
    Result<std::vector<Vec3>> samples = cosine_samples(curve.raw, at[j], spline);
    if (!samples) return about(describe(j, planes[j]), std::move(samples).error());
    // A profile is a function of height (its front-most section): samples that double back in height (the
    // cosine fit ringing at a wall, where the front switches surfaces) would fold the surface; the spline's
    // samples, which follow the polyline, are taken there instead.
    const bool doubles_back = std::ranges::adjacent_find(*samples, [](const Vec3& a, const Vec3& b) {
                                return b.y() < a.y();
                              }) != samples->end();
    if (doubles_back)
      for (double t : at[j])
        curve.points.push_back(splines[j].evaluate(t));
    else
      curve.points = *std::move(samples);
  }
  for (ProfileCurve& curve : set.curves)
    for (const Vec3& p : curve.points)
      curve.filled.push_back(
          std::ranges::any_of(curve.holes, [&](const auto& h) { return p.y() > h[0] && p.y() < h[1]; }));

  Result<std::vector<EvaluationProfile>> evaluation =
      evaluation_from(specs, std::span(cuts).subspan(planes.size()), set.region());
  if (!evaluation) return evaluation.error();
  set.evaluation = std::move(evaluation).value();
  set.spacing_mm = set.point_cloud ? section.spacing_mm : 0.0;
  set.missing = missing_parts(set, *layout);
  return set;
}

} // namespace pdeface::slice
