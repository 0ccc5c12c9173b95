#pragma once
// The paper's four evaluation profiles: their planes, and reading them off their sections within the
// curves' region.

#include "pdeface/slice/profiles.hpp"

#include <array>
#include <span>
#include <vector>

namespace pdeface::slice::detail {

//! One evaluation profile's plane, how it is read, and the line in the x–y plane it follows.
struct EvaluationSpec {
  const char* name;
  Plane plane;
  ProfileAxes axes;
  const char* axis;
  Eigen::Vector2d origin, direction;
};

//! Symmetry, eyes (at `eye_height`), and the two diagonals through the nose tip.
[[nodiscard]] std::array<EvaluationSpec, 4> evaluation_specs(double eye_height);

//! The profiles from their sections (`cuts[i]` of `specs[i]`), each over its line's stretch inside
//! `region`, trimmed to where the scan has surface; holes inside are gaps.
[[nodiscard]] Result<std::vector<EvaluationProfile>>
evaluation_from(const std::array<EvaluationSpec, 4>& specs, std::span<const Section> cuts,
                const CurveRegion& region);

} // namespace pdeface::slice::detail
