#include "pdeface/slice/spline.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace pdeface::slice {

namespace {

// Σ c_n cos(n v) over the rows of `c` (any number of columns), by the recurrence
// cos((n+1) v) = 2 cos v cos(n v) − cos((n−1) v).
template <typename Coefficients> auto cosine_series(const Coefficients& c, double v) {
  using Row = Eigen::Matrix<double, 1, Coefficients::ColsAtCompileTime>;
  Row sum = c.row(0);
  double previous = 1.0, current = std::cos(v);
  const double twice = 2.0 * current;
  for (Eigen::Index n = 1; n < c.rows(); ++n) {
    sum += current * c.row(n);
    const double next = twice * current - previous;
    previous = current;
    current = next;
  }
  return sum;
}

// The K samples at v_k = kπ/(K − 1) of the least-squares fit of the first K cosines to the M + 1 rows of `p`
// (the curve at v_r = rπ/M), held to `front` and `back` at its ends.
std::vector<Vec3> fit_and_sample(const Eigen::MatrixX3d& p, std::size_t k, const Vec3& front,
                                 const Vec3& back) {
  const auto m = static_cast<std::size_t>(p.rows() - 1);
  const double dv = std::numbers::pi / static_cast<double>(k - 1);
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
  miss.row(0) = front.transpose() - c.row(0) * alpha;
  miss.row(1) = back.transpose() - c.row(1) * alpha;
  alpha += ginv_ct * (c * ginv_ct).ldlt().solve(miss);

  std::vector<Vec3> out(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = cosine_series(alpha, dv * static_cast<double>(i)).transpose();
  out.front() = front; // exactly, whatever the rounding
  out.back() = back;
  return out;
}

// The polyline at M + 1 values of v evenly over [0, π], v following the parameter piecewise linearly through
// (at[k], v_k): the parameter of v_m is interpolated between the samples' parameters. Each row's segment in
// `segments` when given.
Eigen::MatrixX3d by_parameter(std::span<const Vec3> points, std::span<const double> t,
                              std::span<const double> at, std::size_t m, std::vector<std::size_t>* segments) {
  const std::size_t k = at.size();
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
    if (segments != nullptr) segments->push_back(seg);
  }
  return p;
}

// The point where the polyline, walked from `q` on segment `seg` towards height h (forwards over the points
// after the segment when q is below h, backwards over its start and those before when above), first reaches
// h; the last point walked when it never does.
Vec3 walk_to_height(std::span<const Vec3> points, std::size_t seg, const Vec3& q, double h) {
  if (q.y() == h) return q;
  const bool up = q.y() < h;
  const std::size_t ahead = up ? points.size() - seg - 1 : seg + 1;
  Vec3 from = q;
  for (std::size_t i = 0; i < ahead; ++i) {
    const Vec3& to = points[up ? seg + 1 + i : seg - i];
    if (up ? to.y() >= h : to.y() <= h) return from + (h - from.y()) / (to.y() - from.y()) * (to - from);
    from = to;
  }
  return from;
}

std::optional<Error> check_parameters(std::span<const double> at) {
  if (at.size() < 4 || at.front() != 0.0 || at.back() != 1.0 || !std::ranges::is_sorted(at))
    return Error{ErrorCode::InvalidArgument,
                 "cosine samples: the parameters must ascend from 0 to 1 (4 or more)"};
  return std::nullopt;
}

Result<std::vector<double>> polyline_parameters(std::span<const Vec3> points, const SplineOptions& options) {
  std::vector<double> t = parameters(points, options);
  if (t.empty())
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("the points do not advance along the {} parameter", to_string(options.parameter)));
  return t;
}

} // namespace

Result<std::vector<Vec3>> cosine_samples(std::span<const Vec3> points, std::span<const double> at,
                                         const SplineOptions& options) {
  if (std::optional<Error> e = check_parameters(at)) return *e;
  Result<std::vector<double>> t = polyline_parameters(points, options);
  if (!t) return t.error();
  const std::size_t m = std::max<std::size_t>(8 * at.size(), 512);
  return fit_and_sample(by_parameter(points, *t, at, m, nullptr), at.size(), points.front(), points.back());
}

Result<std::vector<Vec3>> cosine_samples(std::span<const Vec3> points, std::span<const double> at,
                                         std::span<const double> heights, const SplineOptions& options) {
  if (std::optional<Error> e = check_parameters(at)) return *e;
  const std::size_t k = at.size();
  if (heights.size() != k || !std::ranges::is_sorted(heights))
    return make_error(ErrorCode::InvalidArgument, "cosine samples: one height per parameter, ascending");
  Result<std::vector<double>> t = polyline_parameters(points, options);
  if (!t) return t.error();
  const std::size_t m = std::max<std::size_t>(8 * k, 512);
  std::vector<std::size_t> segments;
  Eigen::MatrixX3d p = by_parameter(points, *t, at, m, &segments);
  // The heights' cosine interpolant h(v) (the DCT-I through them: the series the surface follows in y)...
  const double n1 = static_cast<double>(k - 1);
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(k));
  for (std::size_t n = 0; n < k; ++n) {
    const auto row = static_cast<Eigen::Index>(n);
    for (std::size_t i = 0; i < k; ++i)
      beta(row) += (i == 0 || i + 1 == k ? 0.5 : 1.0) * heights[i] *
                   std::cos(std::numbers::pi * static_cast<double>(n * i % (2 * (k - 1))) / n1);
    beta(row) *= (n == 0 || n + 1 == k ? 1.0 : 2.0) / n1;
  }
  // ...and each row moved along the polyline from where the parameter put it to where the profile is at
  // h(v): so the fit's y is the heights' series itself, and its z the least-squares cosine fit of the
  // profile's depth along it (where the profile runs level, under the nose, the parameter still spreads
  // the rows along it).
  for (std::size_t r = 0; r <= m; ++r) {
    const double v = std::numbers::pi * static_cast<double>(r) / static_cast<double>(m);
    const double h = cosine_series(beta, v)(0);
    const auto row = static_cast<Eigen::Index>(r);
    Vec3 q = walk_to_height(points, segments[r], p.row(row).transpose(), h);
    q.y() = h;
    p.row(row) = q.transpose();
  }
  Vec3 front = points.front(), back = points.back();
  front.y() = heights.front();
  back.y() = heights.back();
  std::vector<Vec3> out = fit_and_sample(p, k, front, back);
  for (std::size_t i = 0; i < k; ++i)
    out[i].y() = heights[i];
  return out;
}

} // namespace pdeface::slice
