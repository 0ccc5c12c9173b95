// The scan's offset from a PDE surface along its normal, on a grid over the surface's (u, v) domain.

#include "pdeface/residual/measure.hpp"

#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/residual/ray_cast.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pdeface::residual {

double Measured::found_share() const {
  if (found.empty()) return 0.0;
  return static_cast<double>(std::count(found.begin(), found.end(), 1)) / static_cast<double>(found.size());
}

GridSize grid_for(const pde::Surface& surface, double spacing_mm) {
  constexpr std::size_t probe = 48;
  const pde::Grid g = surface.evaluate(probe, probe);
  double width = 0, height = 0;
  for (std::size_t k = 0; k < probe; ++k) {
    double across = 0;
    for (std::size_t i = 1; i < probe; ++i)
      across += (g(i, k) - g(i - 1, k)).norm();
    width = std::max(width, across);
  }
  for (std::size_t i = 0; i < probe; ++i) {
    double along = 0;
    for (std::size_t k = 1; k < probe; ++k)
      along += (g(i, k) - g(i, k - 1)).norm();
    height = std::max(height, along);
  }
  auto nodes = [&](double length) {
    const double n = std::ceil(length / spacing_mm);
    return n >= 1 && n < 4096 ? static_cast<std::size_t>(n) + 1 : n >= 4096 ? std::size_t{4097} : 2;
  };
  return {nodes(width), nodes(height)};
}

Hit along_normal(const metrics::SurfaceDistance& distance, const Mesh& scan, const Vec3& x, const Vec3& n,
                 const MeasureOptions& options) {
  Hit hit;
  if (n.isZero()) return hit;
  const bool cloud = scan.is_point_cloud();
  double t = 0;
  for (int iteration = 0; iteration < 6; ++iteration) {
    const Vec3 at = x + t * n;
    const metrics::SurfaceDistance::Nearest near = distance.nearest(at);
    if (near.distance <= options.tolerance_mm) {
      if (std::abs(t) <= options.max_offset_mm) hit = {near.point, near.triangle, t, true};
      break;
    }
    double next = t + (near.point - at).dot(n); // along the normal: a point cloud's step
    if (!cloud) {                               // a mesh: where the line meets the nearest triangle's plane
      const Triangle& tri = scan.triangles[near.triangle];
      const Vec3 a = scan.positions[tri[0]], b = scan.positions[tri[1]], c = scan.positions[tri[2]];
      Vec3 m = (b - a).cross(c - a);
      const double length = m.norm();
      if (length > 0) {
        m /= length;
        const double cosine = n.dot(m);
        if (std::abs(cosine) > 0.25) next = (near.point - x).dot(m) / cosine;
      }
    }
    if (!(std::abs(next) <= options.max_offset_mm)) break;
    t = next;
  }
  if (!hit.found && options.rim_reach_mm > 0) {
    // The line misses (over a hole, past an edge): where the scan is near, move towards its nearest point
    // along the normal, so that the surface meets a hole's rim instead of spanning it high or low.
    const metrics::SurfaceDistance::Nearest near = distance.nearest(x);
    if (near.distance <= options.rim_reach_mm)
      hit = {near.point, near.triangle, (near.point - x).dot(n), true};
  }
  return hit;
}

Measured measure(const pde::Surface& surface, const Mesh& scan, std::size_t width, std::size_t height,
                 const MeasureOptions& options) {
  if (scan.positions.empty()) throw std::invalid_argument("residual::measure: an empty scan");
  const pde::NormalGrid grid = pde::normal_grid(surface, width, height);
  const metrics::SurfaceDistance distance(scan);
  Measured out{{width, height, std::vector<double>(width * height, 0.0)},
               std::vector<std::uint8_t>(width * height, 0)};
  if (scan.is_point_cloud()) {
    for (std::size_t p = 0; p < grid.points.size(); ++p) {
      const Hit hit = along_normal(distance, scan, grid.points[p], grid.normals[p], options);
      if (hit.found) {
        out.field.values[p] = hit.offset;
        out.found[p] = 1;
      }
    }
  } else { // a mesh: where the normal line crosses its triangles, nearest to the surface
    const RayCaster caster(scan);
    for (std::size_t p = 0; p < grid.points.size(); ++p) {
      if (grid.normals[p].isZero()) continue;
      if (const std::optional<RayHit> hit =
              caster.nearest(grid.points[p], grid.normals[p], options.max_offset_mm)) {
        out.field.values[p] = hit->t;
        out.found[p] = 1;
      }
    }
  }
  fill(out.field, out.found);
  return out;
}

