// The lossy grid: samples rounded to it, and the check that the decoded surface stays within the maximum
// error of the original (tightening the grid until it does).

#include "lossy.hpp"

#include "frame.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

namespace pdeface::pdef::detail {
namespace {

// The steps stay below 2^26 units (64 mm), so that a value (≤ 2^26 steps) times its step is an exact
// integer below 2^52 before it is scaled by 2^-20: decoding involves no rounding at all.
constexpr std::uint32_t kMaxStepUnits = std::uint32_t{1} << 26;

double value(std::int64_t q, std::uint32_t units) { return static_cast<double>(q * units) * kStepUnit; }

std::optional<std::int64_t> rounded(double v, double step) {
  const double q = std::round(v / step);
  if (!(std::abs(q) <= static_cast<double>(kMaxQuantised))) return std::nullopt;
  return static_cast<std::int64_t>(q);
}

Grid grid_of(std::uint32_t step) { return {step, std::max<std::uint32_t>(1, step / kPlaneRefinement)}; }

// The largest distance between the face's samples and those decoded from `decoded`.
double sample_error(const Face& face, const Face& decoded) {
  double worst = 0;
  for (std::size_t j = 0; j < face.curve_count(); ++j)
    worst = std::max(worst, (face.curves.samples[j] - decoded.curves.samples[j]).rowwise().norm().maxCoeff());
  return worst;
}

// How far (mm) mapping the face back with the frame stored as float32 moves it: the largest over the
// corners of the curves' bounding box (the difference of two affine maps is largest at a corner).
double float32_frame_error(const Face& face) {
  const Frame rounded32 = as_float32(face.frame);
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const pde::Curve& c : face.curves.samples) {
    lo = lo.cwiseMin(c.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(c.colwise().maxCoeff().transpose());
  }
  double worst = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                 (corner & 4) ? hi.z() : lo.z());
    worst = std::max(worst, (rounded32.to_scan(p) - face.frame.to_scan(p)).norm() * face.frame.scale);
  }
  return worst;
}

bool frame_is_float32(const Frame& f) {
  const Frame back = as_float32(f);
  return back.rotation == f.rotation && back.translation == f.translation && back.scale == f.scale;
}

// A point of `surface` and its two tangents.
struct Local {
  Vec3 x, xu, xv;
};
Local local(const pde::Surface& surface, double u, double v) {
  const std::array<double, 1> us{u}, vs{v};
  return {surface.evaluate(us, vs).points[0], surface.evaluate(us, vs, pde::Derivative::U).points[0],
          surface.evaluate(us, vs, pde::Derivative::V).points[0]};
}

// The distance from p to `surface`, starting at (u, v): a few damped Gauss-Newton steps (the tangents
// vanish at v = 0 and π, where the surface folds over in v), the smallest distance met.
double distance_to(const pde::Surface& surface, const Vec3& p, double u, double v, double step_u,
                   double step_v) {
  double best = std::numeric_limits<double>::max();
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Local l = local(surface, u, v);
    const Vec3 d = p - l.x;
    best = std::min(best, d.norm());
    Eigen::Matrix<double, 3, 2> jacobian;
    jacobian << l.xu, l.xv;
    Eigen::Matrix2d normal = jacobian.transpose() * jacobian;
    normal.diagonal().array() += 1e-9 * normal.trace() + 1e-300;
    const Eigen::Vector2d delta = normal.ldlt().solve(jacobian.transpose() * d);
    if (!delta.allFinite()) break;
    u = std::clamp(u + std::clamp(delta(0), -step_u, step_u), 0.0, surface.u_max());
    v = std::clamp(v + std::clamp(delta(1), -step_v, step_v), 0.0, std::numbers::pi);
  }
  return std::min(best, (p - local(surface, u, v).x).norm());
}

} // namespace

std::optional<Quantised> quantise(const Face& face, const Grid& grid) {
  Quantised q;
  q.curves = face.curve_count();
  q.samples = face.sample_count();
  const double step = grid.step_mm(), plane_step = grid.plane_step_mm();
  for (std::size_t j = 0; j < q.curves; ++j) {
    const std::optional<std::int64_t> x = rounded(face.planes[j], plane_step);
    if (!x || (j > 0 && *x <= q.planes.back())) return std::nullopt;
    q.planes.push_back(*x);
    const pde::Curve& c = face.curves.samples[j];
    for (Eigen::Index k = 0; k < c.rows(); ++k) {
      const std::optional<std::int64_t> y = rounded(c(k, 1), step), z = rounded(c(k, 2), step);
      if (!y || !z) return std::nullopt;
      q.y.push_back(*y);
      q.z.push_back(*z);
    }
  }
  return q;
}

void dequantise(const Quantised& q, const Grid& grid, Face& face) {
  face.planes.resize(q.curves);
  face.curves.units = Units::Millimetres;
  face.curves.samples.assign(q.curves, pde::Curve(static_cast<Eigen::Index>(q.samples), 3));
  for (std::size_t j = 0; j < q.curves; ++j) {
    face.planes[j] = value(q.planes[j], grid.plane_step);
    pde::Curve& c = face.curves.samples[j];
    for (std::size_t k = 0; k < q.samples; ++k) {
      const auto row = static_cast<Eigen::Index>(k);
      c(row, 0) = face.planes[j];
      c(row, 1) = value(q.y[j * q.samples + k], grid.step);
      c(row, 2) = value(q.z[j * q.samples + k], grid.step);
    }
  }
}

