#include "pdeface/slice/spline.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pdeface::slice {

Result<std::vector<Vec3>> cosine_samples(std::span<const Vec3> points, std::span<const double> at,
                                         const SplineOptions& options) {
  const std::size_t k = at.size();
  if (k < 4 || at.front() != 0.0 || at.back() != 1.0 || !std::ranges::is_sorted(at))
    return make_error(ErrorCode::InvalidArgument,
                      "cosine samples: the parameters must ascend from 0 to 1 (4 or more)");
  const std::vector<double> t = parameters(points, options);
  if (t.empty())
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("the points do not advance along the {} parameter", to_string(options.parameter)));
  // v as a function of the parameter: piecewise linear through (at[k], v_k).
  const double dv = std::numbers::pi / static_cast<double>(k - 1);
  auto v_of = [&](double u) {
    const auto hi = std::upper_bound(at.begin(), at.end(), u);
    if (hi == at.begin()) return 0.0;
    if (hi == at.end()) return std::numbers::pi;
    const auto i = static_cast<std::size_t>(hi - at.begin());
    const double span = at[i] - at[i - 1];
    return dv * (static_cast<double>(i - 1) + (span > 0.0 ? (u - at[i - 1]) / span : 0.0));
  };
  // The polyline sampled evenly in its parameter, densely enough for K cosines (rows weighted alike: an L2
  // fit of the curve, not of where the scanner happened to put points).
  const std::size_t m = std::max<std::size_t>(8 * k, 400);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(k));
  Eigen::MatrixXd b(static_cast<Eigen::Index>(m), 3);
  std::size_t seg = 0;
  for (std::size_t r = 0; r < m; ++r) {
    const double u = static_cast<double>(r) / static_cast<double>(m - 1);
    while (seg + 2 < t.size() && t[seg + 1] < u)
      ++seg;
    const double span = t[seg + 1] - t[seg];
    const double w = span > 0.0 ? std::clamp((u - t[seg]) / span, 0.0, 1.0) : 0.0;
    const Vec3 p = points[seg] + w * (points[seg + 1] - points[seg]);
    const double v = v_of(u);
    for (std::size_t n = 0; n < k; ++n)
      a(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(n)) = std::cos(static_cast<double>(n) * v);
    b.row(static_cast<Eigen::Index>(r)) = p.transpose();
  }
  // The ends held: heavily weighted rows at v = 0 and v = π.
  Eigen::MatrixXd normal = a.transpose() * a;
  Eigen::MatrixXd rhs = a.transpose() * b;
  const double heavy = 1e4 * static_cast<double>(m);
  for (int end = 0; end < 2; ++end) {
    Eigen::RowVectorXd row(static_cast<Eigen::Index>(k));
    for (std::size_t n = 0; n < k; ++n)
      row(static_cast<Eigen::Index>(n)) = end == 0 ? 1.0 : (n % 2 == 0 ? 1.0 : -1.0);
    const Vec3& p = end == 0 ? points.front() : points.back();
    normal += heavy * row.transpose() * row;
    rhs += heavy * row.transpose() * p.transpose();
  }
  normal.diagonal().array() += 1e-12 * normal.diagonal().maxCoeff();
  const Eigen::MatrixXd alpha = normal.ldlt().solve(rhs);
  std::vector<Vec3> out(k);
  for (std::size_t i = 0; i < k; ++i) {
    Vec3 p = Vec3::Zero();
    for (std::size_t n = 0; n < k; ++n)
      p += std::cos(static_cast<double>(n * i) * dv) * alpha.row(static_cast<Eigen::Index>(n)).transpose();
    out[i] = p;
  }
  out.front() = points.front();
  out.back() = points.back();
  return out;
}

} // namespace pdeface::slice
