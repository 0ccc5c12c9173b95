#pragma once
//! \file
//! The profile of one plane: the front-most part of a scan's cut, ordered, holes bridged, clipped to a
//! range. Works on meshes (the polylines of `intersect`) and on point clouds (a thin slab of points).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/slice/intersect.hpp"

#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pdeface::slice {

//! How a profile is read off a plane. `along` orders the profile (height, +y, for the 28 curves) and
//! `front` is the direction it is seen from (+z, towards the viewer); both lie in the plane.
struct ProfileAxes {
  Vec3 along = Vec3::UnitY();
  Vec3 front = Vec3::UnitZ();
};

struct SectionOptions {
  double max_gap_mm = 8.0;  //!< holes up to this long (along the profile's axis) are bridged linearly
  double slab_factor = 1.5; //!< point clouds: half-width of the slab, in median point spacings
  double spacing_mm = 0.0;  //!< point clouds: the median point spacing (0: measured by `sections`)
  //! A height whose front-most surface lies more than `hidden_depth_mm` behind the front within a reach
  //! both above and below is hidden, a gap and not the profile: in a point cloud (reach
  //! `hidden_reach_mm`), a sparse cloud's front surface missed by the slab, with an ear or the far side of
  //! the head behind it; in a mesh (reach `max_gap_mm`, the longest hole bridged), a hole through which the
  //! inside of a head, the far side of a bust or the inside of an open mouth shows. Deeper than eye sockets
  //! and the lip under the nose (the nose is in front on one side only).
  double hidden_depth_mm = 20.0;
  double hidden_reach_mm = 10.0;
};

//! What the front of one plane shows: the visible points ordered along the profile's axis, and where
//! along that axis there is surface at all (merged intervals, with the holes between them).
struct Section {
  std::vector<Vec3> points;                 //!< front-most points, ascending along `along`
  std::vector<std::array<double, 2>> cover; //!< ascending, disjoint intervals of `along · p` with surface
};

//! The front-most part of a mesh's cut by one plane (the polylines `intersect` gave for it): a polyline
//! point is kept when nothing on the plane lies in front of it at its height (ears, the far side and
//! hidden folds go), and heights where what is in front lies far behind the surface above and below
//! (`SectionOptions::hidden_depth_mm`) are a gap: what a hole shows of the inside.
[[nodiscard]] Section mesh_section(std::span<const Polyline> cut, const ProfileAxes& axes,
                                   const SectionOptions& options = {});

//! The same for a point cloud: the points within `slab_factor · spacing` of `plane`, projected onto it,
//! the front-most layer kept (points more than 3 spacings behind the front of their neighbourhood go, and
//! heights whose front lies far behind the front above and below them are gaps: `hidden_depth_mm`)
//! and thinned to one point per `spacing` of height (a local linear fit in height and distance to the
//! plane, evaluated on the plane). `spacing` is the median nearest-neighbour distance of the cloud. The
//! cover is half a spacing about each point, and points no further apart than the slab is wide
//! (2 · `slab_factor` · spacing) are one stretch of surface: a hole is a longer stretch without points.
[[nodiscard]] Section cloud_section(std::span<const Vec3> points, const Plane& plane, const ProfileAxes& axes,
                                    double spacing, const SectionOptions& options = {});

//! The sections of a mesh (one pass over it, `intersect`) or of a point cloud (`cloud_section`, with
//! `options.spacing_mm` its point spacing, measured when 0) by `planes`, each read along its `axes`.
//! \pre `axes.size() == planes.size()`.
[[nodiscard]] std::vector<Section> sections(const Mesh& scan, std::span<const Plane> planes,
                                            std::span<const ProfileAxes> axes,
                                            const SectionOptions& options = {});
//! The same for the parallel planes `normal · p = offsets[j]`, all read along `axes`.
[[nodiscard]] std::vector<Section> sections(const Mesh& scan, const Vec3& normal,
                                            std::span<const double> offsets, const ProfileAxes& axes,
                                            const SectionOptions& options = {});

