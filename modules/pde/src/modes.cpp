#include "pdeface/pde/modes.hpp"

#include "basis.hpp"
#include "mode_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pdeface::pde {
namespace {

// Taylor coefficients in y = x² of sinh(x)/x = Σ x^{2k}/(2k+1)! and of
// g(x) = (x cosh x − sinh x)/x³ = Σ_{k≥1} 2k x^{2k−2}/(2k+1)!. Ten terms reach 1e-17 for |x| ≤ 1,
// which is all the series basis meets (x = m t with m < 1, t ∈ [0, 1]).
constexpr int series_terms = 10;
struct SeriesCoefficients {
  std::array<double, series_terms> shc{}, g{};
  constexpr SeriesCoefficients() {
    double factorial = 1; // (2k+1)!
    for (int k = 0; k < series_terms + 1; ++k) {
      if (k > 0) factorial *= (2 * k) * (2 * k + 1);
      if (k < series_terms) shc[k] = 1 / factorial;
      if (k > 0) g[k - 1] = 2 * k / factorial;
    }
  }
};
constexpr SeriesCoefficients series;

double horner(const std::array<double, series_terms>& c, double y) {
  double sum = 0;
  for (int k = series_terms - 1; k >= 0; --k)
    sum = sum * y + c[k];
  return sum;
}

void check_derivative(int derivative) {
  if (derivative < 0 || derivative > 2)
    throw std::invalid_argument("pde: derivative order must be 0, 1 or 2");
}

// cosh(mt), t·shc, t²·shc, t³·g with shc = sinh(x)/x, g = (x cosh x − sinh x)/x³ at x = m t: the series
// basis, equal to 1, t, t², t³/3 at m = 0 and well separated for every m < 1.
Eigen::Vector4d series_basis(double m, double t, int derivative) {
  const double x = m * t, y = x * x, m2 = m * m;
  const double c = std::cosh(x), s = horner(series.shc, y), g = horner(series.g, y);
  switch (derivative) {
  case 0: return {c, t * s, t * t * s, t * t * t * g};
  case 1: return {m2 * t * s, c, t * (s + c), t * t * s};
  default: return {m2 * c, m2 * t * s, 2 * c + m2 * t * t * s, t * (s + c)};
  }
}

} // namespace

Eigen::Vector4d stable_basis(double m, double t, int derivative) {
  check_derivative(derivative);
  if (!(m > 0)) throw std::invalid_argument("pde: the stable basis needs m > 0");
  const double e0 = std::exp(-m * t), e1 = std::exp(-m * (1 - t)), s = 1 - t, m2 = m * m;
  switch (derivative) {
  case 0: return {e0, m * t * e0, e1, m * s * e1};
  case 1: return {-m * e0, m * (1 - m * t) * e0, m * e1, m * (m * s - 1) * e1};
  default: return {m2 * e0, m2 * (m * t - 2) * e0, m2 * e1, m2 * (m * s - 2) * e1};
  }
}

namespace detail {

Eigen::Vector4d mode_basis(double m, double t, int derivative) {
  check_derivative(derivative);
  return m < small_mode_limit ? series_basis(m, t, derivative) : stable_basis(m, t, derivative);
}

void mode_basis_powers(double a, double length, double t, std::span<Eigen::Vector4d> out) {
  // m = a·f·length grows with f, so the series basis takes the first frequencies and the stable one the
  // rest; e^{−f·a·length·t}, e^{−f·a·length·(1−t)} and e^{f·a·length·t} are powers of their f = 1 values.
  const double step = a * length, s = 1 - t;
  const double down0 = std::exp(-step * t), down1 = std::exp(-step * s), up0 = std::exp(step * t);
  double e0 = 1, e1 = 1, up = 1; // the powers for frequency f
  std::size_t f = 0;
  for (; f < out.size(); ++f) {
    const double m = local_m(a, static_cast<double>(f), length);
    if (!(m < small_mode_limit)) break;
    const double x = m * t, y = x * x;
    const double c = (up + e0) / 2, sh = horner(series.shc, y), g = horner(series.g, y); // c = cosh(x)
    out[f] = {c, t * sh, t * t * sh, t * t * t * g};
    e0 *= down0;
    e1 *= down1;
    up *= up0;
  }
  for (; f < out.size(); ++f) {
    const double m = local_m(a, static_cast<double>(f), length);
    out[f] = {e0, m * t * e0, e1, m * s * e1};
    e0 *= down0;
    e1 *= down1;
  }
}

namespace {
Eigen::Matrix4d condition_matrix(double m, const std::array<Condition, 4>& conditions) {
  Eigen::Matrix4d rows;
  for (int i = 0; i < 4; ++i)
    rows.row(i) = mode_basis(m, conditions[i].t, conditions[i].derivative).transpose();
  return rows;
}
} // namespace

PieceSystem::PieceSystem(double m, const std::array<Condition, 4>& conditions) : m_(m) {
  const Eigen::PartialPivLU<Eigen::Matrix4d> lu(condition_matrix(m, conditions));
  inverse_ = lu.inverse();
  usable_ = inverse_.allFinite(); // a zero pivot (rows that underflowed to 0) makes it inf or NaN
}

} // namespace detail

