// Evaluation of a solved surface on a grid, and the grid as a mesh.

#include "pdeface/pde/surface.hpp"

#include "pdeface/pde/mesher.hpp"

#include "basis.hpp"
#include "grid_points.hpp"
#include "mode_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pdeface::pde {

const Surface::Piece& Surface::piece_at(double u) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), u,
                                      [](double value, const Piece& piece) { return value < piece.start; });
  return after == pieces_.begin() ? pieces_.front() : *(after - 1);
}

namespace {
// The v values come in mirrored pairs v and π − v (to rounding), as on any grid spread evenly over [0, π].
bool mirrored(std::span<const double> vs) {
  constexpr double tolerance = 16 * std::numeric_limits<double>::epsilon();
  for (std::size_t k = 0; k < vs.size(); ++k)
    if (std::abs(vs[k] + vs[vs.size() - 1 - k] - std::numbers::pi) > tolerance) return false;
  return true;
}
} // namespace

Grid Surface::evaluate(std::span<const double> us, std::span<const double> vs, Derivative derivative) const {
  Grid grid;
  evaluate(us, vs, derivative, grid);
  return grid;
}

void Surface::evaluate(std::span<const double> us, std::span<const double> vs, Derivative derivative,
                       Grid& grid) const {
  for (double u : us)
    if (!(u >= 0 && u <= u_max())) throw std::invalid_argument("pde: u outside [0, u_max()] or not finite");
  for (double v : vs)
    if (!std::isfinite(v)) throw std::invalid_argument("pde: v is not finite");
  const auto nu = static_cast<Eigen::Index>(us.size()), nv = static_cast<Eigen::Index>(vs.size());
  grid.u_count = static_cast<std::size_t>(nu);
  grid.v_count = static_cast<std::size_t>(nv);
  grid.points.resize(static_cast<std::size_t>(nu * nv));
  if (grid.points.empty()) return;

  // X = Σ_n A_n(u) cos(n v) = E + O, the sums over even and odd n. On a grid whose v come in pairs
  // (v, π − v), cos(n(π − v)) = (−1)^n cos(n v) gives X(π − v) = E − O (for ∂X/∂v, −n sin(n v): O − E),
  // so only the first half of the v need the products: half the arithmetic of one product over all v.
  const bool mirror = mirrored(vs);
  const Eigen::Index half = mirror ? (nv + 1) / 2 : nv; // v computed directly; the rest are mirrored
  const double mirror_sign = derivative == Derivative::V ? -1.0 : 1.0;
  const auto columns = static_cast<Eigen::Index>(columns_);
  const Eigen::Index even_columns = (columns + 1) / 2, odd_columns = columns / 2;

  // T: cos(n v_k) (or −n sin(n v_k)), even n in one matrix and odd n in the other.
  Eigen::MatrixXd trig_even(even_columns, half), trig_odd(odd_columns, half);
  for (Eigen::Index k = 0; k < half; ++k)
    for (Eigen::Index n = 0; n < columns; ++n) {
      const double nd = static_cast<double>(n), angle = nd * vs[static_cast<std::size_t>(k)];
      (n % 2 == 0 ? trig_even(n / 2, k) : trig_odd(n / 2, k)) =
          derivative == Derivative::V ? -nd * std::sin(angle) : std::cos(angle);
    }

  // A: A_n(U_i), 3 rows per u (xyz), for a block of u at a time, and the products for a block of v at a
  // time, so that every temporary (Eigen's packed copies included) stays small, in cache and on memory
  // already touched, whatever the grid's size and K.
  constexpr Eigen::Index block = 16, chunk = 32;
  const Eigen::Index rows = 3 * std::min(block, nu), width = std::min(chunk, half);
  Eigen::MatrixXd a_even(rows, even_columns), a_odd(rows, odd_columns), even(rows, width), odd(rows, width);
  // Column-major 3nu × nv is exactly the points' memory: point (i, k) at k·nu + i, xyz interleaved.
  Eigen::Map<Eigen::MatrixXd> out(grid.points.data()->data(), 3 * nu, nv);
  const int order = derivative == Derivative::U ? 1 : 0;
  for (Eigen::Index first = 0; first < nu; first += block) {
    const Eigen::Index count = std::min(block, nu - first), r = 3 * count;
    for (Eigen::Index i = 0; i < count; ++i) {
      const double u = us[static_cast<std::size_t>(first + i)];
      const Piece& piece = piece_at(u);
      const double t = (u - piece.start) / piece.length;
      const double scale = order == 1 ? 1 / piece.length : 1.0;
      Eigen::Vector4d basis;
      for (Eigen::Index n = 0; n < columns; ++n) {
        const auto column = static_cast<std::size_t>(n);
        if (n == 0 || frequency(column) != frequency(column - 1)) // the remainder columns share one basis
          basis = scale * detail::mode_basis(detail::local_m(a_, frequency(column), piece.length), t, order);
        (n % 2 == 0 ? a_even : a_odd).block<3, 1>(3 * i, n / 2).noalias() =
            piece.coefficients.middleCols<4>(4 * n) * basis;
      }
    }
    for (Eigen::Index k0 = 0; k0 < half; k0 += width) {
      const Eigen::Index w = std::min(width, half - k0);
      auto e = even.topLeftCorner(r, w);
      auto o = odd.topLeftCorner(r, w);
      e.noalias() = a_even.topRows(r) * trig_even.middleCols(k0, w);
      if (odd_columns > 0) {
        o.noalias() = a_odd.topRows(r) * trig_odd.middleCols(k0, w);
      } else {
        o.setZero();
      }
      for (Eigen::Index j = 0; j < w; ++j) {
        const Eigen::Index k = k0 + j;
        out.block(3 * first, k, r, 1) = e.col(j) + o.col(j);
        if (mirror && nv - 1 - k > k)
          out.block(3 * first, nv - 1 - k, r, 1) = mirror_sign * (e.col(j) - o.col(j));
      }
    }
  }
}

