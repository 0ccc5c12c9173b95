#include "pdeface/slice/planes.hpp"

#include "detail.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::slice {
namespace {

using align::Landmark;

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
  // A corner at the end of an eye hole may lie just inside it: the line starts on the nearest surface
  // inwards, within a hole's length.
  double lo = landmarks[Landmark::EyeOuterRight]->x(), hi = landmarks[Landmark::EyeOuterLeft]->x();
  const auto& cover = eye_line.cover;
  if (!section_at(eye_line, axes, lo))
    if (const auto next = std::ranges::find_if(cover, [&](const auto& c) { return c[0] > lo; });
        next != cover.end() && (*next)[0] - lo <= section.max_gap_mm)
      lo = (*next)[0];
  if (!section_at(eye_line, axes, hi))
    if (const auto next =
            std::ranges::find_if(cover.rbegin(), cover.rend(), [&](const auto& c) { return c[1] < hi; });
        next != cover.rend() && hi - (*next)[1] <= section.max_gap_mm)
      hi = (*next)[1];
  Result<Profile> line = clip(eye_line, axes, lo, hi, section, "x");
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
  if (auto ok = detail::require_landmarks(landmarks, {Landmark::EyeOuterLeft, Landmark::EyeOuterRight},
                                          "the central width");
      !ok)
    return ok.error();
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
  if (auto ok = detail::require_landmarks(landmarks,
                                          {Landmark::NoseTip, Landmark::EyeInnerLeft, Landmark::EyeInnerRight,
                                           Landmark::EyeOuterLeft, Landmark::EyeOuterRight},
                                          "placing the profile planes");
      !ok)
    return ok.error();
  Result<FaceMask> mask = face_mask(landmarks, options.mask);
  if (!mask) return mask.error();
  PlaneLayout layout;

  // One pass over the scan for the horizontal sections: the eye line (for W) and three heights across the
  // middle of the face mask, on which the border must still be on the face.
  layout.eye_height_mm = eye_line_height(landmarks);
  const double c = mask->centre_y, b = mask->half_height;
  // The nose tip's height too: every curve's walk starts there, so the border must be on the face there.
  const std::array<double, 5> heights{layout.eye_height_mm, c - 0.35 * b, c, c + 0.35 * b,
                                      landmarks[Landmark::NoseTip]->y()};
  const std::vector<Section> cuts =
      sections(canonical, Vec3::UnitY(), heights, {Vec3::UnitX(), Vec3::UnitZ()}, section);
  Result<double> width = width_along(cuts[0], landmarks, layout.eye_height_mm, section);
  if (!width) return width.error();
  layout.central_width_mm = *width;
  const double inner = mean_abs_x(landmarks, Landmark::EyeInnerLeft, Landmark::EyeInnerRight);
  const double outer = mean_abs_x(landmarks, Landmark::EyeOuterLeft, Landmark::EyeOuterRight);

