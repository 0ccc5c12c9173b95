#pragma once
//! \file
//! The residual layer of a `.pdef` file (version 3; docs/pdef-format.md, "The residual layer"): the scan's
//! remaining offset along the PDE surface's normal, on a regular grid over the surface's (u, v) domain,
//! wavelet-transformed and coded bit-plane by bit-plane, so that every prefix of the layer decodes to a
//! coarser surface. The geometry (measuring the offsets on a scan) is `modules/residual`'s.

#include "pdeface/core/result.hpp"
#include "pdeface/pde/displacement.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pdef {

//! The finest quantisation step of the layer's wavelet coefficients (mm) unless asked otherwise: far below
//! what any budget reaches, so that a stream is cut by its budget, never by its end.
inline constexpr double kDefaultResidualStep = 1.0 / 2048;
//! The most grid nodes a layer may have without the file's bytes to justify more (a face at 0.25 mm).
inline constexpr std::size_t kFreeResidualNodes = std::size_t{1} << 18;
//! ... and how many more each byte of the file allows.
inline constexpr std::size_t kResidualNodesPerByte = 256;
inline constexpr std::size_t kMaxResidualSide = 4097;

//! A residual layer as decoded: the offsets, its trim, and how much of its streams the file held.
struct Residual {
  pde::Displacement field; //!< offsets along the normal (mm, canonical frame); empty: no stream read
  //! The grid's cells that hold no surface (1), (W − 1) × (H − 1), cell (i, k) between nodes (i, k) and
  //! (i + 1, k + 1) at k·(W − 1) + i; empty: none (a layer without a trim, or none of it held).
  std::vector<std::uint8_t> trimmed;
  std::size_t trim_bytes = 0;      //!< the trim stream's length the layer states (0: no trim)
  std::size_t trim_bytes_read = 0; //!< of it that the file held
  bool trim_complete = false;      //!< the whole trim stream was there (and matched its checksum)
  double step_mm = 0.0;            //!< the coefficients' finest step
  std::size_t levels = 0;          //!< wavelet levels
  std::size_t planes = 0;          //!< bit-planes the stream codes
  std::size_t offset = 0;          //!< where the layer starts in the file
  std::size_t header_bytes = 0;
  std::size_t stream_bytes = 0; //!< the stream's length the layer states
  std::size_t bytes_read = 0;   //!< of it that the file held (fewer: a prefix)
  std::size_t planes_read = 0;  //!< bit-planes reached (the last one partly, unless complete)
  bool complete = false;        //!< the whole stream was there (and matched its checksum)
};

struct ResidualOptions {
  double step_mm = kDefaultResidualStep; //!< the coefficients' finest quantisation step (mm)
  //! The most nodes the grid may have: `kFreeResidualNodes`, or `max_residual_nodes(curves)` for a layer
  //! after a curve-only file of that many bytes.
  std::size_t max_nodes = kFreeResidualNodes;
};

//! The most nodes a layer after a curve-only file of `curves_bytes` may have so that every prefix of the
//! file holding the layer's header decodes (a reader allows 2¹⁸ + 256 per byte it holds; the header's
//! fewest bytes, 16, counted).
[[nodiscard]] constexpr std::size_t max_residual_nodes(std::size_t curves_bytes) {
  return kFreeResidualNodes + kResidualNodesPerByte * (curves_bytes + 16);
}

//! A layer coded whole: its settings and the full embedded streams (`with_residual` cuts them to a budget).
struct CodedResidual {
  std::size_t width = 0, height = 0, levels = 0, planes = 0;
  std::uint32_t step_units = 0; //!< the step in units of 2⁻²⁰ mm
  std::string stream;
  std::string trim; //!< the trim's stream (`code_trim`); empty: a layer without a trim
};

//! How much of a coded layer a file holds: the trim's stream cut to at most `trim_bytes` (the whole by
//! default), then as much of the offsets' stream as the size allows.
struct ResidualCut {
  std::size_t trim_bytes = std::numeric_limits<std::size_t>::max();
};

//! Codes `field` (offsets in mm). Errors: `InvalidArgument` for a grid below 2 × 2, above
//! `kMaxResidualSide` a side or `options.max_nodes` nodes, values that do not match it, or a step outside
//! 2⁻²⁰ … 64 mm; `NonFinite` for a NaN or infinite offset.
[[nodiscard]] Result<CodedResidual> code_residual(const pde::Displacement& field,
                                                  const ResidualOptions& options = {});

//! The trim of a `width` × `height` grid's cells (`trimmed`: (width − 1) × (height − 1), 1 for a cell that
//! holds no surface, as `Residual::trimmed`) as its stream (docs/pdef-format.md, "The trim"); empty when no
//! cell is trimmed. \throw std::invalid_argument for sizes that do not match
[[nodiscard]] std::string code_trim(const std::vector<std::uint8_t>& trimmed, std::size_t width,
                                    std::size_t height);

//! The bytes of a layer's header for a stream cut to `stream_bytes` and a trim cut to `trim_bytes` (each at
//! most the whole).
[[nodiscard]] std::string residual_header(const CodedResidual& layer, std::size_t stream_bytes,
                                          std::size_t trim_bytes = std::numeric_limits<std::size_t>::max());

//! A version 3 file: `curves_file` (a file `encode` made: version 2, no layer) with `layer` after it, cut so
//! that the whole file takes at most `max_bytes`: the trim's stream first (at most `cut.trim_bytes` of it),
//! then the offsets' stream. Errors: `InvalidArgument` when `curves_file` is not a version 2 file or
//! `max_bytes` cannot hold it and the layer's header.
[[nodiscard]] Result<std::string> with_residual(std::string_view curves_file, const CodedResidual& layer,
                                                std::size_t max_bytes, const ResidualCut& cut = {});

//! The offsets a whole layer decodes to (what a reader of the file with all of its stream gets), for an
//! encoder that measures them; `stream_bytes` cuts the stream first.
[[nodiscard]] pde::Displacement decode_residual(const CodedResidual& layer, std::size_t stream_bytes);

} // namespace pdeface::pdef
