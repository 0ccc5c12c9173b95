#pragma once
//! \file
//! The paper's profile error (its Table I): how far a reconstructed profile lies from the original one.

#include "pdeface/core/mesh.hpp"

#include <span>
#include <vector>

namespace pdeface::metrics {

//! A polyline: consecutive points joined by segments.
using Polyline = std::vector<Vec3>;

//! The distance from `p` to the nearest point of any segment of `lines` (a one-point polyline counts
//! as a point). Infinity when `lines` is empty.
[[nodiscard]] double distance_to_polylines(const Vec3& p, std::span<const Polyline> lines);

//! The paper's profile error of one evaluation plane: the mean distance from each point of the
//! reconstructed profile to the nearest segment of the original profile (both cut by the same plane and
//! clipped to the same range by the caller). NaN when either side is empty.
[[nodiscard]] double profile_error(std::span<const Polyline> reconstructed,
                                   std::span<const Polyline> original);

} // namespace pdeface::metrics
