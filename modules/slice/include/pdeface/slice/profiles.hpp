#pragma once
//! \file
//! The whole slicing stage: a scan in the canonical frame (mesh or point cloud) and its landmarks → the
//! profile curves, fitted and resampled, and the paper's four evaluation profiles.

#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/slice/face_mask.hpp"
#include "pdeface/slice/planes.hpp"
#include "pdeface/slice/profile.hpp"
#include "pdeface/slice/spline.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace pdeface::slice {

//! Where the K points of each fitted curve go.
enum class Sampling {
  //! Evenly in each curve's own spline parameter (`ProfileOptions::parameter`): each curve's points
  //! follow its own shape, but point k of two curves can lie at heights 30 mm apart. The default: best
  //! at the compact ratios (mean surface distance on the six facefuns scans 0.462 / 0.194 mm at 5 / 10 %
  //! against 0.575 / 0.212 for shared heights).
  Parameter,
  //! At the same K heights on every curve, spaced so that the curves' arc length (root mean square over
  //! the curves) advances evenly from one to the next: denser at the nose and lips. Point k of every
  //! curve is at one height, so the PDE joins corresponding points across the face; best from 20 % up
  //! (0.126 / 0.115 / 0.113 mm at 20 / 30 / 60 % against 0.140 / 0.137 / 0.137), and the profile error
  //! keeps falling with the ratio instead of levelling off.
  SharedHeights,
  //! Between the two: each curve's K heights follow the arc length of the curves near it (weighted by a
  //! Gaussian of `ProfileOptions::sampling_window_mm` across the face), so that neighbouring curves put
  //! point k at nearly the same height (no shear between them) while curves far apart may differ.
  LocalHeights,
};
//! "local_heights" (or "local"), "parameter", "shared_heights" (or "shared").
inline constexpr std::array<NamedValue<Sampling>, 5> kSamplingNames{
    {{"local_heights", Sampling::LocalHeights},
     {"local", Sampling::LocalHeights},
     {"parameter", Sampling::Parameter},
     {"shared_heights", Sampling::SharedHeights},
     {"shared", Sampling::SharedHeights}}};
[[nodiscard]] std::string_view to_string(Sampling sampling) noexcept;

//! How the K samples of a curve are made from its profile.
enum class Fit {
  //! The profile's least-squares cosine fit, sampled (`cosine_samples`): what the PDE surface draws through
  //! the samples is the best it can draw of the profile.
  Cosine,
  //! The least-squares cubic spline, sampled (`fit_spline`); the surface's cosine interpolant only
  //! approximates the spline between the samples.
  Spline,
};
inline constexpr std::array<NamedValue<Fit>, 2> kFitNames{{{"cosine", Fit::Cosine}, {"spline", Fit::Spline}}};
[[nodiscard]] std::string_view to_string(Fit fit) noexcept;

struct ProfileOptions {
  PlaneOptions planes;
  SectionOptions section; //!< its `max_gap_mm` is set from `max_hole_mm`
  //! K = round(ratio · `reference_points`), within the paper's 5 %–60 %
  double ratio = 0.10;
  //! The raw points per profile the ratio refers to: the paper's "about 300" (its scans had 12k–51k
  //! vertices). A fixed reference keeps K, and the size of the representation, independent of how densely
  //! a scanner sampled the face (3k to 500k vertices).
  std::size_t reference_points = 300;
  std::optional<std::size_t> points;          //!< K given directly (at least 4), instead of the ratio
  Parameter parameter = Parameter::ArcLength; //!< how each curve is fitted
  Sampling sampling = Sampling::LocalHeights;
  Fit fit = Fit::Cosine;
  //! The most the curves may span: the face mask (`face_mask`) grown by these factors across and along
  //! (its chin and forehead ends, its cheeks), so that the curves cover the mask with room to spare.
  double region_across = 1.2;
  double region_along = 1.08;
  //! The longest hole (along a curve) filled; longer ones end the curve. Default: `hole_fraction` of the
  //! face mask's height (chin to forehead): eyes, an open mouth, capture gaps.
  std::optional<double> max_hole_mm;
  double hole_fraction = 0.25;
  //! A curve that ends short of curves on both sides of it, within this fraction of the face mask's height
  //! across, is extended to the shorter side's reach and the stretch filled (a hole at its end).
  double notch_fraction = 0.1;
  //! A curve's ends below the mouth and above the eyes stop where the surface turns away from the viewer
  //! (falls back more steeply than this from the curve's plane's y axis: under the chin, the jaw).
  double max_turn_deg = 70.0;
  //! Refused when the scan has surface on less than this share of the face mask.
  double min_mask_coverage = 0.5;
  double fill_step_mm = 1.0;        //!< holes are filled on a grid of this step along the curves
  double sampling_window_mm = 10.0; //!< `Sampling::LocalHeights`: the Gaussian's σ across the face
  //! Shared and local heights: each radian a curve turns counts as this many mm of its length when the
  //! samples are spaced, so that they crowd where profiles bend (lips, nose) as well as where they are
  //! long. 3 mm: the smallest coverage of the shared scans' face masks at 10 % rises from 97.1 to 97.4 %
  //! and the mean scan → reconstruction distance in them falls from 0.179 to 0.168 mm.
  double turn_weight_mm = 3.0;
};

