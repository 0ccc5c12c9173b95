#pragma once
//! \file
//! A `ProfileSet` as JSON (for later stages and other tools) and as an SVG picture (for people).

#include "pdeface/core/mesh.hpp"
#include "pdeface/slice/profiles.hpp"

#include <string>

namespace pdeface::slice {

//! The profiles as JSON (format "pdeface-profiles", version 1; fields in docs/slice.md): units, the
//! frame (scan → canonical), the height range, the parameterisation, K and the sampling ratio, each
//! curve's plane, role, raw point count and K points, and the 4 evaluation profiles as raw polylines.
[[nodiscard]] std::string write_profiles_json(const ProfileSet& profiles);

struct SvgOptions {
  std::string title; //!< a line under the picture
};

//! An SVG document: on the left the face from the front (`canonical`, shaded) with the curves (joints
//! darker) and the 4 evaluation profiles (dashed) over it; on the right the symmetry profile from the
//! side, raw as a line and fitted (K points) as crosses, like the paper's Figure 4.
[[nodiscard]] std::string profiles_svg(const Mesh& canonical, const ProfileSet& profiles,
                                       const SvgOptions& options = {});

} // namespace pdeface::slice
