#include "pdeface/align/detect.hpp"

#include "search.hpp"
#include "symmetry.hpp"

#include "pdeface/core/parallel.hpp"
#include "pdeface/core/point_index.hpp"
#include "pdeface/core/topology.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

namespace pdeface::align {
namespace {

using detail::Mirror;
using detail::mirror_of;
using detail::mirror_rms;
using detail::plane_of;
using detail::refine;

// Lengths below are in face millimetres: millimetres of the face at the scale being tried. `unit` (scan
// units per face millimetre) turns them into the scan's units.
constexpr double kMinNoseProminence = 8.0; // a nose tip stands 15-30 mm out of its profile
constexpr double kMissing = 30.0;          // how far off a landmark not found counts
constexpr double kFaceShapeMm = 9.5;       // landmarks this close to the average face's: a face (shape cue 1)
constexpr double kFaceSymmetryMm = 2.0;    // a central face this symmetric: a face (symmetry cue 1)
constexpr double kMinEyeHollow = 0.5;      // eye sockets at least this deep (real faces 2.5-7.6 mm, convex
                                           // objects none: a capped cylinder's "eyes" -0.3 mm)
// Bounds whatever the coordinates (docs/robustness.md). A scan that spans more than this many millimetres
// (in its units, or in those its size suggests) holds no face we could find: a whole body is 2 m.
constexpr double kMaxScanMm = 10000.0;
// Whatever its units, a scan whose size (the bounding box's diagonal) is outside these bounds is no face:
// within them the search's arithmetic (squared distances, ratios of sizes) stays far from overflowing.
constexpr double kMinScanSize = 1e-30;
constexpr double kMaxScanSize = 1e30;
// A symmetry profile samples each triangle's cut at most this many times, and holds at most this many
// points: a face's triangles are cut in one or two pieces, a soup of huge triangles must not allocate
// gigabytes.
constexpr int kMaxPiecesPerCut = 16;
constexpr std::size_t kMaxProfilePoints = std::size_t{1} << 22;

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

// A loop over items 0 … n − 1 as the search runs it one after the other: an item is tried when `wanted(i)`
// (which may depend on what earlier items gave), its result handed to `commit(i, result)`, at most `room()`
// more results taken. Here `threads` items are tried at once (0: every core): the next ones wanted as
// things stand, then committed in order, each asked `wanted` again first (a result committed before it
// may have made it unwanted: its try is wasted, and nothing is committed for it). A wanted item stays
// wanted or becomes unwanted as results come in, never the other way, so the outcome is the one-by-one
// loop's to the bit, whatever the number of threads; an exception from `attempt` is thrown where that loop
// would have met it (when its item is committed).
template <class Wanted, class Attempt, class Commit, class Room>
void in_order(std::size_t n, unsigned threads, const Wanted& wanted, const Attempt& attempt,
              const Commit& commit, const Room& room) {
  using Tried = decltype(attempt(std::size_t{}));
  const std::size_t width = threads == 0 ? cores() : threads;
  std::size_t next = 0;
  while (next < n) {
    const std::size_t left = room();
    if (left == 0) return;
    std::vector<std::size_t> batch;
    for (; next < n && batch.size() < std::min(width, left); ++next)
      if (wanted(next)) batch.push_back(next);
    if (batch.empty()) return;
    std::vector<Tried> tried(batch.size());
    std::vector<std::exception_ptr> failed(batch.size());
    parallel_for(batch.size(), static_cast<unsigned>(width), [&](std::size_t k) {
      try {
        tried[k] = attempt(batch[k]);
      } catch (...) {
        failed[k] = std::current_exception();
      }
    });
    for (std::size_t k = 0; k < batch.size(); ++k) {
      if (room() == 0) return;
      if (!wanted(batch[k])) continue;
      if (failed[k]) std::rethrow_exception(failed[k]);
      commit(batch[k], std::move(tried[k]));
    }
  }
}
constexpr auto kNoLimit = [] { return std::numeric_limits<std::size_t>::max(); };

// ---- the scan ------------------------------------------------------------------------------------------

// The scan prepared for the search, in its own units: loose fragments gone, with its k-d tree and a
// subsample for the symmetry search whose spacing follows the scan's size (so the search does not
// depend on the units).
struct Scene {
  // The scan's geometry, loose fragments gone: the scan's own arrays when it has none, else `kept_*`.
  std::span<const Vec3> positions;
  std::span<const Triangle> triangles;
  std::vector<Vec3> kept_positions;
  std::vector<Triangle> kept_triangles;
  std::optional<PointIndex> index;
  double spacing = 0.0;     // median distance between neighbouring points
  double size = 0.0;        // bounding-box diagonal
  std::vector<Vec3> sample; // one point per voxel of size / 100
  std::optional<PointIndex> coarse;
  std::optional<detail::NearGrid> near; // the sample's distances by look-up, to score candidate planes
  std::vector<Vec3> probe;              // 300 of the sample, to score candidate planes
  std::vector<Vec3> fit_points;         // 1000 of the sample, to refine them
  detail::Loops loops;                  // the mesh's boundaries: eyes and mouths may be holes
};

Scene prepare(const Mesh& scan, const DetectOptions& options) {
  Scene s;
  // Only the geometry, and only copied when fragments are dropped (a 490k-vertex scan's whole copy, with
  // its normals, was 31 MB of encode's peak).
  s.positions = scan.positions;
  s.triangles = scan.triangles;
  if (const std::vector<std::uint32_t> index = kept_component_vertices(scan, options.min_fragment);
      !index.empty()) {
    for (std::size_t v = 0; v < index.size(); ++v)
      if (index[v] != kDroppedVertex) s.kept_positions.push_back(scan.positions[v]);
    for (const Triangle& t : scan.triangles)
      if (index[t[0]] != kDroppedVertex) s.kept_triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    s.positions = s.kept_positions;
    s.triangles = s.kept_triangles;
  }
  s.index.emplace(s.positions);
  s.spacing = detail::median_spacing(s.positions, *s.index);
  s.size = bounding_box(s.positions).diagonal();
  const double voxel = std::max(s.size / 100.0, s.spacing);
  s.sample = detail::voxel_subsample(s.positions, voxel);
  s.coarse.emplace(s.sample);
  s.near.emplace(s.sample, voxel);
  s.probe = detail::thin(s.sample, 300);
  s.fit_points = detail::thin(s.sample, 1000);
  s.loops = detail::boundary_loops(s.triangles);
  return s;
}

// The scan's points within `radius` of `centre`, one per voxel of `cell`.
std::vector<Vec3> patch(const Scene& s, const Vec3& centre, double radius, double cell) {
  return detail::voxel_subsample_within(*s.index, s.positions, centre, radius, cell);
}

// ---- the nose on a symmetry profile --------------------------------------------------------------------

struct Nose {
  Vec3 tip;
  Vec3 forward;            // out of the face
  Vec3 up;                 // towards the forehead
  double prominence = 0.0; // face mm
};

// The symmetry profile: the plane's section of the mesh, every triangle it cuts giving the segment across
// it, sampled at most `step` apart, so that the profile is whole and lies on the plane whatever the
// mesh's spacing (the vertices within a slab around the plane thin out on a coarse scan to one every few
// rows, miss the nose tip and leave gaps where the windows of `find_noses` look). A point cloud has no
// triangles: its points within `slab` of the plane. Within `reach` of `near` when given.
std::vector<Vec3> profile_of(const Scene& s, const Plane& plane, double slab, double step,
                             const Vec3* near = nullptr, double reach = 0.0) {
  std::vector<Vec3> out;
  const auto side = [&](const Vec3& p) { return plane.normal.dot(p) - plane.offset; };
  if (s.triangles.empty()) {
    const auto take = [&](const Vec3& p) {
      if (std::abs(side(p)) <= slab) out.push_back(p);
    };
    if (near)
      for (const auto& n : s.index->within(*near, reach))
        take(s.positions[n.index]);
    else
      for (const Vec3& p : s.positions)
        take(p);
    return out;
  }
  const double reach2 = reach * reach;
  for (const Triangle& t : s.triangles) {
    const std::array<Vec3, 3> v{s.positions[t[0]], s.positions[t[1]], s.positions[t[2]]};
    if (near && (v[0] - *near).squaredNorm() > reach2) continue;
    const std::array<double, 3> h{side(v[0]), side(v[1]), side(v[2])};
    std::array<Vec3, 2> cut;
    int n = 0;
    for (int k = 0; k < 3 && n < 2; ++k) {
      const int j = (k + 1) % 3;
      if ((h[k] >= 0.0) != (h[j] >= 0.0)) cut[n++] = v[k] + h[k] / (h[k] - h[j]) * (v[j] - v[k]);
    }
    if (n < 2) continue;
    if (out.size() >= kMaxProfilePoints) break;
    const double length = (cut[1] - cut[0]).norm() / step; // may be anything: compared as a double
    const int pieces =
        length < kMaxPiecesPerCut ? std::max(1, static_cast<int>(std::ceil(length))) : kMaxPiecesPerCut;
    for (int i = 0; i <= pieces; ++i)
      out.push_back(cut[0] + (static_cast<double>(i) / pieces) * (cut[1] - cut[0]));
  }
  return out;
}

// Looking along every direction in the plane, the extreme point of the profile is a nose tip when the
// profile falls away steeply on both sides of it (15 mm on, the dorsum is a few mm back and the upper
// lip 15-20 mm back), yet smoothly (a spike of hair falls away as fast 5 mm on). The dorsum side is up.
// Every such point, the most prominent per place (15 mm apart), most prominent first, at most `most`;
// with `towards`, only looking within 40° of it.
std::vector<Nose> find_noses(const Plane& plane, std::span<const Vec3> profile, double unit, std::size_t most,
                             const Vec3* towards = nullptr) {
  std::vector<Nose> found;
  if (profile.size() < 20) return found;
  const Vec3 b1 = plane.normal.unitOrthogonal();
  const Vec3 b2 = plane.normal.cross(b1);
  // The profile in the plane's coordinates (face mm): d = (cos, sin), lateral = normal × d = (-sin, cos).
  std::vector<Eigen::Vector2d> flat;
  flat.reserve(profile.size());
  for (const Vec3& p : profile)
    flat.emplace_back(b1.dot(p) / unit, b2.dot(p) / unit);
  for (int step = 0; step < 180; ++step) {
    const double theta = 2.0 * std::numbers::pi * step / 180.0;
    const Eigen::Vector2d d2(std::cos(theta), std::sin(theta)), lateral2(-d2.y(), d2.x());
    const Vec3 d = d2.x() * b1 + d2.y() * b2;
    if (towards && d.dot(*towards) < std::cos(0.7)) continue; // only about the way given
    const Vec3 lateral = plane.normal.cross(d);
    const auto top = std::ranges::max_element(flat, {}, [&](const Eigen::Vector2d& p) { return d2.dot(p); });
    const Eigen::Vector2d tip2 = *top;
    const Vec3& tip = profile[static_cast<std::size_t>(top - flat.begin())];
    // How far the profile falls back from the tip at lateral offsets of 3-7 mm (near) and 12-18 mm (far)
    // on either side: the least depth among those points within 30 mm behind the tip. +inf when there
    // are none (an end of the profile, or a curve turning away).
    double far_plus = std::numeric_limits<double>::infinity(), far_minus = far_plus;
    double near_plus = far_plus, near_minus = far_plus;
    for (const Eigen::Vector2d& q : flat) {
      const double behind = d2.dot(tip2 - q);
      if (behind > 30.0) continue;
      const double l = lateral2.dot(q - tip2), a = std::abs(l);
      if (a >= 12.0 && a <= 18.0)
        (l > 0 ? far_plus : far_minus) = std::min(l > 0 ? far_plus : far_minus, behind);
      else if (a >= 3.0 && a <= 7.0)
        (l > 0 ? near_plus : near_minus) = std::min(l > 0 ? near_plus : near_minus, behind);
    }
    if (!std::isfinite(far_plus + far_minus + near_plus + near_minus)) continue; // an end of the profile
    if (near_plus + near_minus > 0.6 * (far_plus + far_minus) + 1.0) continue;   // a spike, not a nose
    const Nose nose{tip, d, far_plus < far_minus ? lateral : Vec3(-lateral), far_plus + far_minus};
    const auto same =
        std::ranges::find_if(found, [&](const Nose& n) { return (n.tip - tip).norm() < 15.0 * unit; });
    if (same == found.end())
      found.push_back(nose);
    else if (nose.prominence > same->prominence)
      *same = nose;
  }
  std::ranges::sort(found, std::greater{}, &Nose::prominence);
  if (found.size() > most) found.resize(most);
  return found;
}

// ---- candidates: a symmetry plane and a nose on it -----------------------------------------------------

struct Candidate {
  Plane plane;
  Nose nose;
  double rms_mm = 0.0; // mirror RMS of the central face (face mm)
};

// Symmetry planes of the whole scan: candidate planes through the centroid in every direction, scored
// on the probe against the subsample; the best 16 distinct directions get a few registration steps (a
// plane through the centroid may be offset from the face's), the best `count` of those are registered
// fully. These find the face's plane when the face is most of the scan.
std::vector<Plane> global_planes(const Scene& s, int directions, std::size_t count, unsigned threads) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : s.sample)
    centroid += p;
  centroid /= static_cast<double>(s.sample.size());
  const double still = 1e-5 * s.size;

