#include "pdeface/slice/spline.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace pdeface::slice {
namespace {

// The span of t and the four non-zero cubic basis functions there (Cox–de Boor on clamped uniform
// knots: n − 3 spans of width h = 1 / (n − 3)).
struct Basis {
  std::size_t first; // index of the first of the four control points
  std::array<double, 4> value;
};

Basis basis(double t, std::size_t n) {
  const std::size_t spans = n - 3;
  t = std::clamp(t, 0.0, 1.0);
  const std::size_t span = std::min(spans - 1, static_cast<std::size_t>(t * static_cast<double>(spans)));
  // Knot k (k = 0..n+3) of the clamped vector, in units of the span width.
  auto knot = [&](std::ptrdiff_t k) {
    return static_cast<double>(std::clamp<std::ptrdiff_t>(k - 3, 0, static_cast<std::ptrdiff_t>(spans)));
  };
  const double x = t * static_cast<double>(spans);
  const auto i = static_cast<std::ptrdiff_t>(span) + 3; // knot[i] <= x < knot[i + 1]
  std::array<double, 4> weights{1.0, 0.0, 0.0, 0.0};
  std::array<double, 4> left{}, right{};
  for (std::size_t d = 1; d <= 3; ++d) {
    left[d] = x - knot(i + 1 - static_cast<std::ptrdiff_t>(d));
    right[d] = knot(i + static_cast<std::ptrdiff_t>(d)) - x;
    double saved = 0.0;
    for (std::size_t r = 0; r < d; ++r) {
      const double denom = right[r + 1] + left[d - r];
      const double temp = denom == 0.0 ? 0.0 : weights[r] / denom;
      weights[r] = saved + right[r + 1] * temp;
      saved = left[d - r] * temp;
    }
    weights[d] = saved;
  }
  return {span, weights};
}

// Solves the symmetric positive definite band system (half-bandwidth 3) in place by Cholesky.
// band[i][k] holds A(i, i − k); rhs is overwritten with the solution. False if not positive definite.
bool solve_band(std::vector<std::array<double, 4>>& band, std::vector<Vec3>& rhs) {
  const std::size_t n = band.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = std::min<std::size_t>(3, i); k >= 1; --k) { // L(i, i−k)
      const std::size_t j = i - k;
      double s = band[i][k];
      for (std::size_t m = 1; m + k <= 3 && m <= j; ++m)
        s -= band[i][k + m] * band[j][m];
      band[i][k] = s / band[j][0];
    }
    double d = band[i][0];
    for (std::size_t k = 1; k <= std::min<std::size_t>(3, i); ++k)
      d -= band[i][k] * band[i][k];
    if (!(d > 0.0)) return false;
    band[i][0] = std::sqrt(d);
  }
  for (std::size_t i = 0; i < n; ++i) { // L y = b
    for (std::size_t k = 1; k <= std::min<std::size_t>(3, i); ++k)
      rhs[i] -= band[i][k] * rhs[i - k];
    rhs[i] /= band[i][0];
  }
  for (std::size_t i = n; i-- > 0;) { // Lᵀ x = y
    for (std::size_t k = 1; k <= 3 && i + k < n; ++k)
      rhs[i] -= band[i + k][k] * rhs[i + k];
    rhs[i] /= band[i][0];
  }
  return true;
}

} // namespace

std::string_view to_string(Parameter parameter) noexcept {
  return name_of<Parameter>(kParameterNames, parameter);
}

Spline::Spline(std::vector<Vec3> controls) : controls_(std::move(controls)) {
  if (controls_.size() < 4) throw std::invalid_argument("slice::Spline: fewer than 4 control points");
}

Vec3 Spline::evaluate(double t) const {
  const Basis b = basis(t, controls_.size());
  Vec3 p = Vec3::Zero();
  for (std::size_t k = 0; k < 4; ++k)
    p += b.value[k] * controls_[b.first + k];
  return p;
}

