#include "pdeface/slice/profile.hpp"

#include "pdeface/core/point_index.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pdeface::slice {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Pits (what a hole shows of the inside) are looked for on the front sampled this often along a section.
constexpr double kPitStepMm = 0.5;

// Merges intervals into ascending disjoint ones.
std::vector<std::array<double, 2>> merged(std::vector<std::array<double, 2>> intervals) {
  std::sort(intervals.begin(), intervals.end());
  std::vector<std::array<double, 2>> out;
  for (const auto& i : intervals) {
    if (!out.empty() && i[0] <= out.back()[1])
      out.back()[1] = std::max(out.back()[1], i[1]);
    else
      out.push_back(i);
  }
  return out;
}

// Sorts points along `along` and keeps the front-most of points at the same height.
void order(std::vector<Vec3>& points, const ProfileAxes& axes) {
  std::sort(points.begin(), points.end(), [&](const Vec3& a, const Vec3& b) {
    const double ua = axes.along.dot(a), ub = axes.along.dot(b);
    return ua != ub ? ua < ub : axes.front.dot(a) > axes.front.dot(b);
  });
  points.erase(
      std::unique(points.begin(), points.end(),
                  [&](const Vec3& a, const Vec3& b) { return axes.along.dot(a) == axes.along.dot(b); }),
      points.end());
}

// The segments of a plane's cut seen in (u, w) = (along, front) coordinates, binned by height so that
// the front-most depth at any height is found by looking at a few segments.
class Envelope {
public:
  Envelope(std::span<const Polyline> cut, const ProfileAxes& axes) {
    for (const Polyline& line : cut) {
      const std::size_t n = line.points.size();
      const std::size_t count = line.closed ? n : n - 1;
      for (std::size_t k = 0; n > 1 && k < count; ++k) {
        const Vec3& a = line.points[k];
        const Vec3& b = line.points[(k + 1) % n];
        segments_.push_back({axes.along.dot(a), axes.front.dot(a), axes.along.dot(b), axes.front.dot(b)});
      }
    }
    if (segments_.empty()) return;
    lo_ = kInf;
    double hi = -kInf, length = 0.0;
    for (const auto& s : segments_) {
      lo_ = std::min({lo_, s[0], s[2]});
      hi = std::max({hi, s[0], s[2]});
      length += std::abs(s[2] - s[0]);
    }
    // Bins about four times the mean segment height: a handful of segments per bin.
    bin_ = std::max(4.0 * length / static_cast<double>(segments_.size()), (hi - lo_) * 1e-6 + 1e-9);
    bins_.resize(static_cast<std::size_t>((hi - lo_) / bin_) + 1);
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const auto& s = segments_[i];
      for (std::size_t b = bin(std::min(s[0], s[2])); b <= bin(std::max(s[0], s[2])); ++b)
        bins_[b].push_back(i);
    }
  }

  // The front-most depth of the cut at height u (-inf where there is none).
  [[nodiscard]] double front(double u) const {
    if (segments_.empty() || u < lo_) return -kInf;
    const std::size_t b = bin(u);
    if (b >= bins_.size()) return -kInf;
    double best = -kInf;
    for (std::size_t i : bins_[b]) {
      const auto& [u0, w0, u1, w1] = segments_[i];
      if (u < std::min(u0, u1) || u > std::max(u0, u1)) continue;
      best = std::max(best, u0 == u1 ? std::max(w0, w1) : w0 + (u - u0) / (u1 - u0) * (w1 - w0));
    }
    return best;
  }

  [[nodiscard]] std::vector<std::array<double, 2>> cover() const {
    std::vector<std::array<double, 2>> intervals;
    intervals.reserve(segments_.size());
    for (const auto& s : segments_)
      intervals.push_back({std::min(s[0], s[2]), std::max(s[0], s[2])});
    return merged(std::move(intervals));
  }

