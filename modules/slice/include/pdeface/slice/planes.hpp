#pragma once
//! \file
//! Where the profile planes x = x_j go: joints at facial features, two intermediate planes inside every
//! patch between joints (the paper's 9 patches × 3 + 1 = 28 curves). See docs/slice.md for the rule.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/slice/face_mask.hpp"
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
  std::size_t curves = 28; //!< 3 · patches + 1, with an odd number of patches (symmetric layout)
  //! The nose-side joints at this fraction of the inner eye corners' |x|: the middle patch then spans the
  //! nose's ridge and tip only. At 0.4 (instead of 0.65, on the alae) the mean scan → reconstruction
  //! distance in the face mask at 10 % falls from 0.269 to 0.179 mm on ict_04 and from 0.151 to 0.138 mm
  //! on facefuns_f18 (ict_02, ict_07, facefuns_m46, stfaces alike or better).
  double wing_fraction = 0.4;
  //! The face-border joints at this multiple of the face mask's half-width (so that the curves cover the
  //! whole mask), or nearer where the scan's surface ends or turns away from the viewer first.
  double border_beyond_mask = 1.06;
  //! The border stays where the face, seen on horizontal cross-sections beyond the outer eye corners,
  //! falls back by less than this angle from the x axis.
  double max_turn_deg = 80.0;
  double min_spacing_mm = 1.0; //!< joints closer than this are an error
  FaceMaskOptions mask;        //!< the face's outline from its landmarks
};

//! The planes, with what placing them measured.
struct PlaneLayout {
  std::vector<ProfilePlane> planes; //!< ascending x
  double central_width_mm = 0.0;    //!< W: geodesic length of the eye line between the outer corners
  double eye_height_mm = 0.0;       //!< height of the eye line (mean of the outer eye corners)
  std::array<double, 2> border{};   //!< |x| of the face border on the face's right (−x) and left (+x)
  double border_mm = 0.0;           //!< the larger of the two
  //! Per side (right, left): the border is nearer than the mask asks for, because the surface ends or turns
  //! away there (a scan cut short at a side).
  std::array<std::optional<ReachEnd>, 2> border_limited{};
  FaceMask mask; //!< the face's outline from its landmarks (`face_mask`)
};

//! The central width W: the length along the surface of the front-most cross-section at the height of
//! the outer eye corners, between them, holes crossed by chords. Errors: `NoFace` (corners missing, or
//! the section has a hole longer than `section.max_gap_mm` between the corners).
[[nodiscard]] Result<double> central_width(const Mesh& canonical, const align::Landmarks& landmarks,
                                           const SectionOptions& section = {});

//! The planes for a scan in the canonical frame (mesh or point cloud) and its landmarks (canonical).
//! Joints, from the midline out on each side: nose side (wing_fraction · inner), inner eye corner, eye
//! centre (midway), outer eye corner (each the mean of the left and right |x|), face border (each side on
//! its own: `border_beyond_mask` times the face mask's half-width, or where the surface ends or turns away
//! first on horizontal cross-sections across the middle of the mask; where that is inside the outer eye
//! corner, the side's joints are drawn in proportionally). Other curve counts interpolate these joints.
//! Holes up to `section.max_gap_mm` are crossed.
//! Errors: `InvalidArgument` for a curve count that is not 3 · (odd) + 1; `NoFace` for landmarks that are
//! missing, joints that collapse (closer than `min_spacing_mm`) or an eye line that cannot be measured.
[[nodiscard]] Result<PlaneLayout> profile_planes(const Mesh& canonical, const align::Landmarks& landmarks,
                                                 const PlaneOptions& options = {},
                                                 const SectionOptions& section = {});

} // namespace pdeface::slice
