#pragma once
//! \file
//! A front-most depth map z(x, y) of a mesh or point cloud seen along −z: the view a range scanner has.
//! Landmark search works on it (a regular grid is simple and robust) and pictures are shaded from it.

#include "pdeface/core/mesh.hpp"

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <optional>
#include <span>

namespace pdeface {

class DepthMap {
public:
  //! Grid over [x0, x1] x [y0, y1] with step `cell` (mm).
  DepthMap(double x0, double x1, double y0, double y1, double cell);

  //! Front-most z of the triangles (z-buffer), or of splatted points (radius `splat` mm) for a cloud.
  void rasterise(std::span<const Vec3> positions, std::span<const Triangle> triangles, double splat);
  //! Forgets the cells that see through a hole of the surface: those more than `depth` mm behind a cell
  //! within `reach` mm on both sides of them, along a row or along a column (the inside of a head through
  //! an eye hole, the far side of a bust through a capture hole). They become holes.
  void drop_pits(double depth, double reach);
  //! Fills holes up to `max_gap` cells wide by averaging known neighbours, a few passes.
  void fill_holes(int max_gap);

  [[nodiscard]] std::optional<double> at(double x, double y) const;
  //! Depth minus the mean depth over a disc of radius r (mm): negative in hollows, positive on bumps.
  [[nodiscard]] std::optional<double> relief(double x, double y, double r) const;

  //! The map blurred by a Gaussian of `sigma` mm (unknown cells stay unknown and do not contribute).
  [[nodiscard]] DepthMap smoothed(double sigma) const;
  //! `smoothed(sigma)` within the box [x0, x1] × [y0, y1] (mm; every cell touching it), unknown outside
  //! it: the same depths to the bit where they are known, for the box's cost rather than the grid's.
  [[nodiscard]] DepthMap smoothed(double sigma, double x0, double x1, double y0, double y1) const;
  //! The smaller eigenvalue of the Hessian of z (1/mm): positive where the surface is a cup (concave
  //! in every direction, as the corners of the eyes and mouth), negative on caps and ridges.
  [[nodiscard]] std::optional<double> cupness(double x, double y) const;

  [[nodiscard]] double cell() const { return cell_; }
  [[nodiscard]] int cols() const { return static_cast<int>(z_.cols()); }
  [[nodiscard]] int rows() const { return static_cast<int>(z_.rows()); }
  [[nodiscard]] double x_of(int col) const { return x0_ + col * cell_; }
  [[nodiscard]] double y_of(int row) const { return y0_ + row * cell_; }
  [[nodiscard]] bool known(int row, int col) const { return !std::isnan(z_(row, col)); }
  [[nodiscard]] double z(int row, int col) const { return z_(row, col); }

private:
  double x0_, y0_, cell_;
  Eigen::MatrixXd z_; // rows: y, cols: x; NaN where nothing was seen
};

} // namespace pdeface