private:
  [[nodiscard]] std::size_t bin(double u) const { return static_cast<std::size_t>((u - lo_) / bin_); }

  std::vector<std::array<double, 4>> segments_; // u0, w0, u1, w1
  std::vector<std::vector<std::size_t>> bins_;
  double lo_ = 0.0, bin_ = 1.0;
};

// The section at height u: interpolated between its visible points (which are ascending), or the end
// point moved to height u where u lies beyond them (within the cover, at most half a cloud's spacing).
Vec3 interpolate(const std::vector<Vec3>& points, const ProfileAxes& axes, double u) {
  auto above = std::lower_bound(points.begin(), points.end(), u,
                                [&](const Vec3& p, double h) { return axes.along.dot(p) < h; });
  Vec3 p;
  if (above == points.begin() || above == points.end()) {
    p = above == points.end() ? points.back() : *above;
  } else {
    const Vec3& a = *(above - 1);
    const Vec3& b = *above;
    const double ua = axes.along.dot(a), ub = axes.along.dot(b);
    p = ua == ub ? b : Vec3(a + (u - ua) / (ub - ua) * (b - a));
  }
  return p + (u - axes.along.dot(p)) * axes.along; // exactly at height u
}

} // namespace

namespace {

// What a hole in the surface shows of what lies behind it: the heights of `cover` where the envelope's front
// lies more than `depth` behind its front somewhere within `reach` above and somewhere within `reach`
// below, sampled every `step` (`intervals`, ascending and disjoint, a step wider on each side than the
// samples found deep), and any point that deep (`hides`: the rim of the hole's far side between samples).
class Pits {
public:
  Pits(const Envelope& envelope, const std::vector<std::array<double, 2>>& cover, double depth, double reach,
       double step)
      : depth_(depth), step_(step) {
    if (cover.empty() || !(depth > 0.0) || !(reach > 0.0)) return;
    lo_ = cover.front()[0];
    const double hi = cover.back()[1];
    const auto n = static_cast<std::size_t>(std::min((hi - lo_) / step, 1e6)) + 1;
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i)
      w[i] = envelope.front(lo_ + static_cast<double>(i) * step);
    const auto window = static_cast<std::size_t>(reach / step);
    // The highest front within the window before and after each sample (a sliding maximum each way).
    const auto sliding_max = [&](bool forward) {
      std::vector<double> best(n, -kInf);
      std::vector<std::size_t> queue; // indices of decreasing w
      std::size_t head = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t i = forward ? k : n - 1 - k;
        while (head < queue.size() && (forward ? i - queue[head] : queue[head] - i) > window)
          ++head;
        if (head < queue.size()) best[i] = w[queue[head]];
        while (queue.size() > head && w[queue.back()] <= w[i])
          queue.pop_back();
        queue.push_back(i);
      }
      return best;
    };
    before_ = sliding_max(true);
    after_ = sliding_max(false);
    for (std::size_t i = 0; i < n; ++i) {
      if (!deep(i, w[i])) continue;
      const double u = lo_ + static_cast<double>(i) * step;
      if (!intervals_.empty() && u - intervals_.back()[1] <= 1.01 * step)
        intervals_.back()[1] = u;
      else
        intervals_.push_back({u, u});
    }
    for (auto& pit : intervals_) {
      pit[0] -= step;
      pit[1] += step;
    }
  }

  [[nodiscard]] const std::vector<std::array<double, 2>>& intervals() const { return intervals_; }

  //! Whether a point at height u, depth w lies in a pit or as deep as one beside it.
  [[nodiscard]] bool hides(double u, double w) const {
    if (std::ranges::any_of(intervals_, [&](const auto& pit) { return u > pit[0] && u < pit[1]; }))
      return true;
    if (before_.empty()) return false;
    const double t = (u - lo_) / step_;
    if (!(t >= 0.0) || t > static_cast<double>(before_.size() - 1)) return false;
    return deep(static_cast<std::size_t>(std::floor(t)), w) &&
           deep(static_cast<std::size_t>(std::ceil(t)), w);
  }

