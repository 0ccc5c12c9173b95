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

Result<double> central_width(const Mesh& canonical, const align::Landmarks& landmarks,
                             const SectionOptions& section) {
  if (auto ok = require(landmarks, {Landmark::EyeOuterLeft, Landmark::EyeOuterRight}); !ok) return ok.error();
  const Vec3 left = *landmarks[Landmark::EyeOuterLeft], right = *landmarks[Landmark::EyeOuterRight];
  const double height = 0.5 * (left.y() + right.y());
  const ProfileAxes axes{Vec3::UnitX(), Vec3::UnitZ()};
  const std::vector<Section> cut = sections(canonical, Vec3::UnitY(), std::span(&height, 1), axes, section);
  Result<Profile> line = clip(cut.front(), axes, right.x(), left.x(), section, "x");
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

  Result<double> width = central_width(canonical, landmarks, section);
  if (!width) return width.error();
  layout.central_width_mm = *width;
  layout.eye_height_mm =
      0.5 * (landmarks[Landmark::EyeOuterLeft]->y() + landmarks[Landmark::EyeOuterRight]->y());
  const double W = *width;
  const double inner = mean_abs_x(landmarks, Landmark::EyeInnerLeft, Landmark::EyeInnerRight);
  const double outer = mean_abs_x(landmarks, Landmark::EyeOuterLeft, Landmark::EyeOuterRight);

  // The face border: the widest candidate whose planes, on both sides, supply the height range (less
  // the slack at each end, for ragged scan outlines), tried in 1 mm steps from the widest.
  const double edge = density(canonical, section);
  const double narrowest = outer + std::max({options.min_border_fraction * W, options.min_spacing_mm, edge});
  const double widest = std::max(narrowest, outer + options.border_fraction * W);
  std::vector<double> candidates;
  for (double b = widest; b > narrowest; b -= 1.0) {
    candidates.push_back(b);
    candidates.push_back(-b);
  }
  layout.border_mm = narrowest;
  const ProfileAxes axes; // height along y, seen from +z
  const std::vector<Section> probes = sections(canonical, Vec3::UnitX(), candidates, axes, section);
  const double need_lo = layout.target[0] + options.border_slack_mm;
  const double need_hi = layout.target[1] - options.border_slack_mm;
  for (std::size_t i = 0; i + 1 < candidates.size(); i += 2) {
    bool supplies = true;
    for (std::size_t side = 0; side < 2; ++side) {
      const auto extent = covered_extent(probes[i + side], 0.0, section.max_gap_mm);
      supplies = supplies && extent[0] <= need_lo && extent[1] >= need_hi;
    }
    if (supplies) {
      layout.border_mm = candidates[i];
      break;
    }
  }

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
