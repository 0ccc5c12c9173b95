#include "pdeface/slice/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace pdeface::slice {
namespace {

// A point of the intersection is either a mesh vertex lying on the plane or the crossing of a mesh edge;
// both are keyed by vertex ids, so that the triangles sharing a vertex or an edge produce one point.
using Key = std::uint64_t;
Key vertex_key(std::uint32_t v) { return (Key{v} << 32U) | v; }
Key edge_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (Key{a} << 32U) | b : (Key{b} << 32U) | a; // a != b, so never a vertex key
}

struct Node {
  Key key;
  Vec3 point;
};
struct Segment {
  Node a, b;
};

// The sign of a signed distance, with an exact zero.
int sign(double s) { return (s > 0.0) - (s < 0.0); }

class Cutter {
public:
  // `heights[v * stride + family]`: the signed heights of vertex v along the family's normal.
  Cutter(const Mesh& mesh, const std::vector<double>& heights, std::size_t stride, std::size_t family,
         const Vec3& normal)
      : p_(mesh.positions), h_(heights), stride_(stride), family_(family), n_(normal) {}

  // The segment (if any) the triangle `t` cuts from the plane n · p = d.
  void cut(const Triangle& t, double d, std::vector<Segment>& out) const {
    std::array<double, 3> s{};
    std::array<int, 3> sg{};
    int zeros = 0, positive = 0, negative = 0;
    for (int k = 0; k < 3; ++k) {
      s[k] = h_[t[k] * stride_ + family_] - d;
      sg[k] = sign(s[k]);
      zeros += sg[k] == 0;
      positive += sg[k] > 0;
      negative += sg[k] < 0;
    }
    if (zeros == 3) return; // lying in the plane: its edges come from the neighbours
    std::array<Node, 2> ends{};
    int found = 0;
    for (int k = 0; k < 3; ++k)
      if (sg[k] == 0) ends[found++] = vertex(t[k]);
    if (zeros == 2) {
      out.push_back({ends[0], ends[1]}); // an edge in the plane (deduplicated later)
      return;
    }
    if (positive == 0 || negative == 0) return; // touching at one vertex, or not at all
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      if (sg[k] * sg[l] < 0) ends[found++] = crossing(t[k], t[l], s[k], s[l], d);
    }
    out.push_back({ends[0], ends[1]});
  }

private:
  Node vertex(std::uint32_t v) const { return {vertex_key(v), p_[v]}; }

  // The crossing computed from the lower vertex id, so both triangles sharing the edge get the same bits.
  Node crossing(std::uint32_t a, std::uint32_t b, double sa, double sb, double d) const {
    if (b < a) {
      std::swap(a, b);
      std::swap(sa, sb);
    }
    Vec3 p = p_[a] + (sa / (sa - sb)) * (p_[b] - p_[a]);
    p += (d - n_.dot(p)) * n_; // onto the plane: exact for an axis-aligned plane
    return {edge_key(a, b), p};
  }

  const std::vector<Vec3>& p_;
  const std::vector<double>& h_;
  std::size_t stride_, family_;
  Vec3 n_;
};

