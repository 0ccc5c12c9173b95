#pragma once
//! \file
//! The PDE surface through a set of profile curves: `(∂²/∂u² + a² ∂²/∂v²)² X = 0`, solved mode by mode.
//!
//! Input: J curves, each K points in 3D sampled at v_k = kπ/(K−1), curve j at U_j. Every coordinate of
//! every curve is expanded in cosines (`cosine_coefficients`); each mode n is solved in u exactly
//! (`modes.hpp`) by one of three schemes; modes beyond the chosen N form the remainder R, solved with the
//! frequency of mode N+1, so that every curve is still met at every sample. The surface caches its
//! per-mode coefficients: evaluating it at any resolution is a dense matrix product (even and odd modes
//! apart on grids symmetric in v, which halves it).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/names.hpp"
#include "pdeface/core/result.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace pdeface::pde {

//! K samples of one curve, one row per sample (x, y, z), at v_k = kπ/(K−1).
using Curve = Eigen::Matrix<double, Eigen::Dynamic, 3>;

//! The most samples per curve a surface accepts: the cosine transform costs O(K²) per curve, so curves read
//! from a file must not be able to make it hang (profiles are resampled to ~15-300 points).
inline constexpr std::size_t max_samples = 4097;

//! The curves a surface goes through, in order across the surface (u). All share K.
struct Curves {
  std::vector<Curve> samples; //!< samples[j] is curve j
  Units units = Units::Unknown;
};

//! How the curves become a surface.
enum class Scheme {
  //! One C² biharmonic spline per mode through all curves (exact mode solution between neighbouring
  //! curves, C¹ and C² at every curve, natural ends A'' − m²A = 0). Every curve is interpolated; no
  //! data amplification (Lebesgue constant ≤ 1.55). The default.
  Spline,
  //! The paper: per patch of 4 curves (3k..3k+3), the end curves plus the u-derivatives that the inner
  //! curves give by one-sided finite differences. The inner curves are not interpolated and the tangent
  //! jumps at every patch joint (~30° on a synthetic face). Kept to reproduce the paper.
  Paper,
  //! Per patch of 4 curves, the four positions. Interpolates every curve but amplifies the data by
  //! ~e^{m/3 − 1}/(m/3) in mode n (m = a·n·patch length): refused beyond `Options::patch4_max_amplification`.
  Patch4,
};
inline constexpr std::array<NamedValue<Scheme>, 3> kSchemeNames{
    {{"spline", Scheme::Spline}, {"paper", Scheme::Paper}, {"patch4", Scheme::Patch4}}};
[[nodiscard]] std::string_view to_string(Scheme scheme) noexcept;

//! Where the curves sit in u.
enum class Spacing {
  Uniform,  //!< curve j at U_j = j/3, as in the paper (patch k = [k, k+1] = curves 3k..3k+3)
  Physical, //!< U_j proportional to the curves' mean x, over the same range [0, (J−1)/3]
};
inline constexpr std::array<NamedValue<Spacing>, 2> kSpacingNames{
    {{"physical", Spacing::Physical}, {"uniform", Spacing::Uniform}}};
[[nodiscard]] std::string_view to_string(Spacing spacing) noexcept;

struct Options {
  Scheme scheme = Scheme::Spline;
  //! The smoothing parameter a. Default: isotropic, a = π·W/L (`isotropic_smoothing`); a = 1 reproduces
  //! the paper, whose high modes then decay ~4× too fast between curves.
  std::optional<double> smoothing;
  //! The number of modes N (cosines 0..N), at most K−1 (the default, which uses every sample).
  std::optional<std::size_t> modes;
  //! With N < K−1: add the remainder R (modes N+1..K−1 solved with mode N+1's frequency) so that every
  //! interpolated curve is met at every sample. R is determined by the curves: it costs no storage.
  bool remainder = true;
  Spacing spacing = Spacing::Uniform;
  //! `Patch4` is refused when its highest frequency would amplify the curves' data more than this. The
  //! default 10 (one digit lost) is reached at m = a·n = 14.5 on a unit patch: frequency 14 at a = 1, 55 at
  //! a = π·15/180.
  double patch4_max_amplification = 10.0;
};

//! The isotropic smoothing parameter a = π·W/L: W is the surface's mean width per unit u (the length of
//! the polyline through sample k of every curve, averaged over k, divided by the u range (J−1)/3), L the
//! curves' mean length (mapped onto v ∈ [0, π]). It makes a step in u and a step in v of the same
//! physical length equally smooth. Errors: `InvalidArgument` when the curves have no length or width.
[[nodiscard]] Result<double> isotropic_smoothing(const Curves& curves);

//! The most modes N that `Surface::build` accepts for these curves and options (whatever `options.modes`
//! says): K−1 for `Spline` and `Paper`; for `Patch4` the largest N whose highest frequency (N+1 with the
//! remainder, unless N = K−1) stays within the amplification cap. Errors: those of `build`, and
//! `InvalidArgument` when no N fits.
[[nodiscard]] Result<std::size_t> max_modes(const Curves& curves, const Options& options = {},
                                            std::string_view source = {});

