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
[[nodiscard]] std::optional<Quantised> quantise(const Face& face, const Grid& grid);
//! The face's planes and curves from their values on `grid` (every sample of curve j at x = its plane).
void dequantise(const Quantised& q, const Grid& grid, Face& face);

//! The coarsest grid (steps 0.98^i of the first that keeps every sample within the maximum error) on which
//! the decoded samples and the decoded surface stay within `options.max_error_mm` of the face's
//! (`surface_error`); a face decoded from a lossy file keeps its own grid when that is fine enough.
//! Errors: `InvalidArgument` when the surface cannot be built or no grid fits.
[[nodiscard]] Result<LossyPlan> plan_lossy(const Face& face, const EncodeOptions& options);

//! The largest distance (mm) from the surface `decoded` to the surface `reference`: both evaluated on a grid
//! of 4 points per curve interval across and 8 per sample interval along; each point of `decoded` farther
//! than `below` from the point of `reference` at the same (u, v) is projected onto `reference` (Newton
//! steps), the distance the smaller. Points whose distance cannot exceed `below` are not refined.
[[nodiscard]] double surface_error(const pde::Surface& reference, const pde::Surface& decoded, double below);

} // namespace pdeface::pdef::detail