// Chains segments into polylines through shared keys: open chains from their free ends first, then the
// closed loops that remain. Segment ends are paired by key (two per key on a
// manifold mesh; more are paired in order, as at a vertex where the surface touches itself).
std::vector<Polyline> chain(std::vector<Segment> segments) {
  // An edge lying in the plane comes from both its triangles: keep it once.
  const auto in_plane = std::partition(segments.begin(), segments.end(), [](const Segment& s) {
    return !(s.a.key == (s.a.key >> 32U | s.a.key << 32U) && s.b.key == (s.b.key >> 32U | s.b.key << 32U));
  });
  if (in_plane != segments.end()) {
    for (auto i = in_plane; i != segments.end(); ++i)
      if (i->b.key < i->a.key) std::swap(i->a, i->b);
    auto by_keys = [](const Segment& l, const Segment& r) {
      return l.a.key != r.a.key ? l.a.key < r.a.key : l.b.key < r.b.key;
    };
    std::sort(in_plane, segments.end(), by_keys);
    segments.erase(std::unique(in_plane, segments.end(),
                               [](const Segment& l, const Segment& r) {
                                 return l.a.key == r.a.key && l.b.key == r.b.key;
                               }),
                   segments.end());
  }

  // Pairs the ends sharing a key through an open-addressing table (ends in index order, so a key met
  // more than twice pairs its first and second ends, then its third and fourth, ...).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  const auto count = static_cast<std::uint32_t>(segments.size());
  std::vector<std::uint32_t> partner(2 * segments.size(), kNone);
  std::size_t size = 16;
  while (size < 4 * segments.size())
    size *= 2;
  struct Slot {
    Key key;
    std::uint32_t pending; // the end waiting for a partner, or kNone
    bool used;
  };
  std::vector<Slot> table(size, Slot{0, kNone, false});
  for (std::uint32_t end = 0; end < 2 * count; ++end) {
    const Key key = end % 2 == 0 ? segments[end / 2].a.key : segments[end / 2].b.key;
    std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 32U) & (size - 1);
    while (table[i].used && table[i].key != key)
      i = (i + 1) & (size - 1);
    Slot& slot = table[i];
    if (!slot.used) {
      slot = {key, end, true};
    } else if (slot.pending == kNone) {
      slot.pending = end;
    } else {
      partner[end] = slot.pending;
      partner[slot.pending] = end;
      slot.pending = kNone;
    }
  }

  auto point = [&](std::uint32_t end) -> const Vec3& {
    const Segment& s = segments[end / 2];
    return end % 2 == 0 ? s.a.point : s.b.point;
  };
  std::vector<bool> used(segments.size(), false);
  std::vector<Polyline> out;
  // Walks from the end `start` through its segment and on through partners; true if it came back round.
  auto walk = [&](std::uint32_t start) {
    Polyline line;
    line.points.push_back(point(start));
    for (std::uint32_t at = start;;) {
      used[at / 2] = true;
      const std::uint32_t exit = at ^ 1U;
      const std::uint32_t next = partner[exit];
      if (next == kNone) {
        line.points.push_back(point(exit));
        break;
      }
      if (next == start) {
        line.closed = true;
        break;
      }
      if (used[next / 2]) {
        line.points.push_back(point(exit));
        break;
      }
      line.points.push_back(point(exit));
      at = next;
    }
    out.push_back(std::move(line));
  };
  for (std::uint32_t e = 0; e < 2 * count; ++e)
    if (partner[e] == kNone && !used[e / 2]) walk(e);
  for (std::uint32_t i = 0; i < count; ++i)
    if (!used[i]) walk(2 * i);
  return out;
}

} // namespace