//! Which partial derivative `Surface::evaluate` returns.
enum class Derivative { None, U, V };

//! Surface points on a grid U_i × v_k; point (i, k) is `points[k·u_count + i]`.
struct Grid {
  std::size_t u_count = 0;
  std::size_t v_count = 0;
  std::vector<Vec3> points;

  [[nodiscard]] const Vec3& operator()(std::size_t i, std::size_t k) const { return points[k * u_count + i]; }
};

//! The grid as a regular triangle mesh with vertex normals: two triangles per cell, oriented so that
//! normals point along X_u × X_v (towards +z in the canonical face frame, for curves running chin to
//! forehead and ordered from the face's right to its left). Vertex (i, k) is vertex k·u_count + i.
//! \throw std::invalid_argument when the grid has fewer than 2 points either way or the wrong size
[[nodiscard]] Mesh triangulate(Grid grid, Units units = Units::Unknown);

//! A PDE surface, solved once from its curves; evaluating it costs one dense matrix product.
class Surface {
public:
  //! Solves every mode. Errors (`InvalidArgument` unless said): fewer than 4 curves, fewer than 2 or more
  //! than `max_samples` samples, different sample counts, a curve count that is not 3p+1 for `Paper` and
  //! `Patch4`, more than K−1 modes, a smoothing parameter that is not positive and finite, curves not ordered
  //! by mean x for `Physical` spacing, `Patch4` beyond its amplification cap (the message says how many modes
  //! fit); `NonFinite` for a NaN or infinite coordinate. `source` names the curves in errors.
  [[nodiscard]] static Result<Surface> build(const Curves& curves, const Options& options = {},
                                             std::string_view source = {});

  //! X (or ∂X/∂u, ∂X/∂v) on the grid us × vs. u must lie in [0, u_max()]; any finite v is allowed (the
  //! surface is even and 2π-periodic in v; the curves span [0, π]).
  //! \throw std::invalid_argument for u outside the domain or a non-finite coordinate
  [[nodiscard]] Grid evaluate(std::span<const double> us, std::span<const double> vs,
                              Derivative derivative = Derivative::None) const;
  //! The same into `out`, reusing its memory (a caller evaluating many grids of one size allocates once).
  //! \throw std::invalid_argument for u outside the domain or a non-finite coordinate
  void evaluate(std::span<const double> us, std::span<const double> vs, Derivative derivative,
                Grid& out) const;
  //! X on u_count × v_count points spread evenly over [0, u_max()] × [0, π].
  //! \throw std::invalid_argument when a count is below 2
  [[nodiscard]] Grid evaluate(std::size_t u_count, std::size_t v_count) const;
  //! `GridMesher(*this, u_count, v_count).mesh(units())` (mesher.hpp): the points of
  //! `evaluate(u_count, v_count)` (to rounding), triangulated with normals as `triangulate` does.
  [[nodiscard]] Mesh mesh(std::size_t u_count, std::size_t v_count) const;

  [[nodiscard]] Scheme scheme() const { return scheme_; }
  [[nodiscard]] double smoothing() const { return a_; }      //!< a
  [[nodiscard]] std::size_t modes() const { return modes_; } //!< N
  [[nodiscard]] std::size_t sample_count() const { return sample_count_; }
  [[nodiscard]] bool has_remainder() const { return columns_ > modes_ + 1; }
  [[nodiscard]] const std::vector<double>& knots() const { return knots_; } //!< U_j of every curve
  [[nodiscard]] double u_max() const { return knots_.back(); }
  [[nodiscard]] Units units() const { return units_; }

private:
  friend class GridMesher; // reads the pieces' coefficients (mesher.hpp)

  // One piece of the surface in u (between neighbouring curves for `Spline`, a patch otherwise): every
  // cosine column n has 4 basis coefficients per coordinate, for local m = a·frequency(n)·length.
  struct Piece {
    double start = 0;
    double length = 0;
    Eigen::Matrix<double, 3, Eigen::Dynamic> coefficients; // columns 4n..4n+3: column n's coefficients
  };

  Surface() = default;
  [[nodiscard]] double frequency(std::size_t column) const {
    return static_cast<double>(column <= modes_ ? column : modes_ + 1);
  }
  [[nodiscard]] const Piece& piece_at(double u) const;

  Scheme scheme_ = Scheme::Spline;
  double a_ = 1;
  std::size_t modes_ = 0;        // N
  std::size_t columns_ = 0;      // cosine columns evaluated: K with the remainder, N+1 without
  std::size_t sample_count_ = 0; // K
  Units units_ = Units::Unknown;
  std::vector<double> knots_;
  std::vector<Piece> pieces_;
};

} // namespace pdeface::pde
