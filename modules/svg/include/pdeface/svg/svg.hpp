#pragma once
//! \file
//! What the SVG pictures share (align's landmark preview, slice's profile curves, compare's reconstruction
//! preview): a mesh seen from the front, shaded from its depth map, as an embedded PNG; polylines; escaping.

#include "pdeface/core/mesh.hpp"

#include <fmt/format.h>

#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace pdeface::svg {

//! The region of the canonical frame (mm) a front view covers.
struct FrontViewBox {
  double x0 = -110.0, x1 = 110.0, y0 = -150.0, y1 = 130.0;
  double pixel_mm = 0.5;
};

//! An SVG `<image>` element (an embedded PNG) of `canonical` seen along −z, Lambert-shaded from its
//! front-most depth map, placed in SVG user units = mm with y flipped (SVG y = −canonical y), so that
//! curves drawn as (x, −y) lie on it.
[[nodiscard]] std::string front_view_image(const Mesh& canonical, const FrontViewBox& box = {});

//! The colour (linear RGB in [0, 1]) of the surface point a pixel shows.
using Colouring = std::function<Eigen::Vector3f(const Vec3&)>;
//! The same view, each pixel in `colour` of the front-most surface point it shows (canonical frame), shaded:
//! a map of any per-point measure (an error heat map) on the surface.
[[nodiscard]] std::string front_view_image(const Mesh& canonical, const FrontViewBox& box,
                                           const Colouring& colour);

//! `text` with the characters SVG/XML reserve escaped.
[[nodiscard]] std::string escape(std::string_view text);

//! An SVG polyline through `points` projected by `project` (a point → {u, v} in SVG user units), with the
//! attributes `style` ("stroke=\"red\" ...").
template <class Project>
[[nodiscard]] std::string polyline(std::span<const Vec3> points, const Project& project,
                                   std::string_view style) {
  std::string d;
  for (const Vec3& p : points) {
    const auto [u, v] = project(p);
    d += fmt::format("{:.2f},{:.2f} ", u, v);
  }
  return fmt::format("<polyline fill=\"none\" {} points=\"{}\"/>\n", style, d);
}

} // namespace pdeface::svg
