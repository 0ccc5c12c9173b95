#include "sampling.hpp"

#include "detail.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace pdeface::slice::detail {
namespace {

// A fitted curve tabulated densely: heights (made non-decreasing) and arc length from its start.
struct HeightTable {
  Spline spline;
  std::vector<double> t, y, length;
};

// Heights relative to the curve's extent (0 at its bottom, 1 at its top), so that curves of different
// extents share the relative heights. The "length" counts each radian the curve turns as `turn_weight` mm:
// samples spaced evenly in it crowd where the profile bends (the lips, the nose), not only where it is long.
HeightTable height_table(Spline spline, std::array<double, 2> extent, double turn_weight) {
  constexpr std::size_t dense = 512;
  const double span = std::max(extent[1] - extent[0], 1e-9);
  HeightTable table{std::move(spline), {}, {}, {}};
  Vec3 previous = table.spline.evaluate(0.0);
  Vec3 direction = Vec3::Zero();
  for (std::size_t i = 0; i < dense; ++i) {
    const double t = static_cast<double>(i) / (dense - 1);
    const Vec3 p = table.spline.evaluate(t);
    table.t.push_back(t);
    const double y = (p.y() - extent[0]) / span;
    table.y.push_back(i == 0 ? y : std::max(table.y.back(), y));
    const Vec3 step = p - previous;
    double turn = 0.0;
    if (i > 1 && step.norm() > 0 && direction.norm() > 0)
      turn = std::acos(std::clamp(step.normalized().dot(direction), -1.0, 1.0));
    if (step.norm() > 0) direction = step.normalized();
    table.length.push_back(i == 0 ? 0.0 : table.length.back() + step.norm() + turn_weight * turn);
    previous = p;
  }
  return table;
}

// Linear interpolation of `to` at `x` in the non-decreasing `from`.
double interpolate(const std::vector<double>& from, const std::vector<double>& to, double x) {
  const auto hi = std::upper_bound(from.begin(), from.end(), x);
  if (hi == from.begin()) return to.front();
  if (hi == from.end()) return to.back();
  const auto i = static_cast<std::size_t>(hi - from.begin());
  const double span = from[i] - from[i - 1];
  const double w = span > 0 ? (x - from[i - 1]) / span : 0.0;
  return to[i - 1] + w * (to[i] - to[i - 1]);
}

// Each curve's share of its arc length in each of `grid` steps of relative height.
std::vector<std::vector<double>> arc_increments(std::span<const HeightTable> tables, std::size_t grid) {
  std::vector<std::vector<double>> out;
  for (const HeightTable& table : tables) {
    std::vector<double> d(grid, 0.0);
    double previous = 0.0;
    for (std::size_t g = 0; g < grid; ++g) {
      const double h = static_cast<double>(g) / static_cast<double>(grid - 1);
      const double fraction = interpolate(table.y, table.length, h) / table.length.back();
      if (g > 0) d[g] = std::max(0.0, fraction - previous);
      previous = fraction;
    }
    out.push_back(std::move(d));
  }
  return out;
}

// Relative heights whose gaps change by at most kMaxGapRatio from one to the next: the surface's cosine
// series in v through samples that crowd abruptly (under the nose tip, where a profile runs almost level)
// overshoots in height between them and folds the surface back on itself (ict_02: 0.08 % of the face's
// area facing away, a fold 0.04 mm deep under the nose). Small gaps beside large ones are widened, taking
// the room from the large ones, until the ratio holds.
constexpr double kMaxGapRatio = 2.5;
std::vector<double> limited_gaps(std::vector<double> heights) {
  const std::size_t k = heights.size();
  if (k < 3) return heights;
  std::vector<double> gap(k - 1);
  for (std::size_t i = 0; i + 1 < k; ++i)
    gap[i] = std::max(heights[i + 1] - heights[i], 0.0);
  for (int pass = 0; pass < 200; ++pass) {
    bool changed = false;
    for (std::size_t i = 0; i < gap.size(); ++i) {
      double floor = 0.0;
      if (i > 0) floor = std::max(floor, gap[i - 1] / kMaxGapRatio);
      if (i + 1 < gap.size()) floor = std::max(floor, gap[i + 1] / kMaxGapRatio);
      if (gap[i] < floor * (1.0 - 1e-9)) {
        gap[i] = floor;
        changed = true;
      }
    }
    double total = 0.0;
    for (double g : gap)
      total += g;
    for (double& g : gap)
      g /= total;
    if (!changed) break;
  }
  for (std::size_t i = 0; i + 1 < k; ++i)
    heights[i + 1] = heights[i] + gap[i];
  heights.back() = 1.0;
  return heights;
}

// K relative heights from 0 to 1 between which the curves' arc length advances evenly: the root mean square
// of the curves' increments, each curve weighted by `weights`. The root mean square leans towards the curves
// that are long there (the nose, the lips), which the plain mean dilutes by the outer curves: on
// facefuns_f18, m46 and f56 the surface lies 0.190 / 0.108 mm from the scan at 10 / 30 % on average, against
// 0.210 / 0.093 with the plain mean (all curves weighted alike).
std::vector<double> even_heights(const std::vector<std::vector<double>>& increments,
                                 std::span<const double> weights, std::size_t k) {
  const std::size_t grid = increments.front().size();
  std::vector<double> heights(grid), cumulative(grid, 0.0);
  for (std::size_t g = 0; g < grid; ++g)
    heights[g] = static_cast<double>(g) / static_cast<double>(grid - 1);
  for (std::size_t g = 1; g < grid; ++g) {
    double squares = 0.0;
    for (std::size_t i = 0; i < increments.size(); ++i)
      squares += weights[i] * increments[i][g] * increments[i][g];
    cumulative[g] = cumulative[g - 1] + std::sqrt(squares);
  }
  for (double& c : cumulative)
    c /= cumulative.back();
  std::vector<double> out(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = interpolate(cumulative, heights, static_cast<double>(i) / static_cast<double>(k - 1));
  out.front() = 0.0;
  out.back() = 1.0;
  return limited_gaps(out);
}

// The spline parameters where the curve is at `heights` (its ends exactly at 0 and 1).
std::vector<double> at_heights(const HeightTable& table, std::span<const double> heights) {
  std::vector<double> ts;
  for (double h : heights)
    ts.push_back(interpolate(table.y, table.t, h));
  ts.front() = 0.0;
  ts.back() = 1.0;
  for (std::size_t i = 1; i < ts.size(); ++i)
    ts[i] = std::max(ts[i], ts[i - 1]);
  return ts;
}

// The relative heights' grid for K samples: 2^-bits with 16 grid steps per sample interval on average
// (0.3-0.4 mm on a face at 10 %), so that placing the samples there moves them by a negligible amount.
int height_bits(std::size_t k) { return std::min(16, static_cast<int>(std::bit_width(k - 1)) + 4); }

// Heights are chosen at every third curve, the joints of a layout of 3 × patches + 1 curves (every curve
// otherwise), and blended between them.
std::size_t anchor_stride(std::size_t n) { return n >= 4 && (n - 1) % 3 == 0 ? 3 : 1; }

// Relative heights on the grid of 2^-bits, strictly ascending from exactly 0 to exactly 1: a `.pdef` stores a
// curve's heights as these integers (docs/pdef-format.md, "Heights").
std::vector<double> on_grid(std::span<const double> heights, int bits) {
  const auto top = static_cast<std::int64_t>(1) << bits;
  const std::size_t k = heights.size();
  std::vector<std::int64_t> n(k);
  for (std::size_t i = 0; i < k; ++i)
    n[i] = std::llround(std::clamp(heights[i], 0.0, 1.0) * static_cast<double>(top));
  n.front() = 0;
  n.back() = top;
  for (std::size_t i = 1; i + 1 < k; ++i) // ascending, with room for the ones above
    n[i] = std::clamp(n[i], n[i - 1] + 1, top - static_cast<std::int64_t>(k - 1 - i));
  std::vector<double> out(k);
  for (std::size_t i = 0; i < k; ++i)
    out[i] = std::ldexp(static_cast<double>(n[i]), -bits);
  return out;
}

} // namespace

Result<CurveSamples> sample_curves(std::span<const ProfileCurve> curves, std::size_t k,
                                   const ProfileOptions& options) {
  const SplineOptions spline{.parameter = options.parameter, .controls = k};
  const std::size_t n = curves.size();
  auto name = [&](std::size_t j) { return describe_plane(curves[j].index, curves[j].x, curves[j].feature); };
  std::vector<Spline> splines;
  for (std::size_t j = 0; j < n; ++j) {
    Result<Spline> fitted = fit_spline(curves[j].raw, spline);
    if (!fitted) return about(name(j), std::move(fitted).error());
    splines.push_back(*std::move(fitted));
  }
  // Where each curve's samples go, as spline parameters.
  CurveSamples out;
  std::vector<std::vector<double>> at(n), heights; // heights: relative (0 at a curve's bottom, 1 at its top)
  if (options.sampling == Sampling::Parameter) {
    for (auto& ts : at)
      for (std::size_t i = 0; i < k; ++i)
        ts.push_back(static_cast<double>(i) / static_cast<double>(k - 1));
  } else {
    std::vector<HeightTable> tables;
    for (std::size_t j = 0; j < n; ++j)
      tables.push_back(height_table(splines[j], curves[j].extent, options.turn_weight_mm));
    const auto increments = arc_increments(tables, 1024);
    const int bits = height_bits(k);
    heights.resize(n);
    if (options.sampling == Sampling::SharedHeights) {
      heights.assign(n, on_grid(even_heights(increments, std::vector<double>(n, 1.0), k), bits));
    } else {
      // Local heights at the anchors (every third curve: the joints), the same for a mirrored pair (the
      // face is symmetric in the canonical frame), on the grid; between anchors blended linearly in x.
      const std::size_t stride = anchor_stride(n);
      const auto local = [&](std::size_t j) {
        std::vector<double> weights(n);
        for (std::size_t i = 0; i < n; ++i)
          weights[i] = std::exp(-0.5 * std::pow((curves[i].x - curves[j].x) / options.sampling_window_mm, 2));
        return even_heights(increments, weights, k);
      };
      for (std::size_t a = 0; a < n; a += stride) {
        const std::size_t mirror = n - 1 - a;
        if (mirror < a) {
          heights[a] = heights[mirror];
          continue;
        }
        std::vector<double> h = local(a);
        if (mirror != a) {
          const std::vector<double> other = local(mirror);
          for (std::size_t i = 0; i < k; ++i)
            h[i] = 0.5 * (h[i] + other[i]);
        }
        heights[a] = on_grid(h, bits);
      }
      for (std::size_t j = 0; j < n; ++j) {
        if (j % stride == 0) continue;
        const std::size_t a = j - j % stride, b = a + stride;
        const double w = (curves[j].x - curves[a].x) / (curves[b].x - curves[a].x);
        heights[j].resize(k);
        for (std::size_t i = 0; i < k; ++i)
          heights[j][i] = (1 - w) * heights[a][i] + w * heights[b][i];
      }
    }
    for (std::size_t j = 0; j < n; ++j)
      at[j] = at_heights(tables[j], heights[j]);
    out.heights = heights[n / 2];
  }
  // The samples there.
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<Vec3> points;
    std::vector<double> absolute;
    if (!heights.empty()) {
      const double span = curves[j].extent[1] - curves[j].extent[0];
      for (std::size_t i = 0; i < k; ++i)
        absolute.push_back(i + 1 == k ? curves[j].extent[1] : curves[j].extent[0] + heights[j][i] * span);
    }
    if (options.fit == Fit::Cosine) {
      Result<std::vector<Vec3>> samples = absolute.empty()
                                              ? cosine_samples(curves[j].raw, at[j], spline)
                                              : cosine_samples(curves[j].raw, at[j], absolute, spline);
      if (!samples) return about(name(j), std::move(samples).error());
      points = *std::move(samples);
    }
    // A profile is a function of height (its front-most section): samples that double back in height (the
    // cosine fit ringing at a wall, where the front switches surfaces) would fold the surface; the spline's
    // samples, which follow the polyline, are taken there instead.
    const bool doubles_back = std::ranges::adjacent_find(points, [](const Vec3& a, const Vec3& b) {
                                return b.y() < a.y();
                              }) != points.end();
    if (points.empty() || doubles_back) {
      points.clear();
      for (double t : at[j])
        points.push_back(splines[j].evaluate(t));
      for (std::size_t i = 0; i < absolute.size(); ++i)
        points[i].y() = absolute[i];
    }
    out.points.push_back(std::move(points));
  }
  return out;
}

} // namespace pdeface::slice::detail
