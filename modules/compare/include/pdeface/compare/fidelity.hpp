#pragma once
//! \file
//! How faithful a reconstruction is to its scan (`../shared/docs/method.md` §5): the paper's profile error
//! on the 4 evaluation profiles, and the two-sided surface distance within the face region.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/slice/profiles.hpp"

#include <array>

namespace pdeface::compare {

struct FidelityOptions {
  double sample_spacing_mm = 0.5; //!< surface samples for the distance, on each side
  double depth_margin_mm = 10.0;  //!< the face region reaches this far behind the deepest curve point
};

struct Fidelity {
  //! The paper's profile error (mm) of each evaluation profile, in the order of `ProfileSet::evaluation`
  //! (symmetry, eyes, diagonal up, diagonal down).
  std::array<double, 4> profile_error{};
  double mean_profile_error = 0.0; //!< their mean: the paper's Table I figure
  //! The same measure on the planes of the curves themselves (mean over the curves): what fitting and
  //! resampling each profile to K points lost, without what lies between the curves.
  double curve_error = 0.0;
  metrics::TwoSidedDistance surface; //!< mm, within `face_region`
};

//! The face region the curves describe (canonical frame, mm): x within the border curves, y within the
//! height range, z from `depth_margin_mm` behind the deepest curve point to anything in front. The back of
//! a head, ears and neck fall outside.
[[nodiscard]] Box face_region(const slice::ProfileSet& profiles, double depth_margin_mm);

//! Compares `reconstruction` (canonical frame, e.g. `Reconstruction::canonical`) with `scan` (the scan in
//! the canonical frame) on the planes and region of `profiles`: each evaluation profile of the
//! reconstruction is its front-most cut within the original profile's extent, measured where it exists.
//! Errors: `NoFace` when the reconstruction has no surface on an evaluation plane (it is named),
//! `InvalidArgument` when no sample falls in the region.
[[nodiscard]] Result<Fidelity> measure_fidelity(const Mesh& scan, const slice::ProfileSet& profiles,
                                                const Mesh& reconstruction,
                                                const FidelityOptions& options = {});

} // namespace pdeface::compare