  const std::vector<Vec3> normals = detail::fibonacci_directions(directions);
  std::vector<std::pair<double, Vec3>> scored(normals.size());
  parallel_for(normals.size(), threads, [&](std::size_t i) {
    const Vec3& n = normals[i];
    scored[i] = {mirror_rms(mirror_of({n, n.dot(centroid)}), s.probe, *s.near), n};
  });
  std::ranges::sort(scored, {}, &std::pair<double, Vec3>::first);

  const double distinct = std::cos(0.17); // 10 degrees
  std::vector<Vec3> tried;
  for (const auto& entry : scored) {
    const Vec3& n = entry.second;
    if (tried.size() == 16) break;
    if (std::ranges::any_of(tried, [&](const Vec3& t) { return std::abs(t.dot(n)) > distinct; })) continue;
    tried.push_back(n);
  }
  std::vector<std::pair<double, Plane>> rough(tried.size());
  parallel_for(tried.size(), threads, [&](std::size_t i) {
    const Vec3& n = tried[i];
    const Mirror m = refine(mirror_of({n, n.dot(centroid)}), s.probe, s.sample, *s.coarse, 0.7, 6, still);
    const Plane plane = plane_of(m, s.probe);
    rough[i] = {mirror_rms(mirror_of(plane), s.probe, *s.coarse), plane};
  });
  std::ranges::sort(rough, {}, &std::pair<double, Plane>::first);
  std::vector<Plane> planes;
  in_order(
      rough.size(), threads,
      [&](std::size_t i) {
        return !std::ranges::any_of(planes, [&](const Plane& q) {
          return std::abs(q.normal.dot(rough[i].second.normal)) > distinct;
        });
      },
      [&](std::size_t i) {
        return plane_of(refine(mirror_of(rough[i].second), s.fit_points, s.sample, *s.coarse, 0.7, 30, still),
                        s.fit_points);
      },
      [&](std::size_t, const Plane& plane) { planes.push_back(plane); },
      [&] { return count - planes.size(); });
  return planes;
}

