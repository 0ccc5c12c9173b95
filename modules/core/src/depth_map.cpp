#include "pdeface/core/depth_map.hpp"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace pdeface {
namespace {

// `v` (a cell index or a count of cells, as a double) as an int, clamped to [-1, limit]: coordinates and
// radii come from files and can be anything; converting a double beyond int's range is undefined, and no
// loop over cells needs to reach further than the grid.
int clamped(double v, int limit) {
  if (!(v > -1.0)) return -1; // NaN too
  return v >= static_cast<double>(limit) ? limit : static_cast<int>(v);
}

} // namespace

DepthMap::DepthMap(double x0, double x1, double y0, double y1, double cell)
    : x0_(x0), y0_(y0), cell_(cell),
      z_(Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(std::ceil((y1 - y0) / cell)) + 1,
                                   static_cast<Eigen::Index>(std::ceil((x1 - x0) / cell)) + 1,
                                   std::numeric_limits<double>::quiet_NaN())) {}

void DepthMap::rasterise(std::span<const Vec3> p, std::span<const Triangle> triangles, double splat) {
  auto keep = [&](int r, int c, double z) {
    if (r < 0 || c < 0 || r >= rows() || c >= cols()) return;
    double& cur = z_(r, c);
    if (std::isnan(cur) || z > cur) cur = z;
  };
  if (triangles.empty()) {
    // A point cloud: the front-most layer, smoothly. First the front-most depth within the splat radius,
    // then a Gaussian-weighted mean of the points up to 3 mm behind it, so that the map (and landmarks
    // found in it) moves continuously with the frame instead of jumping from point to point.
    // The cells within the splat radius of a point, only those of the grid: a huge radius (a scan at an
    // absurd scale) costs at most the grid.
    auto for_cells = [&](const Vec3& q, const auto& visit) {
      const int rlo = std::max(0, clamped(std::ceil((q.y() - splat - y0_) / cell_), rows()));
      const int rhi = std::min(rows() - 1, clamped(std::floor((q.y() + splat - y0_) / cell_), rows()));
      const int clo = std::max(0, clamped(std::ceil((q.x() - splat - x0_) / cell_), cols()));
      const int chi = std::min(cols() - 1, clamped(std::floor((q.x() + splat - x0_) / cell_), cols()));
      for (int r = rlo; r <= rhi; ++r)
        for (int c = clo; c <= chi; ++c) {
          const double dx = x_of(c) - q.x(), dy = y_of(r) - q.y();
          if (dx * dx + dy * dy <= splat * splat) visit(r, c, dx * dx + dy * dy);
        }
    };
    for (const Vec3& q : p)
      for_cells(q, [&](int r, int c, double) { keep(r, c, q.z()); });
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(z_.rows(), z_.cols());
    Eigen::MatrixXd weight = Eigen::MatrixXd::Zero(z_.rows(), z_.cols());
    const double sigma2 = 0.25 * splat * splat;
    for (const Vec3& q : p)
      for_cells(q, [&](int r, int c, double d2) {
        if (q.z() < z_(r, c) - 3.0) return; // behind the front: an ear, the other side
        const double w = std::exp(-0.5 * d2 / sigma2);
        sum(r, c) += w * q.z();
        weight(r, c) += w;
      });
    for (Eigen::Index r = 0; r < z_.rows(); ++r)
      for (Eigen::Index c = 0; c < z_.cols(); ++c)
        if (weight(r, c) > 0.0) z_(r, c) = sum(r, c) / weight(r, c);
    return;
  }
  // The cells whose centres a triangle may cover: those between its vertices' extreme columns and rows.
  // Each vertex's bounds are found once (the first column and row at or after it, the last at or before
  // it): (v - origin) / cell, ceil, floor and the clamp are all monotone, so the extreme of the vertices'
  // bounds is the bound of their extreme, the same cells as computing them per triangle. Most triangles
  // of a scan cover no cell centre and end there.
  struct Bounds {
    int col_from, col_to, row_from, row_to;
  };
  std::vector<Bounds> bounds(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double col = (p[i].x() - x0_) / cell_, row = (p[i].y() - y0_) / cell_;
    bounds[i] = {clamped(std::ceil(col), cols()), clamped(std::floor(col), cols()),
                 clamped(std::ceil(row), rows()), clamped(std::floor(row), rows())};
  }
  for (const Triangle& t : triangles) {
    const Bounds& ba = bounds[t[0]];
    const Bounds& bb = bounds[t[1]];
    const Bounds& bc = bounds[t[2]];
    const int cmin = std::max(0, std::min({ba.col_from, bb.col_from, bc.col_from}));
    const int cmax = std::min(cols() - 1, std::max({ba.col_to, bb.col_to, bc.col_to}));
    const int rmin = std::max(0, std::min({ba.row_from, bb.row_from, bc.row_from}));
    const int rmax = std::min(rows() - 1, std::max({ba.row_to, bb.row_to, bc.row_to}));
    if (cmin > cmax || rmin > rmax) continue;
    const Vec3& a = p[t[0]];
    const Vec3& b = p[t[1]];
    const Vec3& c = p[t[2]];
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (!(std::abs(area) >= 1e-12) || !std::isfinite(area)) continue; // seen edge-on, or beyond a double
    for (int r = rmin; r <= rmax; ++r) {
      const double y = y_of(r);
      for (int col = cmin; col <= cmax; ++col) {
        const double x = x_of(col);
        // Barycentric coordinates of (x, y) in the projected triangle.
        const double wa = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) / area;
        const double wb = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) / area;
        const double wc = 1.0 - wa - wb;
        if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
        keep(r, col, wa * a.z() + wb * b.z() + wc * c.z());
      }
    }
  }
}

