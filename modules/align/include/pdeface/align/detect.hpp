#pragma once
//! \file
//! Automatic landmark detection on meshes and point clouds in any pose.
//!
//! Hypothesise and verify (see docs/align.md): symmetry planes of the whole scan and local ones around
//! its pointed extreme points; nose-like points on them; each at a few candidate scales (when the file
//! states no units) verified by the landmark search (eye and mouth corners as hollows of a depth map, or
//! the ends of eye and mouth holes) and a fit onto the average face; the best verified face wins; its
//! scale from a similarity fit of its landmarks, snapped to a standard unit when close to one; the frame
//! by a weighted least-squares fit of the landmarks (`Eigen::umeyama`).

#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/geometry.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <optional>
#include <string_view>

namespace pdeface::align {

struct DetectOptions {
  double sample_mm = 3.0;       //!< unused: the subsample now follows the scan's size (kept for callers)
  int directions = 400;         //!< candidate symmetry-plane normals tried (spread over a hemisphere)
  double min_confidence = 0.35; //!< below this, detection fails with `NoFace`
  double min_fragment = 0.02;   //!< mesh pieces with fewer vertices than this fraction are ignored
  //! Threads the search tries its hypotheses on (0: every core); the result is the same to the bit
  //! whatever the count.
  unsigned threads = 1;
};

//! A plane n · p = offset (`pdeface::Plane`), in the scan's frame and units.
using Plane = pdeface::Plane;

//! What detection found, and how sure it is.
struct Detection {
  Landmarks landmarks;             //!< in the scan's frame and units
  FaceFrame frame;                 //!< scan -> canonical (from the landmarks)
  Plane symmetry;                  //!< the symmetry plane, in the scan's frame and units
  double confidence = 0.0;         //!< 0..1, the weakest of the cues below
  double symmetry_rms_mm = 0.0;    //!< how far the mirrored scan lies from itself (trimmed RMS)
  double nose_prominence_mm = 0.0; //!< how sharply the nose tip stands out of the symmetry profile
  double fit_rms_mm = 0.0;         //!< RMS of the nose tip, eye and mouth corners against the average face
                                   //!< after a similarity fit (face mm; a landmark not found counts 30 mm)
  double eye_hollow_mm = 0.0;      //!< how far the inner eye corners lie below the surface within 12 mm of
                                   //!< them (face mm, the shallower corner): eye sockets; no convex object
                                   //!< has them
};

//! Finds the landmarks of the face in `scan`, in its units when it states them, else at the scale the face
//! gives (`FaceFrame::scale`, `scan_units` the standard unit it is close to, or Unknown). Errors: `NoFace`
//! (fewer than 100 points, no nose-like feature on any symmetry plane, or confidence below
//! `options.min_confidence`; the message gives every cue's value).
[[nodiscard]] Result<Detection> detect_landmarks(const Mesh& scan, const DetectOptions& options = {});

//! `given` with its missing landmarks found on the scan in the frame `frame` (which the given ones
//! fixed): e.g. the face's top and bottom for menpo's 68 points, which have neither. Given ones are kept.
[[nodiscard]] Landmarks complete_landmarks(const Mesh& scan, const Landmarks& given, const FaceFrame& frame);

//! A scan's landmarks (scan frame) and its frame, however they were found.
struct Alignment {
  Landmarks landmarks;
  FaceFrame frame;
  std::optional<double> confidence; //!< when detected
};

//! The alignment every stage starts from: detected on `scan` when `given` is empty; otherwise the frame
//! fitted to the given landmarks (in their units, else the scan's, else at the scale they give:
//! `estimate_scale`) and the missing ones completed on the scan. Errors (with `source` set: the scan's name
//! for detection, `landmarks_source` for given landmarks): those of `detect_landmarks` and
//! `frame_from_landmarks`. `detect`: how detection runs.
[[nodiscard]] Result<Alignment> align_scan(const Mesh& scan, std::optional<Landmarks> given = std::nullopt,
                                           std::string_view source = {},
                                           std::string_view landmarks_source = {},
                                           const DetectOptions& detect = {});

} // namespace pdeface::align