// Places that could be a nose tip whatever the scan's pose and scale: the points of the subsample that
// are the extreme point of the scan in some direction (a nose tip is on the scan's convex hull), with
// the directions in which they are.
struct Extreme {
  Vec3 point;
  Vec3 direction; // mean of the directions it is extreme in
  int votes = 0;
};

std::vector<Extreme> extreme_points(const Scene& s, int directions) {
  std::vector<Extreme> out;
  std::vector<int> slot(s.sample.size(), -1);
  for (const Vec3& d : detail::fibonacci_directions(directions, true)) {
    std::size_t best = 0;
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < s.sample.size(); ++i)
      if (const double h = d.dot(s.sample[i]); h > top) {
        top = h;
        best = i;
      }
    if (slot[best] < 0) {
      slot[best] = static_cast<int>(out.size());
      out.push_back({s.sample[best], Vec3::Zero(), 0});
    }
    Extreme& e = out[static_cast<std::size_t>(slot[best])];
    e.direction += d;
    ++e.votes;
  }
  return out;
}

// The extreme points grouped into places 15 mm across (greedily, most votes first), the `most` with the
// most votes (the widest cones of directions: pointed features).
std::vector<Extreme> extreme_places(std::vector<Extreme> points, double unit, std::size_t most) {
  std::ranges::sort(points, std::greater{}, &Extreme::votes);
  std::vector<Extreme> places;
  std::vector<bool> used(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (used[i]) continue;
    Extreme place = points[i];
    for (std::size_t j = i + 1; j < points.size(); ++j)
      if (!used[j] && (points[j].point - points[i].point).norm() < 15.0 * unit) {
        used[j] = true;
        place.direction += points[j].direction;
        place.votes += points[j].votes;
      }
    place.direction.normalize();
    places.push_back(place);
  }
  std::ranges::stable_sort(places, std::greater{}, &Extreme::votes);
  if (places.size() > most) places.resize(most);
  return places;
}

// How far, on average, the scan falls back behind `tip` (along `d`) 10-20 mm to its sides: a nose
// falls 10-20 mm, a gentle bump (a cheek, the crown of a head) a few. 0 when the surface does not go
// all round (the rim of an open scan is extreme in many directions too).
double fall_around(const Scene& s, const Vec3& tip, const Vec3& d, double unit) {
  const Vec3 e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  std::array<bool, 8> sectors{};
  double sum = 0.0;
  int n = 0;
  for (const auto& nb : s.index->within(tip, 25.0 * unit)) {
    const Vec3 v = s.positions[nb.index] - tip;
    const double behind = -d.dot(v);
    const Vec3 across = v + behind * d;
    const double side = across.norm();
    if (side < 10.0 * unit || side > 20.0 * unit) continue;
    const double angle = std::atan2(e2.dot(across), e1.dot(across)) + std::numbers::pi;
    sectors[static_cast<std::size_t>(std::min(7.0, angle / (2.0 * std::numbers::pi) * 8.0))] = true;
    sum += std::min(behind, 25.0 * unit);
    ++n;
  }
  if (n == 0 || !std::ranges::all_of(sectors, [](bool b) { return b; })) return 0.0;
  return sum / n / unit;
}

// The symmetry plane of the scan around an extreme point: planes through it that contain its direction,
// every 10°, scored by how well the central face (70 mm around) matches its mirror image; the best three
// local minima of that score over the angle registered (a head is round: the plane across the face
// through the nose can score as well as the face's own before registration, so one seed is not enough).
std::optional<Plane> local_plane(const Scene& s, const Vec3& tip, const Vec3& d, double unit) {
  const std::vector<Vec3> around = patch(s, tip, 70.0 * unit, 3.0 * unit);
  if (around.size() < 50) return std::nullopt;
  const std::vector<Vec3> probe = detail::thin(around, 200);
  const std::vector<Vec3> fit = detail::thin(around, 600);
  const Vec3 e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  constexpr int kAngles = 18;
  std::array<std::pair<double, Vec3>, kAngles> scored;
  for (int k = 0; k < kAngles; ++k) {
    const double phi = std::numbers::pi * k / kAngles;
    const Vec3 n = std::cos(phi) * e1 + std::sin(phi) * e2;
    scored[static_cast<std::size_t>(k)] = {mirror_rms(mirror_of({n, n.dot(tip)}), probe, *s.index), n};
  }
  std::vector<std::pair<double, Vec3>> seeds; // the local minima over the angle (which wraps at 180°)
  for (std::size_t k = 0; k < kAngles; ++k)
    if (scored[k].first <= scored[(k + 1) % kAngles].first &&
        scored[k].first <= scored[(k + kAngles - 1) % kAngles].first)
      seeds.push_back(scored[k]);
  std::ranges::sort(seeds, {}, &std::pair<double, Vec3>::first);
  if (seeds.size() > 3) seeds.resize(3);
  std::optional<std::pair<double, Plane>> best;
  for (const auto& [score, n] : seeds) {
    const Mirror m = refine(mirror_of({n, n.dot(tip)}), fit, s.positions, *s.index, 0.8, 20, 1e-3 * unit);
    const Plane plane = plane_of(m, fit);
    const double rms = mirror_rms(mirror_of(plane), probe, *s.index);
    if (!best || rms < best->first) best = {rms, plane};
  }
  if (!best) return std::nullopt;
  return best->second;
}

