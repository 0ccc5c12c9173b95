#include "extents.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::slice::detail {

using align::Landmark;

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
                              .max_turn_deg = options.max_turn_deg,
                              .min_front = region.min_z});
    const Reach up = reach(cuts[j], axes, start,
                           {.limit = limits[1],
                            .max_hole_mm = max_hole,
                            .turn_from = eyes,
                            .max_turn_deg = options.max_turn_deg,
                            .min_front = region.min_z});
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
  double slope = 2.0;
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
    double& lo = out.extent[j][0];
    double& hi = out.extent[j][1];
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

double mask_coverage(std::span<const Section> cuts, std::span<const ProfilePlane> planes,
                     const FaceMask& mask) {
  // Each curve's covered share of the mask's heights at its plane, every millimetre.
  std::vector<double> share(planes.size(), 0.0);
  for (std::size_t j = 0; j < planes.size(); ++j)
    if (const auto h = mask.heights_at(planes[j].x)) {
      std::size_t inside = 0, covered = 0;
      for (double y = (*h)[0] + 0.5; y < (*h)[1]; y += 1.0, ++inside)
        covered += section_at(cuts[j], {}, y) ? 1 : 0;
      share[j] = inside == 0 ? 1.0 : static_cast<double>(covered) / static_cast<double>(inside);
    }
  // Across the mask, every half millimetre, weighted by the mask's height there.
  double total = 0.0, covered = 0.0;
  for (double x = -mask.half_width + 0.25; x < mask.half_width; x += 0.5) {
    const auto h = mask.heights_at(x);
    if (!h) continue;
    const double height = (*h)[1] - (*h)[0];
    total += height;
    if (planes.empty() || x < planes.front().x || x > planes.back().x) continue;
    const auto nearest =
        std::ranges::min_element(planes, {}, [&](const ProfilePlane& p) { return std::abs(p.x - x); });
    covered += height * share[static_cast<std::size_t>(nearest - planes.begin())];
  }
  return total > 0.0 ? covered / total : 0.0;
}

std::vector<std::string> missing_parts(const ProfileSet& set, const PlaneLayout& layout) {
  std::vector<std::string> out;
  for (int end = 0; end < 2; ++end) {
    std::size_t j = 0;
    while (j < set.curves.size()) {
      auto short_by = [&](const ProfileCurve& c) {
        const auto h = set.mask.heights_at(c.x);
        if (!h || c.ends[end] == ReachEnd::Limit || c.ends[end] == ReachEnd::Behind) return 0.0;
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
                      layout.border_limited[side] == ReachEnd::TurnsAway ? "turns away"
                      : layout.border_limited[side] == ReachEnd::Behind  ? "goes behind the face"
                                                                         : "ends"));
  return out;
}

} // namespace pdeface::slice::detail
