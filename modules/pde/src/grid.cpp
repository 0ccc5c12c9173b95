// Evaluation of a solved surface on a grid, and the grid as a mesh.

#include "pdeface/pde/surface.hpp"

#include "basis.hpp"
#include "mode_solver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pdeface::pde {

const Surface::Piece& Surface::piece_at(double u) const {
  const auto after = std::upper_bound(pieces_.begin(), pieces_.end(), u,
                                      [](double value, const Piece& piece) { return value < piece.start; });
  return after == pieces_.begin() ? pieces_.front() : *(after - 1);
}

Grid Surface::evaluate(std::span<const double> us, std::span<const double> vs, Derivative derivative) const {
  for (double u : us)
    if (!(u >= 0 && u <= u_max())) throw std::invalid_argument("pde: u outside [0, u_max()] or not finite");
  for (double v : vs)
    if (!std::isfinite(v)) throw std::invalid_argument("pde: v is not finite");
  const auto nu = static_cast<Eigen::Index>(us.size()), nv = static_cast<Eigen::Index>(vs.size());
  const auto columns = static_cast<Eigen::Index>(columns_);

  // X = Σ_n A_n(u) cos(n v): A holds A_n(U_i) (3 rows per u, xyz), T holds cos(n v_k).
  Eigen::MatrixXd a(3 * nu, columns);
  const int order = derivative == Derivative::U ? 1 : 0;
  for (Eigen::Index i = 0; i < nu; ++i) {
    const Piece& piece = piece_at(us[static_cast<std::size_t>(i)]);
    const double t = (us[static_cast<std::size_t>(i)] - piece.start) / piece.length;
    const double scale = order == 1 ? 1 / piece.length : 1.0;
    Eigen::Vector4d basis;
    for (Eigen::Index n = 0; n < columns; ++n) {
      const auto column = static_cast<std::size_t>(n);
      if (n == 0 || frequency(column) != frequency(column - 1)) // the remainder columns share one basis
        basis = scale * detail::mode_basis(detail::local_m(a_, frequency(column), piece.length), t, order);
      a.block<3, 1>(3 * i, n).noalias() = piece.coefficients.middleCols<4>(4 * n) * basis;
    }
  }
  Eigen::MatrixXd trig(columns, nv);
  for (Eigen::Index k = 0; k < nv; ++k)
    for (Eigen::Index n = 0; n < columns; ++n) {
      const double nd = static_cast<double>(n), angle = nd * vs[static_cast<std::size_t>(k)];
      trig(n, k) = derivative == Derivative::V ? -nd * std::sin(angle) : std::cos(angle);
    }

  Grid grid{static_cast<std::size_t>(nu), static_cast<std::size_t>(nv),
            std::vector<Vec3>(static_cast<std::size_t>(nu * nv))};
  if (grid.points.empty()) return grid;
  // Column-major 3nu × nv is exactly the points' memory: point (i, k) at k·nu + i, xyz interleaved.
  Eigen::Map<Eigen::MatrixXd>(grid.points.data()->data(), 3 * nu, nv).noalias() = a * trig;
  return grid;
}

namespace {
std::vector<double> spread(double end, std::size_t count) {
  if (count < 2) throw std::invalid_argument("pde: a grid needs at least 2 points each way");
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i)
    values[i] = end * static_cast<double>(i) / static_cast<double>(count - 1);
  values.back() = end;
  return values;
}
} // namespace

Grid Surface::evaluate(std::size_t u_count, std::size_t v_count) const {
  return evaluate(spread(u_max(), u_count), spread(std::numbers::pi, v_count));
}

Mesh Surface::mesh(std::size_t u_count, std::size_t v_count) const {
  return triangulate(evaluate(u_count, v_count), units_);
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
