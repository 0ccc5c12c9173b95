#include "search.hpp"

#include "pdeface/align/frame.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>

namespace pdeface::align::detail {
namespace {

// The midline is followed across holes up to this long (face mm) when the face's top and bottom are
// looked for: capture holes on the forehead or the chin do not end the face.
constexpr double kMidlineHoleMm = 20.0;
// What a hole of the surface shows of the inside (an eye hole of a full head, a capture hole in a bust) is
// not the face: depth-map cells this far (face mm) behind the surface on both sides within the reach are
// holes. Deeper than an eye socket below the brow and the cheek.
constexpr double kPitDepthMm = 20.0;
constexpr double kPitReachMm = 25.0;
// An eye that is a hole of the mesh is a fissure: at most this high for its width (+2 mm). A capture hole
// that swallowed the eye is rounder, and its ends are not the eye's corners.
constexpr double kEyeHoleAspect = 0.6;
// A smoothed map is made only where a search reads it (`DepthMap::smoothed` within a box): the box is what
// the search visits widened by this many cells, more than a read reaches beyond it (a peak refined by half
// a cell, its neighbours a cell away, the cupness's neighbours another, and the next cell of a bilinear
// look-up).
constexpr double kReadMarginCells = 4.0;

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
// towards x_to along the hollow (each column's most hollow point within [y0, y1] and within a cell and a
// half of the previous column's, so that the walk follows the line, rising with a smile, and does not
// slide off into a fold that leaves it: the furrows running down from the corners of an older mouth), the
// columns at least `fraction` as deep as the deepest one; the end is the last of them reached without a
// gap. On `raw` smoothed by `sigma`, only where the walk reads it.
std::optional<Eigen::Vector2d> hollow_end(const DepthMap& raw, double sigma, double x_from, double x_to,
                                          double y0, double y1, double r, double fraction = 0.35) {
  const double reach = r + kReadMarginCells * raw.cell();
  const DepthMap map = raw.smoothed(sigma, std::min(x_from, x_to) - reach, std::max(x_from, x_to) + reach,
                                    y0 - reach, y1 + reach);
  const double step = x_to > x_from ? map.cell() : -map.cell();
  std::vector<std::pair<double, Eigen::Vector2d>> columns; // (most hollow relief, where)
  std::optional<double> last_y;
  for (double x = x_from; (x_to - x) * step >= 0.0; x += step) {
    std::pair<double, Eigen::Vector2d> best{std::numeric_limits<double>::infinity(), {x, 0.0}};
    const double lo = last_y ? std::max(y0, *last_y - 1.5 * map.cell()) : y0;
    const double hi = last_y ? std::min(y1, *last_y + 1.5 * map.cell()) : y1;
    for (double y = lo; y <= hi + 1e-9; y += map.cell())
      if (const auto rel = map.relief(x, y, r); rel && *rel < best.first)
        best = {*rel, Eigen::Vector2d(x, y)};
    if (std::isfinite(best.first)) last_y = best.second.y();
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

// The most cup-shaped point of a window, as (x, y) in the frame, on `raw` smoothed by `sigma` (only
// where the search reads it).
std::optional<Eigen::Vector2d> most_cupped(const DepthMap& raw, double sigma, double x0, double x1, double y0,
                                           double y1) {
  const double margin = kReadMarginCells * raw.cell();
  const DepthMap map =
      raw.smoothed(sigma, std::min(x0, x1) - margin, std::max(x0, x1) + margin, y0 - margin, y1 + margin);
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

// A hole of the mesh seen in the frame: its extent and its extreme vertices across the face.
struct Hole {
  Eigen::Vector2d centre, size;
  std::uint32_t leftmost = 0, rightmost = 0; // least and greatest x
};

std::vector<Hole> holes_in_view(const Loops& loops, std::span<const Vec3> local, double z_min) {
  std::vector<Hole> out;
  for (const auto& loop : loops) {
    if (loop.size() < 6) continue;
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Hole h;
    bool in_front = true;
    for (std::uint32_t v : loop) {
      const Vec3& q = local[v];
      if (q.z() < z_min) in_front = false;
      if (q.x() < lo.x()) h.leftmost = v;
      if (q.x() > hi.x()) h.rightmost = v;
      lo = lo.cwiseMin(q.head<2>());
      hi = hi.cwiseMax(q.head<2>());
    }
    if (!in_front) continue;
    h.centre = 0.5 * (lo + hi);
    h.size = hi - lo;
    out.push_back(h);
  }
  return out;
}

// The mouth line on a midline profile (y, z), downwards from the nose, whose lips do not stand out of it
// as bumps of z: a frame pitched back (the face looking up) or a receding lower face slopes away from the
// nose to the chin. The bending c(y) = z(y) - (z(y - 4) + z(y + 4)) / 2 ignores any slope: past the
// groove under the nose, its first two bumps are the lips and the most bent-in point between them the
// mouth. Nothing when the profile does not show them.
std::optional<double> lips_by_bending(const std::vector<std::pair<double, double>>& midline) {
  constexpr std::size_t h = 4;  // profile samples are 1 mm apart
  constexpr double kBump = 0.2; // mm: a bump or a groove, not noise
  if (midline.size() < 2 * h + 3) return std::nullopt;
  std::vector<double> c(midline.size(), 0.0);
  for (std::size_t i = h; i + h < midline.size(); ++i)
    c[i] = midline[i].second - 0.5 * (midline[i - h].second + midline[i + h].second);
  std::size_t i = h;
  while (i + h < midline.size() && c[i] > -kBump) // down the nose to the groove under it
    ++i;
  std::vector<std::size_t> bumps;
  for (; i + h + 1 < midline.size() && bumps.size() < 2; ++i)
    if (c[i] > kBump && c[i] >= c[i - 1] && c[i] >= c[i + 1]) bumps.push_back(i);
  if (bumps.size() < 2) return std::nullopt;
  const auto first = c.begin() + static_cast<std::ptrdiff_t>(bumps[0]);
  const auto deepest = std::min_element(first, c.begin() + static_cast<std::ptrdiff_t>(bumps[1]));
  if (*deepest > -kBump) return std::nullopt;
  return midline[static_cast<std::size_t>(deepest - c.begin())].first;
}

// The stable landmarks (nose tip, eye and mouth corners) checked against each other: the average face
// fitted to them (a similarity, `Eigen::umeyama`, in face millimetres); while one lies more than
// `kOutlierMm` from where the fit puts it (a corner taken from the end of a capture hole that swallowed the
// eye) and five or more remain, the worst is dropped and the fit made again. The dropped ones and those not
// found are then put where the fit of the rest puts them, on the surface. The nose tip anchors the fit and
// stays. `local(l)`: a landmark in face mm, or nullopt; `surface(x, y)`: the depth there, if any.
constexpr double kOutlierMm = 14.0;
constexpr std::array<Landmark, 7> kStableLandmarks{
    Landmark::NoseTip,       Landmark::EyeInnerLeft, Landmark::EyeInnerRight, Landmark::EyeOuterLeft,
    Landmark::EyeOuterRight, Landmark::MouthLeft,    Landmark::MouthRight};

std::array<std::optional<Vec3>, 7>
repaired(std::array<std::optional<Vec3>, 7> local,
         const std::function<std::optional<double>(double, double)>& surface) {
  const Landmarks& average = canonical_template();
  std::array<bool, 7> use{};
  for (std::size_t i = 0; i < local.size(); ++i)
    use[i] = local[i].has_value();
  if (!use[0]) return local;
  Eigen::Matrix4d fit = Eigen::Matrix4d::Identity();
  for (;;) {
    const auto n = static_cast<Eigen::Index>(std::ranges::count(use, true));
    if (n < 4) return local; // too few to say which are off
    Eigen::Matrix3Xd from(3, n), to(3, n);
    Eigen::Index k = 0;
    for (std::size_t i = 0; i < local.size(); ++i)
      if (use[i]) {
        from.col(k) = *average[kStableLandmarks[i]];
        to.col(k++) = *local[i];
      }
    fit = Eigen::umeyama(from, to, true);
    std::size_t worst = 0;
    double most = 0.0;
    for (std::size_t i = 1; i < local.size(); ++i)
      if (use[i]) {
        const double off = ((fit * average[kStableLandmarks[i]]->homogeneous()).head<3>() - *local[i]).norm();
        if (off > most) most = off, worst = i;
      }
    if (most <= kOutlierMm || n <= 5) break;
    use[worst] = false;
  }
  for (std::size_t i = 1; i < local.size(); ++i)
    if (!use[i]) {
      const Vec3 p = (fit * average[kStableLandmarks[i]]->homogeneous()).head<3>();
      local[i] = Vec3(p.x(), p.y(), surface(p.x(), p.y()).value_or(p.z()));
    }
  return local;
}

} // namespace

Loops boundary_loops(std::span<const Triangle> triangles) {
  // Undirected edges used once, found without hashing: each edge is filed under its smaller vertex
  // (counting sort), and a vertex's few edges are sorted and counted in place.
  std::uint32_t top = 0;
  for (const Triangle& t : triangles)
    top = std::max({top, t[0], t[1], t[2]});
  const std::size_t n = triangles.empty() ? 0 : std::size_t{top} + 1;
  const auto csr = [n](const auto& for_each_pair) {
    std::vector<std::uint32_t> start(n + 1, 0);
    for_each_pair([&](std::uint32_t a, std::uint32_t) { ++start[a + 1]; });
    for (std::size_t v = 0; v < n; ++v)
      start[v + 1] += start[v];
    std::vector<std::uint32_t> to(start[n]);
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for_each_pair([&](std::uint32_t a, std::uint32_t b) { to[fill[a]++] = b; });
    return std::pair{std::move(start), std::move(to)};
  };
  auto [first, second] = csr([&](const auto& visit) {
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k)
        visit(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> once;
  for (std::size_t v = 0; v < n; ++v) {
    const auto begin = second.begin() + first[v], end = second.begin() + first[v + 1];
    std::sort(begin, end);
    for (auto it = begin; it != end;) {
      auto same = it;
      while (same != end && *same == *it)
        ++same;
      if (same - it == 1) once.emplace_back(static_cast<std::uint32_t>(v), *it);
      it = same;
    }
  }
  // Their connected pieces.
  const auto [start, next] = csr([&](const auto& visit) {
    for (const auto& [a, b] : once) {
      visit(a, b);
      visit(b, a);
    }
  });
  Loops loops;
  std::vector<char> seen(n, 0);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t v0 = 0; v0 < n; ++v0) {
    if (seen[v0] || start[v0] == start[v0 + 1]) continue;
    std::vector<std::uint32_t> loop;
    stack.assign(1, v0);
    seen[v0] = 1;
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      loop.push_back(v);
      for (std::uint32_t i = start[v]; i < start[v + 1]; ++i)
        if (const std::uint32_t w = next[i]; !seen[w]) {
          seen[w] = 1;
          stack.push_back(w);
        }
    }
    std::ranges::sort(loop);
    loops.push_back(std::move(loop));
  }
  std::ranges::sort(loops, {}, [](const auto& l) { return l.front(); }); // already in this order
  return loops;
}

// Landmarks (in the scan's frame and units) found in a depth map of the scan seen in `frame`, whose origin is
// near the nose tip and whose axes are near the canonical ones: the nose tip as the front-most point
// near the origin, eye and mouth corners as the hollows of the windows where faces have them, the face's
// bottom where the midline turns under the chin, its top by the rule of thirds (within the scan).
Landmarks search_landmarks(std::span<const Vec3> points, std::span<const Triangle> triangles, double spacing,
                           const Similarity& frame, double cell, const Loops& loops, bool repair,
                           Landmarks* as_found) {
  std::vector<Vec3> local(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    local[i] = frame.apply(points[i]);
  spacing *= frame.scale;
  DepthMap map(-100.0, 100.0, -140.0, 120.0, cell);
  map.rasterise(local, triangles, std::max(1.5 * cell, 1.5 * spacing));
  map.drop_pits(kPitDepthMm, kPitReachMm);
  map.fill_holes(std::max(1, static_cast<int>(std::lround(4.0 / cell))));

  std::optional<Eigen::Vector3d> tip; // (x, y, z) in the frame
  for (double y = -15.0; y <= 15.0; y += 1.0)
    for (double x = -10.0; x <= 10.0; x += 1.0)
      if (const auto z = map.at(x, y); z && (!tip || *z > tip->z())) tip = Eigen::Vector3d(x, y, *z);
  if (tip) {
    const Eigen::Vector2d xy =
        refined_peak([&](double x, double y) { return map.at(x, y); }, tip->head<2>(), cell);
    tip = Eigen::Vector3d(xy.x(), xy.y(), map.at(xy.x(), xy.y()).value_or(tip->z()));
  }

  Landmarks found;
  auto place = [&](Landmark l, double x, double y) {
    if (const auto z = map.at(x, y)) found[l] = frame.apply_inverse(Vec3(x, y, *z));
  };
  if (!tip) return found;
  place(Landmark::NoseTip, tip->x(), tip->y());
  const double x0 = tip->x(), y0 = tip->y();
  constexpr double kCupSigma = 2.5; // the eye corners' cups
  constexpr double kSoftSigma =
      1.0; // the mouth's hollow: point clouds splat unevenly, their raw map is rough
  const double margin = kReadMarginCells * cell;
  std::vector<double> eye_y, mouth_y;
  // The mouth line where it crosses the midline. Down the midline from the nose the profile rises onto
  // the upper lip, dips into the mouth, rises onto the lower lip, dips under it and rises onto the chin:
  // the mouth is the lowest point between the first two bumps (the lips). Failing that, the deepest
  // groove (relief) between the nose and the chin.
  const DepthMap profile_map =
      map.smoothed(1.5, x0 - margin, x0 + margin, y0 - 60.0 - margin, y0 - 6.0 + margin);
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
  if (const std::optional<double> slit = lips_by_bending(midline)) {
    y_slit = *slit;
  } else if (bumps.size() == 2) {
    const auto lowest = std::min_element(midline.begin() + static_cast<std::ptrdiff_t>(bumps[0]),
                                         midline.begin() + static_cast<std::ptrdiff_t>(bumps[1]),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
    y_slit = lowest->first;
  } else {
    double deepest = 0.0;
    const double reach = 4.0 + margin;
    const DepthMap soft =
        map.smoothed(kSoftSigma, x0 - reach, x0 + reach, y0 - 45.0 - reach, y0 - 18.0 + reach);
    for (double y = y0 - 18.0; y >= y0 - 45.0; y -= 1.0)
      if (const auto rel = soft.relief(x0, y, 4.0); rel && *rel < deepest) {
        deepest = *rel;
        y_slit = y;
      }
  }
  // Eyes and mouths that are holes of the mesh (a morphable model's eyes have no eyeballs; an open mouth
  // or lips apart): their corners are the ends of the hole, the vertices furthest across the face.
  const std::vector<Hole> holes = holes_in_view(loops, local, tip->z() - 80.0);
  const auto eye_hole = [&](double side) -> const Hole* {
    const Hole* best = nullptr;
    for (const Hole& h : holes) {
      const double out = side * (h.centre.x() - x0), up = h.centre.y() - y0;
      if (out < 10.0 || out > 60.0 || up < 15.0 || up > 60.0) continue;
      if (h.size.x() < 12.0 || h.size.x() > 55.0 || h.size.y() > kEyeHoleAspect * h.size.x() + 2.0) continue;
      if (!best || h.size.x() > best->size.x()) best = &h;
    }
    return best;
  };
  const Hole* mouth_hole = nullptr;
  for (const Hole& h : holes) {
    const double down = y0 - h.centre.y();
    if (std::abs(h.centre.x() - x0) > 15.0 || down < 15.0 || down > 60.0) continue;
    if (h.size.x() < 15.0 || h.size.x() > 80.0 || h.size.y() > h.size.x()) continue;
    if (!mouth_hole || h.size.x() > mouth_hole->size.x()) mouth_hole = &h;
  }
  const auto place_vertex = [&](Landmark l, std::uint32_t v) { found[l] = points[v]; };
  if (mouth_hole) y_slit = mouth_hole->centre.y();
  for (double side : {1.0, -1.0}) {
    const bool left = side > 0;
    // Eye corners are the ends of an eye hole, else cups (concave in every direction) on a lightly
    // smoothed map: the inner one between the nose bridge and the eyeball, the outer one 18-40 mm further
    // out at about the same height.
    if (const Hole* eye = eye_hole(side)) {
      // The face's left is +x: its inner corner is the hole's least x, its outer the greatest.
      place_vertex(left ? Landmark::EyeInnerLeft : Landmark::EyeInnerRight,
                   left ? eye->leftmost : eye->rightmost);
      place_vertex(left ? Landmark::EyeOuterLeft : Landmark::EyeOuterRight,
                   left ? eye->rightmost : eye->leftmost);
      eye_y.push_back(eye->centre.y());
    } else if (const auto inner =
                   most_cupped(map, kCupSigma, x0 + side * 6.0, x0 + side * 30.0, y0 + 15.0, y0 + 55.0)) {
      place(left ? Landmark::EyeInnerLeft : Landmark::EyeInnerRight, inner->x(), inner->y());
      eye_y.push_back(inner->y());
      if (const auto outer = most_cupped(map, kCupSigma, inner->x() + side * 18.0, inner->x() + side * 40.0,
                                         inner->y() - 10.0, inner->y() + 8.0))
        place(left ? Landmark::EyeOuterLeft : Landmark::EyeOuterRight, outer->x(), outer->y());
    }
    if (mouth_hole) {
      place_vertex(left ? Landmark::MouthLeft : Landmark::MouthRight,
                   left ? mouth_hole->rightmost : mouth_hole->leftmost);
      mouth_y.push_back(local[left ? mouth_hole->rightmost : mouth_hole->leftmost].y());
    } else if (const auto mouth =
                   hollow_end(map, kSoftSigma, x0, x0 + side * 40.0, y_slit - 8.0, y_slit + 6.0, 5.0)) {
      place(left ? Landmark::MouthLeft : Landmark::MouthRight, mouth->x(), mouth->y());
      mouth_y.push_back(mouth->y());
    }
  }
  // A corner the surface shows on one side only (a shadowed or cut outer corner): mirror the other.
  for (Landmark l : {Landmark::EyeOuterLeft, Landmark::EyeOuterRight, Landmark::EyeInnerLeft,
                     Landmark::EyeInnerRight, Landmark::MouthLeft, Landmark::MouthRight}) {
    const std::optional<Vec3>& other = found[mirrored(l)];
    if (found.has(l) || !other) continue;
    const Vec3 seen = frame.apply(*other);
    place(l, 2.0 * x0 - seen.x(), seen.y());
  }
  auto mean = [](const std::vector<double>& v, double fallback) {
    return v.empty() ? fallback : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  };
  const double y_eyes = mean(eye_y, y0 + 38.0);
  const double y_mouth = mean(mouth_y, y0 - 35.0);

  // Where the midline has surface, holes up to kMidlineHoleMm crossed (a capture hole, a nostril's
  // shadow): from `y` one step at a time towards `step`'s sign while `keep(z)` holds; the last height with
  // surface, and whether the scan ended there (rather than `keep` failing).
  const auto follow = [&](double y, double step, const auto& keep) {
    double last = y;
    for (double gap = 0.0; std::abs(y + step) < 140.0 && gap <= kMidlineHoleMm;) {
      y += step;
      const std::optional<double> z = map.at(x0, y);
      if (!z) {
        gap += std::abs(step);
        continue;
      }
      if (!keep(*z)) return std::pair{last, false};
      last = y;
      gap = 0.0;
    }
    return std::pair{last, true};
  };
  // The chin's most forward point on the midline below the mouth, then down while the profile stays
  // within 15 mm of it (below that, it turns under the chin towards the neck). Where the scan ends first
  // (a chin cut short) or shows no chin, the chin is where the average face has it below the mouth.
  const Landmarks& average = canonical_template();
  const double chin_by_proportion =
      y_mouth + average[Landmark::FaceBottom]->y() -
      0.5 * (average[Landmark::MouthLeft]->y() + average[Landmark::MouthRight]->y());
  std::optional<Eigen::Vector2d> chin; // (y, z)
  for (double y = y_mouth - 12.0; y >= y_mouth - 55.0; y -= 1.0)
    if (const auto z = map.at(x0, y); z && (!chin || *z > chin->y())) chin = Eigen::Vector2d(y, *z);
  double y_bottom = chin_by_proportion;
  if (chin) {
    const auto [end, cut] = follow(chin->x(), -1.0, [&](double z) { return z >= chin->y() - 15.0; });
    y_bottom = cut ? std::min(end, chin_by_proportion) : end;
  }
  const double z_bottom = map.at(x0, y_bottom).value_or(chin ? chin->y() : tip->z() - 28.0);
  found[Landmark::FaceBottom] = frame.apply_inverse(Vec3(x0, y_bottom, z_bottom));
  // Rule of thirds: hairline to nasion ~ half of nasion to chin; the nasion is a few mm above the eyes.
  // Up the midline to there, or to where the scan ends first (holes crossed).
  const double y_nasion = y_eyes + 4.0;
  const double y_top = y_nasion + 0.5 * (y_nasion - y_bottom);
  const double y_scan = std::min(y_top, follow(y_nasion, 1.0, [](double) { return true; }).first);
  const double z_top = map.at(x0, y_scan).value_or(tip->z() - 30.0);
  found[Landmark::FaceTop] = frame.apply_inverse(Vec3(x0, std::max(y_scan, y_nasion), z_top));

  if (as_found) *as_found = found;
  if (!repair) return found;
  std::array<std::optional<Vec3>, 7> stable;
  for (std::size_t i = 0; i < stable.size(); ++i)
    if (found.has(kStableLandmarks[i])) stable[i] = frame.apply(*found[kStableLandmarks[i]]);
  const std::array<std::optional<Vec3>, 7> fixed =
      repaired(stable, [&](double x, double y) { return map.at(x, y); });
  for (std::size_t i = 0; i < stable.size(); ++i)
    if (fixed[i] && fixed[i] != stable[i]) found[kStableLandmarks[i]] = frame.apply_inverse(*fixed[i]);
  return found;
}

std::optional<double> eye_hollowness(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                     double spacing, const Similarity& frame, const Landmarks& landmarks) {
  if (!landmarks.has(Landmark::EyeInnerLeft) || !landmarks.has(Landmark::EyeInnerRight)) return std::nullopt;
  std::vector<Vec3> local(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    local[i] = frame.apply(points[i]);
  spacing *= frame.scale;
  DepthMap map(-100.0, 100.0, -140.0, 120.0, 1.0);
  map.rasterise(local, triangles, std::max(1.5, 1.5 * spacing));
  map.drop_pits(kPitDepthMm, kPitReachMm);
  map.fill_holes(4);
  // Smoothed at least as much as the points are apart: a coarse cloud's splats make hollows of their own.
  const double sigma = std::max(1.5, spacing);
  constexpr double kRadius = 12.0;
  const double reach = kRadius + kReadMarginCells * map.cell();
  std::optional<double> least;
  for (Landmark l : {Landmark::EyeInnerLeft, Landmark::EyeInnerRight}) {
    const Vec3 q = frame.apply(*landmarks[l]);
    const DepthMap soft = map.smoothed(sigma, q.x() - reach, q.x() + reach, q.y() - reach, q.y() + reach);
    const std::optional<double> rel = soft.relief(q.x(), q.y(), kRadius);
    if (!rel) return std::nullopt;
    least = std::min(least.value_or(-*rel), -*rel);
  }
  return least;
}

} // namespace pdeface::align::detail
