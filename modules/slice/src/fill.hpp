#pragma once
// Filling the holes of the profile curves together: the curves' front-most depths on a grid of (curve,
// height) cells, the unknown cells (holes) solved so that the surface bends as little as possible along
// each curve and across neighbouring curves (second differences, a discrete thin plate), with the known
// cells fixed. A hole is then filled from its own curve's surface on both sides and from the neighbouring
// curves where they have surface at its heights: an eye hole or an open mouth gets one smooth membrane,
// not a chord per curve.

#include <array>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace pdeface::slice::detail {

struct FillColumn {
  double x = 0.0;                                     //!< the curve's plane (ascending over the columns)
  std::array<double, 2> extent{};                     //!< the heights it spans
  std::function<std::optional<double>(double)> depth; //!< z of its surface at height y, nullopt in a hole
};

//! For each column, the filled cells (y, z) inside its holes, ascending: the heights are those of a grid
//! of `step` over all the columns' extents.
[[nodiscard]] std::vector<std::vector<std::pair<double, double>>>
fill_holes(std::span<const FillColumn> columns, double step);

} // namespace pdeface::slice::detail