private:
  [[nodiscard]] bool deep(std::size_t i, double w) const {
    return w > -kInf && before_[i] > w + depth_ && after_[i] > w + depth_;
  }

  double depth_, step_, lo_ = 0.0;
  std::vector<double> before_, after_;
  std::vector<std::array<double, 2>> intervals_;
};

// `cover` without the intervals of `gaps` (both ascending and disjoint).
std::vector<std::array<double, 2>> minus(const std::vector<std::array<double, 2>>& cover,
                                         const std::vector<std::array<double, 2>>& gaps) {
  std::vector<std::array<double, 2>> out;
  for (auto piece : cover) {
    for (const auto& g : gaps) {
      if (g[1] <= piece[0] || g[0] >= piece[1]) continue;
      if (g[0] > piece[0]) out.push_back({piece[0], g[0]});
      piece[0] = g[1];
      if (piece[0] >= piece[1]) break;
    }
    if (piece[0] < piece[1]) out.push_back(piece);
  }
  return out;
}

} // namespace

Section mesh_section(std::span<const Polyline> cut, const ProfileAxes& axes, const SectionOptions& options) {
  const Envelope envelope(cut, axes);
  Section section;
  section.cover = envelope.cover();
  const Pits pits(envelope, section.cover, options.hidden_depth_mm,
                  std::max(options.hidden_reach_mm, options.max_gap_mm), kPitStepMm);
  for (const Polyline& line : cut)
    for (const Vec3& p : line.points) {
      const double u = axes.along.dot(p), w = axes.front.dot(p);
      // Visible: nothing in front at this height (a relative tolerance for the interpolated depths).
      if (w >= envelope.front(u) - 1e-9 * (1.0 + std::abs(w)) && !pits.hides(u, w))
        section.points.push_back(p);
    }
  order(section.points, axes);
  section.cover = minus(section.cover, pits.intervals());
  return section;
}

double point_spacing(std::span<const Vec3> points) {
  if (points.size() < 2) return 0.0;
  const PointIndex index(points);
  const std::size_t step = std::max<std::size_t>(1, points.size() / 2000);
  std::vector<double> nearest;
  std::vector<PointIndex::Neighbour> found;
  for (std::size_t i = 0; i < points.size(); i += step) {
    index.nearest(points[i], 2, found);
    if (found.size() == 2) nearest.push_back(found[1].distance);
  }
  auto mid = nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2);
  std::nth_element(nearest.begin(), mid, nearest.end());
  return *mid;
}