std::vector<std::uint8_t> trim(const pde::Surface& surface, const Mesh& scan, const Measured& measured,
                               const TrimOptions& options) {
  const std::size_t w = measured.field.width, h = measured.field.height;
  if (w < 2 || h < 2 || measured.field.values.size() != w * h || measured.found.size() != w * h)
    throw std::invalid_argument("residual::trim: a measured grid of another size");
  const pde::NormalGrid grid = pde::normal_grid(surface, w, h);
  const std::vector<double>& d = measured.field.values;
  std::vector<Vec3> at(w * h);
  for (std::size_t p = 0; p < w * h; ++p)
    at[p] = grid.points[p] + d[p] * grid.normals[p];
  const metrics::SurfaceDistance distance(scan);
  const auto off = [&](const Vec3& p) { return distance.distance(p) > options.off_scan_mm; };
  std::vector<std::uint8_t> lost(w * h, 0); // nodes not found and off the scan
  for (std::size_t p = 0; p < w * h; ++p)
    lost[p] = !measured.found[p] && off(at[p]) ? 1 : 0;
  const auto torn = [&](std::size_t a, std::size_t b) {
    return std::abs(d[a] - d[b]) > options.tear_slope * (grid.points[a] - grid.points[b]).norm();
  };
  std::vector<std::uint8_t> out((w - 1) * (h - 1), 0);
  // The grid's border cells stay: the surface ends where the curves end, at the scan's edge, and a cell
  // there lies within a cell of it.
  for (std::size_t k = 1; k + 2 < h; ++k)
    for (std::size_t i = 1; i + 2 < w; ++i) {
      const std::size_t a = k * w + i, b = a + 1, c = a + w, e = c + 1; // corners: a b below, c e above
      std::uint8_t& cell = out[k * (w - 1) + i];
      if (lost[a] || lost[b] || lost[c] || lost[e]) {
        cell = 1;
        continue;
      }
      if (!(torn(a, b) || torn(c, e) || torn(a, c) || torn(b, e) || torn(a, e))) continue;
      cell = off((at[a] + at[b] + at[c] + at[e]) / 4.0) || off((at[a] + at[b]) / 2.0) ||
                     off((at[c] + at[e]) / 2.0) || off((at[a] + at[c]) / 2.0) || off((at[b] + at[e]) / 2.0)
                 ? 1
                 : 0;
    }
  return out;
}

pde::Displacement kept_field(const Measured& measured, const std::vector<std::uint8_t>& trimmed) {
  const std::size_t w = measured.field.width, h = measured.field.height;
  if (w < 2 || h < 2 || trimmed.size() != (w - 1) * (h - 1) || measured.field.values.size() != w * h)
    throw std::invalid_argument("residual::kept_field: a trim of another grid");
  std::vector<std::uint8_t> used(w * h, 0);
  for (std::size_t k = 0; k + 1 < h; ++k)
    for (std::size_t i = 0; i + 1 < w; ++i)
      if (trimmed[k * (w - 1) + i] == 0)
        for (const std::size_t p : {k * w + i, k * w + i + 1, (k + 1) * w + i, (k + 1) * w + i + 1})
          used[p] = 1;
  pde::Displacement out = measured.field;
  if (std::ranges::find(used, 0) != used.end()) fill(out, used);
  return out;
}

