#pragma once
//! \file
//! The face seen from the front, shaded from its depth map: the backdrop of the SVG pictures of align
//! (landmarks) and slice (profile curves).

#include "pdeface/core/mesh.hpp"

#include <string>

namespace pdeface::align {

//! The region of the canonical frame (mm) a front view covers.
struct FrontViewBox {
  double x0 = -110.0, x1 = 110.0, y0 = -150.0, y1 = 130.0;
  double pixel_mm = 0.5;
};

//! An SVG `<image>` element (an embedded PNG) of `canonical` seen along −z, Lambert-shaded from its
//! front-most depth map, placed in SVG user units = mm with y flipped (SVG y = −canonical y), so that
//! curves drawn as (x, −y) lie on it.
[[nodiscard]] std::string front_view_image(const Mesh& canonical, const FrontViewBox& box = {});

//! `text` with the characters SVG/XML reserve escaped.
[[nodiscard]] std::string svg_escape(std::string_view text);

} // namespace pdeface::align