Eigen::Matrix4d position_derivative_matrix(double m) {
  Eigen::Matrix4d rows;
  for (int i = 0; i < 4; ++i) {
    const auto& c = detail::hermite_conditions[i];
    rows.row(i) = stable_basis(m, c.t, c.derivative).transpose();
  }
  return rows;
}

Eigen::Matrix4d four_position_matrix(double m, double s1, double s2) {
  Eigen::Matrix4d rows;
  const double nodes[4] = {0, s1, s2, 1};
  for (int i = 0; i < 4; ++i)
    rows.row(i) = stable_basis(m, nodes[i]).transpose();
  return rows;
}

Eigen::Vector4d hermite_cardinals(double m, double t, int derivative) {
  return detail::PieceSystem(m, detail::hermite_conditions).cardinals(t, derivative);
}

double four_position_amplification(double m, double s1, double s2) {
  constexpr double infinite = std::numeric_limits<double>::infinity();
  const detail::PieceSystem system(m, detail::four_position_conditions(s1, s2));
  if (!system.usable()) return infinite;
  const auto lebesgue = [&](double t) { return system.cardinals(t, 0).cwiseAbs().sum(); };
  // The peak sits near an end for large m (t ≈ 1 − 1/m): a fine scan, then golden-section refinement
  // between the neighbours of the best sample.
  constexpr int samples = 512;
  double best = 0, best_t = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples, value = lebesgue(t);
    if (!(value <= best)) best = value, best_t = t; // NaN propagates
  }
  if (!std::isfinite(best)) return infinite;
  double lo = std::max(0.0, best_t - 1.0 / samples), hi = std::min(1.0, best_t + 1.0 / samples);
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double t1 = hi - ratio * (hi - lo), t2 = lo + ratio * (hi - lo), f1 = lebesgue(t1), f2 = lebesgue(t2);
  for (int i = 0; i < 40; ++i) {
    if (f1 > f2) {
      hi = t2, t2 = t1, f2 = f1, t1 = hi - ratio * (hi - lo), f1 = lebesgue(t1);
    } else {
      lo = t1, t1 = t2, f1 = f2, t2 = lo + ratio * (hi - lo), f2 = lebesgue(t2);
    }
  }
  return std::max({best, f1, f2});
}

Eigen::MatrixXd cosine_coefficients(const Eigen::MatrixXd& samples) {
  const Eigen::Index count = samples.rows();
  if (count < 2) throw std::invalid_argument("pde: cosine coefficients need at least 2 samples");
  const Eigen::Index intervals = count - 1;
  // cos(n k π/(K−1)) depends only on n·k mod 2(K−1): one table instead of K² cosines.
  std::vector<double> table(static_cast<std::size_t>(2 * intervals));
  for (std::size_t r = 0; r < table.size(); ++r)
    table[r] = std::cos(std::numbers::pi * static_cast<double>(r) / static_cast<double>(intervals));
  // The K × K transform is applied a block of rows at a time: the same product, without a large
  // temporary (at K = 300 a fresh 720 KB matrix per call cost more in page faults than the arithmetic).
  constexpr Eigen::Index block = 32;
  Eigen::MatrixXd rows(std::min(block, count), count), alpha(count, samples.cols());
  const auto period = static_cast<std::size_t>(2 * intervals);
  for (Eigen::Index first = 0; first < count; first += block) {
    const Eigen::Index size = std::min(block, count - first);
    for (Eigen::Index n = first; n < first + size; ++n) {
      const double end_mode = (n == 0 || n == intervals) ? 0.5 : 1.0;
      std::size_t r = 0; // n·k mod 2(K−1), stepped without a division (n < 2(K−1))
      for (Eigen::Index k = 0; k < count; ++k) {
        const double end_sample = (k == 0 || k == intervals) ? 0.5 : 1.0;
        rows(n - first, k) = 2.0 / static_cast<double>(intervals) * end_mode * end_sample * table[r];
        r += static_cast<std::size_t>(n);
        if (r >= period) r -= period;
      }
    }
    alpha.middleRows(first, size).noalias() = rows.topRows(size) * samples;
  }
  return alpha;
}

} // namespace pdeface::pde
