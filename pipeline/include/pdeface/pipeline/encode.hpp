#pragma once
//! \file
//! A scan as a `.pdef` document: aligned, sliced into curves, the PDE options resolved on them, and the
//! document `pdeface::pdef` encodes filled in (`pdeface encode`, `pdeface convert scan.ply face.pdef`).

#include "pdeface/align/pipeline.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/colour.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/pdef.hpp"
#include "pdeface/slice/profiles.hpp"

#include <array>
#include <optional>
#include <string>

namespace pdeface::pipeline {

//! The document of `profiles` and the `surface` built through them with `options`: the curves
//! (`to_curves`), their planes and filled samples, the frame back to the scan, and the options with the
//! smoothing and mode count the surface used.
[[nodiscard]] pdef::Face to_face(const slice::ProfileSet& profiles, const pde::Surface& surface,
                                 const pde::Options& options);

//! Which distance a target error bounds: the decoded surface → the scan in the face mask (mm), as
//! `pdeface compare` measures it (`MeshFidelity::to_scan`).
enum class TargetMeasure { Mean, P95, Max };
inline constexpr std::array<NamedValue<TargetMeasure>, 3> kTargetMeasureNames{
    {{"mean", TargetMeasure::Mean}, {"p95", TargetMeasure::P95}, {"max", TargetMeasure::Max}}};

//! A residual layer after the curves (`.pdef` version 3, docs/pdef-format.md): the file cut to a size, or
//! the fewest bytes that meet an error measured on the decoded file.
struct ResidualRequest {
  std::optional<std::size_t> size_bytes; //!< the whole file at most this many bytes, the best error
  std::optional<double> target_error_mm; //!< or the fewest bytes whose decoded surface meets this
  TargetMeasure target_measure = TargetMeasure::P95;
  //! The grid's spacing (mm); default by the layer's bytes: 1 mm below 6 KB, 0.5 mm below 12 KB, 0.35 mm
  //! above (0.5 mm for a point cloud; docs/compare.md, "The residual layer"); 0.7 mm for a target error.
  std::optional<double> spacing_mm;
  [[nodiscard]] bool wanted() const { return size_bytes || target_error_mm; }
};

//! The sampling ratio of the curves under a residual layer when the caller names none: the paper's
//! fewest points. The bytes the curves do not take go to the layer, and there they remove more error: on
//! the 24 shared scans the file at every size from 1 to 32 KB lies no further off in the mean on 5 % curves
//! than on 10 % ones (nor, but once, in the 95th percentile), and at 1 KB the layer then also holds the
//! trim (docs/compare.md, "The residual layer").
inline constexpr double kResidualRatio = 0.05;

//! The ratio a request without one takes: `kResidualRatio` under a residual layer, else the profiles'
//! default (10 %).
[[nodiscard]] inline double default_ratio(const ResidualRequest& residual) {
  return residual.wanted() ? kResidualRatio : slice::ProfileOptions{}.ratio;
}

//! What the layer took and, for a target, what the file was measured at.
struct ResidualOutcome {
  double spacing_mm = 0.0;
  std::size_t width = 0, height = 0;
  double found_share = 0.0;                      //!< of the grid's nodes whose normal met the scan
  double trimmed_share = 0.0;                    //!< of the grid's cells the file's trim leaves out
  std::size_t trim_bytes = 0;                    //!< the trim in the file (0: none; docs/pdef-format.md)
  std::size_t layer_bytes = 0;                   //!< header and stream in the file
  std::size_t whole_stream = 0;                  //!< the stream coded to its finest step
  std::optional<metrics::MeshFidelity> measured; //!< target: the file's decoded surface measured on the scan
};

//! A texture layer in the file (docs/pdef-format.md, "The texture layer"): the scan's colour (its
//! photograph, else its vertex colours) resampled over the surface's (u, v) domain into one JPEG image.
struct TextureRequest {
  bool wanted = false;
  double texel_mm = 0.5; //!< the texels' spacing on the face (mm)
  int quality = 80;      //!< JPEG quality, 1-100
};

//! What the texture layer took.
struct TextureOutcome {
  std::size_t width = 0, height = 0; //!< texels
  double found_share = 0.0;          //!< of the texels whose normal line met the scan (the rest filled)
  std::size_t bytes = 0;             //!< the JPEG image
  metrics::ColourSource source = metrics::ColourSource::None;
};

struct EncodeRequest {
  align::LandmarkSource landmarks;
  slice::ProfileOptions profiles;
  //! As `reconstruct` builds the surface (physical spacing), so that a lossless file decodes to its mesh.
  pde::Options pde{.spacing = pde::Spacing::Physical};
  pdef::EncodeOptions encoding;
  ResidualRequest residual;     //!< none by default: the curves alone (version 2, ~1 KB)
  TextureRequest texture;       //!< none by default
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
  std::optional<ResidualOutcome> residual; //!< when the request asked for a layer
  std::optional<TextureOutcome> texture;   //!< when the request asked for a texture layer
};

//! `pdeface encode`: aligned (landmarks detected or from a file), then `encode_aligned`. Errors: those of
//! each stage, naming `request.source`, and `SelfCheck` when the decoded file is off (unless `force`).
//! `scan` by value: a scan moved in becomes the canonical one in place (a copy of a 490k-vertex scan was
//! 29 of the 125 MB of heap `encode` peaked at).
[[nodiscard]] Result<EncodeOutcome> encode_request(Mesh scan, const EncodeRequest& request);

//! The same with the scan's `alignment` already made (`request.landmarks` unused): sliced, the surface's
//! options resolved, encoded (`pdeface compare` aligns a scan once for all its variants).
[[nodiscard]] Result<EncodeOutcome> encode_aligned(Mesh scan, align::Alignment alignment,
                                                   const EncodeRequest& request);

} // namespace pdeface::pipeline
