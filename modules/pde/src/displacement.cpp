// Offsets along a surface's normal: sampled, resampled and applied to a grid mesh.

#include "pdeface/pde/displacement.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pdeface::pde {

double Displacement::at(double s, double t) const {
  if (values.empty() || width < 2 || height < 2) return 0.0;
  const double x = std::clamp(s, 0.0, 1.0) * static_cast<double>(width - 1);
  const double y = std::clamp(t, 0.0, 1.0) * static_cast<double>(height - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), width - 2);
  const std::size_t k = std::min(static_cast<std::size_t>(y), height - 2);
  const double fx = x - static_cast<double>(i), fy = y - static_cast<double>(k);
  const double* row = values.data() + k * width + i;
  const double bottom = row[0] + fx * (row[1] - row[0]);
  const double top = row[width] + fx * (row[width + 1] - row[width]);
  return bottom + fy * (top - bottom);
}

NormalGrid normal_grid(const Surface& surface, std::size_t width, std::size_t height) {
  if (width < 2 || height < 2) throw std::invalid_argument("pde::normal_grid: at least 2 x 2 nodes");
  std::vector<double> us(width), vs(height);
  for (std::size_t i = 0; i < width; ++i)
    us[i] = surface.u_max() * static_cast<double>(i) / static_cast<double>(width - 1);
  us.back() = surface.u_max();
  for (std::size_t k = 0; k < height; ++k)
    vs[k] = std::numbers::pi * static_cast<double>(k) / static_cast<double>(height - 1);
  return normal_grid(surface, us, vs);
}

NormalGrid normal_grid(const Surface& surface, std::span<const double> us, std::span<const double> vs) {
  if (us.empty() || vs.empty()) throw std::invalid_argument("pde::normal_grid: no nodes");
  NormalGrid out{us.size(), vs.size(), surface.evaluate(us, vs).points, {}};
  const Grid du = surface.evaluate(us, vs, Derivative::U), dv = surface.evaluate(us, vs, Derivative::V);
  out.normals.resize(out.points.size());
  for (std::size_t p = 0; p < out.points.size(); ++p) {
    const Vec3 n = du.points[p].cross(dv.points[p]);
    const double length = n.norm();
    out.normals[p] = length > 0 && std::isfinite(length) ? Vec3(n / length) : Vec3::Zero();
  }
  return out;
}

std::vector<double> resample(const Displacement& field, std::size_t u_count, std::size_t v_count) {
  if (field.empty() || field.width < 2 || field.height < 2 ||
      field.values.size() != field.width * field.height)
    throw std::invalid_argument("pde::resample: an empty or malformed field");
  if (u_count < 2 || v_count < 2) throw std::invalid_argument("pde::resample: at least 2 x 2 nodes");
  if (u_count == field.width && v_count == field.height) return field.values;
  std::vector<double> out(u_count * v_count);
  // Separable: each field row interpolated across to u_count points once, then rows blended.
  std::vector<std::size_t> left(u_count);
  std::vector<double> frac(u_count);
  for (std::size_t i = 0; i < u_count; ++i) {
    const double x =
        static_cast<double>(i) * static_cast<double>(field.width - 1) / static_cast<double>(u_count - 1);
    left[i] = std::min(static_cast<std::size_t>(x), field.width - 2);
    frac[i] = x - static_cast<double>(left[i]);
  }
  std::vector<double> below(u_count), above(u_count);
  std::size_t loaded = field.height; // the field row `below` holds
  auto across = [&](std::size_t row, std::vector<double>& into) {
    const double* r = field.values.data() + row * field.width;
    for (std::size_t i = 0; i < u_count; ++i)
      into[i] = r[left[i]] + frac[i] * (r[left[i] + 1] - r[left[i]]);
  };
  for (std::size_t k = 0; k < v_count; ++k) {
    const double y =
        static_cast<double>(k) * static_cast<double>(field.height - 1) / static_cast<double>(v_count - 1);
    const std::size_t row = std::min(static_cast<std::size_t>(y), field.height - 2);
    const double fy = y - static_cast<double>(row);
    if (row != loaded) {
      across(row, below);
      across(row + 1, above);
      loaded = row;
    }
    double* o = out.data() + k * u_count;
    for (std::size_t i = 0; i < u_count; ++i)
      o[i] = below[i] + fy * (above[i] - below[i]);
  }
  return out;
}

namespace {
// X_u × X_v of the grid at (i, k) by central differences (one-sided at the borders).
Vec3 grid_cross(std::span<const Vec3> p, std::size_t nu, std::size_t nv, std::size_t i, std::size_t k) {
  const std::size_t i0 = i == 0 ? 0 : i - 1, i1 = i + 1 == nu ? i : i + 1;
  const std::size_t k0 = k == 0 ? 0 : k - 1, k1 = k + 1 == nv ? k : k + 1;
  const Vec3 du = p[k * nu + i1] - p[k * nu + i0], dv = p[k1 * nu + i] - p[k0 * nu + i];
  return du.cross(dv);
}
} // namespace

