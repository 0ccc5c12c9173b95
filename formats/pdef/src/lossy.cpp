// The lossy grid: samples rounded to it, and the check that the decoded surface stays within the maximum
// error of the original (tightening the grid until it does).

#include "lossy.hpp"

#include "frame.hpp"
#include "heights.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace pdeface::pdef::detail {
namespace {

// The check grid: points per interval between curves and between samples; when the largest distance on it
// is at least this share of the limit, the cells around the points that could reach it are searched again
// finer.
constexpr int kCoarse = 8;
constexpr double kRefineShare = 0.85;
// The most a tangent-plane estimate is taken to be off (mm): beyond it, points are not refined.
constexpr double kMaxMargin = 0.01;
// The surface is accepted within this share of the maximum error: the grid's spacing (0.1-0.2 mm) may
// miss the top of a peak of the distance (about 1 mm wide) by up to ~1 %.
constexpr double kCheckShare = 0.97;
// What the checks of one encoding may cost, in multiply-adds: an evaluation of the surface on nu × nv points
// sums every cosine column (K with the remainder, N + 1 without) at every point, after a table of those
// cosines at every v (each cosine about as costly as 64 multiply-adds). A face at 60 % (28 curves of 180
// samples: 217 × 1433 points on the check's grid) costs 72 M per evaluation, eight evaluations per grid
// tried (~40 ms) and at most about seven grids; the budget allows 15 such. A larger document (the format
// allows 1024 curves of 4097 samples) is checked on fewer points per interval, down to one, and refused
// when even that is beyond the budget, so that encoding any face ends within about a second.
constexpr double kGridBudget = double(1 << 27);
constexpr double kPlanBudget = 8.0 * double(1 << 30);
constexpr double kCosineCost = 64;
// The first grids that fail are followed by ones finer in proportion to how far they failed; after this
// many failures (real faces need at most 5), each is at least twice as fine.
constexpr std::size_t kGentleTightenings = 6;
// At most this many points are projected onto the other surface in one search, and at most this many
// cosine columns' worth of them (a projection evaluates the surface 15 times at one point, each summing
// every column); the rest count by their estimate's upper bound (a flat hostile face, whose estimates are
// all alike, would have every point projected). Real faces (the 24 shared scans at 5-60 %) project at most
// 668 points (at 5 %, 15 columns) and 14.5 k columns' worth (242 points at 20 %).
constexpr std::size_t kMaxProjections = 4096;
constexpr std::size_t kProjectionColumns = std::size_t{1} << 15;

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

std::optional<Quantised> quantise(const Face& face, const Grid& grid, bool own) {
  Quantised q;
  q.curves = face.curve_count();
  q.samples = face.sample_count();
  const double step = grid.step_mm(), plane_step = grid.plane_step_mm();
  std::vector<double> heights; // every sample's y (mm)
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
      heights.push_back(c(k, 1));
    }
  }
  // y as heights when that is smaller than predicting it sample by sample (a decoded face: as it was).
  if (own && face.storage.heights_stride == 0) return q;
  std::optional<HeightsFit> fit = fit_heights(
      heights, q.planes, q.samples, grid,
      own ? std::optional<Layout>({face.storage.heights_stride, face.storage.heights_bits}) : std::nullopt);
  if (fit && (own || fit->bytes < write_predicted(q.y, q.planes, q.samples, 0).size())) {
    q.heights = std::move(fit->heights);
    q.y = std::move(fit->residuals);
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
      c(row, 1) = q.heights.used()
                      ? static_cast<double>(height_units(q.heights, q.planes, q.samples, grid.step, j, k) +
                                            q.y[j * q.samples + k] * grid.step) *
                            kStepUnit
                      : value(q.y[j * q.samples + k], grid.step);
      c(row, 2) = value(q.z[j * q.samples + k], grid.step);
    }
  }
}

