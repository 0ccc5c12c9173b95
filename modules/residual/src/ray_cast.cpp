// Segments against a triangle mesh through a hierarchy of boxes.

#include "pdeface/residual/ray_cast.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace pdeface::residual {
namespace {

constexpr std::uint32_t kLeaf = 4;

// Where x + t·d lies inside `box`, clipped to [lo, hi]; empty (lo > hi) when it misses.
std::array<double, 2> clip(const Box& box, const Vec3& x, const Vec3& inverse, double lo, double hi) {
  for (int a = 0; a < 3; ++a) {
    if (std::isinf(inverse[a])) { // parallel to this slab: inside it or never
      if (x[a] < box.min[a] || x[a] > box.max[a]) return {1.0, 0.0};
      continue;
    }
    double t0 = (box.min[a] - x[a]) * inverse[a], t1 = (box.max[a] - x[a]) * inverse[a];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) break;
  }
  return {lo, hi};
}

double nearest_to_zero(const std::array<double, 2>& span) {
  if (span[0] <= 0 && span[1] >= 0) return 0.0;
  return std::min(std::abs(span[0]), std::abs(span[1]));
}

// Möller and Trumbore: t where x + t·d crosses triangle (a, b, c), edges included; nullopt if it does not.
std::optional<double> crossing(const Vec3& x, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (!(std::abs(det) > 1e-12 * scale)) return std::nullopt; // parallel, or a degenerate triangle
  const double inverse = 1.0 / det;
  const Vec3 s = x - a;
  const double u = s.dot(p) * inverse;
  constexpr double kSlack = 1e-9; // a line through an edge or a corner meets the triangles there
  if (u < -kSlack || u > 1 + kSlack) return std::nullopt;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inverse;
  if (v < -kSlack || u + v > 1 + kSlack) return std::nullopt;
  return e2.dot(q) * inverse;
}

} // namespace

RayCaster::RayCaster(const Mesh& mesh) : mesh_(&mesh) {
  const std::size_t n = mesh.triangles.size();
  if (n == 0) return;
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0U);
  std::vector<Vec3> centroids(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = mesh.triangles[i];
    centroids[i] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
  }
  nodes_.reserve(2 * n / kLeaf + 1);
  build(0, static_cast<std::uint32_t>(n), centroids);
}

std::uint32_t RayCaster::build(std::uint32_t begin, std::uint32_t end, std::vector<Vec3>& centroids) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Box box, centres;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Triangle& t = mesh_->triangles[order_[i]];
    for (const std::uint32_t v : t)
      box.extend(mesh_->positions[v]);
    centres.extend(centroids[order_[i]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeaf) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  centres.size().maxCoeff(&axis);
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
  const std::uint32_t left = build(begin, middle, centroids);
  const std::uint32_t right = build(middle, end, centroids);
  nodes_[index].first = left;
  nodes_[index].right = right;
  return index;
}

template <class Visit>
void RayCaster::visit(const Vec3& x, const Vec3& d, double reach, Visit&& on_hit) const {
  if (nodes_.empty()) return;
  const Vec3 inverse(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
  // Each entry: a node and the least |t| its box may hold; `on_hit` returns the bound below which a
  // crossing still matters (a nearest query narrows it, `all` keeps `reach`).
  // On the stack, not the heap: a query allocates nothing. A depth-first walk holds at most one entry a
  // level and two at the deepest; median splits of 2^32 triangles are 31 levels deep.
  std::array<std::pair<std::uint32_t, double>, 64> stack;
  std::size_t top = 0;
  double bound = reach;
  const std::array<double, 2> root = clip(nodes_[0].box, x, inverse, -reach, reach);
  if (root[0] > root[1]) return;
  stack[top++] = {0, nearest_to_zero(root)};
  while (top > 0) {
    const auto [index, least] = stack[--top];
    if (least > bound) continue;
    const Node& node = nodes_[index];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const Triangle& t = mesh_->triangles[order_[i]];
        const std::optional<double> at =
            crossing(x, d, mesh_->positions[t[0]], mesh_->positions[t[1]], mesh_->positions[t[2]]);
        if (at && std::abs(*at) <= bound) bound = on_hit(RayHit{*at, order_[i]});
      }
      continue;
    }
    const std::array<double, 2> a = clip(nodes_[node.first].box, x, inverse, -bound, bound);
    const std::array<double, 2> b = clip(nodes_[node.right].box, x, inverse, -bound, bound);
    const bool has_a = a[0] <= a[1], has_b = b[0] <= b[1];
    const double near_a = has_a ? nearest_to_zero(a) : 0.0, near_b = has_b ? nearest_to_zero(b) : 0.0;
    // The nearer box last, so that it is searched first.
    if (has_a && has_b && near_a < near_b) {
      stack[top++] = {node.right, near_b};
      stack[top++] = {node.first, near_a};
    } else {
      if (has_a) stack[top++] = {node.first, near_a};
      if (has_b) stack[top++] = {node.right, near_b};
    }
  }
}

std::optional<RayHit> RayCaster::nearest(const Vec3& x, const Vec3& d, double reach) const {
  std::optional<RayHit> best;
  visit(x, d, reach, [&](const RayHit& hit) {
    const double a = std::abs(hit.t);
    if (!best || a < std::abs(best->t) || (a == std::abs(best->t) && hit.t < best->t)) best = hit;
    return std::abs(best->t);
  });
  return best;
}

std::vector<RayHit> RayCaster::all(const Vec3& x, const Vec3& d, double reach) const {
  std::vector<RayHit> out;
  visit(x, d, reach, [&](const RayHit& hit) {
    out.push_back(hit);
    return reach;
  });
  std::sort(out.begin(), out.end(), [](const RayHit& a, const RayHit& b) { return a.t < b.t; });
  return out;
}

} // namespace pdeface::residual