// The scan's outline need not be symmetric (a cut, hair, an ear missing, shoulders turned away from the
// head), and a face is close to a cylinder, whose symmetry planes are many: a plane is judged on the
// central face only, 70 mm around its nose, where a face is most symmetric and a scan most complete,
// keeping nearly every pair so that the nose and the eyes (which show the plane's yaw) count. The nose
// is then looked for again on the refined plane, near where it was.
// Quickly (`points` of the central face, `iterations` steps) or thoroughly (every voxel, 30 steps).
std::optional<Candidate> around_the_nose(const Scene& s, const Plane& plane, const Nose& seed, double unit,
                                         std::size_t points = 0, int iterations = 30) {
  const Vec3& tip = seed.tip;
  std::vector<Vec3> central = patch(s, tip, 70.0 * unit, 3.0 * unit);
  if (central.size() < 50) return std::nullopt;
  if (points > 0) central = detail::thin(central, points);
  const Mirror m = refine(mirror_of(plane), central, s.positions, *s.index, 0.95, iterations, 1e-3 * unit);
  const Plane refined = plane_of(m, central);
  const double slab = std::max(1.0 * unit, 0.6 * s.spacing);
  const std::vector<Vec3> profile = profile_of(s, refined, slab, unit, &tip, 90.0 * unit);
  for (const Nose& nose : find_noses(refined, profile, unit, 3, &seed.forward)) {
    if ((nose.tip - tip).norm() > 25.0 * unit || nose.prominence < kMinNoseProminence) continue;
    return Candidate{refined, nose, mirror_rms(mirror_of(refined), central, *s.index) / unit};
  }
  return std::nullopt;
}

// ---- verification: the landmarks a candidate implies ---------------------------------------------------

// How well landmarks (scan units) sit on the average face: the similarity fit (weights as fit_weight)
// gives the face's scale; the RMS, in template millimetres, of the nose tip and the eye and mouth
// corners from the template's with the nose tip on the origin (a landmark not found counts as 30 mm).
// The face's top and bottom do not count: they are derived, and a beard or an open mouth moves the chin.
struct Shape {
  double mm_per_unit = 0.0;
  double rms_mm = std::numeric_limits<double>::infinity();
  FaceFrame frame; // at mm_per_unit
};

constexpr Landmark kStable[] = {Landmark::NoseTip,      Landmark::EyeInnerLeft,  Landmark::EyeInnerRight,
                                Landmark::EyeOuterLeft, Landmark::EyeOuterRight, Landmark::MouthLeft,
                                Landmark::MouthRight};

double stable_rms(const Landmarks& landmarks, const FaceFrame& frame) {
  double sum = 0.0;
  for (Landmark l : kStable)
    sum += landmarks.has(l) ? (frame.to_canonical(*landmarks[l]) - *canonical_template()[l]).squaredNorm()
                            : kMissing * kMissing;
  return std::sqrt(sum / std::size(kStable));
}

std::optional<Shape> shape_of(const Landmarks& landmarks) {
  const Result<ScaleEstimate> scale = estimate_scale(landmarks);
  if (!scale || !landmarks.has(Landmark::NoseTip)) return std::nullopt;
  Result<FaceFrame> frame = frame_from_landmarks(landmarks, scale->estimated, Units::Unknown);
  if (!frame) return std::nullopt;
  return Shape{scale->estimated, stable_rms(landmarks, *frame), *frame};
}

// The scale (mm per unit) landmarks found with windows of a wrong scale say: the median, over the eye
// and mouth corners, of the ratio of the template's distance from the nose tip to theirs. Distances do
// not depend on the frame's rotation, and the median on the corners a wrong window got right (inner eye
// corners are the strongest hollows near a nose, mouth corners the ends of the mouth's line).
std::optional<double> robust_scale(const Landmarks& found) {
  if (!found.has(Landmark::NoseTip)) return std::nullopt;
  std::vector<double> ratios;
  for (Landmark l : kStable)
    if (l != Landmark::NoseTip && found.has(l)) {
      const double d = (*found[l] - *found[Landmark::NoseTip]).norm();
      if (d > 0.0)
        ratios.push_back((*canonical_template()[l] - *canonical_template()[Landmark::NoseTip]).norm() / d);
    }
  if (ratios.size() < 3) return std::nullopt;
  std::ranges::nth_element(ratios, ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2));
  return ratios[ratios.size() / 2];
}

// The landmarks made mirror-symmetric about the candidate's plane: each left/right pair replaced by the
// mean of one and the other's mirror image. A frame fitted to them (onto the symmetric average face)
// takes the plane's normal for its x axis, so that while a candidate is verified, its yaw and roll come
// from the symmetry of the whole central face and pitch from the landmarks: searched in a frame turned by
// a few corners found off on one side (a carved eye without a clear corner, a smile), the corners come
// out further off and the frame turns further. (The final frame is the landmarks' own fit, from the frame
// this gives: a fixed point of the search, which registration's wobble of a fraction of a degree from
// pose to pose does not move.)
Landmarks symmetrised(const Landmarks& found, const Plane& plane) {
  const Mirror m = mirror_of(plane);
  Landmarks out = found;
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    const auto l = static_cast<Landmark>(i);
    const Landmark r = mirrored(l);
    if (r != l && found.has(l) && found.has(r)) out[l] = 0.5 * (*found[l] + m(*found[r]));
  }
  return out;
}

// A first frame from the nose alone: origin at the tip, z forward, y up, x = y × z (the face's left).
Similarity nose_frame(const Nose& nose, const Vec3& up, double mm_per_unit) {
  Eigen::Matrix3d r;
  r.row(1) = up.transpose();
  r.row(2) = nose.forward.transpose();
  r.row(0) = up.cross(nose.forward).transpose();
  return {r, -mm_per_unit * (r * nose.tip), mm_per_unit};
}

struct Verified {
  Landmarks found; // scan units
  double mm_per_unit = 0.0;
  double shape_rms = std::numeric_limits<double>::infinity();
  Similarity frame; // the last one fitted
};

