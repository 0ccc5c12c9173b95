#pragma once
//! \file
//! A scan as a `.pdef` document: aligned, sliced into curves, the PDE options resolved on them, and the
//! document `pdeface::pdef` encodes filled in (`pdeface encode`, `pdeface convert scan.ply face.pdef`).

#include "pdeface/align/pipeline.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/slice/profiles.hpp"

#include <optional>
#include <string>

namespace pdeface::pipeline {

//! The document of `profiles` and the `surface` built through them with `options`: the curves
//! (`to_curves`), their planes and filled samples, the frame back to the scan, and the options with the
//! smoothing and mode count the surface used.
[[nodiscard]] pdef::Face to_face(const slice::ProfileSet& profiles, const pde::Surface& surface,
                                 const pde::Options& options);

struct EncodeRequest {
  align::LandmarkSource landmarks;
  slice::ProfileOptions profiles;
  //! As `reconstruct` builds the surface (physical spacing), so that a lossless file decodes to its mesh.
  pde::Options pde{.spacing = pde::Spacing::Physical};
  pdef::EncodeOptions encoding;
  bool store_landmarks = false; //!< also store the landmarks (canonical frame)
  std::string name;             //!< stored when not empty
  std::string source;           //!< the scan's name, for errors
  //! What the decoded file must meet (`self_check`: the file's bytes decoded and measured against the scan
  //! on its face mask); nullopt: not checked (a caller that measures the result itself).
  std::optional<metrics::CheckLimits> check = metrics::CheckLimits{};
  bool force = false; //!< a file that fails its check is returned anyway (`EncodeOutcome::check` says why)
};

struct EncodeOutcome {
  align::Alignment alignment;
  slice::ProfileSet profiles;
  pdef::Face face;
  pdef::Encoded encoded;
  std::optional<metrics::SelfCheck> check; //!< when the request asked for it
};

//! `pdeface encode`: aligned (landmarks detected or from a file), then `encode_aligned`. Errors: those of
//! each stage, naming `request.source`, and `SelfCheck` when the decoded file is off (unless `force`).
[[nodiscard]] Result<EncodeOutcome> encode_request(const Mesh& scan, const EncodeRequest& request);

//! The same with the scan's `alignment` already made (`request.landmarks` unused): sliced, the surface's
//! options resolved, encoded (`pdeface compare` aligns a scan once for all its variants).
[[nodiscard]] Result<EncodeOutcome> encode_aligned(const Mesh& scan, align::Alignment alignment,
                                                   const EncodeRequest& request);

} // namespace pdeface::pipeline
