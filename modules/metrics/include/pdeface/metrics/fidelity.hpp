#pragma once
//! \file
//! How faithful a reconstruction is to its scan (`docs/method.md`, "Measuring how faithful it is"): the
//! paper's profile error on the 4 evaluation profiles, and the two-sided surface distance within the face
//! region.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/slice/profiles.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace pdeface::metrics {

struct FidelityOptions {
  double sample_spacing_mm = 0.5; //!< surface samples for the distance, on each side
  double depth_margin_mm = 10.0;  //!< the face region reaches this far behind the deepest curve point
  double covered_within_mm = 1.0; //!< coverage: a sample of the scan's face this near the reconstruction
  //! Coverage: samples of the scan more than this behind its front-most surface (seen from the front: the
  //! inside of the mouth and nostrils, behind the eyelids) are hidden, not the face.
  double front_tolerance_mm = 2.0;
};

//! How much of a scan's face (the landmark mask, `slice::face_mask`) a reconstruction covers.
struct Coverage {
  double share = 0.0;              //!< of the face's samples within `covered_within_mm` of the reconstruction
  metrics::DistanceStats distance; //!< scan → reconstruction, inside the mask (mm)
};

struct Fidelity {
  //! The paper's profile error (mm) of each evaluation profile, in the order of `ProfileSet::evaluation`
  //! (symmetry, eyes, diagonal up, diagonal down), where the scan has surface.
  std::array<double, 4> profile_error{};
  double mean_profile_error = 0.0; //!< their mean: the paper's Table I figure
  //! The same measure on the planes of the curves themselves (mean over the curves): what fitting and
  //! resampling each profile to K points lost, without what lies between the curves.
  double curve_error = 0.0;
  //! mm, within `face_region`; `a_to_b` is scan → reconstruction (the scan's front-most surface: what is
  //! hidden behind it, the inside of the mouth and nostrils, is not the face), `b_to_a` reconstruction →
  //! scan except over the holes the curves filled (the scan has nothing there to compare with).
  metrics::TwoSidedDistance surface;
  Coverage coverage; //!< of the face mask, which does not depend on the reconstruction's own region
};

//! The face region the curves describe (canonical frame, mm): within the curves' region (`CurveRegion`: each
//! curve's extent, linearly in between), from `depth_margin_mm` behind the deepest curve point to anything
//! in front. The back of a head, ears and neck fall outside.
struct FaceRegion {
  slice::CurveRegion curves;
  double min_z = 0.0;
  [[nodiscard]] bool contains(const Vec3& p) const { return p.z() >= min_z && curves.contains(p.x(), p.y()); }
};
[[nodiscard]] FaceRegion face_region(const slice::ProfileSet& profiles, double depth_margin_mm);

//! The share of `scan`'s face within `options.covered_within_mm` of `reconstruction`, and the distances
//! (both canonical, mm). The face is the scan's front-most surface seen through `mask`, a point every
//! `options.sample_spacing_mm` across and along it: the share is of the mask's front-view area, so surface
//! turning away from the viewer counts for the area it shows. Errors: `InvalidArgument` when the scan has
//! no surface in the mask.
[[nodiscard]] Result<Coverage> measure_coverage(const Mesh& scan, const slice::FaceMask& mask,
                                                const Mesh& reconstruction,
                                                const FidelityOptions& options = {});

//! Compares `reconstruction` (canonical frame, e.g. `Reconstruction::canonical`) with `scan` (the scan in
//! the canonical frame) on the planes and region of `profiles`: each evaluation profile of the
//! reconstruction is its front-most cut within the original profile's extent, measured where the scan has
//! surface; and the coverage of the face mask (`profiles.mask`).
//! Errors: `NoFace` when the reconstruction has no surface on an evaluation plane (it is named),
//! `InvalidArgument` when no sample falls in the region.
[[nodiscard]] Result<Fidelity> measure_fidelity(const Mesh& scan, const slice::ProfileSet& profiles,
                                                const Mesh& reconstruction,
                                                const FidelityOptions& options = {});

//! How close any mesh claiming to be a scan is to it (a decoded Draco file, a decimated mesh, a PDE surface),
//! judged on the scan's face mask so that every kind of result meets the same yardstick (canonical frame,
//! mm).
struct MeshFidelity {
  Coverage coverage; //!< the scan's face (mask) → the mesh: share within `covered_within_mm`, distances
  //! The mesh → the scan: the mesh's samples inside the mask where the scan has surface (seen from the
  //! front), so that a hole the mesh fills and the scan lacks is not counted against it.
  metrics::DistanceStats to_scan;
  //! The paper's profile error on the 4 evaluation profiles (`Fidelity::profile_error`); NaN on a plane
  //! where the mesh has no surface.
  std::array<double, 4> profile_error{};
  double mean_profile_error = 0.0; //!< their mean (NaN when one is)
};

