#pragma once
// The synthetic face of ../shared/reference/pde/face_lib.py, ported: its height field, its 28 profile
// curves (sampled from the exact height field, where face_lib fits a cubic spline to 300 points first:
// the two differ by < 7e-5 mm, see tests/data/pde/make_oracle.py), and its two error measures.

#include "pdeface/pde/surface.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace pdeface::pde::face {

inline double ztrue(double x, double y) {
  const auto g = [x, y](double x0, double y0, double sx, double sy) {
    return std::exp(-((x - x0) * (x - x0) / (2 * sx * sx) + (y - y0) * (y - y0) / (2 * sy * sy)));
  };
  const double head = 55 * std::exp(-0.5 * ((x / 60) * (x / 60) + (y / 95) * (y / 95)));
  const double nose = 22 * g(0, -5, 7, 18) * (1 / (1 + std::exp(-(y + 25) / 3)));
  const double nostrils = 4 * (g(-9, -22, 4, 3) + g(9, -22, 4, 3));
  const double eyes = -9 * (g(-32, 28, 11, 7) + g(32, 28, 11, 7));
  const double brows = 5 * (g(-30, 42, 16, 4) + g(30, 42, 16, 4));
  const double lips = 4 * g(0, -45, 16, 3.5) - 2 * g(0, -50, 14, 2);
  const double chin = 4 * g(0, -75, 14, 8);
  const double cheeks = 3 * (g(-40, -10, 12, 14) + g(40, -10, 12, 14));
  return head + nose + nostrils + eyes + brows + lips + chin + cheeks;
}

inline constexpr double face_y0 = -90, face_y1 = 90;
inline constexpr int face_curves = 28;
inline double face_x(int j) { return -67.5 + 5.0 * j; }

//! n values evenly over [first, last] as numpy.linspace computes them (last exact).
inline std::vector<double> linspace(double first, double last, std::size_t n) {
  std::vector<double> out(n);
  const double step = (last - first) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = first + static_cast<double>(i) * step;
  out.back() = last;
  return out;
}

//! The 28 profiles x = const, K samples from chin (y = −90) to forehead (y = 90), in mm.
inline Curves profiles(std::size_t samples) {
  Curves curves;
  curves.units = Units::Millimetres;
  const std::vector<double> ys = linspace(face_y0, face_y1, samples);
  for (int j = 0; j < face_curves; ++j) {
    Curve c(static_cast<Eigen::Index>(samples), 3);
    for (std::size_t k = 0; k < samples; ++k) {
      const auto row = static_cast<Eigen::Index>(k);
      c(row, 0) = face_x(j);
      c(row, 1) = ys[k];
      c(row, 2) = ztrue(face_x(j), ys[k]);
    }
    curves.samples.push_back(std::move(c));
  }
  return curves;
}

//! face_run3.py's grid: U = 0..9 in 217 steps, v at the K samples.
inline Grid grid(const Surface& surface) {
  return surface.evaluate(linspace(0, 9, 9 * 24 + 1), linspace(0, std::numbers::pi, surface.sample_count()));
}

struct SurfaceError {
  double mean = 0, max = 0;
};
//! |z − ztrue(x, y)| over the grid.
inline SurfaceError surface_error(const Grid& grid) {
  SurfaceError e;
  for (const Vec3& p : grid.points) {
    const double d = std::abs(p.z() - ztrue(p.x(), p.y()));
    e.mean += d;
    e.max = std::max(e.max, d);
  }
  e.mean /= static_cast<double>(grid.points.size());
  return e;
}

//! The paper's profile error, as make_oracle.profile_errs (face_lib.profile_errs made deterministic): the
//! grid's crossings with 4 planes (symmetry, eye line, the two diagonals through the nose tip), mean
//! distance to the nearest point of the true profile. Grid points within 1e-9 mm of a plane are crossings
//! themselves; otherwise a crossing is a strict change of side between neighbours.
inline std::array<double, 4> profile_errors(const Grid& grid) {
  const double nx = 0, ny = -5; // the synthetic face's nose tip
  std::array<double, 4> out{};
  for (int plane = 0; plane < 4; ++plane) {
    const auto side = [&](const Vec3& p) {
      switch (plane) {
      case 0: return p.x();
      case 1: return p.y() - 28.0;
      case 2: return (p.y() - ny) - (p.x() - nx);
      default: return (p.y() - ny) + (p.x() - nx);
      }
    };
    const auto snapped = [&](const Vec3& p) { return std::abs(side(p)) <= 1e-9 ? 0.0 : side(p); };
    std::vector<Vec3> crossings;
    for (const Vec3& p : grid.points)
      if (snapped(p) == 0) crossings.push_back(p);
    const auto cross = [&](const Vec3& a, const Vec3& b) {
      const double ga = snapped(a), gb = snapped(b);
      if ((ga < 0 && gb > 0) || (ga > 0 && gb < 0)) crossings.push_back(a + ga / (ga - gb) * (b - a));
    };
    for (std::size_t k = 0; k < grid.v_count; ++k)
      for (std::size_t i = 0; i + 1 < grid.u_count; ++i)
        cross(grid(i, k), grid(i + 1, k));
    for (std::size_t i = 0; i < grid.u_count; ++i)
      for (std::size_t k = 0; k + 1 < grid.v_count; ++k)
        cross(grid(i, k), grid(i, k + 1));
    std::vector<Vec3> truth;
    if (plane == 0) {
      for (double y : linspace(face_y0, face_y1, 4000))
        truth.emplace_back(0, y, ztrue(0, y));
    } else if (plane == 1) {
      for (double x : linspace(face_x(0), face_x(face_curves - 1), 4000))
        truth.emplace_back(x, 28, ztrue(x, 28));
    } else {
      const double sign = plane == 2 ? 1 : -1;
      for (double t : linspace(-100, 100, 8000))
        truth.emplace_back(nx + t, ny + sign * t, ztrue(nx + t, ny + sign * t));
    }
    double sum = 0;
    for (const Vec3& p : crossings) {
      double best = INFINITY;
      for (const Vec3& q : truth)
        best = std::min(best, (p - q).squaredNorm());
      sum += std::sqrt(best);
    }
    out[static_cast<std::size_t>(plane)] = sum / static_cast<double>(crossings.size());
  }
  return out;
}

} // namespace pdeface::pde::face