void DepthMap::drop_pits(double depth, double reach) {
  // A window longer than a line holds the whole line: reaching further changes nothing.
  const int n = std::max(1, clamped(std::ceil(reach / cell_), std::max(rows(), cols())));
  const auto width = static_cast<std::size_t>(n);
  // The front-most known depth among the n cells before and among the n cells after each cell of a line
  // (-inf when none), for every cell at once: the line padded with n unknown cells at both ends, and the
  // maximum of every n cells of it from the maxima of blocks of n cells (van Herk / Gil-Werman: a window
  // is the end of one block and the start of the next), without branches, so that the cost does not grow
  // with the reach. Maxima are exact: the same depths as any other way of finding them.
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> padded, prefix, suffix;
  const auto fronts = [&](const double* line, int length, double* before, double* after) {
    const std::size_t total = static_cast<std::size_t>(length) + 2 * width;
    padded.assign(total, none);
    for (int i = 0; i < length; ++i)
      padded[width + static_cast<std::size_t>(i)] = std::isnan(line[i]) ? none : line[i];
    prefix.resize(total);
    suffix.resize(total);
    for (std::size_t b = 0; b < total; b += width) {
      const std::size_t e = std::min(total, b + width);
      prefix[b] = padded[b];
      for (std::size_t j = b + 1; j < e; ++j)
        prefix[j] = std::max(prefix[j - 1], padded[j]);
      suffix[e - 1] = padded[e - 1];
      for (std::size_t j = e - 1; j > b; --j)
        suffix[j - 1] = std::max(suffix[j], padded[j - 1]);
    }
    // The maximum of padded[j, j + n).
    const auto window = [&](std::size_t j) { return std::max(suffix[j], prefix[j + width - 1]); };
    for (int i = 0; i < length; ++i) {
      const auto at = static_cast<std::size_t>(i);
      before[i] = window(at);
      after[i] = window(at + width + 1);
    }
  };
  // Along each column (contiguous in z_), both ways: the front within reach before and after every cell.
  // Then row by row (a copy of the row, taken before any cell of it is dropped): the fronts left and
  // right, and the verdict. Two maps of scratch, not five: detection calls this once a hypothesis, and
  // fresh maps cost more in page faults than the passes do in arithmetic.
  Eigen::MatrixXd below(z_.rows(), z_.cols()), above(z_.rows(), z_.cols());
  for (int c = 0; c < cols(); ++c)
    fronts(z_.col(c).data(), rows(), below.col(c).data(), above.col(c).data());
  const auto row_length = static_cast<std::size_t>(cols());
  std::vector<double> row(row_length), left(row_length), right(row_length);
  for (int r = 0; r < rows(); ++r) {
    for (int c = 0; c < cols(); ++c)
      row[static_cast<std::size_t>(c)] = z_(r, c);
    fronts(row.data(), cols(), left.data(), right.data());
    for (int c = 0; c < cols(); ++c) {
      if (!known(r, c)) continue;
      const auto at = static_cast<std::size_t>(c);
      const double floor = row[at] + depth;
      const bool across = left[at] > floor && right[at] > floor;
      const bool along = below(r, c) > floor && above(r, c) > floor;
      if (across || along) z_(r, c) = std::numeric_limits<double>::quiet_NaN();
    }
  }
}