Section cloud_section(std::span<const Vec3> points, const Plane& plane, const ProfileAxes& axes,
                      double spacing, const SectionOptions& options) {
  Section section;
  if (spacing <= 0.0) return section;
  const double half = options.slab_factor * spacing;
  struct Near {
    double u, w, d; // height, depth, signed distance to the plane
  };
  std::vector<Near> slab;
  for (const Vec3& p : points) {
    const double d = plane.normal.dot(p) - plane.offset;
    if (std::abs(d) <= half) slab.push_back({axes.along.dot(p), axes.front.dot(p), d});
  }
  if (slab.empty()) return section;
  auto [lo_it, hi_it] =
      std::minmax_element(slab.begin(), slab.end(), [](auto& a, auto& b) { return a.u < b.u; });
  const double lo = lo_it->u;
  const std::size_t bins = static_cast<std::size_t>((hi_it->u - lo) / spacing) + 1;
  auto bin_of = [&](double u) { return std::min(bins - 1, static_cast<std::size_t>((u - lo) / spacing)); };

  // The front of each bin: points well behind it (an ear, the far side of the head) are another layer.
  std::vector<double> front(bins, -kInf);
  for (const Near& q : slab)
    front[bin_of(q.u)] = std::max(front[bin_of(q.u)], q.w);
  // Where a sparse cloud has no point of the front surface in the slab at some height, the bin's front is
  // a layer far behind (an ear, the far side of the head, the inside of the mouth): with the front surface
  // on both sides of it, close above and below, it is hidden from the viewer, and the bin is a gap.
  const double reach = options.hidden_reach_mm, depth = options.hidden_depth_mm;
  const auto front_near = [&](std::size_t b, int dir) {
    double best = -kInf;
    for (std::size_t n = b; (dir < 0 ? n > 0 : n + 1 < bins);) {
      n = dir < 0 ? n - 1 : n + 1;
      if (static_cast<double>(dir < 0 ? b - n : n - b) * spacing > reach) break;
      best = std::max(best, front[n]);
    }
    return best;
  };
  std::vector<bool> hidden(bins, false);
  for (std::size_t b = 0; b < bins; ++b)
    hidden[b] =
        front[b] > -kInf && front_near(b, -1) > front[b] + depth && front_near(b, +1) > front[b] + depth;
  std::vector<std::vector<const Near*>> members(bins);
  for (const Near& q : slab)
    if (!hidden[bin_of(q.u)] && q.w >= front[bin_of(q.u)] - 3.0 * spacing) members[bin_of(q.u)].push_back(&q);

  // One point per bin: z ≈ a + b·d + c·(u − u_bin) fitted to the bin and its neighbours, taken at d = 0.
  // Cover: half a spacing about each bin's point; points no further apart than the slab is wide are one
  // stretch of surface. Shorter gaps are the sampling (along a line through a cloud, neighbouring points
  // are often more than a spacing apart), not holes.
  std::vector<std::array<double, 2>> intervals;
  const Vec3 origin = plane.offset * plane.normal;
  for (std::size_t b = 0; b < bins; ++b) {
    if (members[b].empty()) continue;
    const double centre = lo + (static_cast<double>(b) + 0.5) * spacing;
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    double mean_u = 0.0, mean_w = 0.0;
    for (std::size_t n = b == 0 ? 0 : b - 1; n <= std::min(bins - 1, b + 1); ++n)
      for (const Near* q : members[n]) {
        const Eigen::Vector3d row(1.0, q->d, q->u - centre);
        normal += row * row.transpose();
        rhs += q->w * row;
      }
    for (const Near* q : members[b]) {
      mean_u += q->u;
      mean_w += q->w;
    }
    mean_u /= static_cast<double>(members[b].size());
    mean_w /= static_cast<double>(members[b].size());
    const Eigen::LDLT<Eigen::Matrix3d> fit(normal);
    double w = mean_w;
    if (fit.info() == Eigen::Success && std::abs(normal.determinant()) > 1e-9 * std::pow(normal.trace(), 3)) {
      const Eigen::Vector3d coef = fit.solve(rhs);
      const double fitted = coef[0] + coef[2] * (mean_u - centre);
      // A fit on a few nearly collinear points can swing far off: then the bin's mean is safer.
      if (std::abs(fitted - mean_w) <= 2.0 * spacing) w = fitted;
    }
    section.points.push_back(origin + mean_u * axes.along + w * axes.front);
    if (!intervals.empty() && mean_u - 0.5 * spacing - intervals.back()[1] <= 2.0 * half - spacing)
      intervals.back()[1] = mean_u + 0.5 * spacing;
    else
      intervals.push_back({mean_u - 0.5 * spacing, mean_u + 0.5 * spacing});
  }
  order(section.points, axes);
  section.cover = merged(std::move(intervals));
  return section;
}

std::vector<Section> sections(const Mesh& scan, std::span<const Plane> planes,
                              std::span<const ProfileAxes> axes, const SectionOptions& options) {
  if (axes.size() != planes.size()) throw std::invalid_argument("slice::sections: one axes per plane");
  std::vector<Section> out;
  out.reserve(planes.size());
  if (scan.is_point_cloud()) {
    const double spacing = options.spacing_mm > 0.0 ? options.spacing_mm : point_spacing(scan.positions);
    for (std::size_t j = 0; j < planes.size(); ++j)
      out.push_back(cloud_section(scan.positions, planes[j], axes[j], spacing, options));
    return out;
  }
  const std::vector<std::vector<Polyline>> cuts = intersect(scan, planes);
  for (std::size_t j = 0; j < planes.size(); ++j)
    out.push_back(mesh_section(cuts[j], axes[j], options));
  return out;
}

