#include "evaluation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace pdeface::slice {
namespace detail {

std::array<EvaluationSpec, 4> evaluation_specs(double eye_height) {
  const double s = 1.0 / std::sqrt(2.0);
  return {{
      {"symmetry", {Vec3::UnitX(), 0.0}, {Vec3::UnitY(), Vec3::UnitZ()}, "y", {0, 0}, {0, 1}},
      {"eyes", {Vec3::UnitY(), eye_height}, {Vec3::UnitX(), Vec3::UnitZ()}, "x", {0, eye_height}, {1, 0}},
      {"diagonal_up", {Vec3(-s, s, 0.0), 0.0}, {Vec3(s, s, 0.0), Vec3::UnitZ()}, "u", {0, 0}, {s, s}},
      {"diagonal_down", {Vec3(s, s, 0.0), 0.0}, {Vec3(s, -s, 0.0), Vec3::UnitZ()}, "u", {0, 0}, {s, -s}},
  }};
}

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

} // namespace detail

} // namespace pdeface::slice
