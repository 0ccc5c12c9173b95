#pragma once
// The residual layer's steps inside the pipeline (encode.cpp, report.cpp): private to pipeline/.

#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include "pdeface/pdef/residual.hpp"

#include <map>
#include <string_view>

namespace pdeface::pipeline {

//! `limits` for a file with a residual layer, which follows the scan into its own folds (under the nose, the
//! nostrils, eye sockets): the share of area facing away that the scan itself has in `mask` is allowed on
//! top of `limits.max_facing_away`.
[[nodiscard]] metrics::CheckLimits with_scans_folds(metrics::CheckLimits limits, const Mesh& scan,
                                                    const slice::FaceMask& mask);

//! The residual layers of one curve-only file measured and coded at each grid spacing so far, shared by
//! the files cut from it at several sizes (`pdeface compare`'s `pde 10 % + residual B` rows: one grid for
//! every size below 6 KB, not one each). Not thread-safe: its user locks it.
struct ResidualGrids {
  struct Grid {
    double spacing_mm = 0.0; //!< as made: the spacing asked, coarsened when the grid had too many nodes
    std::size_t width = 0, height = 0;
    double found_share = 0.0;
    double trimmed_share = 0.0; //!< of the grid's cells
    pdef::CodedResidual coded;
    double made_ms = 0.0; //!< what measuring and coding it took
  };
  std::map<double, Grid> by_spacing; //!< by the spacing the grid was asked at (before any coarsening)
};

//! The residual layer added to `outcome.encoded.bytes` (a curve-only file of `scan`, canonical) as
//! `request` asks (`encode_aligned` calls it). With `grids`, made for the same curve-only file: a grid
//! measured and coded there is taken from it, one made here is left in it (the bytes are the same either
//! way). Errors: `InvalidArgument` for a size below the curves' bytes, `SelfCheck` for a target the whole
//! layer does not meet.
[[nodiscard]] Result<ResidualOutcome> add_residual(const CanonicalScan& scan, EncodeOutcome& outcome,
                                                   const ResidualRequest& request, std::string_view source,
                                                   ResidualGrids* grids = nullptr);

//! The first steps of `encode_aligned`: the canonical scan sliced as `request.profiles` asks and the PDE
//! surface solved through the curves (`request.pde`), shared by the lossy and lossless files at one ratio.
struct SlicedScan {
  slice::ProfileSet profiles;
  pde::Surface surface;
};
[[nodiscard]] Result<SlicedScan> slice_and_solve(const CanonicalScan& canonical,
                                                 const EncodeRequest& request);

//! The rest of `encode_aligned` but the check: the document filled from `sliced`, encoded as
//! `request.encoding` asks, and the residual layer `request.residual` asks added (through `grids`, as in
//! `add_residual`). `encode_aligned` is `canonical_scan`, `slice_and_solve`, this, then the check, so a
//! file made here is the same byte for byte.
[[nodiscard]] Result<EncodeOutcome> encode_sliced(const CanonicalScan& canonical, align::Alignment alignment,
                                                  const SlicedScan& sliced, const EncodeRequest& request,
                                                  ResidualGrids* grids = nullptr);

} // namespace pdeface::pipeline
