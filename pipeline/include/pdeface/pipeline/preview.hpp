#pragma once
//! \file
//! A picture to judge a reconstruction at a glance: the scan and the reconstruction side by side from the
//! front, and the reconstruction turned, where folds, ridges and streaks show.

#include "pdeface/core/mesh.hpp"
#include "pdeface/slice/profiles.hpp"

#include <string>

namespace pdeface::pipeline {

struct PreviewOptions {
  double pixel_mm = 0.5;  //!< size of a pixel of the shaded views
  double turn_deg = 40.0; //!< the third view: the reconstruction turned by this about the vertical axis
  std::string title;      //!< a line under the picture
};

//! An SVG document of three shaded views (canonical frame, mm): the scan from the front with the face
//! mask's outline dashed, the reconstruction from the front with the curves' region outlined and the
//! filled holes marked, and the reconstruction turned by `turn_deg` to its left.
[[nodiscard]] std::string reconstruction_preview_svg(const Mesh& scan, const Mesh& reconstruction,
                                                     const slice::ProfileSet& profiles,
                                                     const PreviewOptions& options = {});

} // namespace pdeface::pipeline