namespace {

// Points of one surface (`from`) with what the other (`to`) has at the same (u, v): its point and tangents.
struct Pairs {
  std::vector<double> u, v;
  std::vector<Vec3> from, to, to_u, to_v;
  std::vector<bool> border; // on or next to the grid's border
};

// A surface on the grid us × vs: its points, and (when asked) its tangents.
struct Evaluated {
  pde::Grid x, xu, xv;
};
Evaluated evaluated(const pde::Surface& s, std::span<const double> us, std::span<const double> vs,
                    bool tangents) {
  Evaluated e{s.evaluate(us, vs), {}, {}};
  if (tangents) {
    e.xu = s.evaluate(us, vs, pde::Derivative::U);
    e.xv = s.evaluate(us, vs, pde::Derivative::V);
  }
  return e;
}

// The points `p` of one surface on the grid us × vs, with the point and tangents `to` of the other at the
// same (u, v), appended to `out`. `border`: whether a point is on or next to the border of the surfaces'
// domain.
void pairs_of(const pde::Grid& p, const Evaluated& to, std::span<const double> us, std::span<const double> vs,
              const std::function<bool(std::size_t, std::size_t)>& border, Pairs& out) {
  const pde::Grid &q = to.x, &qu = to.xu, &qv = to.xv;
  if (out.u.empty()) { // the coarse grid: one allocation each
    for (auto* v : {&out.u, &out.v})
      v->reserve(p.points.size());
    for (auto* v : {&out.from, &out.to, &out.to_u, &out.to_v})
      v->reserve(p.points.size());
    out.border.reserve(p.points.size());
  }
  for (std::size_t k = 0; k < vs.size(); ++k)
    for (std::size_t i = 0; i < us.size(); ++i) {
      const std::size_t at = k * us.size() + i;
      out.u.push_back(us[i]);
      out.v.push_back(vs[k]);
      out.from.push_back(p.points[at]);
      out.to.push_back(q.points[at]);
      out.to_u.push_back(qu.points[at]);
      out.to_v.push_back(qv.points[at]);
      out.border.push_back(border(i, k));
    }
}

// The points of `from` on the grid us × vs, with the point and tangents of `to` at the same (u, v).
void evaluate_pairs(const pde::Surface& from, const pde::Surface& to, std::span<const double> us,
                    std::span<const double> vs, const std::function<bool(std::size_t, std::size_t)>& border,
                    Pairs& out) {
  pairs_of(from.evaluate(us, vs), evaluated(to, us, vs, true), us, vs, border, out);
}

// Each point's distance to the other surface estimated by its distance to that surface's tangent plane at
// the same (u, v), which is off by about |tangential part|² × curvature / 2 (micrometres; taken as at most
// |tangential part|² / 2, curvature below 1/mm): the estimate and how far off it may be. On the border the
// nearest point may lie on the surface's edge, off its tangent plane: there the estimate is the distance at
// the same (u, v), an upper bound.
void estimate(const Pairs& p, std::vector<double>& estimate, std::vector<double>& margin) {
  estimate.resize(p.from.size());
  margin.resize(p.from.size());
  for (std::size_t i = 0; i < p.from.size(); ++i) {
    const Vec3 d = p.from[i] - p.to[i];
    const Vec3 n = p.to_u[i].cross(p.to_v[i]);
    const double length = n.norm();
    estimate[i] = length > 0 && !p.border[i] ? std::abs(d.dot(n)) / length : d.norm();
    margin[i] = std::min(kMaxMargin, 0.5 * (d.squaredNorm() - estimate[i] * estimate[i]) + 1e-4);
  }
}

// The largest distance of the points to the other surface: those whose estimate could reach the largest
// found are projected onto it (`distance_to`). Stops early above `limit`.
double largest(const Pairs& p, const pde::Surface& to, double limit) {
  if (p.from.empty()) return 0;
  std::vector<double> e, m;
  estimate(p, e, m);
  const double step_u = to.u_max() / static_cast<double>(to.knots().size() - 1);
  const double step_v = std::numbers::pi / static_cast<double>(to.sample_count() - 1);
  const auto distance = [&](std::size_t i) {
    return distance_to(to, p.from[i], p.u[i], p.v[i], step_u, step_v);
  };
  // The point estimated farthest first: only points that could beat it are sorted and projected.
  const auto top = static_cast<std::size_t>(std::ranges::max_element(e) - e.begin());
  double worst = distance(top);
  if (worst > limit) return worst;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < e.size(); ++i)
    if (i != top && e[i] + m[i] > worst) order.push_back(i);
  std::ranges::sort(order, [&](std::size_t l, std::size_t r) { return e[l] > e[r]; });
  const std::size_t columns = to.has_remainder() ? to.sample_count() : to.modes() + 1;
  const std::size_t most = std::clamp<std::size_t>(kProjectionColumns / columns, 16, kMaxProjections);
  std::size_t projected = 1;
  for (std::size_t at = 0; at < order.size(); ++at) {
    const std::size_t i = order[at];
    if (e[i] + m[i] <= worst) continue;
    if (e[i] + kMaxMargin <= worst) break;
    if (projected == most) { // the rest by their upper bounds
      for (; at < order.size(); ++at)
        worst = std::max(worst, e[order[at]] + m[order[at]]);
      break;
    }
    worst = std::max(worst, distance(i));
    ++projected;
    if (worst > limit) break;
  }
  return worst;
}

} // namespace

