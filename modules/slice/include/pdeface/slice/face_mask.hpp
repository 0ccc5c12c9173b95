#pragma once
//! \file
//! The face as the landmarks outline it: an ellipse in the canonical frame's x–y plane, from the chin to
//! the forehead and across the cheeks just beyond the outer eye corners, with a depth limit so that the
//! back of a head does not count. It does not depend on any reconstruction, so it is the yardstick of
//! how much of a face a reconstruction covers (`metrics::measure_coverage`), and, grown, the most the
//! profile curves may span (`ProfileOptions::region`).

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <array>
#include <limits>
#include <optional>

namespace pdeface::slice {

//! An ellipse (x / a)² + ((y − centre_y) / b)² ≤ 1 of the canonical x–y plane (mm), and z ≥ `min_z`.
struct FaceMask {
  double centre_y = 0.0;
  double half_width = 0.0;  //!< a
  double half_height = 0.0; //!< b
  double min_z = -std::numeric_limits<double>::infinity();

  [[nodiscard]] bool contains(const Vec3& p) const {
    const double u = p.x() / half_width, w = (p.y() - centre_y) / half_height;
    return u * u + w * w <= 1.0 && p.z() >= min_z;
  }
  //! The box the ellipse lies in (z from `min_z` up), a millionth wider on each side so that every point
  //! `contains` takes lies in it whatever the rounding: what to look at before asking `contains`.
  [[nodiscard]] Box box() const {
    const double x = half_width * (1.0 + 1e-6), y = half_height * (1.0 + 1e-6);
    return {{-x, centre_y - y, min_z}, {x, centre_y + y, std::numeric_limits<double>::infinity()}};
  }
  //! The heights [bottom, top] the ellipse spans at `x`; nullopt beyond its sides.
  [[nodiscard]] std::optional<std::array<double, 2>> heights_at(double x) const;
  //! The same ellipse with its axes scaled by `across` and `along` about its centre.
  [[nodiscard]] FaceMask grown(double across, double along) const;
};

struct FaceMaskOptions {
  //! At the outer eye corners' height the ellipse is this many times as wide as the corners are.
  double beyond_outer_corners = 1.3;
  //! Surface more than this fraction of the chin-to-forehead height behind the nose tip is not the face
  //! (the back of a head, the far side of a bust).
  double depth_fraction = 0.5;
};

//! The mask of a face from its landmarks in the canonical frame: the chin (`face_bottom`) and the forehead
//! (`face_top`) at the ends of the vertical axis, the outer eye corners (mean |x| and height) inside the
//! side by `beyond_outer_corners`. Errors: `NoFace` when a landmark it needs is missing or the landmarks
//! make no ellipse (the eyes not between the chin and the forehead).
[[nodiscard]] Result<FaceMask> face_mask(const align::Landmarks& canonical,
                                         const FaceMaskOptions& options = {});

} // namespace pdeface::slice
