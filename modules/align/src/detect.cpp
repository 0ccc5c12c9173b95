#include "pdeface/align/detect.hpp"

#include "depth_map.hpp"
#include "pdeface/core/point_index.hpp"
#include "pdeface/core/topology.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_map>

namespace pdeface::align {
namespace {

constexpr double kMinNoseProminence = 8.0; // mm: a nose tip stands 15-30 mm out of its profile

// ---- sampling ------------------------------------------------------------------------------------------

// One point per occupied voxel: an even subsample whatever the scan's density.
std::vector<Vec3> voxel_subsample(std::span<const Vec3> points, double cell) {
  std::unordered_map<std::uint64_t, std::size_t> seen;
  std::vector<Vec3> out;
  for (const Vec3& p : points) {
    const Eigen::Vector3d k = (p / cell).array().floor();
    const auto key = (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.x()) & 0x1FFFFF) << 42U) |
                     (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.y()) & 0x1FFFFF) << 21U) |
                     (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.z()) & 0x1FFFFF));
    if (seen.emplace(key, out.size()).second) out.push_back(p);
  }
  return out;
}

// Every `step`-th point, at most `count` of them.
std::vector<Vec3> thin(std::span<const Vec3> points, std::size_t count) {
  const std::size_t step = std::max<std::size_t>(1, points.size() / std::max<std::size_t>(count, 1));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < points.size(); i += step)
    out.push_back(points[i]);
  return out;
}

double median_spacing(std::span<const Vec3> points, const PointIndex& index) {
  std::vector<double> d;
  for (const Vec3& p : thin(points, 400))
    d.push_back(index.nearest(p, 2).back().distance);
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2));
  return d[d.size() / 2];
}

// ---- symmetry ------------------------------------------------------------------------------------------

// The mirror map x -> a x + b (a is orthogonal with det -1).
struct Mirror {
  Eigen::Matrix3d a;
  Vec3 b;
  [[nodiscard]] Vec3 operator()(const Vec3& p) const { return a * p + b; }
};

Mirror mirror_of(const Plane& plane) {
  return {Eigen::Matrix3d::Identity() - 2.0 * plane.normal * plane.normal.transpose(),
          2.0 * plane.offset * plane.normal};
}

// The symmetry plane of an improper isometry: the normal is the eigenvector of its symmetric part with
// eigenvalue nearest -1; the plane passes through the midpoints of the points and their images.
Plane plane_of(const Mirror& m, std::span<const Vec3> points) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (m.a + m.a.transpose()));
  const Vec3 n = eig.eigenvectors().col(0).normalized();
  double offset = 0.0;
  for (const Vec3& p : points)
    offset += n.dot(0.5 * (p + m(p)));
  return {n, offset / static_cast<double>(points.size())};
}

// Trimmed RMS distance from the mirrored points to the scan: the best `keep` fraction counts, so that
// an asymmetric cut, hair or a missing ear do not hide a good plane.
double mirror_rms(const Mirror& m, std::span<const Vec3> points, const PointIndex& index, double keep = 0.7) {
  std::vector<double> d;
  d.reserve(points.size());
  for (const Vec3& p : points)
    d.push_back(index.nearest(m(p)).distance);
  const auto n = std::max<std::size_t>(1, static_cast<std::size_t>(keep * static_cast<double>(d.size())));
  std::ranges::nth_element(d, d.begin() + static_cast<std::ptrdiff_t>(n - 1));
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum += d[i] * d[i];
  return std::sqrt(sum / static_cast<double>(n));
}

