#pragma once
//! \file
//! Least-squares cubic B-spline fitting of a profile, and its resampling to K points.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/core/result.hpp"

#include <array>
#include <span>
#include <vector>

namespace pdeface::slice {

//! What the spline's parameter t ∈ [0, 1] follows along the raw points.
enum class Parameter {
  ArcLength, //!< normalised chord length of the raw polyline: points equally spaced along the curve
  Height,    //!< normalised height (`SplineOptions::along`): equal t is equal height on every curve
};

//! "arc_length" (or "arc") and "height".
inline constexpr std::array<NamedValue<Parameter>, 3> kParameterNames{
    {{"arc_length", Parameter::ArcLength}, {"arc", Parameter::ArcLength}, {"height", Parameter::Height}}};
[[nodiscard]] std::string_view to_string(Parameter parameter) noexcept;

struct SplineOptions {
  Parameter parameter = Parameter::ArcLength;
  std::size_t controls = 30;  //!< control points (at least 4); the pipeline uses K, the resampled count
  Vec3 along = Vec3::UnitY(); //!< the height axis, for `Parameter::Height`
  double smoothing = 1e-9;    //!< weight of a second-difference penalty on the control points,
                              //!< relative to the data term: keeps spans without data well defined
};

//! A clamped cubic B-spline on uniform knots over t ∈ [0, 1] (value type).
class Spline {
public:
  //! \pre at least 4 control points.
  explicit Spline(std::vector<Vec3> controls);

  //! The point at t (clamped to [0, 1]).
  [[nodiscard]] Vec3 evaluate(double t) const;
  //! K points at t_k = k / (K − 1), k = 0..K−1 (v_k = kπ / (K − 1) on the PDE's [0, π]). \pre K ≥ 2.
  [[nodiscard]] std::vector<Vec3> resample(std::size_t k) const;
  [[nodiscard]] const std::vector<Vec3>& controls() const noexcept { return controls_; }

private:
  std::vector<Vec3> controls_;
};

//! The parameter values of `points` under `options.parameter`, from 0 to 1 (empty if they do not
//! advance: all at one height, or all one point).
[[nodiscard]] std::vector<double> parameters(std::span<const Vec3> points, const SplineOptions& options);

//! The least-squares cubic spline with `options.controls` control points through the ordered `points`,
//! taken as a polyline: a chord longer than half a knot span (a bridged hole, a jump where the front
//! switches surfaces) contributes points along it, so more control points than points is allowed. It
//! passes exactly through the first and last points (its end control points), so curves clipped to one
//! height range keep it after fitting.
//! Errors: `InvalidArgument` when there are fewer than 4 control points or the points do not advance
//! along the parameter.
[[nodiscard]] Result<Spline> fit_spline(std::span<const Vec3> points, const SplineOptions& options = {});

//! K samples of the ordered `points` (a polyline) whose cosine interpolant is the polyline's least-squares
//! cosine fit. Sample k stands at the polyline's parameter `at[k]` (under `options.parameter`; ascending,
//! from 0 to 1) and at v_k = kπ/(K − 1) of the cosine series X(v) = Σ_n α_n cos(n v), n = 0..K − 1, which
//! is how the PDE surface runs along a curve between its samples (the DCT-I that passes through them): the
//! series is fitted to the polyline with v following the parameter piecewise linearly through (at[k], v_k),
//! and evaluated at the v_k. Its ends are held to the polyline's ends. The samples then lose less of the
//! profile than samples of a spline, which the cosine interpolant would only approximate.
//! Errors: `InvalidArgument` when the points do not advance along the parameter or `at` is not ascending
//! from 0 to 1 with at least 4 entries.
[[nodiscard]] Result<std::vector<Vec3>>
cosine_samples(std::span<const Vec3> points, std::span<const double> at, const SplineOptions& options = {});

//! The same at given heights (mm, ascending, one per parameter): sample k is at exactly y = heights[k], and
//! the series is fitted with y following the heights' own cosine interpolant h(v) (the series the surface
//! follows in y between the samples): each point of the polyline the parameter puts at v is moved along the
//! polyline to height h(v). Samples at heights a `.pdef` knows cost it almost nothing but their depth.
//! Errors: those above, and `InvalidArgument` when the heights do not ascend or are not one per parameter.
[[nodiscard]] Result<std::vector<Vec3>> cosine_samples(std::span<const Vec3> points,
                                                       std::span<const double> at,
                                                       std::span<const double> heights,
                                                       const SplineOptions& options = {});

} // namespace pdeface::slice
