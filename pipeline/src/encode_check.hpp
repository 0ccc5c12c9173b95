#pragma once
// The self-check of a written file inside `encode` (encode.cpp): private to pipeline/.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/slice/profiles.hpp"

#include <string_view>

namespace pdeface::pipeline {

//! The spacing (mm) of the encoder's self-check samples, each side: a file is refused for what it is on
//! average (its mean distance, its coverage share) or where it folds, not for one point, so a sample every
//! 1 mm (a quarter of `metrics::FidelityOptions`' 0.5 mm grid) judges it alike at a quarter of the queries.
inline constexpr double kEncodeCheckSpacingMm = 1.0;

//! `metrics::checked` as `encode` runs it: `result` (the file decoded and meshed, canonical frame) measured
//! against `scan` (canonical) on the face mask of `profiles` with samples every `kEncodeCheckSpacingMm`,
//! without the evaluation profiles' errors that the check does not judge. The check, or a `SelfCheck` error
//! naming `source` and what failed when it fails and `force` is false; a result that cannot be measured
//! (no surface in the mask) fails.
[[nodiscard]] Result<metrics::SelfCheck> encode_check(const Mesh& scan, const slice::ProfileSet& profiles,
                                                      const Mesh& result, const metrics::CheckLimits& limits,
                                                      bool force, std::string_view source);

} // namespace pdeface::pipeline