// The landmarks searched in the frame the nose gives (both ways up), the frame and the scale refitted
// to them, a few times: a candidate that is a face ends with its landmarks on the average face's.
// With `stated` (the file stated the units: millimetres per unit), the face's scale stays within a factor
// `kUnitSnapFactor` of it: a child's face, or a large adult's, is searched at its own size, in the units
// the file gave.
Verified verify(const Scene& s, const Candidate& c, double mm_per_unit, std::optional<double> stated,
                int rounds, double cell, const Similarity* from = nullptr) {
  // The first round both ways up (or from the frame a quicker verification ended in); the rest the
  // better way.
  Verified best;
  Similarity frame;
  std::vector<Similarity> starts;
  if (from) {
    starts.push_back(from->with_scale(mm_per_unit));
  } else {
    for (const Vec3& up : {c.nose.up, Vec3(-c.nose.up)})
      starts.push_back(nose_frame(c.nose, up, mm_per_unit));
  }
  for (const Similarity& start : starts) {
    const Landmarks found =
        detail::search_landmarks(s.positions, s.triangles, s.spacing, start, cell, s.loops);
    const std::optional<Shape> shape = shape_of(found);
    if (shape && shape->rms_mm < best.shape_rms) {
      best = {found, mm_per_unit, shape->rms_mm, start};
      frame = start;
    }
  }
  for (int round = 1; round <= rounds && std::isfinite(best.shape_rms); ++round) {
    // The next round at the scale the landmarks say (within reason: one round moves it 1.5× at most).
    double mm =
        std::clamp(robust_scale(best.found).value_or(frame.scale), frame.scale / 1.5, frame.scale * 1.5);
    if (stated) mm = std::clamp(mm, *stated / kUnitSnapFactor, *stated * kUnitSnapFactor);
    Result<FaceFrame> next = frame_from_landmarks(symmetrised(best.found, c.plane), mm, Units::Unknown);
    if (!next) break;
    const double turn = Eigen::AngleAxisd(next->rotation * frame.rotation.transpose()).angle();
    if (turn < 0.01 && std::abs(mm / frame.scale - 1.0) < 0.01) break; // settled
    frame = Similarity(*next);
    if (round == rounds) break;
    const Landmarks found =
        detail::search_landmarks(s.positions, s.triangles, s.spacing, frame, cell, s.loops);
    const std::optional<Shape> shape = shape_of(found);
    if (!shape) break;
    best = {found, frame.scale, shape->rms_mm, frame};
  }
  return best;
}

// ---- the final frame ------------------------------------------------------------------------------------

struct Fitted {
  Landmarks found; // scan units
  FaceFrame frame;
  double shape_rms = std::numeric_limits<double>::infinity();
};

// The landmarks searched in `start`, the frame fitted to them (rigidly, at the scale chosen), and again
// until the frame stops moving (a fixed point does not depend on where the search started).
std::optional<Fitted> fit_landmarks(const Scene& s, const Similarity& start, double mm_per_unit,
                                    Units units) {
  Similarity frame = start.with_scale(mm_per_unit);
  std::optional<Fitted> fitted;
  for (int round = 0; round < 10; ++round) {
    Landmarks found = detail::search_landmarks(s.positions, s.triangles, s.spacing, frame, 1.0, s.loops);
    Result<FaceFrame> fit = frame_from_landmarks(found, mm_per_unit, units);
    if (!fit) break;
    const std::optional<Shape> shape = shape_of(found);
    Fitted now{std::move(found), *fit, shape ? shape->rms_mm : std::numeric_limits<double>::infinity()};
    const double turn = Eigen::AngleAxisd(fit->rotation * frame.rotation.transpose()).angle();
    const double shift = (fit->translation - frame.translation).norm();
    frame = Similarity(*fit);
    const bool settled = round > 0 && turn < 1e-4 && shift < 0.01; // 0.006°, 10 µm
    // Settled: the fixed point. Else (landmarks jumping between two places) the round that fitted best.
    if (settled || !fitted || now.shape_rms < fitted->shape_rms) fitted = std::move(now);
    if (settled) break;
  }
  return fitted;
}

// ---- confidence -----------------------------------------------------------------------------------------

struct Cues {
  double symmetry = 0.0, nose = 0.0, shape = 0.0, coverage = 0.0, hollow = 0.0;
  [[nodiscard]] double confidence() const { return std::min({symmetry, nose, shape, coverage, hollow}); }
};

Cues cues(const Detection& d) {
  return {clamp01(1.0 - (d.symmetry_rms_mm - kFaceSymmetryMm) / 6.0),
          clamp01((d.nose_prominence_mm - kMinNoseProminence) / 12.0),
          clamp01(1.0 - (d.fit_rms_mm - kFaceShapeMm) / 4.5),
          static_cast<double>(d.landmarks.count()) / kLandmarkCount,
          clamp01((d.eye_hollow_mm - kMinEyeHollow) / 1.5)};
}

// The scales (mm per unit) to try when the file states no units: the scan, whatever it holds, is a
// face patch (0.2-0.35 m across), a head (0.35-0.6 m) or a bust (0.6-1.2 m).
std::vector<double> candidate_scales(const Scene& s) {
  std::vector<double> out;
  for (double across : {260.0, 480.0, 880.0})
    out.push_back(across / s.size);
  return out;
}

// Which candidate is the face: the one whose landmarks sit best on the average face and whose central
// face is most symmetric about its plane (a wrong plane through a face can show a bigger "nose", the
// chin or the nose seen askew, but not a symmetric face around it; a pedestal's corner is symmetric but
// has no eyes and mouth around it). Millimetres of misfit, negated.
double rank(const Candidate& c, const Verified& v) { return -(v.shape_rms + 3.0 * c.rms_mm); }

struct Hypothesis {
  Candidate candidate;
  Verified verified;
  double rank = -1.0;
};

// ---- the search, step by step ---------------------------------------------------------------------------

// How the search runs. Lengths are face millimetres (`unit` turns them into scan units) unless said.
// Where candidates come from:
constexpr std::size_t kGlobalPlanes = 4;         // the scan's own symmetry planes tried, best first
constexpr int kExtremeDirections = 600;          // directions in which the scan's extreme points are taken
constexpr std::size_t kMostExtremePlaces = 1000; // extreme places (points far out along a direction) kept
constexpr double kMinFallMm = 5.0;               // a pointed place: the surface falls this far around it
                                                 // (a nose tip falls 15-30 mm)
