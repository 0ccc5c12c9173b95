#pragma once
//! \file
//! The whole slicing stage: a scan in the canonical frame (mesh or point cloud) and its landmarks → the
//! profile curves, fitted and resampled, and the paper's four evaluation profiles.

#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
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
};
[[nodiscard]] std::string_view to_string(Sampling sampling) noexcept;

struct ProfileOptions {
  PlaneOptions planes;
  SectionOptions section;
  double ratio = 0.10;               //!< K = round(ratio · raw points), within the paper's 5 %–60 %
  std::optional<std::size_t> points; //!< K given directly (at least 4), instead of the ratio
  Parameter parameter = Parameter::ArcLength; //!< how each curve is fitted
  Sampling sampling = Sampling::Parameter;
  double core_margin_mm =
      10.0; //!< the profiles must span from the mouth corners less this to the eyes plus this
};

//! One profile curve of the layout.
struct ProfileCurve {
  std::size_t index = 0; //!< 0 .. curves − 1, ascending x (the face's right to its left)
  double x = 0.0;        //!< the plane x = `x` (mm, canonical frame)
  PlaneRole role = PlaneRole::Joint;
  std::string feature;
  std::vector<Vec3> raw;    //!< the profile before fitting: bottom (y_bottom) to top (y_top)
  std::vector<Vec3> points; //!< K points of the fitted spline, uniform in its parameter, bottom to top
  std::size_t bridged = 0;  //!< holes bridged
  double longest_bridge_mm = 0.0;
};

//! A profile of the original scan to measure a reconstruction against (the paper's §V).
struct EvaluationProfile {
  std::string name; //!< "symmetry", "eyes", "diagonal_up", "diagonal_down"
  Plane plane;      //!< canonical frame
  Vec3 along;       //!< the direction the points ascend along
  std::vector<Vec3> points;
};

//! Everything the slicing stage produces (canonical frame, mm).
struct ProfileSet {
  std::vector<ProfileCurve> curves;
  std::vector<EvaluationProfile> evaluation;
  std::array<double, 2> height_range{}; //!< y_bottom, y_top: every curve spans exactly this
  double border_mm = 0.0;               //!< the curves span x ∈ [−border, border]
  double central_width_mm = 0.0;
  double eye_height_mm = 0.0; //!< the eye evaluation profile's height: mean of the four eye corners
  align::FaceFrame frame;     //!< scan → canonical, to map results back into the scan
  Parameter parameter = Parameter::ArcLength;
  Sampling sampling = Sampling::Parameter;
  std::vector<double> heights;      //!< `SharedHeights`: the K heights every curve is sampled at (mm)
  std::size_t k = 0;                //!< points per fitted curve
  std::size_t reference_points = 0; //!< the median raw point count of the curves
  double ratio = 0.0;               //!< k / reference_points
  bool point_cloud = false;
  double spacing_mm = 0.0; //!< point clouds: the median point spacing used
};

//! The sampling ratio range of the paper.
inline constexpr double kMinRatio = 0.05;
inline constexpr double kMaxRatio = 0.60;

//! The four evaluation profiles: the symmetry profile (x = 0, ascending y over `height_range`), the
//! cross-section through the eyes (y = `eye_height`, ascending x over [−border, border]) and the two
//! diagonals through the nose tip (planes holding the z axis and (1, ±1, 0)/√2, within the same
//! rectangle). Errors: `NoFace` naming the profile when the scan cannot supply it.
[[nodiscard]] Result<std::vector<EvaluationProfile>> evaluation_profiles(const Mesh& canonical,
                                                                         std::array<double, 2> height_range,
                                                                         double border_mm, double eye_height,
                                                                         const SectionOptions& section = {});

//! The whole stage on a scan in the canonical frame (`align::to_canonical`) with its landmarks in that
//! frame; `frame` is recorded in the result. The height range is the target of `options.planes`
//! (default: the face's bottom and top landmarks) narrowed to where every plane's surface ends (never
//! across a hole), and must still reach from the mouth to above the eyes.
//! Errors: `InvalidArgument` (ratio outside 5–60 %, K < 4, curve count, missing landmarks), `NoFace`
//! naming the plane that the scan cannot supply ("plane 3 (x = -41.2 mm, outer eye corner (right)): ...").
[[nodiscard]] Result<ProfileSet> extract_profiles(const Mesh& canonical, const align::Landmarks& landmarks,
                                                  const align::FaceFrame& frame,
                                                  const ProfileOptions& options = {});

} // namespace pdeface::slice