//! One profile curve of the layout.
struct ProfileCurve {
  std::size_t index = 0; //!< 0 .. curves − 1, ascending x (the face's right to its left)
  double x = 0.0;        //!< the plane x = `x` (mm, canonical frame)
  PlaneRole role = PlaneRole::Joint;
  std::string feature;
  //! The profile before fitting, bottom to top: the scan's front-most section and, in its holes, the
  //! filled points.
  std::vector<Vec3> raw;
  std::vector<Vec3> points;                 //!< K points of the fitted spline, bottom to top
  std::vector<bool> filled;                 //!< per point of `points`: it lies in a filled hole
  std::array<double, 2> extent{};           //!< the heights the curve spans: [bottom, top] (mm)
  std::array<ReachEnd, 2> ends{};           //!< why the bottom and the top are where they are
  std::vector<std::array<double, 2>> holes; //!< heights [from, to] where the scan had no surface: filled
  std::size_t surface_points = 0;           //!< points of `raw` from the scan (the rest were filled)
  std::size_t bridged = 0;                  //!< holes filled (`holes.size()`)
  double longest_bridge_mm = 0.0;           //!< the longest of them (mm)
};

//! A profile of the original scan to measure a reconstruction against (the paper's §V).
struct EvaluationProfile {
  std::string name; //!< "symmetry", "eyes", "diagonal_up", "diagonal_down"
  Plane plane;      //!< canonical frame
  Vec3 along;       //!< the direction the points ascend along
  std::vector<Vec3> points;
  //! Stretches along `along` where the scan has no surface (holes): the points on either side are not
  //! joined there.
  std::vector<std::array<double, 2>> gaps;
};

//! The face region the curves span: between the border curves, each curve over its own extent, linearly
//! in between (canonical frame, mm).
struct CurveRegion {
  std::vector<double> xs;                                //!< the curves' planes, ascending
  std::vector<std::array<double, 2>> extents;            //!< their [bottom, top]
  std::vector<std::vector<std::array<double, 2>>> holes; //!< their filled holes (heights)
  //! The heights [bottom, top] the region spans at `x`; nullopt outside the border curves.
  [[nodiscard]] std::optional<std::array<double, 2>> heights_at(double x) const;
  [[nodiscard]] bool contains(double x, double y) const {
    const auto h = heights_at(x);
    return h && y >= (*h)[0] && y <= (*h)[1];
  }
  //! Whether (x, y) lies in a filled hole: in the holes of the two curves around x, weighted by nearness,
  //! half or more.
  [[nodiscard]] bool filled_at(double x, double y) const;
  //! Along the line o + t·d (x–y plane), the stretch [t0, t1] of t around t = 0 inside the region (empty,
  //! t0 > t1, when o is outside).
  [[nodiscard]] std::array<double, 2> span_along(const Eigen::Vector2d& o, const Eigen::Vector2d& d) const;
};

//! Everything the slicing stage produces (canonical frame, mm).
struct ProfileSet {
  std::vector<ProfileCurve> curves;
  std::vector<EvaluationProfile> evaluation;
  std::array<double, 2> height_range{}; //!< the lowest bottom and the highest top of the curves
  std::array<double, 2> border{};       //!< |x| of the border curves on the face's right and left
  double border_mm = 0.0;               //!< the larger of the two
  double central_width_mm = 0.0;
  double eye_height_mm = 0.0; //!< the eye evaluation profile's height: mean of the four eye corners
  FaceMask mask;              //!< the face's outline from its landmarks
  align::FaceFrame frame;     //!< scan → canonical, to map results back into the scan
  Parameter parameter = Parameter::ArcLength;
  Sampling sampling = Sampling::Parameter;
  Fit fit = Fit::Cosine;
  //! `SharedHeights`: the K relative heights (0 at a curve's bottom, 1 at its top) every curve is sampled at
  //! (`LocalHeights`: those of the middle curve; each curve has its own)
  std::vector<double> heights;
  std::size_t k = 0;                //!< points per fitted curve
  std::size_t reference_points = 0; //!< the raw points per profile the ratio refers to
  std::size_t raw_points = 0;       //!< the median raw point count of the curves (the scan's density)
  double ratio = 0.0;               //!< k / reference_points
  bool point_cloud = false;
  double spacing_mm = 0.0;      //!< point clouds: the median point spacing used
  double max_hole_mm = 0.0;     //!< the longest hole that could be filled
  double filled_fraction = 0.0; //!< the share of the curves' length that was filled (holes)
  double mask_coverage = 0.0;   //!< the share of the face mask where the scan has surface
  //! What the scan lacks of the face, in words ("the chin: the scan ends up to 12.0 mm above the face's
  //! outline between x = -20.1 and 18.5 mm"); empty when the curves cover the whole mask.
  std::vector<std::string> missing;

  [[nodiscard]] CurveRegion region() const;
  //! The curves' holes in all: how many, and the longest (mm).
  [[nodiscard]] std::size_t holes() const;
  [[nodiscard]] double longest_hole_mm() const;
};

//! The sampling ratio range of the paper.
inline constexpr double kMinRatio = 0.05;
inline constexpr double kMaxRatio = 0.60;

//! The whole stage on a scan in the canonical frame (`align::to_canonical`) with its landmarks in that
//! frame; `frame` is recorded in the result. Each curve spans its own extent: from a seed at the nose
//! tip's height down and up along its plane's front-most section while there is surface (holes up to
//! `max_hole_mm` crossed), within the region (the face mask grown), below the mouth and above the eyes
//! stopping where the surface turns away; extents are then kept from changing faster across the curves
//! than the region's outline does. Holes inside a curve are filled from the curve and its neighbours (a
//! thin-plate fill on the curves' grid) and recorded. Errors: `InvalidArgument` (ratio outside 5–60 %,
//! K < 4, curve count), `NoFace` for missing landmarks, a plane the scan cannot supply ("plane 3 (x =
//! -41.2 mm, outer eye corner (right)): ...") or a face mostly missing.
[[nodiscard]] Result<ProfileSet> extract_profiles(const Mesh& canonical, const align::Landmarks& landmarks,
                                                  const align::FaceFrame& frame,
                                                  const ProfileOptions& options = {});

} // namespace pdeface::slice
