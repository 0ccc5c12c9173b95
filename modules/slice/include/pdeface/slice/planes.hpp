#pragma once
//! \file
//! Where the profile planes x = x_j go: joints at facial features, two intermediate planes inside every
//! patch between joints (the paper's 9 patches × 3 + 1 = 28 curves). See docs/slice.md for the rule.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/slice/profile.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace pdeface::slice {

enum class PlaneRole {
  Joint,        //!< a patch boundary, at a feature
  Intermediate, //!< at 1/3 or 2/3 inside a patch
};
[[nodiscard]] std::string_view to_string(PlaneRole role) noexcept;

//! One profile plane x = `x` of the canonical frame.
struct ProfilePlane {
  double x = 0.0;
  PlaneRole role = PlaneRole::Joint;
  std::string feature; //!< "outer eye corner (right)", "patch 4, 1/3", ...
};

struct PlaneOptions {
  std::size_t curves = 28;           //!< 3 · patches + 1, with an odd number of patches (symmetric layout)
  double wing_fraction = 0.65;       //!< nose-wing joints at this fraction of the inner eye corners' |x|
  double border_fraction = 0.12;     //!< face border at most this fraction of W beyond the outer eye corners,
  double min_border_fraction = 0.02; //!< and at least this fraction (and one mesh edge)
  double border_slack_mm = 10.0;     //!< the border must reach the height range less this at each end
  double min_spacing_mm = 1.0;       //!< joints closer than this (or than one mesh edge) are an error
  //! The height range [bottom, top] (mm, nose tip at 0) profiles should span; default: the face's
  //! bottom and top landmarks.
  std::optional<std::array<double, 2>> height_range;
};

//! The planes, with what placing them measured.
struct PlaneLayout {
  std::vector<ProfilePlane> planes; //!< ascending x
  double central_width_mm = 0.0;    //!< W: geodesic length of the eye line between the outer corners
  double eye_height_mm = 0.0;       //!< height of the eye line (mean of the outer eye corners)
  double border_mm = 0.0;           //!< |x| of the face-border joints
  std::array<double, 2> target{};   //!< the height range asked for
};

//! The central width W: the length along the surface of the front-most cross-section at the height of
//! the outer eye corners, between them. Errors: `InvalidArgument` (corners missing), `NoFace` (the
//! section has a hole longer than `section.max_gap_mm` between the corners).
[[nodiscard]] Result<double> central_width(const Mesh& canonical, const align::Landmarks& landmarks,
                                           const SectionOptions& section = {});

//! The planes for a scan in the canonical frame (mesh or point cloud) and its landmarks (canonical).
//! Joints, from the midline out on each side: nose wing (wing_fraction · inner), inner eye corner, eye
//! centre (midway), outer eye corner (each the mean of the left and right |x|), face border (as wide as
//! the face's front surface reaches at both ends of the height range, less `border_slack_mm`, kept
//! within [outer + min_border_fraction · W, outer + border_fraction · W]). Other curve counts interpolate
//! these joints.
//! Errors: `InvalidArgument` for a curve count that is not 3 · (odd) + 1 or landmarks that are missing;
//! `NoFace` when joints collapse (closer than `min_spacing_mm`) or the eye line cannot be measured.
[[nodiscard]] Result<PlaneLayout> profile_planes(const Mesh& canonical, const align::Landmarks& landmarks,
                                                 const PlaneOptions& options = {},
                                                 const SectionOptions& section = {});

} // namespace pdeface::slice
