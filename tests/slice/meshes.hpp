#pragma once
// Analytic meshes whose plane sections are known exactly.

#include "pdeface/core/mesh.hpp"

#include <cmath>
#include <functional>
#include <numbers>

namespace pdeface::test {

//! A UV sphere of radius r about the origin: `rings` latitude rings of `segments` vertices between
//! the poles (on z). Ring k is at z = r cos(π (k + 1) / (rings + 1)).
inline Mesh uv_sphere(double r, int rings, int segments) {
  Mesh m;
  const auto n = static_cast<std::uint32_t>(segments);
  m.positions.push_back({0, 0, r});
  for (int k = 0; k < rings; ++k) {
    const double theta = std::numbers::pi * (k + 1) / (rings + 1);
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.push_back(
          {r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
    }
  }
  m.positions.push_back({0, 0, -r});
  const auto south = static_cast<std::uint32_t>(m.positions.size() - 1);
  auto ring = [&](int k, std::uint32_t s) { return 1 + static_cast<std::uint32_t>(k) * n + s % n; };
  for (std::uint32_t s = 0; s < n; ++s) {
    m.triangles.push_back({0, ring(0, s), ring(0, s + 1)});
    for (int k = 0; k + 1 < rings; ++k) {
      m.triangles.push_back({ring(k, s), ring(k + 1, s), ring(k + 1, s + 1)});
      m.triangles.push_back({ring(k, s), ring(k + 1, s + 1), ring(k, s + 1)});
    }
    m.triangles.push_back({ring(rings - 1, s), south, ring(rings - 1, s + 1)});
  }
  return m;
}

//! An open cylinder of radius r about the z axis from z = 0 to `height`, `rings` + 1 rings of `segments`
//! vertices (vertex s at angle 2πs/segments), quads split along a diagonal.
inline Mesh cylinder(double r, double height, int rings, int segments) {
  Mesh m;
  const auto n = static_cast<std::uint32_t>(segments);
  for (int k = 0; k <= rings; ++k)
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.push_back({r * std::cos(phi), r * std::sin(phi), height * k / rings});
    }
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(rings); ++k)
    for (std::uint32_t s = 0; s < n; ++s) {
      const std::uint32_t a = k * n + s, b = k * n + (s + 1) % n, c = a + n, d = b + n;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

//! A height field z = f(x, y) on a regular grid over [x0, x1] × [y0, y1] with step h, quads split along a
//! diagonal; `keep(x, y)` drops triangles whose centroid it rejects (to punch holes).
inline Mesh height_field(
    const std::function<double(double, double)>& f, double x0, double x1, double y0, double y1, double h,
    const std::function<bool(double, double)>& keep = [](double, double) { return true; }) {
  Mesh m;
  const int nx = static_cast<int>(std::lround((x1 - x0) / h)),
            ny = static_cast<int>(std::lround((y1 - y0) / h));
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = x0 + i * h, y = y0 + j * h;
      m.positions.push_back({x, y, f(x, y)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double cx = x0 + (i + 0.5) * h, cy = y0 + (j + 0.5) * h;
      if (!keep(cx, cy)) continue;
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.units = Units::Millimetres;
  return m;
}

} // namespace pdeface::test
