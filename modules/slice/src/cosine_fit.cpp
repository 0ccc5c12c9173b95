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
  // The polyline at M + 1 values of v evenly over [0, π], v following the parameter piecewise linearly
  // through (at[k], v_k): the parameter of v_m is interpolated between the samples' parameters.
  const std::size_t m = std::max<std::size_t>(8 * k, 512);
  const double dv = std::numbers::pi / static_cast<double>(k - 1);
  Eigen::MatrixX3d p(static_cast<Eigen::Index>(m + 1), 3);
  std::size_t seg = 0;
  for (std::size_t r = 0; r <= m; ++r) {
    const double v = std::numbers::pi * static_cast<double>(r) / static_cast<double>(m);
    const double f = std::min(v / dv, static_cast<double>(k - 1));
    const auto i = std::min(static_cast<std::size_t>(f), k - 2);
    const double u = at[i] + (f - static_cast<double>(i)) * (at[i + 1] - at[i]);
    while (seg + 2 < t.size() && t[seg + 1] < u)
      ++seg;
    const double span = t[seg + 1] - t[seg];
    const double w = span > 0.0 ? std::clamp((u - t[seg]) / span, 0.0, 1.0) : 0.0;
    p.row(static_cast<Eigen::Index>(r)) = (points[seg] + w * (points[seg + 1] - points[seg])).transpose();
  }
  // On M + 1 even points with trapezoid weights the cosines are orthogonal (a DCT-I), so the least-squares
  // fit of the first K of them is the projection α_n = (2/M) Σ w_r p_r cos(n v_r) (α_0 halved), with the
  // weights the Gram matrix's diagonal g_n (M for n = 0, M/2 otherwise)...
  Eigen::MatrixX3d alpha = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(k), 3);
  Eigen::VectorXd gram(static_cast<Eigen::Index>(k));
  for (std::size_t r = 0; r <= m; ++r) {
    const double v = std::numbers::pi * static_cast<double>(r) / static_cast<double>(m);
    const double w = (r == 0 || r == m) ? 0.5 : 1.0;
    // cos(n v) by the recurrence cos((n+1) v) = 2 cos v cos(n v) − cos((n−1) v).
    double previous = 1.0, current = std::cos(v);
    const double twice = 2.0 * current;
    alpha.row(0) += w * p.row(static_cast<Eigen::Index>(r));
    for (std::size_t n = 1; n < k; ++n) {
      alpha.row(static_cast<Eigen::Index>(n)) += (w * current) * p.row(static_cast<Eigen::Index>(r));
      const double next = twice * current - previous;
      previous = current;
      current = next;
    }
  }
  for (std::size_t n = 0; n < k; ++n)
    gram(static_cast<Eigen::Index>(n)) = n == 0 ? static_cast<double>(m) : 0.5 * static_cast<double>(m);
  for (std::size_t n = 0; n < k; ++n)
    alpha.row(static_cast<Eigen::Index>(n)) /= gram(static_cast<Eigen::Index>(n));
  // ...then held to the polyline's ends: the least change in that metric for which Σ α_n = p(0) and
  // Σ (−1)^n α_n = p(π) (two constraints, solved in closed form).
  Eigen::Matrix<double, 2, Eigen::Dynamic> c(2, static_cast<Eigen::Index>(k));
  for (std::size_t n = 0; n < k; ++n) {
    c(0, static_cast<Eigen::Index>(n)) = 1.0;
    c(1, static_cast<Eigen::Index>(n)) = n % 2 == 0 ? 1.0 : -1.0;
  }
  const Eigen::MatrixXd ginv_ct = gram.cwiseInverse().asDiagonal() * c.transpose();
  Eigen::Matrix<double, 2, 3> miss;
  miss.row(0) = points.front().transpose() - c.row(0) * alpha;
  miss.row(1) = points.back().transpose() - c.row(1) * alpha;
  alpha += ginv_ct * (c * ginv_ct).ldlt().solve(miss);

  std::vector<Vec3> out(k);
  for (std::size_t i = 0; i < k; ++i) {
    const double v = dv * static_cast<double>(i);
    Vec3 q = alpha.row(0).transpose();
    double previous = 1.0, current = std::cos(v);
    const double twice = 2.0 * current;
    for (std::size_t n = 1; n < k; ++n) {
      q += current * alpha.row(static_cast<Eigen::Index>(n)).transpose();
      const double next = twice * current - previous;
      previous = current;
      current = next;
    }
    out[i] = q;
  }
  out.front() = points.front(); // exactly, whatever the rounding
  out.back() = points.back();
  return out;
}

} // namespace pdeface::slice