double surface_error(const pde::Surface& reference, const pde::Surface& decoded, double limit) {
  const std::vector<double>& knots = reference.knots();
  std::vector<double> us, vs;
  for (std::size_t j = 0; j + 1 < knots.size(); ++j)
    for (int i = 0; i < 4; ++i)
      us.push_back(knots[j] + (knots[j + 1] - knots[j]) * i / 4.0);
  us.push_back(reference.u_max());
  const std::size_t intervals = reference.sample_count() - 1;
  for (std::size_t k = 0; k < intervals; ++k)
    for (int i = 0; i < 8; ++i)
      vs.push_back(std::numbers::pi * (static_cast<double>(k) + i / 8.0) / static_cast<double>(intervals));
  vs.push_back(std::numbers::pi);
  const pde::Grid a = reference.evaluate(us, vs), b = decoded.evaluate(us, vs);

  // Points in decreasing order of their distance at the same (u, v): the distance to the surface is at
  // most that, so once it falls below the largest found the rest cannot change the answer.
  std::vector<double> same(a.points.size());
  for (std::size_t i = 0; i < same.size(); ++i)
    same[i] = (a.points[i] - b.points[i]).norm();
  std::vector<std::size_t> order(same.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::ranges::sort(order, [&](std::size_t l, std::size_t r) { return same[l] > same[r]; });
  const double step_u = reference.u_max() / static_cast<double>(knots.size() - 1);
  const double step_v = std::numbers::pi / static_cast<double>(intervals);
  double worst = 0;
  for (const std::size_t i : order) {
    if (same[i] <= worst) break;
    const std::size_t iu = i % a.u_count, iv = i / a.u_count;
    worst = std::max(worst, distance_to(reference, b.points[i], us[iu], vs[iv], step_u, step_v));
    if (worst > limit) break;
  }
  return worst;
}

Result<LossyPlan> plan_lossy(const Face& face, const EncodeOptions& options) {
  const double e = options.max_error_mm;
  // Every sample within e: y and z within half a step, x within half a plane step (step / 8).
  const double first = e / std::sqrt(0.5 + 0.25 / (kPlaneRefinement * kPlaneRefinement));
  if (!(first / kStepUnit >= 1.0) || first / kStepUnit >= kMaxStepUnits)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("pdef: a maximum error of {} mm is outside the range the format can hold "
                                  "({:.2g} to {:.3g} mm)",
                                  e, kStepUnit, (kMaxStepUnits - 1) * kStepUnit * 0.7));
  const auto first_units = static_cast<std::uint32_t>(first / kStepUnit);
  const double frame_error = float32_frame_error(face);
  LossyPlan plan;
  plan.frame64 = !(frame_error <= e / 100);

  // A face decoded from a lossy file whose grid is fine enough keeps its grid (and its frame's precision):
  // its values are exact there, so encoding it again gives the same bytes.
  if (!face.storage.lossless && face.storage.step_mm > 0 && face.storage.step_mm <= first) {
    const Grid own{static_cast<std::uint32_t>(std::llround(face.storage.step_mm / kStepUnit)),
                   static_cast<std::uint32_t>(std::llround(face.storage.plane_step_mm / kStepUnit))};
    if (own.step > 0 && own.plane_step > 0 && own.step_mm() == face.storage.step_mm &&
        own.plane_step_mm() == face.storage.plane_step_mm) {
      if (std::optional<Quantised> q = quantise(face, own)) {
        Face back = face;
        dequantise(*q, own, back);
        if (back.planes == face.planes && sample_error(face, back) == 0 &&
            (face.storage.frame_float64 || frame_is_float32(face.frame))) {
          plan.grid = own;
          plan.frame64 = face.storage.frame_float64;
          plan.quantised = std::move(*q);
          return plan;
        }
      }
    }
  }

  Result<pde::Surface> reference = pde::Surface::build(face.curves, face.pde);
  if (!reference)
    return make_error(ErrorCode::InvalidArgument,
                      "pdef: the face's surface cannot be built: " + reference.error().message);
  const double frame_part = plan.frame64 ? 0.0 : frame_error;
  std::uint32_t units = first_units;
  for (std::size_t attempt = 0; units >= 1 && attempt < 200; ++attempt) {
    const Grid grid = grid_of(units);
    units = std::min(units - 1, static_cast<std::uint32_t>(units * 0.98));
    std::optional<Quantised> q = quantise(face, grid);
    if (!q) continue;
    Face decoded = face;
    dequantise(*q, grid, decoded);
    const double samples = sample_error(face, decoded);
    if (samples + frame_part > e) {
      ++plan.tightenings;
      continue;
    }
    Result<pde::Surface> surface = pde::Surface::build(decoded.curves, decoded.pde);
    if (!surface) {
      ++plan.tightenings;
      continue;
    }
    const double surface_part = surface_error(*reference, *surface, e - frame_part);
    if (surface_part + frame_part > e) {
      ++plan.tightenings;
      continue;
    }
    plan.grid = grid;
    plan.quantised = std::move(*q);
    plan.max_sample_error = samples + frame_part;
    plan.max_surface_error = surface_part + frame_part;
    return plan;
  }
  return make_error(ErrorCode::InvalidArgument,
                    fmt::format("pdef: no grid keeps the surface within {} mm of the original", e));
}

} // namespace pdeface::pdef::detail