std::vector<Section> sections(const Mesh& scan, const Vec3& normal, std::span<const double> offsets,
                              const ProfileAxes& axes, const SectionOptions& options) {
  std::vector<Plane> planes;
  for (double d : offsets)
    planes.push_back({normal, d});
  return sections(scan, planes, std::vector<ProfileAxes>(planes.size(), axes), options);
}

std::array<double, 2> covered_extent(const Section& section, double seed, double max_gap_mm) {
  const auto& cover = section.cover;
  if (cover.empty()) return {seed, seed};
  // The interval holding the seed, else the first one above it, else the last.
  std::size_t k = 0;
  while (k + 1 < cover.size() && cover[k][1] < seed)
    ++k;
  std::size_t first = k, last = k;
  while (first > 0 && cover[first][0] - cover[first - 1][1] <= max_gap_mm)
    --first;
  while (last + 1 < cover.size() && cover[last + 1][0] - cover[last][1] <= max_gap_mm)
    ++last;
  return {cover[first][0], cover[last][1]};
}

std::string_view to_string(ReachEnd end) noexcept { return name_of<ReachEnd>(kReachEndNames, end); }

std::optional<Vec3> section_at(const Section& section, const ProfileAxes& axes, double u) {
  const auto& cover = section.cover;
  const auto it = std::lower_bound(cover.begin(), cover.end(), u,
                                   [](const std::array<double, 2>& c, double h) { return c[1] < h; });
  if (it == cover.end() || (*it)[0] > u || section.points.empty()) return std::nullopt;
  return interpolate(section.points, axes, u);
}

std::vector<std::array<double, 2>> holes_within(const Section& section, double lo, double hi) {
  std::vector<std::array<double, 2>> out;
  const auto& cover = section.cover;
  for (std::size_t k = 1; k < cover.size(); ++k)
    if (cover[k - 1][1] >= lo && cover[k][0] <= hi) out.push_back({cover[k - 1][1], cover[k][0]});
  return out;
}

Reach reach(const Section& section, const ProfileAxes& axes, double seed, const ReachOptions& options) {
  const auto& cover = section.cover;
  const double dir = options.limit >= seed ? 1.0 : -1.0;
  if (cover.empty() || section.points.empty()) return {seed, ReachEnd::SurfaceEnd};
  // The interval holding the seed, else the nearest one.
  std::size_t k = 0;
  double best = kInf;
  for (std::size_t i = 0; i < cover.size(); ++i) {
    const double d = seed < cover[i][0] ? cover[i][0] - seed : seed > cover[i][1] ? seed - cover[i][1] : 0.0;
    if (d < best) best = d, k = i;
  }
  const double start = std::clamp(seed, cover[k][0], cover[k][1]);
  if ((options.limit - start) * dir <= 0.0) return {options.limit, ReachEnd::Limit};
  Reach out{start, ReachEnd::Limit};
  for (;;) {
    const double edge = dir > 0 ? cover[k][1] : cover[k][0];
    if ((edge - options.limit) * dir >= 0.0) {
      out.end = options.limit;
      break;
    }
    const bool last = dir > 0 ? k + 1 == cover.size() : k == 0;
    const std::size_t next = dir > 0 ? k + 1 : k - 1;
    if (last || std::abs((dir > 0 ? cover[next][0] : cover[next][1]) - edge) > options.max_hole_mm) {
      out = {edge, ReachEnd::SurfaceEnd};
      break;
    }
    k = next;
  }
  // Where the surface lies behind the face, the walk ends at the last height in front of it.
  if (std::isfinite(options.min_front)) {
    double last = start;
    std::vector<const Vec3*> ahead;
    for (const Vec3& p : section.points) {
      const double u = axes.along.dot(p);
      if ((u - start) * dir >= 0.0 && (out.end - u) * dir >= 0.0) ahead.push_back(&p);
    }
    if (dir < 0) std::reverse(ahead.begin(), ahead.end());
    for (const Vec3* p : ahead) {
      if (axes.front.dot(*p) < options.min_front) {
        out = {last, ReachEnd::Behind};
        break;
      }
      last = axes.along.dot(*p);
    }
  }
  if (!options.turn_from) return out;
  // Where the surface falls back more steeply than the turn allows, over the window, it faces away.
  const double steep = std::tan(options.max_turn_deg * std::numbers::pi / 180.0);
  const double from = (*options.turn_from - start) * dir > 0.0 ? *options.turn_from : start;
  std::vector<double> heights;
  for (const Vec3& p : section.points) {
    const double u = axes.along.dot(p);
    if ((u - from) * dir >= 0.0 && (out.end - u) * dir >= 0.0) heights.push_back(u);
  }
  if (dir < 0) std::reverse(heights.begin(), heights.end());
  // Within the last window before the end, the end itself is looked at, as if a window away: a curve must
  // not end on a wall (the edge of a scan cut across the chin, seen from the front, falls straight back).
  const std::optional<Vec3> last = section_at(section, axes, out.end);
  for (double u : heights) {
    const std::optional<Vec3> here = section_at(section, axes, u);
    std::optional<Vec3> ahead = section_at(section, axes, u + dir * options.window_mm);
    if (!ahead && std::abs(out.end - u) < options.window_mm) ahead = last;
    if (!here || !ahead) continue;
    if (axes.front.dot(*here - *ahead) > steep * options.window_mm) return {u, ReachEnd::TurnsAway};
  }
  return out;
}

