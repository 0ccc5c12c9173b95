#include "pdeface/slice/intersect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
  Cutter(const Mesh& mesh, const std::vector<double>& heights, const Vec3& normal)
      : p_(mesh.positions), h_(heights), n_(normal) {}

  // The segment (if any) the triangle `t` cuts from the plane n · p = d.
  void cut(const Triangle& t, double d, std::vector<Segment>& out) const {
    std::array<double, 3> s{};
    std::array<int, 3> sg{};
    int zeros = 0, positive = 0, negative = 0;
    for (int k = 0; k < 3; ++k) {
      s[k] = h_[t[k]] - d;
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
  Vec3 n_;
};

// Chains segments into polylines through shared keys: open chains from their free ends first, then
// the closed loops that remain.
std::vector<Polyline> chain(std::vector<Segment> segments) {
  for (Segment& s : segments)
    if (s.b.key < s.a.key) std::swap(s.a, s.b);
  std::sort(segments.begin(), segments.end(), [](const Segment& l, const Segment& r) {
    return l.a.key != r.a.key ? l.a.key < r.a.key : l.b.key < r.b.key;
  });
  segments.erase(std::unique(segments.begin(), segments.end(),
                             [](const Segment& l, const Segment& r) {
                               return l.a.key == r.a.key && l.b.key == r.b.key;
                             }),
                 segments.end());

  // Nodes by key, and each node's incident segments (compressed rows).
  std::vector<Node> nodes;
  nodes.reserve(2 * segments.size());
  for (const Segment& s : segments) {
    nodes.push_back(s.a);
    nodes.push_back(s.b);
  }
  auto by_key = [](const Node& l, const Node& r) { return l.key < r.key; };
  std::sort(nodes.begin(), nodes.end(), by_key);
  nodes.erase(
      std::unique(nodes.begin(), nodes.end(), [](const Node& l, const Node& r) { return l.key == r.key; }),
      nodes.end());
  auto index_of = [&](Key key) {
    return static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), Node{key, {}}, by_key) -
                                    nodes.begin());
  };
  std::vector<std::array<std::size_t, 2>> ends(segments.size());
  std::vector<std::size_t> start(nodes.size() + 1, 0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    ends[i] = {index_of(segments[i].a.key), index_of(segments[i].b.key)};
    ++start[ends[i][0] + 1];
    ++start[ends[i][1] + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::size_t> incident(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < segments.size(); ++i)
    for (std::size_t e : ends[i])
      incident[fill[e]++] = i;

  std::vector<bool> used(segments.size(), false);
  auto next_segment = [&](std::size_t node) -> std::optional<std::size_t> {
    for (std::size_t k = start[node]; k < start[node + 1]; ++k)
      if (!used[incident[k]]) return incident[k];
    return std::nullopt;
  };
  std::vector<Polyline> out;
  auto walk = [&](std::size_t first) {
    Polyline line;
    line.points.push_back(nodes[first].point);
    std::size_t at = first;
    while (const auto s = next_segment(at)) {
      used[*s] = true;
      at = ends[*s][0] == at ? ends[*s][1] : ends[*s][0];
      if (at == first) {
        line.closed = true;
        break;
      }
      line.points.push_back(nodes[at].point);
    }
    out.push_back(std::move(line));
  };
  // Odd degree: the free end of an open chain (or a junction where the surface is not manifold).
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if ((start[n + 1] - start[n]) % 2 == 1 && next_segment(n)) walk(n);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    while (next_segment(n))
      walk(n);
  return out;
}

} // namespace

std::vector<std::vector<Polyline>> intersect(const Mesh& mesh, const Vec3& normal,
                                             std::span<const double> offsets) {
  if (std::abs(normal.norm() - 1.0) > 1e-9) throw std::invalid_argument("slice::intersect: normal not unit");
  for (double d : offsets)
    if (!std::isfinite(d)) throw std::invalid_argument("slice::intersect: offset not finite");

  std::vector<double> heights(mesh.positions.size());
  for (std::size_t i = 0; i < heights.size(); ++i)
    heights[i] = normal.dot(mesh.positions[i]);

  // Planes in order of offset, so that a triangle finds the planes it spans by two binary searches.
  std::vector<std::size_t> order(offsets.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return offsets[a] < offsets[b]; });
  std::vector<double> sorted(offsets.size());
  for (std::size_t j = 0; j < order.size(); ++j)
    sorted[j] = offsets[order[j]];

  const Cutter cutter(mesh, heights, normal);
  std::vector<std::vector<Segment>> segments(offsets.size());
  for (const Triangle& t : mesh.triangles) {
    const auto [lo, hi] = std::minmax({heights[t[0]], heights[t[1]], heights[t[2]]});
    for (auto j = std::lower_bound(sorted.begin(), sorted.end(), lo); j != sorted.end() && *j <= hi; ++j)
      cutter.cut(t, *j, segments[static_cast<std::size_t>(j - sorted.begin())]);
  }
  std::vector<std::vector<Polyline>> out(offsets.size());
  for (std::size_t j = 0; j < order.size(); ++j)
    out[order[j]] = chain(std::move(segments[j]));
  return out;
}

std::vector<Polyline> intersect(const Mesh& mesh, const Plane& plane) {
  return std::move(intersect(mesh, plane.normal, std::span<const double>(&plane.offset, 1)).front());
}

} // namespace pdeface::slice