double check_cost(std::size_t curves, std::size_t samples, std::size_t columns, int density) {
  const double nu = static_cast<double>(curves - 1) * density + 1;
  const double nv = static_cast<double>(samples - 1) * density + 1;
  return nv * (nu + kCosineCost) * static_cast<double>(columns);
}

int check_density(std::size_t curves, std::size_t samples, std::size_t columns) {
  for (int d = kCoarse; d >= 1; --d)
    if (check_cost(curves, samples, columns, d) <= kGridBudget) return d;
  return 0;
}

namespace {

struct CoarseReference {
  std::vector<double> us, vs;
  Evaluated at; // the reference's points and tangents on us × vs
};

// The check's coarse grid: `density` points per curve interval across and per sample interval along, and
// the reference surface on it (the same for every grid `plan_lossy` tries: evaluated once).
CoarseReference coarse_reference(const pde::Surface& reference, int density) {
  if (density < 1) throw std::invalid_argument("pdef::detail::surface_error: a density of at least 1");
  CoarseReference c;
  const std::vector<double>& knots = reference.knots();
  std::vector<double>&us = c.us, &vs = c.vs;
  for (std::size_t j = 0; j + 1 < knots.size(); ++j)
    for (int i = 0; i < density; ++i)
      us.push_back(knots[j] + (knots[j + 1] - knots[j]) * i / density);
  us.push_back(reference.u_max());
  const std::size_t intervals = reference.sample_count() - 1;
  for (std::size_t k = 0; k < intervals; ++k)
    for (int i = 0; i < density; ++i)
      vs.push_back(std::numbers::pi * (static_cast<double>(k) + static_cast<double>(i) / density) /
                   static_cast<double>(intervals));
  vs.push_back(std::numbers::pi);
  c.at = evaluated(reference, us, vs, true);
  return c;
}

double surface_error(const pde::Surface& reference, const CoarseReference& coarse_reference,
                     const pde::Surface& decoded, double limit) {
  const std::vector<double>&us = coarse_reference.us, &vs = coarse_reference.vs;
  const auto grid_border = [&](std::size_t i, std::size_t k) {
    return i < 2 || i + 2 >= us.size() || k < 2 || k + 2 >= vs.size();
  };
  const auto domain_border = [&](double u, double v) {
    return u <= us[1] || u >= us[us.size() - 2] || v <= vs[1] || v >= vs[vs.size() - 2];
  };

  double worst = 0;
  Evaluated on_decoded{decoded.evaluate(us, vs), {}, {}}; // its tangents when the second way needs them
  for (const bool back : {false, true}) {                 // decoded to reference, then reference to decoded
    const pde::Surface& from = back ? reference : decoded;
    const pde::Surface& to = back ? decoded : reference;
    if (back) {
      on_decoded.xu = decoded.evaluate(us, vs, pde::Derivative::U);
      on_decoded.xv = decoded.evaluate(us, vs, pde::Derivative::V);
    }
    Pairs coarse;
    pairs_of(back ? coarse_reference.at.x : on_decoded.x, back ? on_decoded : coarse_reference.at, us, vs,
             grid_border, coarse);
    const double found = largest(coarse, to, limit);
    worst = std::max(worst, found);
    if (found > limit) return found;
    if (found < kRefineShare * limit) continue;
    // The distance between two such surfaces has peaks about 1 mm wide across the curves where they bend
    // sharply, which the coarse grid (0.2-0.5 mm apart) may miss by a few per cent: near the limit, the
    // cells around the highest coarse points are searched again 4 times finer.
    std::vector<double> e, m;
    estimate(coarse, e, m);
    Pairs fine;
    for (std::size_t at = 0; at < e.size(); ++at) {
      if (e[at] + m[at] < kRefineShare * limit) continue;
      const std::size_t i = at % us.size(), k = at / us.size();
      std::array<double, 6> su{}, sv{};
      std::size_t nu = 0, nv = 0;
      for (int t = -3; t <= 3; ++t) { // the two cells either side, each way
        if (t == 0) continue;
        if (!(t < 0 && i == 0) && !(t > 0 && i + 1 >= us.size())) {
          const double a = us[t < 0 ? i - 1 : i], b = us[t < 0 ? i : i + 1];
          su[nu++] = a + (b - a) * (t < 0 ? t + 4 : t) / 4.0;
        }
        if (!(t < 0 && k == 0) && !(t > 0 && k + 1 >= vs.size())) {
          const double a = vs[t < 0 ? k - 1 : k], b = vs[t < 0 ? k : k + 1];
          sv[nv++] = a + (b - a) * (t < 0 ? t + 4 : t) / 4.0;
        }
      }
      evaluate_pairs(
          from, to, std::span(su.data(), nu), std::span(sv.data(), nv),
          [&](std::size_t ii, std::size_t kk) { return domain_border(su[ii], sv[kk]); }, fine);
    }
    const double refined = largest(fine, to, limit);
    worst = std::max(worst, refined);
    if (refined > limit) return refined;
  }
  return worst;
}

} // namespace

