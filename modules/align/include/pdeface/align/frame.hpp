#pragma once
//! \file
//! The canonical face frame and the similarity that takes a scan into it: found from landmarks, applied to
//! meshes and landmarks. The frame itself (`FaceFrame`, a `Similarity` and the scan's units) is core's
//! (`pdeface/core/similarity.hpp`), shared with the `.pdef` codec and the pipeline.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/core/similarity.hpp"

#include <Eigen/Geometry>

#include <optional>
#include <string>

namespace pdeface::align {

//! p_canonical = scale · rotation · p_scan + translation, and the units the scan was found to be in
//! (`pdeface::FaceFrame`).
using FaceFrame = pdeface::FaceFrame;

//! Units of a face scan: those it states, else a first guess from its size (a bounding-box diagonal
//! under 2 means metres, under 60 centimetres, else millimetres). Only a guess: a bust or a scan in
//! arbitrary units breaks it; detection and `align_scan` find the scale from the face itself
//! (`estimate_scale`).
[[nodiscard]] Units detect_units(const Mesh& scan);
//! `detect_units`' guess for a scan of no stated units whose bounding box has this diagonal.
[[nodiscard]] Units units_by_size(double diagonal);

//! Where the landmarks sit on an average adult face, in the canonical frame (mm). The rigid fit aligns
//! found landmarks onto these.
[[nodiscard]] const Landmarks& canonical_template();

//! How much a landmark counts when a frame is fitted to landmarks: the stable ones (nose tip, eye corners)
//! twice as much as the mouth corners, which move with expressions; the face's top and bottom not at all
//! (they are derived, and a beard or an open mouth moves the chin), unless the others cannot fix a
//! rotation on their own.
[[nodiscard]] double fit_weight(Landmark landmark) noexcept;

//! The least-squares rigid fit (`Eigen::umeyama`, no scaling beyond the unit conversion, landmarks
//! weighted by `fit_weight`) of the given landmarks onto `canonical_template()`, then shifted so that the
//! nose tip lands exactly on the origin. Needs the nose tip and at least three landmarks that are not
//! collinear. `Units::Unknown` counts as millimetres. Errors: `InvalidArgument` with the landmarks that
//! are missing.
[[nodiscard]] Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, Units scan_units);
//! The same with an explicit scale (millimetres per scan unit, e.g. from `estimate_scale`); `scan_units`
//! is recorded in the frame.
[[nodiscard]] Result<FaceFrame> frame_from_landmarks(const Landmarks& landmarks, double mm_per_unit,
                                                     Units scan_units);

//! A scan's scale as the face in it says.
struct ScaleEstimate {
  double mm_per_unit = 1.0;     //!< the scale the frame uses: a standard unit's, or the estimate itself
  Units units = Units::Unknown; //!< the standard unit the estimate was snapped to, or Unknown
  double estimated = 1.0;       //!< millimetres per unit from the landmarks alone (before snapping)
};

//! The standard unit (mm, cm, inch, m) nearest to `mm_per_unit` on a log scale, when within a factor
//! `kUnitSnapFactor` of it (adult faces differ in size by less); else Unknown.
inline constexpr double kUnitSnapFactor = 1.6;
[[nodiscard]] Units snap_units(double mm_per_unit) noexcept;

//! The scale of a scan from its landmarks: the similarity fit (`Eigen::umeyama` with scaling, weights
//! as `fit_weight`) of the landmarks onto `canonical_template()` gives millimetres per unit, which is
//! snapped to a standard unit by `snap_units`. Needs at least three landmarks that are not collinear.
//! Errors: `InvalidArgument`.
[[nodiscard]] Result<ScaleEstimate> estimate_scale(const Landmarks& landmarks);

//! The mesh with positions (and normals) mapped into the canonical frame; units become mm. Taken by
//! value: a mesh moved in is mapped in place, without a second copy.
[[nodiscard]] Mesh to_canonical(Mesh scan, const FaceFrame& frame);
//! The mesh mapped back from the canonical frame into the scan's frame and units (in place if moved in).
[[nodiscard]] Mesh to_scan(Mesh canonical, const FaceFrame& frame);
//! Landmarks mapped into the canonical frame (units become mm).
[[nodiscard]] Landmarks to_canonical(const Landmarks& scan, const FaceFrame& frame);

//! The landmark JSON of `write_landmarks_json`, plus what alignment found: `"to_canonical"` (rotation
//! rows, translation in mm, scale in mm per scan unit) and, when given, `"confidence"`. Readers of
//! landmark files ignore both, so the file can be passed back with `--landmarks`.
[[nodiscard]] std::string write_alignment_json(const Landmarks& landmarks, const FaceFrame& frame,
                                               std::optional<double> confidence = std::nullopt);

} // namespace pdeface::align