  // How far out the face goes on each side at the three heights: to the mask's outline (grown by
  // `border_beyond_mask`), unless the surface ends or turns away from the viewer first. Holes across the
  // face (an open mouth, the eyes of a mesh without eyeballs) do not end it.
  const ProfileAxes across{Vec3::UnitX(), Vec3::UnitZ()};
  const auto walk = [&](std::size_t k, double sign, double limit) {
    return reach(cuts[k], across, 0.0,
                 {.limit = sign * limit,
                  .max_hole_mm = std::max(section.max_gap_mm, mask->half_width),
                  .turn_from = sign * outer,
                  .max_turn_deg = options.max_turn_deg,
                  .min_front = mask->min_z});
  };
  // The mask reaches across the cheeks to where the face turns away from the viewer in front of the ears
  // (its silhouette seen from the front) or goes further back than the face (hair over the ears), when
  // that is nearer than the landmarks' outline: the wider side's
  // silhouette, at the height where it is nearest. A side that only ends (a scan cut short) does not
  // narrow it.
  double silhouette = 0.0;
  for (std::size_t side = 0; side < 2; ++side) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < cuts.size(); ++k) {
      const Reach r = walk(k, side == 0 ? -1.0 : 1.0, mask->half_width);
      const double w = (heights[k] - c) / b;
      if ((r.why == ReachEnd::TurnsAway || r.why == ReachEnd::Behind) && std::abs(w) < 1.0)
        nearest = std::min(nearest, std::abs(r.end) / std::sqrt(1.0 - w * w));
    }
    silhouette = std::max(silhouette, nearest);
  }
  if (silhouette < mask->half_width) mask->half_width = std::max(silhouette, outer);
  layout.mask = *mask;

  // The face border, each side on its own: beyond the mask, unless the surface ends or turns away first.
  // Planes closer than a mesh edge still cut it well (sections interpolate inside triangles): only joints
  // that all but coincide are an error.
  const double min_gap = options.min_spacing_mm;
  const double target = options.border_beyond_mask * mask->half_width;
  std::array<std::array<double, 5>, 2> features{};
  for (std::size_t side = 0; side < 2; ++side) {
    const double sign = side == 0 ? -1.0 : 1.0;
    double border = target;
    for (std::size_t k = 1; k < cuts.size(); ++k) {
      const Reach r = walk(k, sign, target);
      if (std::abs(r.end) < border) {
        border = std::abs(r.end);
        layout.border_limited[side] = r.why;
      }
    }
    layout.border[side] = border;
  }
  // Every curve's walk starts at the nose tip's height: the border plane must meet the face there, in
  // front of the mask's depth limit (a cheek that turns back under a steep slope can lie behind it a few
  // millimetres beyond where the horizontal walk ended). Else the border is drawn in, a step at a time.
  {
    constexpr std::array<double, 6> kSteps{1.0, 0.96, 0.92, 0.88, 0.84, 0.80};
    std::vector<double> xs;
    for (std::size_t side = 0; side < 2; ++side)
      for (double f : kSteps)
        xs.push_back((side == 0 ? -1.0 : 1.0) * f * layout.border[side]);
    const std::vector<Section> planes_cut = sections(canonical, Vec3::UnitX(), xs, {}, section);
    const double tip = landmarks[Landmark::NoseTip]->y();
    for (std::size_t side = 0; side < 2; ++side)
      for (std::size_t k = 0; k < kSteps.size(); ++k) {
        const std::optional<Vec3> p = section_at(planes_cut[side * kSteps.size() + k], {}, tip);
        if (p && p->z() >= mask->min_z) {
          if (k > 0) layout.border_limited[side] = ReachEnd::Behind;
          layout.border[side] *= kSteps[k];
          break;
        }
      }
  }
  for (std::size_t side = 0; side < 2; ++side) {
    const double border = layout.border[side];
    // Where the side ends inside the outer eye corner (a scan cut short), its joints are drawn in.
    const double room = outer + std::max(4.0, 2.0 * min_gap);
    const double shrink = std::min(1.0, border / room);
    features[side] = {shrink * options.wing_fraction * inner, shrink * inner, shrink * 0.5 * (inner + outer),
                      shrink * outer, border};
  }
  layout.border_mm = std::max(layout.border[0], layout.border[1]);

  static constexpr std::array<const char*, 5> kNames{"nose side", "inner eye corner", "eye centre",
                                                     "outer eye corner", "face border"};
  for (std::size_t side = 0; side < 2; ++side)
    for (std::size_t k = 0; k < 5; ++k) {
      const double previous = k == 0 ? 0.0 : features[side][k - 1];
      if (features[side][k] - previous < min_gap)
        return make_error(
            ErrorCode::NoFace,
            fmt::format("the {} joint (|x| = {:.1f} mm, {}) is within {:.1f} mm of the {} (|x| = "
                        "{:.1f} mm): the features do not leave room for a patch between them",
                        kNames[k], features[side][k], side == 0 ? "right" : "left", min_gap,
                        k == 0 ? "midline" : kNames[k - 1], previous));
    }

  // Joints, ascending: −b … −w, w … b; then two intermediates inside every patch.
  const std::size_t patches = (n - 1) / 3, per_side = (patches + 1) / 2;
  const std::vector<double> right = spread(features[0], per_side), left = spread(features[1], per_side);
  std::vector<ProfilePlane> joints;
  for (std::size_t k = per_side; k-- > 0;)
    joints.push_back({-right[k], PlaneRole::Joint, ""});
  for (std::size_t k = 0; k < per_side; ++k)
    joints.push_back({left[k], PlaneRole::Joint, ""});
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const bool is_left = joints[j].x > 0;
    const std::size_t rank = is_left ? j - per_side : per_side - 1 - j;
    joints[j].feature = per_side == 5 ? fmt::format("{} ({})", kNames[rank], is_left ? "left" : "right")
                                      : fmt::format("joint {} ({})", rank + 1, is_left ? "left" : "right");
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