// Registration of the mirrored scan onto the scan (trimmed ICP, rigid fits by Eigen::umeyama).
Mirror refine(Mirror m, std::span<const Vec3> points, std::span<const Vec3> all, const PointIndex& index,
              double keep = 0.7, int iterations = 30) {
  const auto n = points.size();
  Eigen::Matrix3Xd src(3, static_cast<Eigen::Index>(n)), dst(3, static_cast<Eigen::Index>(n));
  std::vector<std::pair<double, std::size_t>> order(n);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    std::vector<Vec3> moved(n), target(n);
    for (std::size_t i = 0; i < n; ++i) {
      moved[i] = m(points[i]);
      const auto nn = index.nearest(moved[i]);
      target[i] = all[nn.index];
      order[i] = {nn.distance, i};
    }
    const std::size_t kept =
        std::max<std::size_t>(3, static_cast<std::size_t>(keep * static_cast<double>(n)));
    std::ranges::nth_element(order, order.begin() + static_cast<std::ptrdiff_t>(kept - 1));
    for (std::size_t j = 0; j < kept; ++j) {
      src.col(static_cast<Eigen::Index>(j)) = moved[order[j].second];
      dst.col(static_cast<Eigen::Index>(j)) = target[order[j].second];
    }
    const auto k = static_cast<Eigen::Index>(kept);
    const Eigen::Matrix4d t = Eigen::umeyama(src.leftCols(k), dst.leftCols(k), false);
    const Eigen::Matrix3d r = t.topLeftCorner<3, 3>();
    m = {r * m.a, r * m.b + t.topRightCorner<3, 1>()};
    if (Eigen::AngleAxisd(r).angle() < 1e-4 && t.topRightCorner<3, 1>().norm() < 1e-3) break; // 0.006°, 1 µm
  }
  return m;
}

// Unit vectors spread evenly over the hemisphere z >= 0 (a Fibonacci spiral).
std::vector<Vec3> hemisphere(int count) {
  std::vector<Vec3> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (i + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z);
    out.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return out;
}

// ---- the nose on the symmetry profile ------------------------------------------------------------------

struct Nose {
  Vec3 tip;
  Vec3 forward; // out of the face
  Vec3 up;      // towards the forehead
  double prominence = 0.0;
};

// The symmetry profile is the scan near the plane. Looking along every direction in the plane, the
// extreme point is a nose tip when the profile falls away steeply on both sides of it (15 mm on, the
// dorsum is a few mm back and the upper lip 15-20 mm back), yet smoothly (a spike of hair falls away as
// fast 5 mm on). The dorsum side is up.
std::optional<Nose> find_nose(const Plane& plane, std::span<const Vec3> points, double slab) {
  std::vector<Vec3> profile;
  for (const Vec3& p : points)
    if (std::abs(plane.normal.dot(p) - plane.offset) <= slab) profile.push_back(p);
  if (profile.size() < 20) return std::nullopt;
  const Vec3 b1 = plane.normal.unitOrthogonal();
  const Vec3 b2 = plane.normal.cross(b1);

  std::optional<Nose> best;
  for (int step = 0; step < 180; ++step) {
    const double theta = 2.0 * std::numbers::pi * step / 180.0;
    const Vec3 d = std::cos(theta) * b1 + std::sin(theta) * b2;
    const Vec3 lateral = plane.normal.cross(d);
    const Vec3& tip = *std::ranges::max_element(profile, {}, [&](const Vec3& p) { return d.dot(p); });
    // How far the profile falls back from the tip at lateral offsets in [lo, hi] on one side: the
    // least depth among those points within 30 mm behind the tip. +inf when there are none (an end of
    // the profile, or a curve turning away).
    auto nearest_depth = [&](double lo, double hi, double side) {
      double drop = std::numeric_limits<double>::infinity();
      for (const Vec3& q : profile) {
        const double l = side * lateral.dot(q - tip);
        const double behind = d.dot(tip - q);
        if (l >= lo && l <= hi && behind <= 30.0) drop = std::min(drop, behind);
      }
      return drop;
    };
    const double far_plus = nearest_depth(12.0, 18.0, 1.0), far_minus = nearest_depth(12.0, 18.0, -1.0);
    const double near_plus = nearest_depth(3.0, 7.0, 1.0), near_minus = nearest_depth(3.0, 7.0, -1.0);
    if (!std::isfinite(far_plus + far_minus + near_plus + near_minus)) continue; // an end of the profile
    if (near_plus + near_minus > 0.6 * (far_plus + far_minus) + 1.0) continue;   // a spike, not a nose
    const double prominence = far_plus + far_minus;
    if (!best || prominence > best->prominence)
      best = Nose{tip, d, far_plus < far_minus ? lateral : Vec3(-lateral), prominence};
  }
  return best;
}