std::vector<Vec3> Spline::resample(std::size_t k) const {
  if (k < 2) throw std::invalid_argument("slice::Spline::resample: fewer than 2 points");
  std::vector<Vec3> out(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = evaluate(static_cast<double>(i) / static_cast<double>(k - 1));
  return out;
}

std::vector<double> parameters(std::span<const Vec3> points, const SplineOptions& options) {
  std::vector<double> t(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i)
    t[i] = options.parameter == Parameter::Height ? options.along.dot(points[i] - points[0])
                                                  : t[i - 1] + (points[i] - points[i - 1]).norm();
  if (t.empty() || !(t.back() > 0.0)) return {};
  const double total = t.back();
  for (double& v : t)
    v /= total;
  return t;
}

Result<Spline> fit_spline(std::span<const Vec3> points, const SplineOptions& options) {
  const std::size_t n = options.controls;
  if (n < 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("a cubic spline needs at least 4 control points, "
                                  "not {}",
                                  n));
  const std::vector<double> t = parameters(points, options);
  if (t.empty())
    return make_error(
        ErrorCode::InvalidArgument,
        fmt::format("the points do not advance along the {} parameter", to_string(options.parameter)));

  // A chord longer than half a span (a bridged hole, a jump at an occlusion) gets points along it every
  // quarter span, so that no span is left without data; shorter chords are left alone, since points on
  // a chord are only as good as linear interpolation.
  const double span = 1.0 / static_cast<double>(n - 3), step = 0.25 * span;
  std::vector<std::pair<double, Vec3>> data;
  data.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i > 0 && t[i] - t[i - 1] > 0.5 * span) {
      const auto pieces = static_cast<std::size_t>(std::ceil((t[i] - t[i - 1]) / step));
      for (std::size_t k = 1; k < pieces; ++k) {
        const double f = static_cast<double>(k) / static_cast<double>(pieces);
        data.emplace_back(t[i - 1] + f * (t[i] - t[i - 1]), points[i - 1] + f * (points[i] - points[i - 1]));
      }
    }
    data.emplace_back(t[i], points[i]);
  }

  // Normal equations AᵀA c = Aᵀp: a band matrix of half-bandwidth 3.
  std::vector<std::array<double, 4>> band(n, std::array<double, 4>{});
  std::vector<Vec3> rhs(n, Vec3::Zero());
  for (const auto& [ti, pi] : data) {
    const Basis b = basis(ti, n);
    for (std::size_t r = 0; r < 4; ++r) {
      rhs[b.first + r] += b.value[r] * pi;
      for (std::size_t c = 0; c <= r; ++c)
        band[b.first + r][r - c] += b.value[r] * b.value[c];
    }
  }
  // A small penalty on second differences of the control points (Dᵀ D, rows [1 −2 1]).
  double scale = 0.0;
  for (const auto& row : band)
    scale = std::max(scale, row[0]);
  const double lambda = options.smoothing * scale;
  for (std::size_t i = 0; i + 2 < n; ++i) {
    const std::array<double, 3> d{1.0, -2.0, 1.0};
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t c = 0; c <= r; ++c)
        band[i + r][r - c] += lambda * d[r] * d[c];
  }
  // The ends are the profile's ends: a clamped spline passes through its first and last control points,
  // so fixing them to the first and last points keeps every curve on the common height range exactly
  // (a free least-squares end drifts by the local misfit: up to 1.1 mm on the coarse scans).
  const std::array<std::pair<std::size_t, Vec3>, 2> ends{{{0, points.front()}, {n - 1, points.back()}}};
  auto entry = [&](std::size_t i, std::size_t j) -> double& {
    return i >= j ? band[i][i - j] : band[j][j - i];
  };
  auto near = [&](std::size_t j) { return std::pair{j >= 3 ? j - 3 : 0, std::min(n - 1, j + 3)}; };
  for (const auto& [j, value] : ends) {
    const auto [from, to] = near(j);
    for (std::size_t i = from; i <= to; ++i)
      if (i != 0 && i != n - 1) rhs[i] -= entry(i, j) * value;
  }
  for (const auto& [j, value] : ends) {
    const auto [from, to] = near(j);
    for (std::size_t i = from; i <= to; ++i)
      entry(i, j) = i == j ? 1.0 : 0.0;
    rhs[j] = value;
  }
  if (!solve_band(band, rhs))
    return make_error(ErrorCode::InvalidArgument,
                      "the spline fit is singular: spans of the parameter hold no "
                      "points (raise the smoothing or lower the control points)");
  return Spline(std::move(rhs));
}

} // namespace pdeface::slice
