#pragma once
// Measures of Draco's position quantisation, for the Draco tests and the glTF tests of
// KHR_draco_mesh_compression.

#include "pdeface/core/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace pdeface::test {

//! Half a step of Draco's position grid (one cube over the largest bounding-box side, 2^bits - 1 steps),
//! plus float32 rounding of the largest coordinate: the most a coordinate may move.
inline double half_step(const Mesh& mesh, int bits) {
  const Box box = bounding_box(mesh);
  const double ulp =
      box.max.cwiseAbs().cwiseMax(box.min.cwiseAbs()).maxCoeff() * std::numeric_limits<float>::epsilon();
  return box.size().maxCoeff() / ((1 << bits) - 1) / 2 + 2 * ulp;
}

//! The largest per-axis difference between the sorted coordinates of two point sets of the same size. A
//! permutation that moves no point further than d along an axis moves no sorted coordinate further than d,
//! so this bounds Draco's error without knowing how it reordered the vertices.
inline double sorted_axis_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> x, y;
    for (const Vec3& p : a)
      x.push_back(p[axis]);
    for (const Vec3& p : b)
      y.push_back(p[axis]);
    std::ranges::sort(x);
    std::ranges::sort(y);
    for (std::size_t i = 0; i < x.size(); ++i)
      worst = std::max(worst, std::abs(x[i] - y[i]));
  }
  return worst;
}

//! The largest per-axis difference between vertices of the same index.
inline double max_vertex_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, (a[i] - b[i]).cwiseAbs().maxCoeff());
  return worst;
}

} // namespace pdeface::test