double surface_error(const pde::Surface& reference, const pde::Surface& decoded, double limit, int density) {
  return surface_error(reference, coarse_reference(reference, density), decoded, limit);
}

Result<LossyPlan> plan_lossy(const Face& face, const EncodeOptions& options) {
  const double e = options.max_error_mm;
  // The coarsest grid that could keep every sample within e: z within half a step, x within half a plane
  // step (step / 8), y exact (stored as heights); a face whose y is on the grid too fails its first check
  // and continues on a grid finer by what it missed.
  const double first = e / std::sqrt(0.25 + 0.25 / (kPlaneRefinement * kPlaneRefinement));
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
      if (std::optional<Quantised> q = quantise(face, own, true)) {
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

  const std::size_t modes = face.pde.modes.value_or(face.sample_count() - 1);
  const std::size_t columns = face.pde.remainder ? face.sample_count() : modes + 1;
  const int density = check_density(face.curve_count(), face.sample_count(), columns);
  if (density == 0)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("pdef: {} curves of {} samples: more than a lossy encoding can check the "
                                  "surface of; encode it lossless",
                                  face.curve_count(), face.sample_count()));
  const double cost = check_cost(face.curve_count(), face.sample_count(), columns, density);
  double spent = 0;
  Result<pde::Surface> reference = pde::Surface::build(face.curves, face.pde);
  if (!reference)
    return make_error(ErrorCode::InvalidArgument,
                      "pdef: the face's surface cannot be built: " + reference.error().message);
  const double frame_part = plan.frame64 ? 0.0 : frame_error;
  std::optional<CoarseReference> on_reference; // made at the first check that reaches the surface
  // The first grid that keeps every sample within e is tried first; each that fails is followed by one
  // finer in proportion to how far it failed (the error grows about linearly with the step), at least 2 %
  // finer; once one passes, the step between it and the finest that failed is bisected twice (the error is
  // not monotonic in the step: a file a few per cent smaller is often found).
  struct Checked {
    bool passed = false;
    double ratio = 0.5; // limit / error when it failed
    double samples = 0, surface = 0;
    std::optional<Quantised> q;
  };
  const double limit = kCheckShare * e - frame_part;
  const auto check = [&](std::uint32_t units) {
    Checked c;
    const Grid grid = grid_of(units);
    c.q = quantise(face, grid);
    if (!c.q) return c;
    Face decoded = face;
    dequantise(*c.q, grid, decoded);
    c.samples = sample_error(face, decoded);
    if (c.samples + frame_part > e) {
      c.ratio = (e - frame_part) / c.samples;
      return c;
    }
    Result<pde::Surface> surface = pde::Surface::build(decoded.curves, decoded.pde);
    if (!surface) return c;
    spent += 8 * cost;
    if (!on_reference) on_reference = coarse_reference(*reference, density);
    c.surface = surface_error(*reference, *on_reference, *surface, limit);
    c.passed = c.surface <= limit;
    if (!c.passed) c.ratio = limit / c.surface; // c.surface is where the search stopped: at most the error
    return c;
  };
  std::uint32_t units = first_units, failed = 0, best = 0;
  Checked passed;
  int bisections = 0;
  for (std::size_t attempt = 0; units >= 1 && attempt < 200 && spent + 8 * cost <= kPlanBudget; ++attempt) {
    Checked c = check(units);
    const double ratio = c.ratio;
    if (c.passed) {
      best = units;
      passed = std::move(c);
    } else {
      ++plan.tightenings;
      failed = units;
    }
    if (best == 0) {
      const double finer = plan.tightenings > kGentleTightenings ? 0.5 : 0.98;
      units = std::min(units - 1, static_cast<std::uint32_t>(units * std::min(finer, 0.995 * ratio)));
      continue;
    }
    if (failed == 0 || bisections == 2 || failed - best <= std::max<std::uint32_t>(1, best / 100)) break;
    ++bisections;
    units = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(failed) * best));
    if (units == best || units == failed) break;
  }
  if (best != 0) {
    plan.grid = grid_of(best);
    plan.quantised = *std::move(passed.q);
    plan.max_sample_error = passed.samples + frame_part;
    plan.max_surface_error = passed.surface + frame_part;
    return plan;
  }
  return make_error(
      ErrorCode::InvalidArgument,
      fmt::format("pdef: no grid keeps the surface within {} mm of the original{}", e,
                  spent + 8 * cost > kPlanBudget ? " (within the checks one encoding may make)" : ""));
}

} // namespace pdeface::pdef::detail