void fill(pde::Displacement& field, const std::vector<std::uint8_t>& found) {
  const std::size_t w = field.width, h = field.height;
  if (w * h == 0 || found.size() != w * h) return;
  if (std::none_of(found.begin(), found.end(), [](std::uint8_t f) { return f != 0; })) {
    std::fill(field.values.begin(), field.values.end(), 0.0);
    return;
  }
  // Pull: a pyramid of weighted means (weight 1 where found); push: every level's holes take the coarser
  // level's value, bilinearly.
  struct Level {
    std::size_t w, h;
    std::vector<double> value, weight;
  };
  std::vector<Level> levels;
  levels.push_back({w, h, field.values, {}});
  levels[0].weight.resize(w * h);
  for (std::size_t p = 0; p < w * h; ++p) {
    levels[0].weight[p] = found[p] ? 1.0 : 0.0;
    if (!found[p]) levels[0].value[p] = 0.0;
  }
  while (levels.back().w > 1 || levels.back().h > 1) {
    const Level& fine = levels.back();
    Level coarse{(fine.w + 1) / 2, (fine.h + 1) / 2, {}, {}};
    coarse.value.assign(coarse.w * coarse.h, 0.0);
    coarse.weight.assign(coarse.w * coarse.h, 0.0);
    for (std::size_t k = 0; k < fine.h; ++k)
      for (std::size_t i = 0; i < fine.w; ++i) {
        const std::size_t c = (k / 2) * coarse.w + i / 2, f = k * fine.w + i;
        coarse.value[c] += fine.value[f] * fine.weight[f];
        coarse.weight[c] += fine.weight[f];
      }
    for (std::size_t c = 0; c < coarse.value.size(); ++c)
      if (coarse.weight[c] > 0) {
        coarse.value[c] /= coarse.weight[c];
        coarse.weight[c] = std::min(coarse.weight[c], 1.0);
      }
    levels.push_back(std::move(coarse));
  }
  for (std::size_t l = levels.size() - 1; l-- > 0;) {
    Level& fine = levels[l];
    const Level& coarse = levels[l + 1];
    for (std::size_t k = 0; k < fine.h; ++k)
      for (std::size_t i = 0; i < fine.w; ++i) {
        const std::size_t f = k * fine.w + i;
        if (fine.weight[f] >= 1) continue;
        // the coarse value at this node's position (node centres at (2i + 1/2) in fine units)
        const double x =
            std::clamp((static_cast<double>(i) - 0.5) / 2.0, 0.0, static_cast<double>(coarse.w - 1));
        const double y =
            std::clamp((static_cast<double>(k) - 0.5) / 2.0, 0.0, static_cast<double>(coarse.h - 1));
        const std::size_t i0 = std::min(static_cast<std::size_t>(x), coarse.w > 1 ? coarse.w - 2 : 0);
        const std::size_t k0 = std::min(static_cast<std::size_t>(y), coarse.h > 1 ? coarse.h - 2 : 0);
        const std::size_t i1 = std::min(i0 + 1, coarse.w - 1), k1 = std::min(k0 + 1, coarse.h - 1);
        const double fx = std::clamp(x - static_cast<double>(i0), 0.0, 1.0);
        const double fy = std::clamp(y - static_cast<double>(k0), 0.0, 1.0);
        const auto at = [&](std::size_t a, std::size_t b) { return coarse.value[b * coarse.w + a]; };
        const double up = (1 - fy) * ((1 - fx) * at(i0, k0) + fx * at(i1, k0)) +
                          fy * ((1 - fx) * at(i0, k1) + fx * at(i1, k1));
        fine.value[f] = fine.weight[f] * fine.value[f] + (1 - fine.weight[f]) * up;
      }
  }
  field.values = levels[0].value;
  // Relax the filled nodes towards a harmonic continuation (the found ones stay), so that the wavelet's
  // detail there is close to zero.
  std::vector<double>& v = field.values;
  for (int sweep = 0; sweep < 60; ++sweep)
    for (std::size_t k = 0; k < h; ++k)
      for (std::size_t i = 0; i < w; ++i) {
        const std::size_t p = k * w + i;
        if (found[p]) continue;
        double sum = 0;
        int count = 0;
        if (i > 0) sum += v[p - 1], ++count;
        if (i + 1 < w) sum += v[p + 1], ++count;
        if (k > 0) sum += v[p - w], ++count;
        if (k + 1 < h) sum += v[p + w], ++count;
        v[p] = sum / count;
      }
}

} // namespace pdeface::residual