constexpr std::size_t kMostLocalPlanes = 10;     // local symmetry planes kept, the most pointed places first
constexpr double kProfileSlabMm = 1.0;           // a point cloud's symmetry profile: points this near the
constexpr double kProfileSlabSpacings = 0.6;     // plane, or this many point spacings when that is more
constexpr std::size_t kNosesPerPlane = 3;        // nose candidates taken from each global plane's profile
constexpr double kLocalReachMm = 40.0;           // a local plane's profile: within this of its pointed place
// When two candidates are one:
constexpr double kSameSeedMm = 3.0;         // seeds with nose tips this close, on planes whose normals
constexpr double kSamePlaneCos = 0.995;     // are within ~5.7° (cosine), are one seed
constexpr double kTriedNoseMm = 5.0;        // a seed this close to the nose of a hypothesis already tried
constexpr double kTriedScaleFactor = 1.3;   // at a scale within this factor (either way) is skipped
constexpr double kSameHypothesisMm = 5.0;   // hypotheses with nose tips this close and scales within
constexpr double kSameHypothesisLog = 0.15; // this in log (~16 %) are verified thoroughly once
// How hard each candidate is tried:
constexpr std::size_t kQuickPoints = 400;    // a seed's plane registered quickly: points of the central face
constexpr int kQuickIterations = 10;         // and mirror-ICP steps (thoroughly: every voxel, 30 steps)
constexpr int kVerifyRounds = 3;             // refits of the frame and scale to the landmarks it implies
constexpr double kQuickCellMm = 2.0;         // depth-map cell for the quick verification of every seed
constexpr double kFinalCellMm = 1.0;         // and for the thorough one and the final landmarks
constexpr std::size_t kThoroughPerRound = 3; // hypotheses verified thoroughly and finished per round
constexpr std::size_t kLastRounds = 3;       // rounds over the remaining hypotheses when no stage found one
// The final frame:
constexpr double kRegisterAgainShare = 0.02; // the plane registered again when the landmarks' scale differs
                                             // from the verified one by more than 2 %
constexpr int kScalePasses = 3;              // landmark fits at the scale they give, until it moves less
constexpr double kSettledScaleShare = 1e-3;  // than 0.1 %
// Stated units: the face at that scale, then as a child's (mm per unit × 1.4: a face 0.7 times as large)
// or a large adult's (÷ 1.2).
constexpr double kChildScale = 1.4;
constexpr double kLargeAdultScale = 1.2;

// The candidate symmetry plane through a pointed place of the scan.
struct Local {
  Extreme place;
  Plane plane;
};

// Detection as a search over hypotheses (a symmetry plane, a nose on it, a scale), cheapest first:
//   1. the scan's own symmetry planes at the scale the file states or its size suggests;
//   2. the local planes around its pointed places (a face turned on its shoulders, a bust);
//   3. every candidate scale (a bust, a head, units of no rule);
// each stage stopping once a face is found. Every seed is tried quickly (`try_scale`: the landmarks it
// implies on a coarse depth map, the scale they imply); the most face-like few are verified thoroughly and
// finished (`conclude`, `finish`) into landmarks, a frame and the cues that judge them.
class FaceSearch {
public:
  FaceSearch(const Mesh& scan, const Scene& scene, const DetectOptions& options)
      : scan_(scan), scene_(scene), options_(options), fixed_scale_(scan.units != Units::Unknown),
        stated_(fixed_scale_ ? std::optional<double>(millimetres_per(scan.units)) : std::nullopt),
        scales_(stated_ ? std::vector<double>{*stated_, *stated_ * kChildScale, *stated_ / kLargeAdultScale}
                        : candidate_scales(scene)),
        mid_(scales_[scales_.size() / 2]),
        planes_(global_planes(scene, options.directions, kGlobalPlanes, options.threads)) {
    // The first scale: the file's, else the one its size suggests (`detect_units`: right for a face scan
    // in mm, cm or m); for units of no rule (a scan too large in any), the middle candidate.
    first_ = fixed_scale_ ? scales_.front() : millimetres_per(units_by_size(scene.size));
    if (scene.size * first_ > kMaxScanMm) first_ = mid_;
  }

  Result<Detection> run() {
    // Stage by stage, stopping at the first face that passes every cue: a pedestal's corner can pass the
    // quick test (symmetric, a "nose", landmarks near the average face's) but has no eye sockets, and
    // must not end the search before the bust's face above it is tried.
    try_scale(first_, true, false);
    if (found_a_face())
      if (std::optional<Detection> d = conclude()) return std::move(*d);
    find_local_planes();
    try_scale(first_, false, true);
    if (found_a_face())
      if (std::optional<Detection> d = conclude()) return std::move(*d);
    for (const double mm : scales_)
      try_scale(mm, true, true);
    // Last, every remaining hypothesis, the most face-like first, a few at a time.
    for (std::size_t round = 0; round < kLastRounds; ++round)
      if (std::optional<Detection> d = conclude()) return std::move(*d);
    if (first_failure_) return *std::move(first_failure_);
    return make_error(ErrorCode::NoFace,
                      fmt::format("no face found: no nose-like point on any symmetry plane (most prominent "
                                  "{:.1f} mm, a nose stands at least {:.0f} mm out of its profile)",
                                  best_prominence_, kMinNoseProminence),
                      scan_.name);
  }

private:
  // Step 2's planes: around the most pointed extreme places of the scan (at the middle scale), the local
  // symmetry plane.
  void find_local_planes() {
    std::vector<std::pair<double, Extreme>> pointed;
    for (const Extreme& e :
         extreme_places(extreme_points(scene_, kExtremeDirections), 1.0 / mid_, kMostExtremePlaces))
      if (const double fall = fall_around(scene_, e.point, e.direction, 1.0 / mid_); fall >= kMinFallMm)
        pointed.emplace_back(fall, e);
    std::ranges::sort(pointed, std::greater{}, &std::pair<double, Extreme>::first);
    in_order(
        pointed.size(), options_.threads, [](std::size_t) { return true; },
        [&](std::size_t i) {
          const Extreme& e = pointed[i].second;
          return local_plane(scene_, e.point, e.direction, 1.0 / mid_);
        },
        [&](std::size_t i, const std::optional<Plane>& plane) {
          if (plane) locals_.push_back({pointed[i].second, *plane});
        },
        [&] { return kMostLocalPlanes - locals_.size(); });
  }

  // The seeds at scale `mm`: every nose-like point on the global planes' profiles and the best one on
  // each local plane's, one per place and plane.
  std::vector<Candidate> seeds_at(double mm, bool on_planes, bool on_locals) {
    const double unit = 1.0 / mm;
    const double slab = std::max(kProfileSlabMm * unit, kProfileSlabSpacings * scene_.spacing);
    std::vector<Candidate> seeds;
    const auto add = [&](const Plane& plane, const Nose& nose) {
      best_prominence_ = std::max(best_prominence_, nose.prominence);
      if (nose.prominence < kMinNoseProminence) return;
      if (std::ranges::any_of(seeds, [&](const Candidate& o) {
            return (o.nose.tip - nose.tip).norm() < kSameSeedMm * unit &&
                   std::abs(o.plane.normal.dot(plane.normal)) > kSamePlaneCos;
          }))
        return;
      seeds.push_back({plane, nose, 0.0});
    };
    for (const Plane& plane : on_planes ? std::span<const Plane>(planes_) : std::span<const Plane>())
      for (const Nose& nose : find_noses(plane, profile_of(scene_, plane, slab, unit), unit, kNosesPerPlane))
        add(plane, nose);
    for (const Local& l : on_locals ? std::span<const Local>(locals_) : std::span<const Local>()) {
      const auto noses =
          find_noses(l.plane, profile_of(scene_, l.plane, slab, unit, &l.place.point, kLocalReachMm * unit),
                     unit, 1, &l.place.direction);
      if (!noses.empty()) add(l.plane, noses.front());
    }
    return seeds;
  }