Grid Surface::evaluate(std::size_t u_count, std::size_t v_count) const {
  return evaluate(detail::spread(u_max(), u_count), detail::spread(std::numbers::pi, v_count));
}

Mesh Surface::mesh(std::size_t u_count, std::size_t v_count) const {
  return GridMesher(*this, u_count, v_count).mesh(units_);
}

namespace {
// Normals of a regular grid from its differences along u and v (central inside, one-sided at the
// borders): X_u × X_v to second order, without the scatter of per-triangle normals over a mesh.
std::vector<Vec3f> grid_normals(const std::vector<Vec3>& p, std::size_t nu, std::size_t nv) {
  std::vector<Vec3f> normals(p.size());
  for (std::size_t k = 0; k < nv; ++k) {
    const std::size_t k0 = k == 0 ? 0 : k - 1, k1 = k + 1 == nv ? k : k + 1;
    for (std::size_t i = 0; i < nu; ++i) {
      const std::size_t i0 = i == 0 ? 0 : i - 1, i1 = i + 1 == nu ? i : i + 1;
      const Vec3 n = (p[k * nu + i1] - p[k * nu + i0]).cross(p[k1 * nu + i] - p[k0 * nu + i]);
      const double length = n.norm();
      normals[k * nu + i] = length > 0 ? Vec3f((n / length).cast<float>()) : Vec3f::Zero();
    }
  }
  return normals;
}
} // namespace

Mesh triangulate(Grid grid, Units units) {
  const std::size_t nu = grid.u_count, nv = grid.v_count;
  if (nu < 2 || nv < 2 || grid.points.size() != nu * nv)
    throw std::invalid_argument("pde: triangulate needs a grid of at least 2 × 2 points, all present");
  Mesh mesh;
  mesh.units = units;
  mesh.positions = std::move(grid.points);
  mesh.triangles.resize(2 * (nu - 1) * (nv - 1));
  std::size_t t = 0;
  const auto index = [nu](std::size_t i, std::size_t k) { return static_cast<std::uint32_t>(k * nu + i); };
  for (std::size_t k = 0; k + 1 < nv; ++k)
    for (std::size_t i = 0; i + 1 < nu; ++i) { // counter-clockwise in (u, v): normals along X_u × X_v
      mesh.triangles[t++] = {index(i, k), index(i + 1, k), index(i + 1, k + 1)};
      mesh.triangles[t++] = {index(i, k), index(i + 1, k + 1), index(i, k + 1)};
    }
  mesh.normals = grid_normals(mesh.positions, nu, nv);
  return mesh;
}

} // namespace pdeface::pde
