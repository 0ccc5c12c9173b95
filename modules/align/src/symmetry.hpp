#pragma once
// Mirror symmetry of point sets: the mirror map of a plane, how well a scan matches its mirror image,
// and registration of the mirrored scan onto the scan (trimmed ICP, rigid steps by Eigen::umeyama).
// Internal to align. Lengths are in the scan's units unless a parameter says otherwise.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/point_index.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
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

// A grid over a point set (its bounding box widened by two cells) whose every cell names a point of the
// set near its centre: the nearest to the centre of those the cells around it name, handed on from cell to
// cell in two raster passes (forward, then back). A distance from it is a look-up and a few subtractions
// instead of a tree search, however far the query lies from the set (a wrong plane mirrors much of a scan
// into the air, where a k-d tree search visits every leaf within that distance). A query outside the box is
// answered from the nearest cell on its border.
class NearGrid {
public:
  // \pre `points` is not empty and stays alive and unchanged while the grid is used; `cell` > 0 (it is
  // made larger when the box would hold more than ~2M cells).
  NearGrid(std::span<const Vec3> points, double cell);
  // The distance from `q` to the nearest of the points the 8 cells around it name: never less than the
  // distance to the nearest point, and equal to it for a query near the set in nearly every case.
  [[nodiscard]] double distance(const Vec3& q) const;
  [[nodiscard]] double cell() const { return cell_; }

private:
  std::span<const Vec3> points_;
  Vec3 origin_; // the centre of cell (0, 0, 0)
  double cell_ = 0.0;
  std::array<int, 3> dims_{};
  std::vector<Eigen::Vector3f> site_; // each cell's point, from origin_ (float: contiguous and small)
};

// The trimmed mirror RMS (as `mirror_rms`) with distances from a `NearGrid`: to rank many candidate planes.
[[nodiscard]] double mirror_rms(const Mirror& m, std::span<const Vec3> points, const NearGrid& grid,
                                double keep = 0.7);

// Registration of the mirrored `points` onto `all` (indexed by `index`): trimmed ICP keeping the best
// `keep` of the pairs, until a step turns less than 0.006° and moves less than `still`.
[[nodiscard]] Mirror refine(Mirror m, std::span<const Vec3> points, std::span<const Vec3> all,
                            const PointIndex& index, double keep, int iterations, double still);

// Unit vectors spread evenly over the hemisphere z >= 0 (or the whole sphere): a Fibonacci spiral.
[[nodiscard]] std::vector<Vec3> fibonacci_directions(int count, bool whole_sphere = false);

// One point per occupied voxel of size `cell`: an even subsample whatever the scan's density.
[[nodiscard]] std::vector<Vec3> voxel_subsample(std::span<const Vec3> points, double cell);
// The same of the points of `positions` (indexed by `index`) within `radius` of `centre`, nearest first,
// without listing them: a patch of a large scan costs its voxels' memory, not its points'.
[[nodiscard]] std::vector<Vec3> voxel_subsample_within(const PointIndex& index,
                                                       std::span<const Vec3> positions, const Vec3& centre,
                                                       double radius, double cell);
// Every k-th point, about `count` of them.
[[nodiscard]] std::vector<Vec3> thin(std::span<const Vec3> points, std::size_t count);
// Median distance from a point to its nearest neighbour.
[[nodiscard]] double median_spacing(std::span<const Vec3> points, const PointIndex& index);

} // namespace pdeface::align::detail
