#include "pdeface/slice/planes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pdeface::slice {
namespace {

using align::Landmark;

// Mesh density: the median edge length (point spacing for a cloud).
double density(const Mesh& scan, const SectionOptions& section) {
  if (scan.is_point_cloud())
    return section.spacing_mm > 0.0 ? section.spacing_mm : point_spacing(scan.positions);
  std::vector<double> lengths;
  const std::size_t step = std::max<std::size_t>(1, scan.triangles.size() / 2000);
  for (std::size_t i = 0; i < scan.triangles.size(); i += step)
    lengths.push_back((scan.positions[scan.triangles[i][0]] - scan.positions[scan.triangles[i][1]]).norm());
  if (lengths.empty()) return 0.0;
  auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return *mid;
}

Result<void> require(const align::Landmarks& landmarks, std::initializer_list<Landmark> needed) {
  std::string missing;
  for (Landmark l : needed)
    if (!landmarks.has(l)) missing += fmt::format("{}{}", missing.empty() ? "" : ", ", align::name(l));
  if (missing.empty()) return {};
  return make_error(ErrorCode::InvalidArgument, fmt::format("profile planes need the landmarks {}", missing));
}

double mean_abs_x(const align::Landmarks& l, Landmark a, Landmark b) {
  return 0.5 * (std::abs(l[a]->x()) + std::abs(l[b]->x()));
}

// The joints on one side, from the midline out, for `per_side` joints: the five feature joints when
// there are five, else points along the piecewise-linear map through (0, 0) and them.
std::vector<double> spread(const std::array<double, 5>& features, std::size_t per_side) {
  std::vector<double> out;
  for (std::size_t k = 1; k <= per_side; ++k) {
    const double r = 5.0 * static_cast<double>(k) / static_cast<double>(per_side); // in (0, 5]
    const auto i = std::min<std::size_t>(4, static_cast<std::size_t>(std::floor(r - 1e-12)));
    const double from = i == 0 ? 0.0 : features[i - 1];
    out.push_back(from + (r - static_cast<double>(i)) * (features[i] - from));
  }
  return out;
}

} // namespace

std::string_view to_string(PlaneRole role) noexcept {
  return role == PlaneRole::Joint ? "joint" : "intermediate";
}

namespace {

// W from the eye line's section (ascending x, seen from +z): its length between the outer eye corners.
Result<double> width_along(const Section& eye_line, const align::Landmarks& landmarks, double height,
                           const SectionOptions& section) {
  const ProfileAxes axes{Vec3::UnitX(), Vec3::UnitZ()};
  Result<Profile> line = clip(eye_line, axes, landmarks[Landmark::EyeOuterRight]->x(),
                              landmarks[Landmark::EyeOuterLeft]->x(), section, "x");
  if (!line)
    return make_error(ErrorCode::NoFace,
                      fmt::format("the cross-section through the outer eye corners (y = {:.1f} "
                                  "mm): {}",
                                  height, line.error().message));
  double length = 0.0;
  for (std::size_t i = 1; i < line->points.size(); ++i)
    length += (line->points[i] - line->points[i - 1]).norm();
  return length;
}

double eye_line_height(const align::Landmarks& l) {
  return 0.5 * (l[Landmark::EyeOuterLeft]->y() + l[Landmark::EyeOuterRight]->y());
}

} // namespace

Result<double> central_width(const Mesh& canonical, const align::Landmarks& landmarks,
                             const SectionOptions& section) {
  if (auto ok = require(landmarks, {Landmark::EyeOuterLeft, Landmark::EyeOuterRight}); !ok) return ok.error();
  const double height = eye_line_height(landmarks);
  const std::vector<Section> cut =
      sections(canonical, Vec3::UnitY(), std::span(&height, 1), {Vec3::UnitX(), Vec3::UnitZ()}, section);
  return width_along(cut.front(), landmarks, height, section);
}