  // Every seed at scale `mm` tried quickly: its plane registered roughly on the central face, the nose
  // found on it again, and the landmarks it implies verified on a coarse depth map.
  void try_scale(double mm, bool on_planes, bool on_locals) {
    const double unit = 1.0 / mm;
    const std::vector<Candidate> seeds = seeds_at(mm, on_planes, on_locals);
    in_order(
        seeds.size(), options_.threads,
        [&](std::size_t i) { // a seed where an earlier try ended up near this scale is tried already
          return !std::ranges::any_of(quick_, [&](const Hypothesis& h) {
            return (h.candidate.nose.tip - seeds[i].nose.tip).norm() < kTriedNoseMm * unit &&
                   std::abs(std::log(h.verified.mm_per_unit / mm)) < std::log(kTriedScaleFactor);
          });
        },
        [&](std::size_t i) -> std::optional<Hypothesis> {
          const std::optional<Candidate> c =
              around_the_nose(scene_, seeds[i].plane, seeds[i].nose, unit, kQuickPoints, kQuickIterations);
          if (!c) return std::nullopt;
          Hypothesis h{*c, verify(scene_, *c, mm, stated_, kVerifyRounds, kQuickCellMm)};
          h.rank = rank(*c, h.verified);
          return h;
        },
        [&](std::size_t, std::optional<Hypothesis> h) {
          if (h) quick_.push_back(*std::move(h));
        },
        kNoLimit);
  }

  // A face among the quick tries: symmetric, its landmarks on the average face, and (when the scale was a
  // guess) saying the same unit as the first scale.
  [[nodiscard]] bool found_a_face() const {
    return std::ranges::any_of(quick_, [&](const Hypothesis& h) {
      return h.verified.shape_rms < kFaceShapeMm && h.candidate.rms_mm < kFaceSymmetryMm &&
             (fixed_scale_ || snap_units(h.verified.mm_per_unit) == snap_units(first_));
    });
  }

  // The most face-like few hypotheses so far (distinct nose tips or scales), verified thoroughly and
  // finished; the first that is confidently a face is the answer. Those tried are not tried again; the
  // first failure is kept to report.
  std::optional<Detection> conclude() {
    const auto same = [](const Hypothesis& h, const Hypothesis& q) {
      const double mm = q.verified.mm_per_unit;
      return (h.candidate.nose.tip - q.candidate.nose.tip).norm() < kSameHypothesisMm / mm &&
             std::abs(std::log(h.verified.mm_per_unit / mm)) < kSameHypothesisLog;
    };
    std::ranges::sort(quick_, std::greater{}, &Hypothesis::rank);
    std::vector<Hypothesis> hypotheses;
    in_order(
        quick_.size(), options_.threads,
        [&](std::size_t i) {
          const Hypothesis& q = quick_[i];
          return !std::ranges::any_of(hypotheses, [&](const Hypothesis& h) { return same(h, q); }) &&
                 !std::ranges::any_of(tried_, [&](const Hypothesis& h) { return same(h, q); });
        },
        [&](std::size_t i) -> std::optional<Hypothesis> {
          const Hypothesis& q = quick_[i];
          const double mm = q.verified.mm_per_unit;
          const std::optional<Candidate> c =
              around_the_nose(scene_, q.candidate.plane, q.candidate.nose, 1.0 / mm);
          if (!c) return std::nullopt;
          Hypothesis h{*c, verify(scene_, *c, mm, stated_, kVerifyRounds, kFinalCellMm, &q.verified.frame)};
          h.rank = rank(*c, h.verified);
          return h;
        },
        [&](std::size_t i, std::optional<Hypothesis> h) {
          tried_.push_back(quick_[i]);
          if (h) hypotheses.push_back(*std::move(h));
        },
        [&] { return kThoroughPerRound - hypotheses.size(); });
    std::ranges::sort(hypotheses, std::greater{}, &Hypothesis::rank);
    for (const Hypothesis& h : hypotheses) {
      Result<Detection> found = finish(h);
      if (found) return std::move(*found);
      if (!first_failure_) first_failure_ = std::move(found).error();
    }
    return std::nullopt;
  }

  // What `final_fit` makes of a verified hypothesis.
  struct FinalFit {
    Candidate chosen;             // the plane and nose, registered again at the final scale if it moved
    double face_mm = 0.0;         // the face's scale (mm per unit)
    std::optional<Fitted> fitted; // the landmarks and the frame fitted to them; none: too few corners
  };

  // The scale: the one the landmarks give (stated units aside, see `finish`), again until it stays. The
  // landmarks are searched in face millimetres whatever the units (the windows fit the face, be it larger
  // than life or a child's), from the frame the refined symmetry plane and nose give (it fixes the roll
  // and yaw better than landmarks searched on a coarse map), the way up verification found.
  FinalFit final_fit(const Hypothesis& best) const {
    FinalFit out{best.candidate, best.verified.mm_per_unit, std::nullopt};
    if (const std::optional<Shape> shape = shape_of(best.verified.found)) out.face_mm = shape->mm_per_unit;
    if (std::abs(out.face_mm / best.verified.mm_per_unit - 1.0) > kRegisterAgainShare)
      if (const std::optional<Candidate> again =
              around_the_nose(scene_, out.chosen.plane, out.chosen.nose, 1.0 / out.face_mm))
        out.chosen = *again;
    const Nose& nose = out.chosen.nose;
    const Vec3 up = best.verified.frame.rotation.row(1).dot(nose.up) >= 0.0 ? nose.up : Vec3(-nose.up);
    Similarity start = nose_frame(nose, up, out.face_mm);
    for (int pass = 0; pass < kScalePasses; ++pass) {
      out.fitted = fit_landmarks(scene_, start, out.face_mm, Units::Unknown);
      if (!out.fitted) break;
      const std::optional<Shape> shape = shape_of(out.fitted->found);
      // Until the scale settles: a fixed point, whatever the pose the search started from.
      if (!shape || std::abs(shape->mm_per_unit / out.face_mm - 1.0) < kSettledScaleShare) break;
      start = out.fitted->frame;
      out.face_mm = shape->mm_per_unit;
    }
    return out;
  }

