#pragma once
// One frequency of the surface, solved for every piece at once: from a mode's values at the curves to each
// piece's basis coefficients, by the chosen scheme. Built once per frequency, applied to every cosine
// column that shares it (mode n, or every remainder column).

#include "pdeface/pde/surface.hpp"

#include "basis.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pdeface::pde::detail {

//! A piece of the surface in u: where it starts, its length, its first curve, and (for patches) where its
//! two inner curves sit in local t.
struct PieceSpan {
  double start = 0;
  double length = 0;
  std::size_t first_curve = 0;
  double inner1 = 0, inner2 = 0;

  [[nodiscard]] bool same_shape(const PieceSpan& o) const {
    return length == o.length && inner1 == o.inner1 && inner2 == o.inner2;
  }
};

//! The pieces of a scheme over the knots: one per interval for `Spline`, one per patch of 4 curves else.
[[nodiscard]] std::vector<PieceSpan> piece_spans(Scheme scheme, const std::vector<double>& knots);

//! The local mode parameter m of a piece; solver and evaluator must agree on it to the bit, since the
//! basis (series or exponential) is chosen by m.
[[nodiscard]] inline double local_m(double a, double frequency, double length) {
  return a * frequency * length;
}

using ModeValues = Eigen::Matrix<double, Eigen::Dynamic, 3>; // one mode's coefficients at every curve
using PieceCoefficients = Eigen::Matrix<double, 4, 3>;       // basis coefficients × (x, y, z)

class ModeSolver {
public:
  ModeSolver(Scheme scheme, const std::vector<double>& knots, const std::vector<PieceSpan>& pieces, double a,
             double frequency);

  //! The basis coefficients of every piece for the mode whose values at the curves are `values` (J × 3).
  void solve(const ModeValues& values, std::vector<PieceCoefficients>& out) const;

  //! `Patch4`: the largest data amplification over the pieces (four_position_amplification).
  [[nodiscard]] double amplification() const;

private:
  [[nodiscard]] const PieceSystem& system(std::size_t piece) const { return systems_[system_of_[piece]]; }
  void factor_spline();
  [[nodiscard]] ModeValues spline_slopes(const ModeValues& values) const;

  Scheme scheme_;
  const std::vector<double>& knots_;
  const std::vector<PieceSpan>& pieces_;
  double an_;                          // a · frequency: the mode parameter per unit u
  std::vector<PieceSystem> systems_;   // one per distinct piece shape
  std::vector<std::size_t> system_of_; // piece -> its system
  // Spline: the C² conditions on the slopes at the knots, a diagonally dominant tridiagonal system,
  // factorised (Thomas): sub-diagonal, pivots, and super-diagonal divided by the pivots; and the end
  // second derivatives of every system (a''(0), a''(1) as maps of local Hermite data).
  Eigen::VectorXd sub_, pivot_, upper_;
  std::vector<Eigen::Vector4d> curvature0_, curvature1_; // per system
  [[nodiscard]] const Eigen::Vector4d& curvature0(std::size_t piece) const {
    return curvature0_[system_of_[piece]];
  }
  [[nodiscard]] const Eigen::Vector4d& curvature1(std::size_t piece) const {
    return curvature1_[system_of_[piece]];
  }
};

} // namespace pdeface::pde::detail
