#pragma once
// The residual layer's steps inside the pipeline (encode.cpp, report.cpp): private to pipeline/.

#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include <string_view>

namespace pdeface::pipeline {

//! `limits` for a file with a residual layer, which follows the scan into its own folds (under the nose, the
//! nostrils, eye sockets): the share of area facing away that the scan itself has in `mask` is allowed on
//! top of `limits.max_facing_away`.
[[nodiscard]] metrics::CheckLimits with_scans_folds(metrics::CheckLimits limits, const Mesh& scan,
                                                    const slice::FaceMask& mask);

//! The residual layer added to `outcome.encoded.bytes` (a curve-only file of `scan`, canonical) as
//! `request` asks (`encode_aligned` calls it). Errors: `InvalidArgument` for a size below the curves'
//! bytes, `SelfCheck` for a target the whole layer does not meet.
[[nodiscard]] Result<ResidualOutcome> add_residual(const CanonicalScan& scan, EncodeOutcome& outcome,
                                                   const ResidualRequest& request, std::string_view source);

} // namespace pdeface::pipeline