  // One verified hypothesis refined into landmarks and a frame (`final_fit`), measured again around the
  // nose tip found, and judged on every cue.
  Result<Detection> finish(const Hypothesis& best) const {
    const FinalFit fit = final_fit(best);
    const Candidate& chosen = fit.chosen;
    const double face_mm = fit.face_mm;
    if (!fit.fitted)
      return make_error(
          ErrorCode::NoFace,
          fmt::format("no face found: the nose-like point at ({:.4g}, {:.4g}, {:.4g}) has too few "
                      "eye or mouth corners around it to fix a face frame",
                      chosen.nose.tip.x(), chosen.nose.tip.y(), chosen.nose.tip.z()),
          scan_.name);
    const Fitted& fitted = *fit.fitted;

    // The frame at the scan's scale: its units' when it states them or the face's scale is close to a
    // standard unit's, else the face's.
    const Units units = fixed_scale_ ? scan_.units : snap_units(face_mm);
    const double mm = units == Units::Unknown ? face_mm : millimetres_per(units);
    Result<FaceFrame> frame = frame_from_landmarks(fitted.found, mm, units);
    if (!frame) return make_error(ErrorCode::NoFace, "no face found: " + frame.error().message, scan_.name);

    Detection out;
    out.landmarks = fitted.found;
    out.landmarks.units = units;
    out.frame = *frame;
    out.symmetry = chosen.plane;
    // The symmetry and the nose measured again around the nose tip found, in face millimetres.
    const double rescale = face_mm / best.verified.mm_per_unit;
    out.symmetry_rms_mm = chosen.rms_mm * rescale;
    out.nose_prominence_mm = chosen.nose.prominence * rescale;
    Nose final_nose = chosen.nose;
    final_nose.tip = *fitted.found[Landmark::NoseTip];
    final_nose.forward = out.frame.axis_in_scan(2); // looking at the face from the front
    if (const std::optional<Candidate> around =
            around_the_nose(scene_, chosen.plane, final_nose, 1.0 / face_mm)) {
      out.symmetry = around->plane;
      out.symmetry_rms_mm = around->rms_mm;
      out.nose_prominence_mm = around->nose.prominence;
    }
    out.fit_rms_mm = fitted.shape_rms;
    out.eye_hollow_mm = detail::eye_hollowness(scene_.positions, scene_.triangles, scene_.spacing,
                                               out.frame.with_scale(face_mm), out.landmarks)
                            .value_or(0.0);
    const Cues c = cues(out);
    out.confidence = c.confidence();
    if (out.confidence < options_.min_confidence)
      return make_error(
          ErrorCode::NoFace,
          fmt::format("no face found: confidence {:.2f} < {:.2f} (symmetry {:.1f} mm, nose {:.1f} mm, "
                      "landmark fit {:.1f} mm, {} of {} landmarks, eye hollows {:.1f} mm)",
                      out.confidence, options_.min_confidence, out.symmetry_rms_mm, out.nose_prominence_mm,
                      out.fit_rms_mm, out.landmarks.count(), kLandmarkCount, out.eye_hollow_mm),
          scan_.name);
    return out;
  }

  const Mesh& scan_;
  const Scene& scene_;
  const DetectOptions& options_;
  bool fixed_scale_;                   // the file states its units
  std::optional<double> stated_;       // their mm per unit
  std::vector<double> scales_;         // the scales (mm per unit) step 3 tries
  double mid_;                         // the middle one: pointed places are judged at it
  std::vector<Plane> planes_;          // the scan's own symmetry planes
  double first_ = 1.0;                 // the scale steps 1 and 2 try
  std::vector<Local> locals_;          // step 2's planes
  double best_prominence_ = 0.0;       // the most prominent nose-like point seen (for the error)
  std::vector<Hypothesis> quick_;      // every seed tried quickly
  std::vector<Hypothesis> tried_;      // those verified thoroughly
  std::optional<Error> first_failure_; // why the first finished hypothesis was not a face
};

// Why a scan can hold no face before any search: too few points, a size no face scan has in any unit, or
// no surface at all.
std::optional<Error> unsearchable(const Mesh& scan) {
  if (scan.vertex_count() < 100)
    return make_error(ErrorCode::NoFace,
                      fmt::format("no face found: {} points are too few to hold one", scan.vertex_count()),
                      scan.name);
  if (const double size = bounding_box(scan).diagonal(); size > kMaxScanSize)
    return make_error(
        ErrorCode::NoFace,
        fmt::format("no face found: the scan spans {:.3g} units, which no face scan does in any "
                    "unit",
                    size),
        scan.name);
  return std::nullopt;
}

std::optional<Error> unsearchable(const Mesh& scan, const Scene& scene) {
  if (!(scene.size >= kMinScanSize) || scene.spacing <= 0.0)
    return make_error(ErrorCode::NoFace, "no face found: the points do not span a surface", scan.name);
  if (scan.units != Units::Unknown && scene.size * millimetres_per(scan.units) > kMaxScanMm)
    return make_error(
        ErrorCode::NoFace,
        fmt::format("no face found: the scan spans {:.3g} m, more than any face scan ({:.0f} m)",
                    scene.size * millimetres_per(scan.units) / 1000.0, kMaxScanMm / 1000.0),
        scan.name);
  return std::nullopt;
}

} // namespace

Landmarks complete_landmarks(const Mesh& scan, const Landmarks& given, const FaceFrame& frame) {
  if (given.count() == kLandmarkCount || scan.vertex_count() == 0) return given;
  const PointIndex index(scan.positions);
  const Landmarks found =
      detail::search_landmarks(scan.positions, scan.triangles, detail::median_spacing(scan.positions, index),
                               Similarity(frame), 1.0, detail::boundary_loops(scan.triangles), true);
  Landmarks out = given;
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    if (!out.points[i] && found.points[i]) out.points[i] = *found.points[i];
  return out;
}

Result<Detection> detect_landmarks(const Mesh& scan, const DetectOptions& options) {
  if (std::optional<Error> e = unsearchable(scan)) return *std::move(e);
  const Scene scene = prepare(scan, options);
  if (std::optional<Error> e = unsearchable(scan, scene)) return *std::move(e);
  return FaceSearch(scan, scene, options).run();
}

Result<Alignment> align_scan(const Mesh& scan, std::optional<Landmarks> given, std::string_view source,
                             std::string_view landmarks_source, const DetectOptions& detect) {
  if (!given) {
    Result<Detection> found = detect_landmarks(scan, detect);
    if (!found) {
      Error e = std::move(found).error();
      e.source = source;
      return e;
    }
    return Alignment{std::move(found->landmarks), found->frame, found->confidence};
  }
  // Units: the landmark file's, else the scan's, else the scale the landmarks themselves give.
  if (given->units == Units::Unknown) given->units = scan.units;
  Result<FaceFrame> fitted = [&]() -> Result<FaceFrame> {
    if (given->units != Units::Unknown) return frame_from_landmarks(*given, given->units);
    Result<ScaleEstimate> scale = estimate_scale(*given);
    if (!scale) return scale.error();
    given->units = scale->units;
    return frame_from_landmarks(*given, scale->mm_per_unit, scale->units);
  }();
  if (!fitted) {
    Error e = std::move(fitted).error();
    e.source = landmarks_source;
    return e;
  }
  return Alignment{complete_landmarks(scan, *given, *fitted), *fitted, std::nullopt};
}

} // namespace pdeface::align
