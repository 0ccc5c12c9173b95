#include "pdeface/metrics/fidelity.hpp"

#include "pdeface/metrics/front_view.hpp"
#include "pdeface/metrics/profile_error.hpp"
#include "pdeface/slice/profile.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <span>

namespace pdeface::metrics {

namespace {

bool in_any(const std::vector<std::array<double, 2>>& gaps, double t) {
  return std::ranges::any_of(gaps, [&](const auto& g) { return t > g[0] && t < g[1]; });
}

// The points of a section whose position along `along` lies in [lo, hi] and outside the gaps.
metrics::Polyline within(const std::vector<Vec3>& points, const Vec3& along, double lo, double hi,
                         const std::vector<std::array<double, 2>>& gaps = {}) {
  metrics::Polyline out;
  std::ranges::copy_if(points, std::back_inserter(out), [&](const Vec3& q) {
    const double t = along.dot(q);
    return t >= lo && t <= hi && !in_any(gaps, t);
  });
  return out;
}

// A polyline cut into pieces at its gaps (no segment joins points across a hole); points inside a gap go.
std::vector<metrics::Polyline> pieces(const std::vector<Vec3>& points, const Vec3& along,
                                      const std::vector<std::array<double, 2>>& gaps) {
  std::vector<metrics::Polyline> out(1);
  std::size_t gap = 0;
  for (const Vec3& p : points) {
    const double t = along.dot(p);
    if (in_any(gaps, t)) continue;
    while (gap < gaps.size() && t >= gaps[gap][1]) {
      if (!out.back().empty()) out.emplace_back();
      ++gap;
    }
    out.back().push_back(p);
  }
  if (out.back().empty()) out.pop_back();
  return out;
}

// The scan seen from the front over |x| <= half_width and the heights a face can have (the canonical frame's
// origin is the nose tip), a cell every `step` mm.
metrics::FrontView front_view(const Mesh& scan, double half_width, double y0, double y1, double step) {
  return {scan, -half_width, half_width, y0, y1, step};
}

metrics::FrontView front_view(const Mesh& scan, const slice::FaceMask& mask, double half_width, double step) {
  return front_view(scan, half_width, mask.centre_y - mask.half_height - step,
                    mask.centre_y + mask.half_height + step, step);
}

} // namespace

FaceRegion face_region(const slice::ProfileSet& profiles, double depth_margin_mm) {
  double deepest = std::numeric_limits<double>::infinity();
  for (const slice::ProfileCurve& c : profiles.curves)
    for (const Vec3& p : c.raw)
      deepest = std::min(deepest, p.z());
  return {profiles.region(), deepest - depth_margin_mm};
}

namespace {

// The scan's face as the coverage measures it: the mask is a region of the front view, so its share is
// measured per unit of that view's area, at the scan's front-most surface in every cell of the view inside
// the mask. Surface that turns away from the viewer (the cheeks' sides, under the chin) counts for the area
// it shows, not for its own area; what the front hides (the inside of the mouth and nostrils) is not the
// face; a hole shows nothing and is not sampled. Every sample is a point of the scan's own surface (a
// triangle's, or a point of a cloud), so a lossless copy of the scan measures 0.
std::vector<Vec3> mask_samples(const slice::FaceMask& mask, const metrics::FrontView& view) {
  return view.samples([&](const Vec3& p) { return mask.contains(p); });
}

Result<Coverage> coverage_from(std::span<const Vec3> samples, const Mesh& reconstruction,
                               const FidelityOptions& options) {
  if (reconstruction.positions.empty())
    return make_error(ErrorCode::InvalidArgument, "coverage: a mesh is empty");
  if (samples.empty())
    return make_error(ErrorCode::InvalidArgument, "coverage: the scan has no surface in the face mask");
  const metrics::SurfaceDistance to_reconstruction(reconstruction);
  std::vector<double> distances;
  distances.reserve(samples.size());
  std::size_t near = 0;
  for (const Vec3& p : samples) {
    const double d = to_reconstruction.distance(p);
    distances.push_back(d);
    if (d <= options.covered_within_mm) ++near;
  }
  Coverage c;
  c.share = static_cast<double>(near) / static_cast<double>(distances.size());
  c.distance = metrics::statistics(std::move(distances));
  return c;
}

// The paper's profile error of `reconstruction` on each evaluation plane: its front-most cut within the
// original profile's extent and outside its gaps, against the original cut into pieces at its gaps. A
// reconstruction that falls short of the range is measured where it exists; NaN where it has none.
std::array<double, 4> evaluation_errors(std::span<const slice::EvaluationProfile> evaluation,
                                        const Mesh& reconstruction) {
  std::vector<slice::Plane> planes;
  std::vector<slice::ProfileAxes> axes;
  for (const slice::EvaluationProfile& e : evaluation) {
    planes.push_back(e.plane);
    axes.push_back({e.along, Vec3::UnitZ()});
  }
  const std::vector<slice::Section> cuts = slice::sections(reconstruction, planes, axes);
  std::array<double, 4> errors{};
  errors.fill(std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < std::min<std::size_t>(4, evaluation.size()); ++i) {
    const slice::EvaluationProfile& e = evaluation[i];
    if (e.points.empty()) continue;
    const double lo = e.along.dot(e.points.front()), hi = e.along.dot(e.points.back());
    const metrics::Polyline rebuilt = within(cuts[i].points, e.along, lo, hi, e.gaps);
    if (!rebuilt.empty())
      errors[i] = metrics::profile_error(std::span(&rebuilt, 1), pieces(e.points, e.along, e.gaps));
  }
  return errors;
}

} // namespace

Result<Coverage> measure_coverage(const Mesh& scan, const slice::FaceMask& mask, const Mesh& reconstruction,
                                  const FidelityOptions& options) {
  if (scan.positions.empty()) return make_error(ErrorCode::InvalidArgument, "coverage: a mesh is empty");
  const metrics::FrontView view = front_view(scan, mask, mask.half_width, options.sample_spacing_mm);
  return coverage_from(mask_samples(mask, view), reconstruction, options);
}

Result<Fidelity> measure_fidelity(const Mesh& scan, const slice::ProfileSet& profiles,
                                  const Mesh& reconstruction, const FidelityOptions& options) {
  if (profiles.evaluation.size() != 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("expected 4 evaluation profiles, got {}", profiles.evaluation.size()));
  Fidelity f;
  for (const slice::EvaluationProfile& e : profiles.evaluation)
    if (e.points.empty())
      return make_error(ErrorCode::InvalidArgument, fmt::format("the {} profile is empty", e.name));
  f.profile_error = evaluation_errors(profiles.evaluation, reconstruction);
  for (std::size_t i = 0; i < 4; ++i) {
    if (std::isnan(f.profile_error[i]))
      return make_error(ErrorCode::NoFace,
                        fmt::format("the reconstruction has no surface on the {} evaluation "
                                    "profile",
                                    profiles.evaluation[i].name));
    f.mean_profile_error += f.profile_error[i] / 4.0;
  }

  // The reconstruction cut by the curves' planes (its front-most part within each curve's extent, outside
  // its holes), against the scan's part of each raw profile.
  // The border curves lie on the reconstruction's edge: they are cut 1 µm inside it, where it surely is.
  const double x_lo = profiles.curves.front().x + 1e-3, x_hi = profiles.curves.back().x - 1e-3;
  std::vector<double> offsets;
  for (const slice::ProfileCurve& c : profiles.curves)
    offsets.push_back(std::clamp(c.x, x_lo, x_hi));
  const std::vector<slice::Section> cuts = slice::sections(reconstruction, Vec3::UnitX(), offsets, {});
  for (std::size_t j = 0; j < profiles.curves.size(); ++j) {
    const slice::ProfileCurve& c = profiles.curves[j];
    const metrics::Polyline rebuilt =
        within(cuts[j].points, Vec3::UnitY(), c.extent[0], c.extent[1], c.holes);
    f.curve_error += metrics::profile_error(std::span(&rebuilt, 1), pieces(c.raw, Vec3::UnitY(), c.holes)) /
                     static_cast<double>(profiles.curves.size());
  }

  // The scan's side counts what a viewer sees from the front: the inside of the mouth and the nostrils,
  // which no front-most profile holds, are not the face.
  const FaceRegion region = face_region(profiles, options.depth_margin_mm);
  const slice::FaceMask& mask = profiles.mask;
  const metrics::FrontView view = front_view(
      scan, std::max(mask.half_width, profiles.border_mm) + 1.0,
      std::min(mask.centre_y - mask.half_height, profiles.height_range[0]) - 1.0,
      std::max(mask.centre_y + mask.half_height, profiles.height_range[1]) + 1.0, options.sample_spacing_mm);
  Result<metrics::TwoSidedDistance> distance = metrics::surface_distance(
      scan, reconstruction,
      {.spacing = options.sample_spacing_mm,
       .region = std::nullopt,
       .keep_a =
           [&](const Vec3& p) { return region.contains(p) && !view.hidden(p, options.front_tolerance_mm); },
       .keep_b =
           [&](const Vec3& p) { return region.contains(p) && !region.curves.filled_at(p.x(), p.y()); }});
  if (!distance) return std::move(distance).error();
  f.surface = *distance;
  Result<Coverage> coverage = coverage_from(mask_samples(profiles.mask, view), reconstruction, options);
  if (!coverage) return std::move(coverage).error();
  f.coverage = *coverage;
  return f;
}

struct FaceYardstick::State {
  State(const Mesh& canonical, const slice::ProfileSet& profiles, const FidelityOptions& fidelity)
      : scan(canonical), mask(profiles.mask), evaluation(profiles.evaluation), options(fidelity),
        view(front_view(scan, mask, mask.half_width + 1.0, options.sample_spacing_mm)),
        samples(mask_samples(mask, view)), to_scan(scan) {}
  Mesh scan;
  slice::FaceMask mask;
  std::vector<slice::EvaluationProfile> evaluation;
  FidelityOptions options;
  metrics::FrontView view;
  std::vector<Vec3> samples;        // the scan's face: front-most samples inside the mask
  metrics::SurfaceDistance to_scan; // over `scan`, which lives as long as this
};

Result<FaceYardstick> FaceYardstick::make(const Mesh& scan, const slice::ProfileSet& profiles,
                                          const FidelityOptions& options) {
  if (scan.positions.empty()) return make_error(ErrorCode::InvalidArgument, "the scan is empty");
  if (profiles.evaluation.size() != 4)
    return make_error(ErrorCode::InvalidArgument,
                      fmt::format("expected 4 evaluation profiles, got {}", profiles.evaluation.size()));
  auto state = std::make_shared<const State>(scan, profiles, options);
  if (state->samples.empty())
    return make_error(ErrorCode::InvalidArgument, "coverage: no sample of the scan lies in the face mask");
  return FaceYardstick(std::move(state));
}

Result<MeshFidelity> FaceYardstick::measure(const Mesh& mesh) const {
  const State& s = *state_;
  Result<Coverage> coverage = coverage_from(s.samples, mesh, s.options);
  if (!coverage) return std::move(coverage).error();
  MeshFidelity f{.coverage = *coverage};
  std::vector<double> distances;
  for (const Vec3& p : metrics::sample_surface(mesh, s.options.sample_spacing_mm, s.mask.box()))
    if (s.mask.contains(p) && s.view.sees_surface(p.x(), p.y())) distances.push_back(s.to_scan.distance(p));
  f.to_scan = metrics::statistics(std::move(distances));
  if (f.to_scan.samples == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    f.to_scan.mean = f.to_scan.rms = f.to_scan.p95 = f.to_scan.max = nan;
  }
  f.profile_error = evaluation_errors(s.evaluation, mesh);
  f.mean_profile_error =
      (f.profile_error[0] + f.profile_error[1] + f.profile_error[2] + f.profile_error[3]) / 4;
  return f;
}

double FaceYardstick::quick_mask_mean(const Mesh& mesh, std::size_t stride) const {
  const State& s = *state_;
  if (mesh.positions.empty()) return std::numeric_limits<double>::infinity();
  const metrics::SurfaceDistance to_mesh(mesh);
  stride = std::max<std::size_t>(stride, 1);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = stride / 2; i < s.samples.size(); i += stride, ++n)
    sum += to_mesh.distance(s.samples[i]);
  return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

double FaceYardstick::distance_to_scan(const Vec3& p) const { return state_->to_scan.distance(p); }

const slice::FaceMask& FaceYardstick::mask() const { return state_->mask; }

double facing_away(const Mesh& mesh, const slice::FaceMask& mask) {
  double area = 0.0, away = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3& b = mesh.positions[t[1]];
    const Vec3& c = mesh.positions[t[2]];
    if (!mask.contains((a + b + c) / 3.0)) continue;
    const Vec3 n = (b - a).cross(c - a);
    area += n.norm();
    if (n.z() < 0.0) away += n.norm();
  }
  return area > 0.0 ? away / area : 0.0;
}