void displace_grid(std::span<Vec3> positions, std::span<Vec3f> normals, std::size_t u_count,
                   std::size_t v_count, std::span<const double> offsets, double scale) {
  const std::size_t n = u_count * v_count;
  if (u_count < 2 || v_count < 2 || positions.size() != n || normals.size() != n || offsets.size() != n)
    throw std::invalid_argument("pde::displace_grid: sizes that do not match the grid");
  // Which way the mesh's normals face against the grid's X_u × X_v (a map may reverse it).
  const Vec3 probe = grid_cross(positions, u_count, v_count, u_count / 2, v_count / 2);
  const double orientation =
      probe.dot(normals[(v_count / 2) * u_count + u_count / 2].cast<double>()) < 0 ? -1.0 : 1.0;
  for (std::size_t p = 0; p < n; ++p)
    positions[p] += (offsets[p] * scale) * normals[p].cast<double>();
  for (std::size_t k = 0; k < v_count; ++k) {
    const std::size_t k0 = k == 0 ? 0 : k - 1, k1 = k + 1 == v_count ? k : k + 1;
    const Vec3* row = positions.data() + k * u_count;
    const Vec3* below = positions.data() + k0 * u_count;
    const Vec3* above = positions.data() + k1 * u_count;
    Vec3f* out = normals.data() + k * u_count;
    for (std::size_t i = 0; i < u_count; ++i) {
      const std::size_t i0 = i == 0 ? 0 : i - 1, i1 = i + 1 == u_count ? i : i + 1;
      const Vec3 c = (row[i1] - row[i0]).cross(above[i] - below[i]);
      const double length = c.norm();
      if (length > 0 && std::isfinite(length)) out[i] = (c * (orientation / length)).cast<float>();
    }
  }
}

std::vector<std::uint8_t> resample_trim(std::span<const std::uint8_t> trimmed, std::size_t width,
                                        std::size_t height, std::size_t u_count, std::size_t v_count) {
  if (width < 2 || height < 2 || trimmed.size() != (width - 1) * (height - 1))
    throw std::invalid_argument("pde::resample_trim: a trim that does not match its grid");
  if (u_count < 2 || v_count < 2) throw std::invalid_argument("pde::resample_trim: at least 2 x 2 nodes");
  if (u_count == width && v_count == height) return {trimmed.begin(), trimmed.end()};
  const std::size_t across = u_count - 1, down = v_count - 1, from_across = width - 1, from_down = height - 1;
  // A cell's centre (i + 1/2) / across of the way across lies in the trim's cell ⌊that · from_across⌋.
  std::vector<std::size_t> column(across);
  for (std::size_t i = 0; i < across; ++i)
    column[i] = std::min(from_across - 1, (2 * i + 1) * from_across / (2 * across));
  std::vector<std::uint8_t> out(across * down);
  for (std::size_t k = 0; k < down; ++k) {
    const std::size_t row = std::min(from_down - 1, (2 * k + 1) * from_down / (2 * down));
    for (std::size_t i = 0; i < across; ++i)
      out[k * across + i] = trimmed[row * from_across + column[i]] != 0 ? 1 : 0;
  }
  return out;
}

std::vector<std::uint32_t> trim_grid(Mesh& mesh, std::size_t u_count, std::size_t v_count,
                                     std::span<const std::uint8_t> trimmed) {
  const std::size_t across = u_count - 1, cells = (u_count - 1) * (v_count - 1);
  if (u_count < 2 || v_count < 2 || mesh.vertex_count() != u_count * v_count ||
      mesh.triangle_count() != 2 * cells || trimmed.size() != cells || mesh.has_corner_texcoords())
    throw std::invalid_argument("pde::trim_grid: a mesh or trim that is not the grid's");
  std::vector<std::uint32_t> kept_vertices;
  if (std::ranges::none_of(trimmed, [](std::uint8_t t) { return t != 0; })) {
    kept_vertices.resize(mesh.vertex_count());
    for (std::size_t v = 0; v < kept_vertices.size(); ++v)
      kept_vertices[v] = static_cast<std::uint32_t>(v);
    return kept_vertices;
  }
  // A vertex stays when a cell around it does; its new index counts those before it. Then the attributes
  // move down and the kept cells' triangles are made again with the new indices, in the mesher's pattern
  // (one pass over each array: the work is moving memory).
  const auto kept = [&](std::size_t i, std::size_t k) { return trimmed[k * across + i] == 0; };
  std::vector<std::uint32_t> index(mesh.vertex_count());
  kept_vertices.reserve(mesh.vertex_count());
  for (std::size_t k = 0; k < v_count; ++k)
    for (std::size_t i = 0; i < u_count; ++i) {
      const bool left = i > 0, right = i<across, below = k> 0, above = k + 1 < v_count;
      const bool used = (left && below && kept(i - 1, k - 1)) || (right && below && kept(i, k - 1)) ||
                        (left && above && kept(i - 1, k)) || (right && above && kept(i, k));
      const std::size_t v = k * u_count + i;
      index[v] = static_cast<std::uint32_t>(kept_vertices.size());
      if (used) kept_vertices.push_back(static_cast<std::uint32_t>(v));
    }
  const auto compact = [&](auto& attribute) {
    if (attribute.size() != index.size()) return;
    for (std::size_t n = 0; n < kept_vertices.size(); ++n)
      attribute[n] = attribute[kept_vertices[n]];
    attribute.resize(kept_vertices.size());
  };
  compact(mesh.positions);
  compact(mesh.normals);
  compact(mesh.colors);
  compact(mesh.texcoords);
  std::size_t t = 0;
  for (std::size_t k = 0; k + 1 < v_count; ++k)
    for (std::size_t i = 0; i < across; ++i) {
      if (!kept(i, k)) continue;
      const std::uint32_t below = index[k * u_count + i], right = index[k * u_count + i + 1];
      const std::uint32_t above = index[(k + 1) * u_count + i], corner = index[(k + 1) * u_count + i + 1];
      mesh.triangles[t++] = {below, right, corner}; // GridMesher::triangles: counter-clockwise in (u, v)
      mesh.triangles[t++] = {below, corner, above};
    }
  mesh.triangles.resize(t);
  return kept_vertices;
}

} // namespace pdeface::pde