// ---- landmarks in the depth map -------------------------------------------------------------------------

// The grid's best point (x, y) of a score, moved to the vertex of the parabola through it and its two
// neighbours along each axis: landmarks then move continuously with the frame instead of by whole cells.
Eigen::Vector2d refined_peak(const auto& score, Eigen::Vector2d at, double h) {
  const std::optional<double> centre = score(at.x(), at.y());
  if (!centre) return at;
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::Vector2d d = axis == 0 ? Eigen::Vector2d(h, 0) : Eigen::Vector2d(0, h);
    const std::optional<double> minus = score(at.x() - d.x(), at.y() - d.y());
    const std::optional<double> plus = score(at.x() + d.x(), at.y() + d.y());
    if (!minus || !plus) continue;
    const double curvature = *minus - 2.0 * *centre + *plus;
    if (curvature < 0.0) shift[axis] = std::clamp(0.5 * (*minus - *plus) / curvature, -0.5, 0.5) * h;
  }
  return at + shift;
}

// The lateral end of a horizontal hollow (the mouth line, the fissure of an eye): walking from x_from
// towards x_to, the columns whose most hollow point (over [y0, y1]) is at least `fraction` as deep as
// the deepest column's; the end is the last of them reached without a gap.
std::optional<Eigen::Vector2d> hollow_end(const detail::DepthMap& map, double x_from, double x_to, double y0,
                                          double y1, double r, double fraction = 0.35) {
  const double step = x_to > x_from ? map.cell() : -map.cell();
  std::vector<std::pair<double, Eigen::Vector2d>> columns; // (most hollow relief, where)
  for (double x = x_from; (x_to - x) * step >= 0.0; x += step) {
    std::pair<double, Eigen::Vector2d> best{std::numeric_limits<double>::infinity(), {x, 0.0}};
    for (double y = y0; y <= y1; y += map.cell())
      if (const auto rel = map.relief(x, y, r); rel && *rel < best.first)
        best = {*rel, Eigen::Vector2d(x, y)};
    columns.push_back(best);
  }
  const auto deepest = std::ranges::min_element(columns, {}, &std::pair<double, Eigen::Vector2d>::first);
  if (deepest == columns.end() || !(deepest->first < 0.0)) return std::nullopt;
  auto end = deepest;
  for (auto it = deepest; it != columns.end() && it->first <= fraction * deepest->first; ++it)
    end = it;
  // Between the last column in the hollow and the next one out, where the relief crosses the threshold.
  Eigen::Vector2d where = end->second;
  if (const auto next = end + 1; next != columns.end() && next->first > end->first) {
    const double t =
        std::clamp((fraction * deepest->first - end->first) / (next->first - end->first), 0.0, 1.0);
    where = end->second + t * (next->second - end->second);
  }
  const auto hollowness = [&](double x, double y) -> std::optional<double> {
    const auto rel = map.relief(x, y, r);
    return rel ? std::optional<double>(-*rel) : std::nullopt;
  };
  return Eigen::Vector2d(where.x(), refined_peak(hollowness, where, map.cell()).y());
}

