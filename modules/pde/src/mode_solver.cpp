#include "mode_solver.hpp"

#include "pdeface/pde/modes.hpp"

#include <algorithm>
#include <cmath>

namespace pdeface::pde::detail {

std::vector<PieceSpan> piece_spans(Scheme scheme, const std::vector<double>& knots) {
  std::vector<PieceSpan> pieces;
  const std::size_t step = scheme == Scheme::Spline ? 1 : 3;
  // Pieces equal up to rounding (uniform knots j/3 differ in the last bit) are made exactly equal, so
  // that they share one factorised system per frequency.
  const auto snap = [](double& value, double previous) {
    if (std::abs(value - previous) <= 1e-12 * std::abs(previous)) value = previous;
  };
  for (std::size_t j = 0; j + step < knots.size(); j += step) {
    PieceSpan piece{.start = knots[j], .length = knots[j + step] - knots[j], .first_curve = j};
    if (step == 3) {
      piece.inner1 = (knots[j + 1] - knots[j]) / piece.length;
      piece.inner2 = (knots[j + 2] - knots[j]) / piece.length;
    }
    if (!pieces.empty()) {
      snap(piece.length, pieces.back().length);
      snap(piece.inner1, pieces.back().inner1);
      snap(piece.inner2, pieces.back().inner2);
    }
    pieces.push_back(piece);
  }
  return pieces;
}

ModeSolver::ModeSolver(Scheme scheme, const std::vector<double>& knots, const std::vector<PieceSpan>& pieces,
                       double a, double frequency)
    : scheme_(scheme), knots_(knots), pieces_(pieces), an_(a * frequency) {
  // Uniform spacing makes every piece the same shape: factorise each distinct shape once.
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (p > 0 && pieces[p].same_shape(pieces[p - 1])) {
      system_of_.push_back(system_of_.back());
      continue;
    }
    const double m = local_m(a, frequency, pieces[p].length);
    system_of_.push_back(systems_.size());
    systems_.emplace_back(m, scheme == Scheme::Patch4
                                 ? four_position_conditions(pieces[p].inner1, pieces[p].inner2)
                                 : hermite_conditions);
  }
  if (scheme == Scheme::Spline) factor_spline();
}

double ModeSolver::amplification() const {
  double worst = 0;
  for (std::size_t p = 0; p < pieces_.size(); ++p)
    if (p == 0 || system_of_[p] != system_of_[p - 1])
      worst =
          std::max(worst, four_position_amplification(system(p).m(), pieces_[p].inner1, pieces_[p].inner2));
  return worst;
}

// Row i of the spline system says A'' is the same on both sides of knot i (and, at the ends, that
// A'' − (a n)² A = 0); the unknowns are the slopes D_j = A'(U_j). On piece j (length h) the local
// Hermite data are (p_j, h D_j, p_{j+1}, h D_{j+1}) and A'' = a''/h².
void ModeSolver::factor_spline() {
  const std::size_t count = knots_.size();
  for (const PieceSystem& s : systems_) {
    curvature0_.push_back(s.cardinals(0, 2));
    curvature1_.push_back(s.cardinals(1, 2));
  }
  Eigen::VectorXd sub = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(count)), diag = sub, super = sub;
  for (std::size_t i = 0; i < count; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (i > 0) { // the piece on the left, at its t = 1
      const double h = pieces_[i - 1].length;
      sub[row] += curvature1(i - 1)[1] / h;
      diag[row] += curvature1(i - 1)[3] / h;
    }
    if (i + 1 < count) { // minus the piece on the right, at its t = 0 (plus, alone at the first knot)
      const double h = pieces_[i].length, sign = i == 0 ? 1.0 : -1.0;
      diag[row] += sign * curvature0(i)[1] / h;
      super[row] += sign * curvature0(i)[3] / h;
    }
  }
  // Thomas factorisation: safe without pivoting because the system is diagonally dominant.
  sub_ = sub;
  pivot_.resize(sub.size());
  upper_.resize(sub.size());
  for (Eigen::Index i = 0; i < sub.size(); ++i) {
    pivot_[i] = diag[i] - (i > 0 ? sub[i] * upper_[i - 1] : 0.0);
    upper_[i] = super[i] / pivot_[i];
  }
}

ModeValues ModeSolver::spline_slopes(const ModeValues& values) const {
  const std::size_t count = knots_.size();
  ModeValues rhs = ModeValues::Zero(values.rows(), 3);
  const auto row = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) {
      const double h2 = pieces_[i - 1].length * pieces_[i - 1].length;
      const Eigen::Vector4d& c = curvature1(i - 1);
      rhs.row(row(i)) -= (c[0] * values.row(row(i - 1)) + c[2] * values.row(row(i))) / h2;
    }
    if (i + 1 < count) {
      const double h2 = pieces_[i].length * pieces_[i].length, sign = i == 0 ? -1.0 : 1.0;
      const Eigen::Vector4d& c = curvature0(i);
      rhs.row(row(i)) += sign * (c[0] * values.row(row(i)) + c[2] * values.row(row(i + 1))) / h2;
    }
    if (i == 0 || i + 1 == count) rhs.row(row(i)) += an_ * an_ * values.row(row(i)); // natural ends
  }
  for (Eigen::Index i = 0; i < rhs.rows(); ++i) {
    if (i > 0) rhs.row(i) -= sub_[i] * rhs.row(i - 1);
    rhs.row(i) /= pivot_[i];
  }
  for (Eigen::Index i = rhs.rows() - 2; i >= 0; --i)
    rhs.row(i) -= upper_[i] * rhs.row(i + 1);
  return rhs;
}

void ModeSolver::solve(const ModeValues& values, std::vector<PieceCoefficients>& out) const {
  out.resize(pieces_.size());
  ModeValues slopes;
  if (scheme_ == Scheme::Spline) slopes = spline_slopes(values);
  for (std::size_t p = 0; p < pieces_.size(); ++p) {
    const auto j = static_cast<Eigen::Index>(pieces_[p].first_curve);
    const double h = pieces_[p].length;
    PieceCoefficients data;
    if (scheme_ == Scheme::Patch4) {
      data = values.middleRows<4>(j);
    } else if (scheme_ == Scheme::Spline) {
      data << values.row(j), h * slopes.row(j), values.row(j + 1), h * slopes.row(j + 1);
    } else { // Paper: the slopes from the inner curves by one-sided differences, as the paper intends
      const auto u = [&](Eigen::Index i) { return knots_[static_cast<std::size_t>(i)]; };
      data << values.row(j), h * (values.row(j + 1) - values.row(j)) / (u(j + 1) - u(j)), values.row(j + 3),
          h * (values.row(j + 3) - values.row(j + 2)) / (u(j + 3) - u(j + 2));
    }
    out[p] = system(p).coefficients(data);
  }
}

} // namespace pdeface::pde::detail
