#pragma once
// The basis the solver works in for one mode on one piece: the stable exponential basis for
// m ≥ small_mode_limit, the series basis below it (see modes.hpp). Both span the same solutions, so a
// piece's coefficients only have meaning together with the m they were computed for.

#include "pdeface/pde/modes.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <array>
#include <span>

namespace pdeface::pde::detail {

//! Values (derivative order 0..2 in local t) of the basis used for m.
[[nodiscard]] Eigen::Vector4d mode_basis(double m, double t, int derivative);

//! `mode_basis(local_m(a, f, length), t, 0)` for every frequency f = 0 … out.size() − 1 at once, into
//! out[f]: the same basis chosen by the same m, its values equal to ~f ulp (the exponentials of f are
//! powers of those of f = 1, where `mode_basis` takes an exponential each). For evaluating many columns at
//! one point: the mesher's cost per grid column.
void mode_basis_powers(double a, double length, double t, std::span<Eigen::Vector4d> out);

//! One condition on a piece: the value (derivative 0) or slope (1) of the solution at local t.
struct Condition {
  double t;
  int derivative;
};
inline constexpr std::array<Condition, 4> hermite_conditions{{{0, 0}, {0, 1}, {1, 0}, {1, 1}}};
[[nodiscard]] inline std::array<Condition, 4> four_position_conditions(double s1, double s2) {
  return {{{0, 0}, {s1, 0}, {s2, 0}, {1, 0}}};
}

//! The system `M c = data` of four conditions in the basis used for m: row i of M is the basis (or its
//! derivative) at condition i. Kept as its inverse (from a pivoted LU): a 4 × 4 is applied far more often
//! than it is built, and fixed-size products are the cheapest way to apply it.
class PieceSystem {
public:
  PieceSystem(double m, const std::array<Condition, 4>& conditions);

  [[nodiscard]] double m() const { return m_; }
  //! Basis coefficients of the solution that meets `data` (4 rows, one column per right-hand side).
  template <class Data> [[nodiscard]] auto coefficients(const Data& data) const { return inverse_ * data; }
  //! The cardinal functions at t: A^{(derivative)}(t) = cardinals(t, derivative) · data.
  [[nodiscard]] Eigen::Vector4d cardinals(double t, int derivative) const {
    return inverse_.transpose() * mode_basis(m_, t, derivative);
  }
  //! False when the system is singular or not finite (four positions with huge m).
  [[nodiscard]] bool usable() const { return usable_; }

private:
  double m_;
  Eigen::Matrix4d inverse_;
  bool usable_;
};

} // namespace pdeface::pde::detail