std::vector<std::vector<Polyline>> intersect(const Mesh& mesh, std::span<const Plane> planes) {
  for (const Plane& plane : planes) {
    if (std::abs(plane.normal.norm() - 1.0) > 1e-9)
      throw std::invalid_argument("slice::intersect: normal not unit");
    if (!std::isfinite(plane.offset)) throw std::invalid_argument("slice::intersect: offset not finite");
  }
  // Planes sharing a normal form a family: one height per vertex, and the offsets in order, so that a
  // triangle finds the planes of the family it spans by a binary search.
  struct Family {
    Vec3 normal;
    std::vector<double> offsets;     // ascending
    std::vector<std::size_t> planes; // index into `planes`, in the order of `offsets`
    // The first plane at or above the start of each of a few uniform bins over the offsets: a triangle
    // finds the planes it spans without a branchy binary search (most span none).
    std::vector<std::size_t> first;
    double start = 0.0, inverse_bin = 0.0;

    void index() {
      start = offsets.front();
      const double span = offsets.back() - start;
      const std::size_t bins = 4 * offsets.size() + 1;
      inverse_bin = span > 0.0 ? static_cast<double>(bins - 1) / span : 0.0;
      first.resize(bins + 1);
      for (std::size_t b = 0, j = 0; b <= bins; ++b) {
        const double at = start + static_cast<double>(b) / (inverse_bin > 0.0 ? inverse_bin : 1.0);
        while (j < offsets.size() && offsets[j] < at)
          ++j;
        first[b] = j;
      }
    }
    // The first plane with offset >= lo.
    [[nodiscard]] std::size_t first_at_or_above(double lo) const {
      if (!(lo > start)) return 0;
      const double bin = (lo - start) * inverse_bin;
      std::size_t j = bin >= static_cast<double>(first.size() - 1) ? offsets.size()
                                                                   : first[static_cast<std::size_t>(bin)];
      while (j < offsets.size() && offsets[j] < lo)
        ++j;
      return j;
    }
  };
  std::vector<Family> families;
  for (std::size_t j = 0; j < planes.size(); ++j) {
    auto f = std::find_if(families.begin(), families.end(),
                          [&](const Family& g) { return g.normal == planes[j].normal; });
    if (f == families.end()) f = families.insert(families.end(), Family{planes[j].normal, {}, {}, {}});
    f->planes.push_back(j);
  }
  for (Family& f : families) {
    std::sort(f.planes.begin(), f.planes.end(),
              [&](std::size_t a, std::size_t b) { return planes[a].offset < planes[b].offset; });
    for (std::size_t j : f.planes)
      f.offsets.push_back(planes[j].offset);
    f.index();
  }
  // Per vertex and family: its height along the normal, and a code placing it among the family's
  // offsets (2j: between offsets j − 1 and j; 2j + 1: exactly on offset j). A triangle spans plane j iff
  // its vertices' codes bracket 2j + 1, so most triangles are dismissed by comparing three codes, and
  // the codes of all families sit together per vertex.
  const std::size_t stride = families.size();
  std::vector<double> heights(mesh.positions.size() * stride);
  std::vector<std::uint32_t> codes(mesh.positions.size() * stride);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (std::size_t k = 0; k < stride; ++k) {
      const double h = families[k].normal.dot(mesh.positions[i]);
      const std::size_t j = families[k].first_at_or_above(h);
      heights[i * stride + k] = h;
      codes[i * stride + k] =
          static_cast<std::uint32_t>(2 * j + (j < families[k].offsets.size() && families[k].offsets[j] == h));
    }
  std::vector<Cutter> cutters;
  for (std::size_t k = 0; k < stride; ++k)
    cutters.emplace_back(mesh, heights, stride, k, families[k].normal);
  std::vector<std::vector<Segment>> segments(planes.size());
  for (auto& s : segments)
    s.reserve(256);
  for (const Triangle& t : mesh.triangles) {
    const std::uint32_t* a = &codes[t[0] * stride];
    const std::uint32_t* b = &codes[t[1] * stride];
    const std::uint32_t* c = &codes[t[2] * stride];
    for (std::size_t k = 0; k < stride; ++k) {
      const std::uint32_t lo = std::min(a[k], std::min(b[k], c[k]));
      const std::uint32_t hi = std::max(a[k], std::max(b[k], c[k]));
      // Planes j with lo <= 2j + 1 <= hi.
      for (std::uint32_t j = lo / 2; 2 * j + 1 <= hi; ++j)
        cutters[k].cut(t, families[k].offsets[j], segments[families[k].planes[j]]);
    }
  }
  std::vector<std::vector<Polyline>> out(planes.size());
  for (std::size_t j = 0; j < planes.size(); ++j)
    out[j] = chain(std::move(segments[j]));
  return out;
}

std::vector<std::vector<Polyline>> intersect(const Mesh& mesh, const Vec3& normal,
                                             std::span<const double> offsets) {
  std::vector<Plane> planes;
  planes.reserve(offsets.size());
  for (double d : offsets)
    planes.push_back({normal, d});
  return intersect(mesh, planes);
}

std::vector<Polyline> intersect(const Mesh& mesh, const Plane& plane) {
  return std::move(intersect(mesh, std::span<const Plane>(&plane, 1)).front());
}

} // namespace pdeface::slice