void DepthMap::fill_holes(int max_gap) {
  // Pass by pass, each unknown cell with two or more known neighbours gets their mean (neighbours as they
  // were before the pass). Only the first pass looks at every cell: a cell can be filled in a later pass
  // only next to one the pass before filled.
  std::vector<std::pair<int, int>> candidates, next_candidates;
  for (int c = 0; c < cols(); ++c)
    for (int r = 0; r < rows(); ++r)
      if (!known(r, c)) candidates.emplace_back(r, c);
  std::vector<std::pair<std::pair<int, int>, double>> filled;
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> queued =
      Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>::Constant(z_.rows(), z_.cols(), -1);
  constexpr std::array<std::pair<int, int>, 4> kNeighbours{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
  for (int pass = 0; pass < max_gap && !candidates.empty(); ++pass) {
    filled.clear();
    for (const auto& [r, c] : candidates) {
      double sum = 0.0;
      int n = 0;
      for (auto [dr, dc] : kNeighbours) {
        const int rr = r + dr, cc = c + dc;
        if (rr < 0 || cc < 0 || rr >= rows() || cc >= cols() || !known(rr, cc)) continue;
        sum += z_(rr, cc);
        ++n;
      }
      if (n >= 2) filled.push_back({{r, c}, sum / n}); // only inside gaps, never growing the outline
    }
    next_candidates.clear();
    for (const auto& [cell, z] : filled)
      z_(cell.first, cell.second) = z;
    for (const auto& [cell, z] : filled)
      for (auto [dr, dc] : kNeighbours) {
        const int rr = cell.first + dr, cc = cell.second + dc;
        if (rr < 0 || cc < 0 || rr >= rows() || cc >= cols() || known(rr, cc) || queued(rr, cc) == pass)
          continue;
        queued(rr, cc) = pass;
        next_candidates.emplace_back(rr, cc);
      }
    std::swap(candidates, next_candidates);
  }
}

std::optional<double> DepthMap::at(double x, double y) const {
  // Bilinear between the four cells around (x, y) when all are known, so that depths, and landmarks found
  // from them, move continuously with the frame; else the nearest cell.
  const double u = (x - x0_) / cell_, v = (y - y0_) / cell_;
  const int c = clamped(std::floor(u), cols()), r = clamped(std::floor(v), rows());
  if (r >= 0 && c >= 0 && r + 1 < rows() && c + 1 < cols() && known(r, c) && known(r + 1, c) &&
      known(r, c + 1) && known(r + 1, c + 1)) {
    const double fu = u - c, fv = v - r;
    return (1 - fv) * ((1 - fu) * z_(r, c) + fu * z_(r, c + 1)) +
           fv * ((1 - fu) * z_(r + 1, c) + fu * z_(r + 1, c + 1));
  }
  const int cn = clamped(std::round(u), cols()), rn = clamped(std::round(v), rows());
  if (rn < 0 || cn < 0 || rn >= rows() || cn >= cols() || !known(rn, cn)) return std::nullopt;
  return z_(rn, cn);
}

std::optional<double> DepthMap::relief(double x, double y, double radius) const {
  const std::optional<double> centre = at(x, y);
  if (!centre) return std::nullopt;
  const int reach = clamped(std::ceil(radius / cell_), std::max(rows(), cols()));
  double sum = 0.0;
  int n = 0, total = 0;
  for (int dr = -reach; dr <= reach; ++dr)
    for (int dc = -reach; dc <= reach; ++dc) {
      if ((dr * dr + dc * dc) * cell_ * cell_ > radius * radius) continue;
      ++total;
      if (const auto z = at(x + dc * cell_, y + dr * cell_)) {
        sum += *z;
        ++n;
      }
    }
  if (n < total / 2) return std::nullopt; // too close to the edge of the scan to judge
  return *centre - sum / n;
}

DepthMap DepthMap::smoothed(double sigma) const {
  return smoothed(sigma, x0_, x_of(cols() - 1), y0_, y_of(rows() - 1));
}

DepthMap DepthMap::smoothed(double sigma, double x0, double x1, double y0, double y1) const {
  // Taps further than the grid is wide change nothing: a huge sigma costs at most the grid.
  const int reach = std::max(0, clamped(std::ceil(3.0 * sigma / cell_), std::max(rows(), cols())));
  const int width = 2 * reach + 1;
  std::vector<double> kernel(static_cast<std::size_t>(width));
  auto tap = [&](int offset) -> double& {
    const int at = offset + reach;
    return kernel[static_cast<std::size_t>(at)];
  };
  for (int i = -reach; i <= reach; ++i)
    tap(i) = std::exp(-0.5 * (i * cell_ / sigma) * (i * cell_ / sigma));
  DepthMap out = *this;
  out.z_.setConstant(std::numeric_limits<double>::quiet_NaN());
  // The cells of the window, and the block of the grid their taps reach: blurred within that block, a
  // window's cell sums the same taps in the same order as over the whole grid.
  const int c0 = std::max(0, clamped(std::floor((std::min(x0, x1) - x0_) / cell_), cols()));
  const int c1 = std::min(cols() - 1, clamped(std::ceil((std::max(x0, x1) - x0_) / cell_), cols()));
  const int r0 = std::max(0, clamped(std::floor((std::min(y0, y1) - y0_) / cell_), rows()));
  const int r1 = std::min(rows() - 1, clamped(std::ceil((std::max(y0, y1) - y0_) / cell_), rows()));
  if (c0 > c1 || r0 > r1) return out;
  const int bc0 = std::max(0, c0 - reach), bc1 = std::min(cols() - 1, c1 + reach);
  const int br0 = std::max(0, r0 - reach), br1 = std::min(rows() - 1, r1 + reach);
  const auto block = z_.block(br0, bc0, br1 - br0 + 1, bc1 - bc0 + 1);
  // Separable blur of z·known and of known, then their ratio: unknown cells do not pull depths to zero.
  const Eigen::MatrixXd mask = block.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : 1.0; });
  const Eigen::MatrixXd values = block.unaryExpr([](double v) { return std::isnan(v) ? 0.0 : v; });
  // Separable, a shifted block at a time (whole columns: Eigen's storage order, so it vectorises).
  auto blur = [&](const Eigen::MatrixXd& in) {
    const Eigen::Index rows = in.rows(), cols = in.cols();
    Eigen::MatrixXd across = Eigen::MatrixXd::Zero(rows, cols);
    for (int k = -reach; k <= reach; ++k) {
      const Eigen::Index n = cols - std::abs(k);
      if (n <= 0) continue;
      across.middleCols(std::max(0, -k), n) += tap(k) * in.middleCols(std::max(0, k), n);
    }
    Eigen::MatrixXd blurred = Eigen::MatrixXd::Zero(rows, cols);
    for (int k = -reach; k <= reach; ++k) {
      const Eigen::Index n = rows - std::abs(k);
      if (n <= 0) continue;
      blurred.middleRows(std::max(0, -k), n) += tap(k) * across.middleRows(std::max(0, k), n);
    }
    return blurred;
  };
  const Eigen::MatrixXd weight = blur(mask);
  const Eigen::MatrixXd sum = blur(values);
  for (int c = c0; c <= c1; ++c)
    for (int r = r0; r <= r1; ++r)
      if (!std::isnan(z_(r, c))) out.z_(r, c) = sum(r - br0, c - bc0) / weight(r - br0, c - bc0);
  return out;
}

std::optional<double> DepthMap::cupness(double x, double y) const {
  const double h = cell_;
  const auto c = at(x, y), e = at(x + h, y), w = at(x - h, y), n = at(x, y + h), s = at(x, y - h);
  const auto ne = at(x + h, y + h), nw = at(x - h, y + h), se = at(x + h, y - h), sw = at(x - h, y - h);
  if (!c || !e || !w || !n || !s || !ne || !nw || !se || !sw) return std::nullopt;
  const double zxx = (*e - 2 * *c + *w) / (h * h);
  const double zyy = (*n - 2 * *c + *s) / (h * h);
  const double zxy = (*ne - *nw - *se + *sw) / (4 * h * h);
  // Smaller eigenvalue of [[zxx, zxy], [zxy, zyy]].
  return 0.5 * (zxx + zyy) - std::sqrt(0.25 * (zxx - zyy) * (zxx - zyy) + zxy * zxy);
}

} // namespace pdeface