Result<PlaneLayout> profile_planes(const Mesh& canonical, const align::Landmarks& landmarks,
                                   const PlaneOptions& options, const SectionOptions& section) {
  const std::size_t n = options.curves;
  if (n < 4 || (n - 1) % 3 != 0 || ((n - 1) / 3) % 2 == 0)
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("{} curves cannot make a symmetric layout of patches: the count must be "
                    "3 · patches + 1 with an odd number of patches (4, 10, 16, 22, 28, 34, ...)",
                    n));
  if (auto ok = require(landmarks, {Landmark::EyeInnerLeft, Landmark::EyeInnerRight, Landmark::EyeOuterLeft,
                                    Landmark::EyeOuterRight});
      !ok)
    return ok.error();
  PlaneLayout layout;
  if (options.height_range) {
    layout.target = *options.height_range;
  } else {
    if (auto ok = require(landmarks, {Landmark::FaceBottom, Landmark::FaceTop}); !ok) return ok.error();
    layout.target = {landmarks[Landmark::FaceBottom]->y(), landmarks[Landmark::FaceTop]->y()};
  }
  if (!(layout.target[0] < layout.target[1]))
    return make_error(ErrorCode::InvalidArgument, fmt::format("empty height range [{:.1f}, {:.1f}] mm",
                                                              layout.target[0], layout.target[1]));

  // One pass over the scan for three horizontal sections: the eye line (for W) and the two heights the
  // face border must reach (the height range less the slack at each end, for ragged outlines).
  layout.eye_height_mm = eye_line_height(landmarks);
  const std::array<double, 3> heights{layout.eye_height_mm, layout.target[0] + options.border_slack_mm,
                                      layout.target[1] - options.border_slack_mm};
  const std::vector<Section> cuts =
      sections(canonical, Vec3::UnitY(), heights, {Vec3::UnitX(), Vec3::UnitZ()}, section);
  Result<double> width = width_along(cuts[0], landmarks, layout.eye_height_mm, section);
  if (!width) return width.error();
  layout.central_width_mm = *width;
  const double W = *width;
  const double inner = mean_abs_x(landmarks, Landmark::EyeInnerLeft, Landmark::EyeInnerRight);
  const double outer = mean_abs_x(landmarks, Landmark::EyeOuterLeft, Landmark::EyeOuterRight);

  // The face border: as wide as the face still is at both ends of the height range, within
  // [narrowest, widest].
  const double edge = density(canonical, section);
  const double narrowest = outer + std::max({options.min_border_fraction * W, options.min_spacing_mm, edge});
  const double widest = std::max(narrowest, outer + options.border_fraction * W);
  double reach = widest;
  for (std::size_t k = 1; k < 3; ++k) {
    const auto extent = covered_extent(cuts[k], 0.0, section.max_gap_mm);
    reach = std::min({reach, -extent[0], extent[1]});
  }
  layout.border_mm = std::clamp(reach, narrowest, widest);

  const std::array<double, 5> features{options.wing_fraction * inner, inner, 0.5 * (inner + outer), outer,
                                       layout.border_mm};
  static constexpr std::array<const char*, 5> kNames{"nose wing", "inner eye corner", "eye centre",
                                                     "outer eye corner", "face border"};
  const double min_gap = std::max(options.min_spacing_mm, edge);
  for (std::size_t k = 0; k < features.size(); ++k) {
    const double previous = k == 0 ? 0.0 : features[k - 1];
    if (features[k] - previous < min_gap)
      return make_error(
          ErrorCode::NoFace,
          fmt::format("the {} joint (|x| = {:.1f} mm) is within {:.1f} mm of the {} (|x| = {:.1f} "
                      "mm): the features do not leave room for a patch between them",
                      kNames[k], features[k], min_gap, k == 0 ? "midline" : kNames[k - 1], previous));
  }

  // Joints, symmetric, ascending: −b … −w, w … b; then two intermediates inside every patch.
  const std::size_t patches = (n - 1) / 3, per_side = (patches + 1) / 2;
  const std::vector<double> side = spread(features, per_side);
  std::vector<ProfilePlane> joints;
  for (std::size_t k = per_side; k-- > 0;)
    joints.push_back({-side[k], PlaneRole::Joint, ""});
  for (std::size_t k = 0; k < per_side; ++k)
    joints.push_back({side[k], PlaneRole::Joint, ""});
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const bool left = joints[j].x > 0;
    const std::size_t rank = left ? j - per_side : per_side - 1 - j;
    joints[j].feature = per_side == 5 ? fmt::format("{} ({})", kNames[rank], left ? "left" : "right")
                                      : fmt::format("joint {} ({})", rank + 1, left ? "left" : "right");
  }
  for (std::size_t j = 0; j < joints.size(); ++j) {
    layout.planes.push_back(joints[j]);
    if (j + 1 == joints.size()) break;
    for (int third = 1; third <= 2; ++third)
      layout.planes.push_back({joints[j].x + third * (joints[j + 1].x - joints[j].x) / 3.0,
                               PlaneRole::Intermediate, fmt::format("patch {}, {}/3", j + 1, third)});
  }
  return layout;
}

} // namespace pdeface::slice
