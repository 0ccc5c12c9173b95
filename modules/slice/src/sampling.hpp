#pragma once
// Where each fitted curve's K samples go and the samples themselves: evenly in each curve's own parameter,
// or at heights shared by all the curves or by the curves near each one, spaced so that the curves' length
// (and turning) advances evenly; then the profile's least-squares cosine fit (or its spline) sampled there.

#include "pdeface/slice/profiles.hpp"

#include <span>
#include <vector>

namespace pdeface::slice::detail {

struct CurveSamples {
  std::vector<std::vector<Vec3>> points; //!< per curve, K samples bottom to top
  std::vector<double> heights;           //!< shared or local heights: those of the middle curve
};

//! The K samples of every curve of `curves` (their `raw` profiles, extents and planes) under `options`'
//! parameter, sampling and fit. Errors: a fit that fails, naming the curve.
[[nodiscard]] Result<CurveSamples> sample_curves(std::span<const ProfileCurve> curves, std::size_t k,
                                                 const ProfileOptions& options);

} // namespace pdeface::slice::detail
