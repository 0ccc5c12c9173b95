#pragma once
//! \file
//! The mathematics of one Fourier mode, exposed for analysis and tests (`Surface` is the everyday API).
//!
//! A surface `X(u, v) = Σ_n A_n(u) cos(n v)` solves `(∂²/∂u² + a² ∂²/∂v²)² X = 0` when every `A_n` solves
//! `A'''' − 2m²A'' + m⁴A = 0` with `m = a·n`. On a piece of length h, with local `t = (u − u₀)/h ∈ [0, 1]`,
//! the local parameter is `m = a·n·h`. Its solutions are spanned by the *stable basis*
//! `e^{−mt}, m t e^{−mt}, e^{−m(1−t)}, m(1−t) e^{−m(1−t)}` (every value in [0, 1], no overflow), which
//! becomes degenerate as m → 0; below `small_mode_limit` the library works in
//! `cosh(mt), sinh(mt)/m, t sinh(mt)/m, (t cosh(mt) − sinh(mt)/m)/m²` instead (series-evaluated; the
//! cubic `1, t, t², t³/3` at m = 0), so every function below is accurate to ~1e-15 for all m ≥ 0.

#include <Eigen/Core>

namespace pdeface::pde {

//! Below this m the solver uses the series basis, at and above it the stable exponential basis.
inline constexpr double small_mode_limit = 1.0;

//! The stable basis at local t (derivative order 0, 1 or 2 in t), for m > 0.
//! \throw std::invalid_argument for m ≤ 0 or a derivative order outside 0..2
[[nodiscard]] Eigen::Vector4d stable_basis(double m, double t, int derivative = 0);

//! Rows A(0), A'(0), A(1), A'(1) of the stable basis: the position+derivative system that the paper's
//! printed c1..c4 solve. Its determinant is −m²·(1 − (4m² + 2)e^{−2m} + e^{−4m}) = −m² e^{−4m} d with
//! the paper's `d = e^{4m} − 4m²e^{2m} − 2e^{2m} + 1`.
[[nodiscard]] Eigen::Matrix4d position_derivative_matrix(double m);

//! Rows A(0), A(s1), A(s2), A(1) of the stable basis: four positions, the paper's equation 2. For s1 = 1/3,
//! s2 = 2/3 its determinant is −m² e^{−2m}·(16/9)·sinh⁴(m/3).
[[nodiscard]] Eigen::Matrix4d four_position_matrix(double m, double s1, double s2);

//! The Hermite cardinal functions of one mode at t (derivative order 0..2): the solution with A(0) = p0,
//! A'(0) = d0, A(1) = p1, A'(1) = d1 is `H·(p0, d0, p1, d1)`. Accurate for every m ≥ 0.
[[nodiscard]] Eigen::Vector4d hermite_cardinals(double m, double t, int derivative = 0);

//! How much four-position interpolation at 0, s1, s2, 1 can amplify its data (the Lebesgue constant
//! max_t Σ_i |L_i(t)|): 1.63 for small m, ~e^{m/3 − 1}/(m/3) for large m at s1 = 1/3, s2 = 2/3 (3.6 at
//! m = 10, 44 at m = 20, 8.9e6 at m = 60). Infinite when the system is singular or overflows.
[[nodiscard]] double four_position_amplification(double m, double s1, double s2);

//! Cosine (DCT-I) coefficients of open curves sampled at v_k = kπ/(K−1): row n of the result holds α_n,
//! with `f(v_k) = Σ_{n<K} α_n cos(n v_k)` exactly (the even extension of the curve, so no Gibbs ringing
//! at the ends). `samples` is K × C (one column per coordinate and curve), K ≥ 2.
//! \throw std::invalid_argument when K < 2
[[nodiscard]] Eigen::MatrixXd cosine_coefficients(const Eigen::MatrixXd& samples);

} // namespace pdeface::pde
