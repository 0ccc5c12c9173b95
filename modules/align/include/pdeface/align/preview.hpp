#pragma once
//! \file
//! A picture to judge an alignment at a glance: the face seen from the front in the canonical frame,
//! shaded, with the landmarks and the symmetry line drawn over it.

#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"

#include <string>

namespace pdeface::align {

struct PreviewOptions {
  double pixel_mm = 0.5; //!< size of a pixel of the shaded view
  std::string title;     //!< a line under the picture (file name, confidence, ...)
};

//! An SVG document: the scan mapped by `frame` and seen along -z (the face's left on the right of the
//! picture), shaded by its depth map (an embedded PNG), the symmetry line x = 0 dashed, and every known
//! landmark as a labelled dot. `landmarks` are in the scan's frame and units.
[[nodiscard]] std::string preview_svg(const Mesh& scan, const FaceFrame& frame, const Landmarks& landmarks,
                                      const PreviewOptions& options = {});

} // namespace pdeface::align
