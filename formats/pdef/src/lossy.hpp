#pragma once
// The lossy grid: choosing it so that the samples and the surface stay within the maximum error, and the
// samples on it.

#include "codec.hpp"

#include "pdeface/core/result.hpp"
#include "pdeface/pde/surface.hpp"
#include "pdeface/pdef/pdef.hpp"

namespace pdeface::pdef::detail {

struct LossyPlan {
  Grid grid;
  bool frame64 = false;
  Quantised quantised;
  double max_sample_error = 0.0;
  double max_surface_error = 0.0;
  std::size_t tightenings = 0;
};

//! The samples on `grid` (nullopt when one leaves ±kMaxQuantised or the planes stop ascending).
//! y as heights when that is smaller, or (`own`) as the face's storage says it was when it was decoded.
[[nodiscard]] std::optional<Quantised> quantise(const Face& face, const Grid& grid, bool own = false);
//! The face's planes and curves from their values on `grid` (every sample of curve j at x = its plane).
void dequantise(const Quantised& q, const Grid& grid, Face& face);

//! The coarsest grid (steps 0.98^i of the first that keeps every sample within the maximum error, halving
//! after a few failures) on which the decoded samples and the decoded surface stay within
//! `options.max_error_mm` of the face's (`surface_error`); a face decoded from a lossy file keeps its own
//! grid when that is fine enough. The checks are bounded in work whatever the document's size.
//! Errors: `InvalidArgument` when the surface cannot be built, no grid fits, or the document is too large
//! to check.
[[nodiscard]] Result<LossyPlan> plan_lossy(const Face& face, const EncodeOptions& options);

//! The Hausdorff distance (mm) between the surfaces `reference` and `decoded`: both evaluated on a grid of
//! `density` points per curve interval across and per sample interval along (8 on a face: 0.2-0.5 mm
//! apart; the distance between two such surfaces has peaks about 1 mm wide where they bend sharply, so the
//! cells around the highest points are searched again 4 times finer), each point's distance to the other
//! surface estimated by its tangent plane, and the largest projected onto it (damped Gauss-Newton from the
//! same (u, v)), both ways. The search stops as soon as it exceeds `limit`.
[[nodiscard]] double surface_error(const pde::Surface& reference, const pde::Surface& decoded, double limit,
                                   int density);

//! The coarse grid of `surface_error` at `density` and the reference surface's points and tangents on it:
//! the same for every grid `plan_lossy` tries, so made once (3 of the 8 evaluations a check made).
//! \throw std::invalid_argument for a density below 1
struct CheckGrid {
  CheckGrid(const pde::Surface& reference, int density);
  std::vector<double> us, vs;
  pde::Grid x, xu, xv;
};

//! What one check of the decoded surface on the coarse grid fills: kept between the grids `plan_lossy`
//! tries, so that their memory is allocated (and faulted in) once.
struct CheckScratch {
  pde::Grid x, xu, xv;      // the decoded surface's points and tangents
  std::vector<double> e, m; // each point's estimated distance and how far off it may be
};

//! `surface_error` with the reference's side made once (`grid`, made from `reference`).
[[nodiscard]] double surface_error(const pde::Surface& reference, const CheckGrid& grid,
                                   const pde::Surface& decoded, double limit, CheckScratch& scratch);

//! The density `plan_lossy` checks a face of that size with: 8, or fewer for documents so large that the
//! checks would exceed their budget (`columns`: the cosines each point sums); 0 when even one point per
//! interval would.
[[nodiscard]] int check_density(std::size_t curves, std::size_t samples, std::size_t columns);

} // namespace pdeface::pdef::detail
