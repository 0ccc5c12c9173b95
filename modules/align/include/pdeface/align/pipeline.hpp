#pragma once
//! \file
//! The alignment step as a command runs it: landmarks read (from a file's bytes) or detected, the scan
//! moved into the canonical frame and, if asked, cropped to the face, with the documents that describe it.

#include "pdeface/align/crop.hpp"
#include "pdeface/align/detect.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <optional>
#include <string>

namespace pdeface::align {

//! Where a scan's landmarks come from.
struct LandmarkSource {
  std::optional<std::string> bytes; //!< a landmark file's bytes (ours or menpo LJSON); empty: detect
  std::string name;                 //!< that file's name, for errors
  DetectOptions detect;             //!< how detection runs when there are no bytes
};

//! `align_scan` from a landmark file's bytes (parsed here: bad bytes are an error naming `landmarks.name`)
//! or by detection when there are none; errors name `source`.
[[nodiscard]] Result<Alignment> align_from(const Mesh& scan, const LandmarkSource& landmarks,
                                           std::string_view source);

struct AlignRequest {
  LandmarkSource landmarks;
  bool crop = false; //!< keep only the face region (`crop_face`)
  CropOptions crop_options;
  bool landmarks_json = false; //!< also make the landmark document (`write_alignment_json`)
  bool preview = false;        //!< also make the preview picture (`preview_svg`)
  std::string source;          //!< the scan's name, for errors and the preview's title
};

struct AlignOutcome {
  Alignment alignment;
  Mesh canonical;             //!< the scan in the canonical frame (mm), cropped when asked
  std::string landmarks_json; //!< when asked
  std::string preview_svg;    //!< when asked
};

//! The whole `pdeface align` step on a scan already read. Errors: those of `align_from` and `crop_face`,
//! naming `request.source`.
[[nodiscard]] Result<AlignOutcome> align_request(const Mesh& scan, const AlignRequest& request);

} // namespace pdeface::align
