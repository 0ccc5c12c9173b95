#include "pdeface/metrics/front_view.hpp"

#include "pdeface/core/depth_map.hpp"
#include "pdeface/core/point_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pdeface::metrics {

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// A point cloud's cell whose point lies this far behind the front of the cells around it shows the far
// side (an ear, the back of the head) through a gap in a sparse front: nothing is seen there. Deeper than
// any step of a face between cells a few millimetres apart (the side of the nose falls ~5 mm in 2 mm).
constexpr double kCloudHiddenMm = 10.0;

// The median distance from a point of `points` to its nearest neighbour, over at most ~2,000 of them.
double median_spacing(std::span<const Vec3> points) {
  if (points.size() < 2) return 0.0;
  const PointIndex index(points);
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 2000);
  std::vector<double> gaps;
  std::vector<PointIndex::Neighbour> n;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    index.nearest(points[i], 2, n);
    if (n.size() == 2) gaps.push_back(n[1].distance);
  }
  std::ranges::nth_element(gaps, gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2));
  return gaps[gaps.size() / 2];
}

} // namespace

FrontView::FrontView(const Mesh& scan, double x0, double x1, double y0, double y1, double cell)
    : x0_(x0), y0_(y0), cloud_(scan.is_point_cloud()) {
  if (!(cell > 0.0) || !std::isfinite(cell)) throw std::invalid_argument("FrontView: cell must be positive");
  if (cloud_) cell = std::max(cell, 2.0 * median_spacing(scan.positions));
  cell_ = cell;
  const double cols = std::ceil((x1 - x0) / cell) + 1.0, rows = std::ceil((y1 - y0) / cell) + 1.0;
  if (!(cols >= 1.0 && rows >= 1.0) || cols * rows > 1e8)
    throw std::invalid_argument("FrontView: the box must hold between 1 and 10^8 cells");
  cols_ = static_cast<int>(cols);
  rows_ = static_cast<int>(rows);
  front_.assign(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_), Vec3(0.0, 0.0, kNone));

  if (!cloud_) {
    // A z-buffer: the front-most triangle's plane evaluated exactly at each cell's centre.
    DepthMap map(x0, x0 + (cols_ - 1) * cell_, y0, y0 + (rows_ - 1) * cell_, cell_);
    map.rasterise(scan.positions, scan.triangles, 0.0);
    for (int r = 0; r < std::min(rows_, map.rows()); ++r)
      for (int c = 0; c < std::min(cols_, map.cols()); ++c)
        if (map.known(r, c))
          front_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) +
                 static_cast<std::size_t>(c)] = Vec3(map.x_of(c), map.y_of(r), map.z(r, c));
    return;
  }
  // A point cloud: its front-most point in each cell, then cells showing only the far side dropped.
  for (const Vec3& p : scan.positions) {
    const double c = std::round((p.x() - x0_) / cell_), r = std::round((p.y() - y0_) / cell_);
    if (!(c >= 0.0 && r >= 0.0 && c < cols_ && r < rows_)) continue;
    Vec3& slot =
        front_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c)];
    if (std::isnan(slot.z()) || p.z() > slot.z()) slot = p;
  }
  std::vector<Vec3> kept = front_;
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      const double z = point(r, c).z();
      if (std::isnan(z)) continue;
      double top = z;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc)
          if (r + dr >= 0 && c + dc >= 0 && r + dr < rows_ && c + dc < cols_)
            if (const double q = point(r + dr, c + dc).z(); q > top) top = q;
      if (z < top - kCloudHiddenMm)
        kept[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(c)]
            .z() = kNone;
    }
  front_ = std::move(kept);
}

std::optional<Vec3> FrontView::at_cell(int row, int col) const {
  if (row < 0 || col < 0 || row >= rows_ || col >= cols_) return std::nullopt;
  const Vec3& p = point(row, col);
  if (std::isnan(p.z())) return std::nullopt;
  return p;
}

std::optional<Vec3> FrontView::front(double x, double y) const {
  const double c = std::round((x - x0_) / cell_), r = std::round((y - y0_) / cell_);
  if (!(c >= 0.0 && r >= 0.0 && c < cols_ && r < rows_)) return std::nullopt;
  return at_cell(static_cast<int>(r), static_cast<int>(c));
}

bool FrontView::sees_surface(double x, double y) const {
  if (front(x, y)) return true;
  if (!cloud_) return false;
  for (const double dy : {-cell_, 0.0, cell_})
    for (const double dx : {-cell_, 0.0, cell_})
      if (front(x + dx, y + dy)) return true;
  return false;
}

bool FrontView::hidden(const Vec3& p, double tolerance) const {
  const std::optional<Vec3> f = front(p.x(), p.y());
  return f && p.z() < f->z() - tolerance;
}

std::vector<Vec3> FrontView::samples(const std::function<bool(const Vec3&)>& keep) const {
  std::vector<Vec3> out;
  for (const Vec3& p : front_)
    if (!std::isnan(p.z()) && keep(p)) out.push_back(p);
  return out;
}

} // namespace pdeface::metrics