std::string SelfCheck::summary() const {
  if (!failures.empty()) return fmt::format("{}", fmt::join(failures, "; "));
  return fmt::format("mean distance {:.3f} mm, {:.1f} % of the face within 1 mm, {:.2f} % of its area facing "
                     "away",
                     mean_mm, 100.0 * coverage, 100.0 * facing_away);
}

SelfCheck self_check(const MeshFidelity& fidelity, double away, const CheckLimits& limits) {
  SelfCheck c{fidelity.to_scan.mean, fidelity.coverage.share, away, {}};
  if (!(c.mean_mm <= limits.max_mean_mm))
    c.failures.push_back(
        fmt::format("mean distance to the scan {:.3f} mm > {:g} mm", c.mean_mm, limits.max_mean_mm));
  if (!(c.coverage >= limits.min_coverage))
    c.failures.push_back(fmt::format("{:.1f} % of the face within 1 mm < {:g} %", 100.0 * c.coverage,
                                     100.0 * limits.min_coverage));
  if (!(c.facing_away <= limits.max_facing_away))
    c.failures.push_back(fmt::format("{:.2f} % of its area faces away from the viewer > {:g} % (a fold)",
                                     100.0 * c.facing_away, 100.0 * limits.max_facing_away));
  return c;
}

Result<SelfCheck> self_check(const FaceYardstick& yardstick, const Mesh& result, const CheckLimits& limits) {
  Result<MeshFidelity> f = yardstick.measure(result);
  if (!f) return std::move(f).error();
  return self_check(*f, facing_away(result, yardstick.mask()), limits);
}

Result<SelfCheck> checked(const Mesh& scan, const slice::ProfileSet& profiles, const Mesh& result,
                          const CheckLimits& limits, bool force, std::string_view source) {
  const auto refused = [&](const std::string& why) -> Result<SelfCheck> {
    if (force) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return SelfCheck{nan, nan, nan, {why}};
    }
    return make_error(
        ErrorCode::SelfCheck,
        fmt::format("the result is off, so it was not written: {} (--force writes it anyway)", why),
        std::string(source));
  };
  Result<FaceYardstick> yardstick = FaceYardstick::make(scan, profiles);
  if (!yardstick) return refused(yardstick.error().message);
  Result<SelfCheck> check = self_check(*yardstick, result, limits);
  if (!check) return refused(check.error().message);
  if (!check->passed() && !force) return refused(check->summary());
  return check;
}

} // namespace pdeface::metrics