// The most cup-shaped point of a window, as (x, y) in the frame.
std::optional<Eigen::Vector2d> most_cupped(const detail::DepthMap& map, double x0, double x1, double y0,
                                           double y1) {
  std::optional<Eigen::Vector2d> best;
  double top = 0.0; // only cups count
  for (double y = y0; y <= y1; y += map.cell())
    for (double x = std::min(x0, x1); x <= std::max(x0, x1); x += map.cell())
      if (const auto k = map.cupness(x, y); k && *k > top) {
        top = *k;
        best = Eigen::Vector2d(x, y);
      }
  if (!best) return best;
  return refined_peak([&](double x, double y) { return map.cupness(x, y); }, *best, map.cell());
}

// A rigid map into a face frame (mm): q = rotation · p + translation.
struct Rigid {
  Eigen::Matrix3d rotation;
  Vec3 translation;
};

// Landmarks (in mm, the scan's frame) found in a depth map of the scan seen in `frame`, whose origin is
// near the nose tip and whose axes are near the canonical ones: the nose tip as the front-most point
// near the origin, eye and mouth corners as the hollows of the windows where faces have them, the face's
// bottom where the midline turns under the chin, its top by the rule of thirds (within the scan).
Landmarks search_landmarks(std::span<const Vec3> points, std::span<const Triangle> triangles, double spacing,
                           const Rigid& frame) {
  std::vector<Vec3> local(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    local[i] = frame.rotation * points[i] + frame.translation;
  detail::DepthMap map(-100.0, 100.0, -140.0, 120.0, 1.0);
  map.rasterise(local, triangles, std::max(1.5, 1.5 * spacing));
  map.fill_holes(4);

  std::optional<Eigen::Vector3d> tip; // (x, y, z) in the frame
  for (double y = -15.0; y <= 15.0; y += 1.0)
    for (double x = -10.0; x <= 10.0; x += 1.0)
      if (const auto z = map.at(x, y); z && (!tip || *z > tip->z())) tip = Eigen::Vector3d(x, y, *z);
  if (tip) {
    const Eigen::Vector2d xy =
        refined_peak([&](double x, double y) { return map.at(x, y); }, tip->head<2>(), 1.0);
    tip = Eigen::Vector3d(xy.x(), xy.y(), map.at(xy.x(), xy.y()).value_or(tip->z()));
  }

  Landmarks found;
  auto place = [&](Landmark l, double x, double y) {
    if (const auto z = map.at(x, y))
      found[l] = Vec3(frame.rotation.transpose() * (Vec3(x, y, *z) - frame.translation));
  };
  if (!tip) return found;
  place(Landmark::NoseTip, tip->x(), tip->y());
  const double x0 = tip->x(), y0 = tip->y();
  const detail::DepthMap cups = map.smoothed(2.5);
  const detail::DepthMap soft = map.smoothed(1.0); // point clouds splat unevenly: their raw map is rough
  std::vector<double> eye_y, mouth_y;
  // The mouth line where it crosses the midline. Down the midline from the nose the profile rises onto
  // the upper lip, dips into the mouth, rises onto the lower lip, dips under it and rises onto the chin:
  // the mouth is the lowest point between the first two bumps (the lips). Failing that, the deepest
  // groove (relief) between the nose and the chin.
  const detail::DepthMap profile_map = map.smoothed(1.5);
  std::vector<std::pair<double, double>> midline; // (y, z), downwards
  for (double y = y0 - 6.0; y >= y0 - 60.0; y -= 1.0)
    if (const auto z = profile_map.at(x0, y)) midline.emplace_back(y, *z);
  std::vector<std::size_t> bumps;
  for (std::size_t i = 2; i + 2 < midline.size() && bumps.size() < 2; ++i) {
    const double z = midline[i].second;
    if (z >= midline[i - 1].second && z >= midline[i + 1].second && z > midline[i - 2].second &&
        z > midline[i + 2].second)
      bumps.push_back(i);
  }
  double y_slit = y0 - 30.0;
  if (bumps.size() == 2) {
    const auto lowest = std::min_element(midline.begin() + static_cast<std::ptrdiff_t>(bumps[0]),
                                         midline.begin() + static_cast<std::ptrdiff_t>(bumps[1]),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
    y_slit = lowest->first;
  } else {
    double deepest = 0.0;
    for (double y = y0 - 18.0; y >= y0 - 45.0; y -= 1.0)
      if (const auto rel = soft.relief(x0, y, 4.0); rel && *rel < deepest) {
        deepest = *rel;
        y_slit = y;
      }
  }
  for (double side : {1.0, -1.0}) {
    const bool left = side > 0;
    // Eye corners are cups (concave in every direction) on a lightly smoothed map: the inner one between
    // the nose bridge and the eyeball, the outer one 18-40 mm further out at about the same height.
    if (const auto inner = most_cupped(cups, x0 + side * 6.0, x0 + side * 30.0, y0 + 15.0, y0 + 55.0)) {
      place(left ? Landmark::EyeInnerLeft : Landmark::EyeInnerRight, inner->x(), inner->y());
      eye_y.push_back(inner->y());
      if (const auto outer = most_cupped(cups, inner->x() + side * 18.0, inner->x() + side * 40.0,
                                         inner->y() - 10.0, inner->y() + 8.0))
        place(left ? Landmark::EyeOuterLeft : Landmark::EyeOuterRight, outer->x(), outer->y());
    }
    if (const auto mouth = hollow_end(soft, x0, x0 + side * 40.0, y_slit - 8.0, y_slit + 6.0, 5.0)) {
      place(left ? Landmark::MouthLeft : Landmark::MouthRight, mouth->x(), mouth->y());
      mouth_y.push_back(mouth->y());
    }
  }
  // A corner the surface shows on one side only (a shadowed or cut outer corner): mirror the other.
  for (Landmark l : {Landmark::EyeOuterLeft, Landmark::EyeOuterRight, Landmark::EyeInnerLeft,
                     Landmark::EyeInnerRight, Landmark::MouthLeft, Landmark::MouthRight}) {
    const std::optional<Vec3>& other = found[mirrored(l)];
    if (found.has(l) || !other) continue;
    const Vec3 seen = frame.rotation * *other + frame.translation;
    place(l, 2.0 * x0 - seen.x(), seen.y());
  }
  auto mean = [](const std::vector<double>& v, double fallback) {
    return v.empty() ? fallback : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  };
  const double y_eyes = mean(eye_y, y0 + 38.0);
  const double y_mouth = mean(mouth_y, y0 - 35.0);

  // The chin's most forward point on the midline below the mouth, then down while the profile stays
  // within 15 mm of it (below that, it turns under the chin towards the neck).
  std::optional<Eigen::Vector2d> chin; // (y, z)
  for (double y = y_mouth - 12.0; y >= y_mouth - 55.0; y -= 1.0)
    if (const auto z = map.at(x0, y); z && (!chin || *z > chin->y())) chin = Eigen::Vector2d(y, *z);
  if (!chin) return found;
  double y_bottom = chin->x();
  while (y_bottom > -140.0) {
    const auto z = map.at(x0, y_bottom - 1.0);
    if (!z || *z < chin->y() - 15.0) break;
    y_bottom -= 1.0;
  }
  place(Landmark::FaceBottom, x0, y_bottom);
  // Rule of thirds: hairline to nasion ~ half of nasion to chin; the nasion is a few mm above the eyes.
  const double y_nasion = y_eyes + 4.0;
  const double y_top = y_nasion + 0.5 * (y_nasion - y_bottom);
  double y_scan = y_nasion;
  while (y_scan < y_top && map.at(x0, y_scan + 1.0))
    y_scan += 1.0;
  place(Landmark::FaceTop, x0, y_scan);
  return found;
}

// RMS distance of the landmarks, mapped by the frame, from the average face's; a landmark not found
// counts as 30 mm off (else finding fewer would look like fitting better).
double fit_rms(const Landmarks& landmarks, const FaceFrame& frame) {
  constexpr double kMissing = 30.0;
  double sum = 0.0;
  const Landmarks canonical = to_canonical(landmarks, frame);
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    sum += canonical.points[i] ? (*canonical.points[i] - *canonical_template().points[i]).squaredNorm()
                               : kMissing * kMissing;
  return std::sqrt(sum / kLandmarkCount);
}

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

} // namespace

Landmarks complete_landmarks(const Mesh& scan, const Landmarks& given, const FaceFrame& frame) {
  if (given.count() == kLandmarkCount || scan.vertex_count() == 0) return given;
  std::vector<Vec3> points(scan.positions.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = frame.scale * scan.positions[i];
  const PointIndex index(points);
  const Landmarks found = search_landmarks(points, scan.triangles, median_spacing(points, index),
                                           Rigid{frame.rotation, frame.translation});
  Landmarks out = given;
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    if (!out.points[i] && found.points[i]) out.points[i] = *found.points[i] / frame.scale;
  return out;
}

namespace {

// The scan prepared for the search: in millimetres, loose fragments gone, with its k-d trees.
struct Scene {
  Mesh mesh; // mm
  std::optional<PointIndex> index;
  double spacing = 0.0;     // median distance between neighbouring points
  std::vector<Vec3> sample; // one point per voxel of DetectOptions::sample_mm
  std::optional<PointIndex> coarse;
  std::vector<Vec3> probe;      // 300 of the sample, to score candidate planes
  std::vector<Vec3> fit_points; // 1000 of the sample, to refine them
};

Scene prepare(const Mesh& scan, double mm, const DetectOptions& options) {
  Scene s;
  s.mesh = drop_small_components(scan, options.min_fragment);
  for (Vec3& p : s.mesh.positions)
    p *= mm;
  s.index.emplace(s.mesh.positions);
  s.spacing = median_spacing(s.mesh.positions, *s.index);
  s.sample = voxel_subsample(s.mesh.positions, std::max(options.sample_mm, s.spacing));
  s.coarse.emplace(s.sample);
  s.probe = thin(s.sample, 300);
  s.fit_points = thin(s.sample, 1000);
  return s;
}

// Symmetry plane candidates through the centroid in every direction, scored on the probe against the
// subsample (nearest-neighbour queries dominate the cost); the best 16 distinct directions get a few
// registration steps (a plane through the centroid may be offset from the face's, e.g. on a scan cut
// asymmetrically); the best 4 of those are the seeds.
std::vector<Plane> symmetry_seeds(const Scene& s, int directions) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : s.sample)
    centroid += p;
  centroid /= static_cast<double>(s.sample.size());

  std::vector<std::pair<double, Vec3>> scored;
  for (const Vec3& n : hemisphere(directions))
    scored.emplace_back(mirror_rms(mirror_of({n, n.dot(centroid)}), s.probe, *s.coarse), n);
  std::ranges::sort(scored, {}, &std::pair<double, Vec3>::first);

  const double distinct = std::cos(0.17); // 10 degrees
  std::vector<std::pair<double, Plane>> rough;
  std::vector<Vec3> tried;
  for (const auto& [rms, n] : scored) {
    if (tried.size() == 16) break;
    if (std::ranges::any_of(tried, [&](const Vec3& t) { return std::abs(t.dot(n)) > distinct; })) continue;
    tried.push_back(n);
    const Mirror m = refine(mirror_of({n, n.dot(centroid)}), s.probe, s.sample, *s.coarse, 0.7, 6);
    const Plane plane = plane_of(m, s.probe);
    rough.emplace_back(mirror_rms(mirror_of(plane), s.probe, *s.coarse), plane);
  }
  std::ranges::sort(rough, {}, &std::pair<double, Plane>::first);
  std::vector<Plane> seeds;
  for (const auto& [rms, plane] : rough) {
    if (seeds.size() == 4) break;
    if (std::ranges::none_of(seeds,
                             [&](const Plane& q) { return std::abs(q.normal.dot(plane.normal)) > distinct; }))
      seeds.push_back(plane);
  }
  return seeds;
}

struct Candidate {
  Plane plane;
  double rms; // mirror RMS around the nose
  Nose nose;
};

// The scan's outline need not be symmetric (a cut, hair, an ear missing), and a face is close to a
// cylinder, whose symmetry planes are many: a plane is judged on the central face only, 70 mm around its
// nose, where a face is most symmetric and a scan most complete, keeping nearly every pair so that the
// nose and the eyes (which show the plane's yaw) count.
std::optional<Candidate> around_the_nose(const Scene& s, const Candidate& c, double slab) {
  std::vector<Vec3> central;
  for (const Vec3& p : s.sample)
    if ((p - c.nose.tip).norm() < 70.0) central.push_back(p);
  if (central.size() < 50) return std::nullopt;
  const Mirror m = refine(mirror_of(c.plane), central, s.mesh.positions, *s.index, 0.95);
  const Plane plane = plane_of(m, central);
  const std::optional<Nose> nose = find_nose(plane, s.mesh.positions, slab);
  if (!nose || nose->prominence < kMinNoseProminence) return std::nullopt;
  return Candidate{plane, mirror_rms(mirror_of(plane), central, *s.index), *nose};
}

// Each seed refined, its nose found, judged around its nose; the plane most symmetric there wins (a
// wrong plane through a face can show a bigger "nose": the chin, or the nose seen askew, but not a
// symmetric face around it). Also reports the most prominent "nose" seen, for the error message.
std::optional<Candidate> choose_plane(const Scene& s, std::span<const Plane> seeds, double& best_prominence) {
  const double slab = std::max(1.0, 0.6 * s.spacing);
  std::optional<Candidate> chosen;
  for (const Plane& seed : seeds) {
    const Plane plane = plane_of(refine(mirror_of(seed), s.fit_points, s.sample, *s.coarse), s.fit_points);
    const std::optional<Nose> nose = find_nose(plane, s.mesh.positions, slab);
    if (!nose) continue;
    best_prominence = std::max(best_prominence, nose->prominence);
    if (nose->prominence < kMinNoseProminence) continue;
    const std::optional<Candidate> refined =
        around_the_nose(s, {plane, mirror_rms(mirror_of(plane), s.fit_points, *s.coarse), *nose}, slab);
    if (refined && (!chosen || refined->rms < chosen->rms)) chosen = refined;
  }
  if (chosen)
    if (const std::optional<Candidate> again = around_the_nose(s, *chosen, slab)) chosen = again;
  return chosen;
}

struct Fitted {
  Landmarks found; // mm
  double fit_rms = std::numeric_limits<double>::infinity();
};

// A first frame from the nose alone: origin at the tip, z forward, y up, x = y × z (the face's left).
// The landmarks are searched in it, the frame fitted to them, and again until the frame stops moving (a
// fixed point does not depend on where the search started). The nose's shape says which way is up, but
// not always clearly (a short nose, a low-resolution scan): both ways are tried, and the one whose
// landmarks sit best on an average face wins.
Fitted fit_landmarks(const Scene& s, const Nose& nose) {
  std::optional<Fitted> best;
  for (const Vec3& up : {nose.up, Vec3(-nose.up)}) {
    Eigen::Matrix3d r;
    r.row(1) = up.transpose();
    r.row(2) = nose.forward.transpose();
    r.row(0) = up.cross(nose.forward).transpose();
    Rigid frame{r, -r * nose.tip};
    Fitted attempt;
    for (int round = 0; round < 6; ++round) {
      attempt.found = search_landmarks(s.mesh.positions, s.mesh.triangles, s.spacing, frame);
      Result<FaceFrame> fit = frame_from_landmarks(attempt.found, Units::Millimetres);
      if (!fit) break;
      attempt.fit_rms = fit_rms(attempt.found, *fit);
      const double turn = Eigen::AngleAxisd(fit->rotation * frame.rotation.transpose()).angle();
      const double shift = (fit->translation - frame.translation).norm();
      frame = {fit->rotation, fit->translation};
      if (round > 0 && turn < 1e-4 && shift < 0.01) break; // 0.006°, 10 µm
    }
    if (!best || attempt.fit_rms < best->fit_rms) best = std::move(attempt);
  }
  return *best;
}

} // namespace

