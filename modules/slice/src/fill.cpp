#include "fill.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pdeface::slice::detail {

std::vector<std::vector<std::pair<double, double>>> fill_holes(std::span<const FillColumn> columns,
                                                               double step) {
  const std::size_t n = columns.size();
  std::vector<std::vector<std::pair<double, double>>> out(n);
  if (n == 0 || !(step > 0.0)) return out;
  double y0 = std::numeric_limits<double>::infinity(), y1 = -y0;
  for (const FillColumn& c : columns) {
    y0 = std::min(y0, c.extent[0]);
    y1 = std::max(y1, c.extent[1]);
  }
  if (!(y1 > y0)) return out;
  const auto rows = static_cast<std::size_t>(std::floor((y1 - y0) / step)) + 1;
  auto height = [&](std::size_t i) { return y0 + static_cast<double>(i) * step; };

  // Cell (j, i): inactive outside the column's extent, known (a depth), or unknown (a variable).
  constexpr int kInactive = -2, kKnown = -1;
  std::vector<std::vector<int>> id(n, std::vector<int>(rows, kInactive));
  std::vector<std::vector<double>> z(n, std::vector<double>(rows, 0.0));
  std::vector<std::pair<std::size_t, std::size_t>> unknowns;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < rows; ++i) {
      const double y = height(i);
      if (y < columns[j].extent[0] || y > columns[j].extent[1]) continue;
      if (const std::optional<double> d = columns[j].depth(y)) {
        id[j][i] = kKnown;
        z[j][i] = *d;
      } else {
        id[j][i] = static_cast<int>(unknowns.size());
        unknowns.emplace_back(j, i);
      }
    }
  if (unknowns.empty()) return out;

  // One equation per second difference touching an unknown: along each column (step h) and across
  // neighbouring columns at one height (divided differences over their spacing). Least squares.
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> rhs;
  auto equation = [&](std::initializer_list<std::pair<std::pair<std::size_t, std::size_t>, double>> terms) {
    bool any = false;
    for (const auto& [cell, w] : terms) {
      if (id[cell.first][cell.second] == kInactive) return;
      any = any || id[cell.first][cell.second] >= 0;
    }
    if (!any) return;
    const auto row = static_cast<int>(rhs.size());
    double b = 0.0;
    for (const auto& [cell, w] : terms) {
      const int v = id[cell.first][cell.second];
      if (v >= 0)
        entries.emplace_back(row, v, w);
      else
        b -= w * z[cell.first][cell.second];
    }
    rhs.push_back(b);
  };
  const double along = 1.0 / (step * step);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 1; i + 1 < rows; ++i)
      equation({{{j, i - 1}, along}, {{j, i}, -2.0 * along}, {{j, i + 1}, along}});
  for (std::size_t j = 1; j + 1 < n; ++j) {
    const double a = columns[j].x - columns[j - 1].x, b = columns[j + 1].x - columns[j].x;
    if (!(a > 0.0) || !(b > 0.0)) continue;
    const double left = 2.0 / (a * (a + b)), right = 2.0 / (b * (a + b));
    for (std::size_t i = 0; i < rows; ++i)
      equation({{{j - 1, i}, left}, {{j, i}, -(left + right)}, {{j + 1, i}, right}});
  }

  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(rhs.size()),
                                static_cast<Eigen::Index>(unknowns.size()));
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::Map<const Eigen::VectorXd> b(rhs.data(), static_cast<Eigen::Index>(rhs.size()));
  Eigen::SparseMatrix<double> normal = a.transpose() * a;
  // A whisper of ridge keeps a cell no equation reaches defined (at zero bending it is free otherwise).
  double scale = 0.0;
  for (Eigen::Index k = 0; k < normal.outerSize(); ++k)
    scale = std::max(scale, normal.coeff(k, k));
  for (Eigen::Index k = 0; k < normal.outerSize(); ++k)
    normal.coeffRef(k, k) += 1e-10 * scale;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  Eigen::VectorXd solution = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(unknowns.size()));
  if (solver.info() == Eigen::Success) solution = solver.solve(a.transpose() * b);

  for (std::size_t v = 0; v < unknowns.size(); ++v) {
    const auto [j, i] = unknowns[v];
    out[j].emplace_back(height(i), solution[static_cast<Eigen::Index>(v)]);
  }
  return out;
}

} // namespace pdeface::slice::detail
