#pragma once
// Mirror symmetry of point sets: the mirror map of a plane, how well a scan matches its mirror image,
// and registration of the mirrored scan onto the scan (trimmed ICP, rigid steps by Eigen::umeyama).
// Internal to align. Lengths are in the scan's units unless a parameter says otherwise.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/point_index.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace pdeface::align::detail {

// The mirror map x -> a x + b (a is orthogonal with det -1).
struct Mirror {
  Eigen::Matrix3d a;
  Vec3 b;
  [[nodiscard]] Vec3 operator()(const Vec3& p) const { return a * p + b; }
};

[[nodiscard]] Mirror mirror_of(const Plane& plane);

// The symmetry plane of an improper isometry: the normal is the eigenvector of its symmetric part with
// eigenvalue nearest -1; the plane passes through the midpoints of the points and their images.
[[nodiscard]] Plane plane_of(const Mirror& m, std::span<const Vec3> points);

// Trimmed RMS distance from the mirrored points to the indexed ones: the best `keep` fraction counts,
// so that an asymmetric cut, hair or a missing ear do not hide a good plane.
[[nodiscard]] double mirror_rms(const Mirror& m, std::span<const Vec3> points, const PointIndex& index,
                                double keep = 0.7);

// Registration of the mirrored `points` onto `all` (indexed by `index`): trimmed ICP keeping the best
// `keep` of the pairs, until a step turns less than 0.006° and moves less than `still`.
[[nodiscard]] Mirror refine(Mirror m, std::span<const Vec3> points, std::span<const Vec3> all,
                            const PointIndex& index, double keep, int iterations, double still);

// Unit vectors spread evenly over the hemisphere z >= 0 (or the whole sphere): a Fibonacci spiral.
[[nodiscard]] std::vector<Vec3> fibonacci_directions(int count, bool whole_sphere = false);

// One point per occupied voxel of size `cell`: an even subsample whatever the scan's density.
[[nodiscard]] std::vector<Vec3> voxel_subsample(std::span<const Vec3> points, double cell);
// Every k-th point, about `count` of them.
[[nodiscard]] std::vector<Vec3> thin(std::span<const Vec3> points, std::size_t count);
// Median distance from a point to its nearest neighbour.
[[nodiscard]] double median_spacing(std::span<const Vec3> points, const PointIndex& index);

} // namespace pdeface::align::detail
