#pragma once
//! \file
//! The canonical face frame and the similarity that takes a scan into it.
//!
//! Canonical frame: origin at the nose tip, +x across the face from its right to its left (the normal
//! of the symmetry plane), +y up (chin to forehead), +z out of the face towards the viewer, millimetres.
//! The transform is kept as data so that results computed in the canonical frame (profiles, a PDE
//! surface) can be mapped back into the scan's own frame and units.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <string>

namespace pdeface::align {

//! p_canonical = scale · rotation · p_scan + translation.
struct FaceFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); //!< proper rotation (det +1)
  Vec3 translation = Vec3::Zero();                        //!< in mm
  double scale = 1.0;                                     //!< millimetres per scan unit
  Units scan_units = Units::Unknown;                      //!< the units the scan was found to be in

  [[nodiscard]] Vec3 to_canonical(const Vec3& p) const { return scale * (rotation * p) + translation; }
  [[nodiscard]] Vec3 to_scan(const Vec3& q) const {
    return rotation.transpose() * ((q - translation) / scale);
  }
  //! The canonical frame's axes and origin expressed in the scan's frame.
  [[nodiscard]] Vec3 axis_in_scan(int axis) const { return rotation.row(axis).transpose(); }
  [[nodiscard]] Vec3 origin_in_scan() const { return to_scan(Vec3::Zero()); }
};

//! Units of a face scan: those it states, else guessed from its size (a face is 0.1-0.4 m across:
//! a bounding-box diagonal under 2 means metres, under 60 centimetres, else millimetres).
[[nodiscard]] Units detect_units(const Mesh& scan);

//! Where the landmarks sit on an average adult face, in the canonical frame (mm). The rigid fit aligns
//! found landmarks onto these.
[[nodiscard]] const Landmarks& canonical_template();

//! The least-squares rigid fit (`Eigen::umeyama`, no scaling beyond the unit conversion) of the given
//! landmarks onto `canonical_template()`, then shifted so that the nose tip lands exactly on the origin.
//! Needs the nose tip and at least three landmarks that are not collinear.
//! Errors: `InvalidArgument` with the landmarks that are missing.
[[nodiscard]] Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, Units scan_units);

//! The mesh with positions (and normals) mapped into the canonical frame; units become mm.
[[nodiscard]] Mesh to_canonical(const Mesh& scan, const FaceFrame& frame);
//! The mesh mapped back from the canonical frame into the scan's frame and units.
[[nodiscard]] Mesh to_scan(const Mesh& canonical, const FaceFrame& frame);
//! Landmarks mapped into the canonical frame (units become mm).
[[nodiscard]] Landmarks to_canonical(const Landmarks& scan, const FaceFrame& frame);

//! The landmark JSON of `write_landmarks_json`, plus what alignment found: `"to_canonical"` (rotation
//! rows, translation in mm, scale in mm per scan unit) and, when given, `"confidence"`. Readers of
//! landmark files ignore both, so the file can be passed back with `--landmarks`.
[[nodiscard]] std::string write_alignment_json(const Landmarks& landmarks, const FaceFrame& frame,
                                               std::optional<double> confidence = std::nullopt);

} // namespace pdeface::align
