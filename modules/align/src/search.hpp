#pragma once
// The landmark search in a depth map of the scan seen from the front of a face frame. Internal to align.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/depth_map.hpp"
#include "pdeface/core/similarity.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <vector>

namespace pdeface::align::detail {

// The boundaries of a mesh (its holes and outer border) as vertex sets: the connected pieces of the
// edges that only one triangle has.
using Loops = std::vector<std::vector<std::uint32_t>>;
[[nodiscard]] Loops boundary_loops(std::span<const Triangle> triangles);

// Landmarks (in the scan's frame and units) found in a depth map of the scan seen in `frame`, whose
// origin is near the nose tip and whose axes are near the canonical ones. `spacing` is the scan's point
// spacing in its units; `cell` the depth map's (mm): 1 for the final landmarks, coarser to try a
// candidate quickly. `loops` are the scan's boundaries (`boundary_loops`): an eye or a mouth that is a
// hole in the mesh has its corners at the ends of the hole. With `repair`, a corner that lies far from
// where the others put it on the average face (the end of a capture hole that swallowed an eye), or that
// was not found, is estimated from the others: for the final landmarks of a face already decided on, never
// while candidates are judged (a repaired non-face would fit the average face by construction); `as_found`
// then receives them before the repair, to judge the face by.
[[nodiscard]] Landmarks search_landmarks(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                         double spacing, const Similarity& frame, double cell = 1.0,
                                         const Loops& loops = {}, bool repair = false,
                                         Landmarks* as_found = nullptr);

// How hollow the scan is at its inner eye corners, seen in `frame` (mm): the least, over the two corners,
// of the mean depth within 12 mm of a corner minus the corner's own depth, on a map smoothed by 1.5 mm
// or the point spacing if larger.
// A face's inner eye corners lie in the sockets between the nose and the brow, a few mm below their
// surroundings; a convex object (a box's corner, a cylinder's rim, a sphere) has no hollow anywhere,
// a flat sheet none either. Nothing when a corner is missing or too near the edge of the scan.
[[nodiscard]] std::optional<double> eye_hollowness(std::span<const Vec3> points,
                                                   std::span<const Triangle> triangles, double spacing,
                                                   const Similarity& frame, const Landmarks& landmarks);

} // namespace pdeface::align::detail
