#pragma once
//! \file
//! A scan as a viewer in front of it sees it (along −z, canonical frame): the front-most point of its surface
//! over every cell of a grid. The face a measure should judge is this view: the inside of an open mouth
//! and of the nostrils lies behind the lips and the nose, and a hole (an eye of a morphable model, a gap of
//! the capture) shows nothing, so it is not sampled as if it were surface.

#include "pdeface/core/mesh.hpp"

#include <functional>
#include <optional>
#include <vector>

namespace pdeface::metrics {

//! The front-most surface of a mesh or point cloud on a grid of the x–y plane. A class because it caches
//! the view; queries are const and thread-safe.
class FrontView {
public:
  //! The view of `scan` over [x0, x1] × [y0, y1] with cells of `cell` (a point cloud's cells are at least
  //! twice its median point spacing, so that a cell of its front surface holds a point of it).
  //! \throw std::invalid_argument for a cell that is not positive or a box of more than 10⁸ cells.
  FrontView(const Mesh& scan, double x0, double x1, double y0, double y1, double cell);

  //! The front-most point of the scan over cell (row, col): of a mesh, the exact point of its front-most
  //! triangle over the cell's centre; of a point cloud, its front-most point inside the cell (its own
  //! coordinates). Nothing where the scan shows no surface.
  [[nodiscard]] std::optional<Vec3> at_cell(int row, int col) const;
  //! `at_cell` of the cell nearest to (x, y).
  [[nodiscard]] std::optional<Vec3> front(double x, double y) const;
  //! Whether the scan shows surface at (x, y): in the nearest cell, or for a point cloud in one next to it.
  [[nodiscard]] bool sees_surface(double x, double y) const;
  //! Whether `p` lies more than `tolerance` behind what the view shows at its (x, y).
  [[nodiscard]] bool hidden(const Vec3& p, double tolerance) const;
  //! The view's points for which `keep` holds, one per cell, row by row.
  [[nodiscard]] std::vector<Vec3> samples(const std::function<bool(const Vec3&)>& keep) const;

  [[nodiscard]] double cell() const { return cell_; }
  [[nodiscard]] int rows() const { return rows_; }
  [[nodiscard]] int cols() const { return cols_; }
  [[nodiscard]] bool point_cloud() const { return cloud_; }

private:
  [[nodiscard]] const Vec3& point(int row, int col) const {
    return front_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                  static_cast<std::size_t>(col)];
  }
  double x0_ = 0.0, y0_ = 0.0, cell_ = 1.0;
  int rows_ = 0, cols_ = 0;
  bool cloud_ = false;
  std::vector<Vec3> front_; //!< row-major; z is NaN where nothing is seen
};

} // namespace pdeface::metrics