Result<Profile> clip(const Section& section, const ProfileAxes& axes, double lo, double hi,
                     const SectionOptions& options, std::string_view axis_name) {
  const auto& cover = section.cover;
  auto no_surface = [&](const std::string& why) {
    return make_error(ErrorCode::NoFace,
                      fmt::format("the scan has no surface between {0} = {1:.1f} and {0} = "
                                  "{2:.1f} mm ({3})",
                                  axis_name, lo, hi, why));
  };
  if (section.points.empty() || cover.empty()) return no_surface("the plane misses it");
  // The covered stretch holding lo (gaps up to max_gap count as covered) must reach hi.
  std::size_t k = 0;
  while (
      k < cover.size() && cover[k][1] < lo &&
      !(k + 1 < cover.size() && cover[k + 1][0] - cover[k][1] <= options.max_gap_mm && cover[k + 1][0] >= lo))
    ++k;
  if (k == cover.size() ||
      (cover[k][0] > lo && (k == 0 || cover[k][0] - cover[k - 1][1] > options.max_gap_mm)))
    return no_surface(fmt::format("the surface starts at {} = {:.1f} mm", axis_name,
                                  k == cover.size() ? cover.back()[1] : cover[k][0]));
  Profile profile;
  for (; cover[k][1] < hi; ++k) {
    if (k + 1 == cover.size())
      return no_surface(fmt::format("the surface ends at {} = {:.1f} mm", axis_name, cover[k][1]));
    const double gap = cover[k + 1][0] - cover[k][1];
    if (gap > options.max_gap_mm)
      return no_surface(fmt::format("hole {:.1f} mm long at {} = {:.1f} mm", gap, axis_name,
                                    0.5 * (cover[k + 1][0] + cover[k][1])));
    if (cover[k + 1][0] < lo) continue; // a bridged gap below the range
    ++profile.bridged;
    profile.longest_bridge = std::max(profile.longest_bridge, gap);
  }

  profile.points.push_back(interpolate(section.points, axes, lo));
  for (const Vec3& p : section.points) {
    const double u = axes.along.dot(p);
    if (u > lo && u < hi) profile.points.push_back(p);
  }
  profile.points.push_back(interpolate(section.points, axes, hi));
  return profile;
}

} // namespace pdeface::slice