//! The median distance from a point to its nearest neighbour (on up to 2000 points spread over the
//! cloud); 0 for fewer than 2 points.
[[nodiscard]] double point_spacing(std::span<const Vec3> points);

//! The covered interval of `section` that contains `seed` (or starts nearest above it), holes up to
//! `max_gap_mm` bridged; {seed, seed} when nothing is covered.
[[nodiscard]] std::array<double, 2> covered_extent(const Section& section, double seed, double max_gap_mm);

//! The section's surface point at height `u` along `axes.along` (interpolated between its visible points),
//! or nullopt where the section has no surface (outside its cover).
[[nodiscard]] std::optional<Vec3> section_at(const Section& section, const ProfileAxes& axes, double u);

//! How far a walk along a section from a seed may go (`reach`).
struct ReachOptions {
  double limit = 0.0;       //!< the furthest coordinate along the axis the walk may reach
  double max_hole_mm = 8.0; //!< a longer stretch without surface ends it (shorter ones are holes)
  //! From this coordinate on (towards `limit`), the walk also ends where the surface turns away: where it
  //! falls back (against `axes.front`) more steeply than `max_turn_deg` from the axis, over `window_mm`.
  std::optional<double> turn_from;
  double max_turn_deg = 70.0;
  double window_mm = 3.0;
  //! The walk also ends where the surface lies further back (along `axes.front`) than this: behind the
  //! face (hair over the ears, the side and back of a head, the neck under the jaw).
  double min_front = -std::numeric_limits<double>::infinity();
};

//! Why a walk ended.
enum class ReachEnd {
  Limit,      //!< it reached `ReachOptions::limit`
  SurfaceEnd, //!< the surface ends (or the next surface lies beyond a hole longer than allowed)
  TurnsAway,  //!< the surface turns away from the viewer
  Behind,     //!< the surface goes further back than the face (`ReachOptions::min_front`)
};

inline constexpr std::array<NamedValue<ReachEnd>, 4> kReachEndNames{{{"limit", ReachEnd::Limit},
                                                                     {"surface_end", ReachEnd::SurfaceEnd},
                                                                     {"turns_away", ReachEnd::TurnsAway},
                                                                     {"behind", ReachEnd::Behind}}};
[[nodiscard]] std::string_view to_string(ReachEnd end) noexcept;

struct Reach {
  double end = 0.0; //!< the coordinate along the axis where the walk ended
  ReachEnd why = ReachEnd::Limit;
};

//! Walks along `section` from `seed` (moved onto the nearest surface first) in the direction of
//! `options.limit`, across holes up to `options.max_hole_mm`, and says where and why it stopped.
[[nodiscard]] Reach reach(const Section& section, const ProfileAxes& axes, double seed,
                          const ReachOptions& options);

//! The holes of `section` inside [lo, hi]: the stretches without surface between covered ones.
[[nodiscard]] std::vector<std::array<double, 2>> holes_within(const Section& section, double lo, double hi);

//! One profile: points ascending along the axis, from exactly `lo` to exactly `hi`.
struct Profile {
  std::vector<Vec3> points;
  std::size_t bridged = 0;     //!< holes bridged
  double longest_bridge = 0.0; //!< mm
};

//! The part of `section` between heights `lo` and `hi` (along `axes.along`), with end points
//! interpolated at `lo` and `hi` and holes up to `options.max_gap_mm` bridged linearly.
//! Errors: `NoFace` when the surface does not reach `lo` or `hi`, or a hole is longer; the message says
//! where ("the scan has no surface between y = -80 and y = -62 mm ..."), with `axis_name` naming the axis.
[[nodiscard]] Result<Profile> clip(const Section& section, const ProfileAxes& axes, double lo, double hi,
                                   const SectionOptions& options = {}, std::string_view axis_name = "y");

} // namespace pdeface::slice
