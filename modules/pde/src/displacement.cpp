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

} // namespace pdeface::pde
