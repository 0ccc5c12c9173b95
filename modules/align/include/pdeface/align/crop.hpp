#pragma once
//! \file
//! The face region of an aligned scan, cut away from hair, ears, neck and shoulders.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

namespace pdeface::align {

struct CropOptions {
  double side_margin_mm = 22.0; //!< beyond the outer eye corners, to the cheeks and temples
  double depth_mm = 75.0;       //!< deepest point kept behind the nose tip (ears and the back of the head go)
  double min_fragment = 0.05;   //!< pieces left with fewer vertices than this fraction of the largest go
};

//! The part of a mesh in the canonical frame between the face's bottom and top landmarks, within the
//! outer eye corners plus `side_margin_mm` on either side, and not deeper than `depth_mm`; triangles
//! kept whole, loose pieces dropped. `landmarks` are in the canonical frame.
//! Errors: `InvalidArgument` when the face's top, bottom or outer eye corners are missing; `NoFace` when
//! nothing is left.
[[nodiscard]] Result<Mesh> crop_face(const Mesh& canonical, const Landmarks& landmarks,
                                     const CropOptions& options = {});

} // namespace pdeface::align