Result<Detection> detect_landmarks(const Mesh& scan, const DetectOptions& options) {
  const std::string source = scan.name;
  if (scan.vertex_count() < 100)
    return make_error(ErrorCode::NoFace,
                      fmt::format("no face found: {} points are too few to hold one", scan.vertex_count()),
                      source);
  const Units units = detect_units(scan);
  const double mm = millimetres_per(units);
  const Scene scene = prepare(scan, mm, options);

  double best_prominence = 0.0;
  const std::optional<Candidate> chosen =
      choose_plane(scene, symmetry_seeds(scene, options.directions), best_prominence);
  if (!chosen)
    return make_error(
        ErrorCode::NoFace,
        fmt::format("no face found: no nose-like point on any symmetry plane (most prominent {:.1f} mm, "
                    "a nose stands at least {:.0f} mm out of its profile)",
                    best_prominence, kMinNoseProminence),
        source);

  const Fitted fitted = fit_landmarks(scene, chosen->nose);
  Landmarks found = fitted.found;
  for (auto& p : found.points)
    if (p) *p /= mm;
  found.units = units;
  Result<FaceFrame> frame = frame_from_landmarks(found, units);
  if (!frame) return make_error(ErrorCode::NoFace, "no face found: " + frame.error().message, source);

  Detection out;
  out.landmarks = found;
  out.frame = *frame;
  out.symmetry = {chosen->plane.normal, chosen->plane.offset / mm};
  out.symmetry_rms_mm = chosen->rms;
  out.nose_prominence_mm = chosen->nose.prominence;
  out.fit_rms_mm = fitted.fit_rms;
  const double coverage = static_cast<double>(found.count()) / kLandmarkCount;
  out.confidence = std::min({clamp01(1.0 - (out.symmetry_rms_mm - 2.0) / 6.0),
                             clamp01((out.nose_prominence_mm - kMinNoseProminence) / 12.0),
                             clamp01(1.0 - (out.fit_rms_mm - 8.0) / 14.0), coverage});
  if (out.confidence < options.min_confidence)
    return make_error(
        ErrorCode::NoFace,
        fmt::format("no face found: confidence {:.2f} < {:.2f} (symmetry {:.1f} mm, nose {:.1f} mm, "
                    "landmark fit {:.1f} mm, {} of {} landmarks)",
                    out.confidence, options.min_confidence, out.symmetry_rms_mm, out.nose_prominence_mm,
                    out.fit_rms_mm, found.count(), kLandmarkCount),
        source);
  return out;
}

Result<Alignment> align_scan(const Mesh& scan, std::optional<Landmarks> given, std::string_view source,
                             std::string_view landmarks_source) {
  if (!given) {
    Result<Detection> found = detect_landmarks(scan);
    if (!found) {
      Error e = std::move(found).error();
      e.source = source;
      return e;
    }
    return Alignment{std::move(found->landmarks), found->frame, found->confidence};
  }
  if (given->units == Units::Unknown) given->units = detect_units(scan);
  Result<FaceFrame> fitted = frame_from_landmarks(*given, given->units);
  if (!fitted) {
    Error e = std::move(fitted).error();
    e.source = landmarks_source;
    return e;
  }
  return Alignment{complete_landmarks(scan, *given, *fitted), *fitted, std::nullopt};
}

} // namespace pdeface::align