//! The scan's side of `MeshFidelity`, made once and shared by every mesh measured against it: the scan's
//! front-most samples inside the face mask, the scan's distance hierarchy and what it shows from the front,
//! and the evaluation profiles. A class because it caches that work; copies share it. Thread-safe.
class FaceYardstick {
public:
  //! `scan` (canonical frame, mm) with its profiles (`profiles.mask`, `profiles.evaluation`). Errors:
  //! `InvalidArgument` when no sample of the scan lies in the mask or the evaluation profiles are not 4.
  [[nodiscard]] static Result<FaceYardstick> make(const Mesh& scan, const slice::ProfileSet& profiles,
                                                  const FidelityOptions& options = {});

  //! Every measure of `mesh` (canonical frame, mm). Errors: `InvalidArgument` for an empty mesh.
  [[nodiscard]] Result<MeshFidelity> measure(const Mesh& mesh) const;
  //! The mean scan → `mesh` distance in the mask over every `stride`-th sample: a quick, unbiased
  //! estimate of `measure(mesh)->coverage.distance.mean` for searches (mm).
  [[nodiscard]] double quick_mask_mean(const Mesh& mesh, std::size_t stride = 8) const;
  //! The distance from `p` to the scan's surface (mm).
  [[nodiscard]] double distance_to_scan(const Vec3& p) const;
  [[nodiscard]] const slice::FaceMask& mask() const;

private:
  struct State;
  explicit FaceYardstick(std::shared_ptr<const State> state) : state_(std::move(state)) {}
  std::shared_ptr<const State> state_;
};

//! The share of `mesh`'s area inside `mask` (canonical frame) whose triangles face away from the viewer
//! (normal · z < 0, with the winding the PDE surface and every reader keep: counter-clockwise seen from the
//! front): a surface folded back over itself. 0 for a mesh without triangles or without area in the mask.
[[nodiscard]] double facing_away(const Mesh& mesh, const slice::FaceMask& mask);

//! What a result must meet to be written (`self_check`). Every figure is judged on the face mask, which
//! comes from the landmarks and the scan (`slice::profile_planes`), not from the curves' own region. The
//! defaults pass every shared scan at every ratio of 5–60 % with room to spare (docs/pipeline.md,
//! "Self-check") and refuse a surface folded over a head, sliced off the face or badly aligned.
struct CheckLimits {
  double max_mean_mm = 1.0; //!< the result's mean distance to the scan inside the mask
  //! The scan's face within `FidelityOptions::covered_within_mm` of the result: at least this share.
  double min_coverage = 0.75;
  double max_facing_away = 0.002; //!< the share of the result's area in the mask facing away (`facing_away`)
};

//! A result measured against its scan, and what it failed.
struct SelfCheck {
  double mean_mm = 0.0;              //!< result → scan inside the mask (mm)
  double coverage = 0.0;             //!< the scan's face within 1 mm of the result (share)
  double facing_away = 0.0;          //!< share of the result's area in the mask facing away from the viewer
  std::vector<std::string> failures; //!< "mean distance 12.981 mm > 0.6 mm", ...; empty when it passed
  [[nodiscard]] bool passed() const { return failures.empty(); }
  //! The failures joined ("...; ..."), or the figures when it passed.
  [[nodiscard]] std::string summary() const;
};

//! The figures of `fidelity` and the `facing_away` share of the result judged against `limits`.
[[nodiscard]] SelfCheck self_check(const MeshFidelity& fidelity, double facing_away,
                                   const CheckLimits& limits = {});

//! `result` (canonical frame, mm) measured on `yardstick` and judged. Errors: those of
//! `FaceYardstick::measure`.
[[nodiscard]] Result<SelfCheck> self_check(const FaceYardstick& yardstick, const Mesh& result,
                                           const CheckLimits& limits = {});

//! `result` (canonical frame, mm) checked against `scan` (canonical) on the face mask of `profiles`: the
//! check, or a `SelfCheck` error naming `source` and what failed when it fails and `force` is false. A
//! result that cannot be measured at all (no surface in the mask) fails.
[[nodiscard]] Result<SelfCheck> checked(const Mesh& scan, const slice::ProfileSet& profiles,
                                        const Mesh& result, const CheckLimits& limits, bool force,
                                        std::string_view source);

} // namespace pdeface::metrics
