// GridMesher: a surface on a regular grid as a mesh with normals (mesher.hpp).
//
// A grid row is a dense product: X(u_i, v) = Σ_n A_n(u_i) cos(n v), the sum split into even and odd n so
// that rows v and π − v come from the same two sums (E + O and E − O). The products are written with the
// compiler's vector extensions and compiled three times, for SSE2, AVX2 and AVX-512F vectors; the widest the
// processor has is picked once, at run time (the build itself targets generic x86-64). Every width sums every
// point in the same order, with separate multiplies and adds (this file is compiled with -ffp-contract=off;
// -fno-math-errno and -fno-trapping-math let the normals' loop vectorise and change no value), so a mesh
// is the same to the bit on every machine.

#include "pdeface/pde/mesher.hpp"

#include "basis.hpp"
#include "grid_points.hpp"
#include "mode_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pdeface::pde {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Vec3f) == 3 * sizeof(float),
              "rows are written as plain arrays of coordinates");

// The widest vector the products use (AVX-512: 8 doubles); coefficient columns are padded to it.
constexpr std::size_t kMaxLanes = 8;

// Grid row `half` (in the first half of the grid) and its mirror v_count − 1 − half share their cosines,
// up to the sign of the odd columns.
struct RowPair {
  std::size_t half = 0;
  double* low = nullptr;  // row `half`'s 3·u_count coordinates, or nullptr when not asked for
  double* high = nullptr; // the mirror row's, or nullptr (also when the mirror is row `half` itself)
};

struct Product {
  const double* coefficients; // column n at n·stride
  std::size_t stride;
  std::size_t columns;
  std::size_t width;     // 3·u_count
  const double* cosines; // row h at h·columns
};

// E and O of four rows at a time over `lanes`-wide stretches of the coefficient columns: each coefficient
// loaded is used four times, each cosine for a whole stretch.
template <std::size_t Lanes>
[[gnu::always_inline]] inline void products(const Product& p, const RowPair* pairs, std::size_t count) {
  // NOLINTNEXTLINE(modernize-use-using): GCC drops the attribute from an alias declaration in a template
  typedef double Vector __attribute__((vector_size(Lanes * sizeof(double))));
  constexpr std::size_t kRows = 4;
  for (std::size_t group = 0; group < count; group += kRows) {
    const double* row_cosines[kRows];
    for (std::size_t r = 0; r < kRows; ++r) // a short last group repeats its last row (made, not stored)
      row_cosines[r] = p.cosines + pairs[std::min(group + r, count - 1)].half * p.columns;
    for (std::size_t j = 0; j < p.width; j += Lanes) {
      Vector even[kRows] = {}, odd[kRows] = {};
      const double* a = p.coefficients + j;
      std::size_t n = 0;
      for (; n + 1 < p.columns; n += 2, a += 2 * p.stride) {
        Vector a0, a1;
        std::memcpy(&a0, a, sizeof a0);
        std::memcpy(&a1, a + p.stride, sizeof a1);
        for (std::size_t r = 0; r < kRows; ++r) {
          even[r] += a0 * row_cosines[r][n];
          odd[r] += a1 * row_cosines[r][n + 1];
        }
      }
      if (n < p.columns) {
        Vector a0;
        std::memcpy(&a0, a, sizeof a0);
        for (std::size_t r = 0; r < kRows; ++r)
          even[r] += a0 * row_cosines[r][n];
      }
      const bool whole = j + Lanes <= p.width; // else the row's last, partial stretch
      const std::size_t bytes = whole ? sizeof(Vector) : (p.width - j) * sizeof(double);
      for (std::size_t r = 0; r < kRows && group + r < count; ++r) {
        const RowPair& pair = pairs[group + r];
        const Vector sum = even[r] + odd[r], difference = even[r] - odd[r];
        if (whole) { // a fixed size: one vector store
          if (pair.low) std::memcpy(pair.low + j, &sum, sizeof(Vector));
          if (pair.high) std::memcpy(pair.high + j, &difference, sizeof(Vector));
        } else {
          if (pair.low) std::memcpy(pair.low + j, &sum, bytes);
          if (pair.high) std::memcpy(pair.high + j, &difference, bytes);
        }
      }
    }
  }
}

// Row `row`'s interleaved points (x, y, z) as three planes, `plane` doubles apart: the normals read each
// row as planes, so that their loop needs no shuffling.
[[gnu::always_inline]] inline void planes(const double* row, std::size_t u_count, std::size_t plane,
                                          double* out) {
  for (std::size_t i = 0; i < u_count; ++i) {
    out[i] = row[3 * i];
    out[plane + i] = row[3 * i + 1];
    out[2 * plane + i] = row[3 * i + 2];
  }
}

// The unit normal X_u × X_v of point i of `row` from its neighbours (u: points i0 and i1 of `row`; v: point i
// of `below` and `above`), all three rows as planes; 0 where the differences are parallel or vanish. The
// cross product is made in double, scaled by `scale` (a power of two that brings the grid's cross products
// near 1, so float's range holds them) and normalised in float, where a square root and a division cost a
// quarter of double's. Written so that the loop over a row vectorises: no branch, the division made whether
// or not it is kept.
[[gnu::always_inline]] inline void normal(const double* row, const double* below, const double* above,
                                          std::size_t plane, std::size_t i0, std::size_t i, std::size_t i1,
                                          double scale, float* out) {
  const double ux = row[i1] - row[i0], uy = row[plane + i1] - row[plane + i0],
               uz = row[2 * plane + i1] - row[2 * plane + i0];
  const double vx = above[i] - below[i], vy = above[plane + i] - below[plane + i],
               vz = above[2 * plane + i] - below[2 * plane + i];
  const auto nx = static_cast<float>(scale * (uy * vz - uz * vy)),
             ny = static_cast<float>(scale * (uz * vx - ux * vz)),
             nz = static_cast<float>(scale * (ux * vy - uy * vx));
  const float length = std::sqrt(nx * nx + ny * ny + nz * nz);
  const bool usable = length > 0 && length <= std::numeric_limits<float>::max();
  const float inverse = 1 / (usable ? length : 1.0F);
  out[3 * i] = usable ? nx * inverse : 0.0F;
  out[3 * i + 1] = usable ? ny * inverse : 0.0F;
  out[3 * i + 2] = usable ? nz * inverse : 0.0F;
}

[[gnu::always_inline]] inline void normals(const double* row, const double* below, const double* above,
                                           std::size_t u_count, std::size_t plane, double scale, float* out) {
  normal(row, below, above, plane, 0, 0, 1, scale, out);
  for (std::size_t i = 1; i + 1 < u_count; ++i)
    normal(row, below, above, plane, i - 1, i, i + 1, scale, out);
  normal(row, below, above, plane, u_count - 2, u_count - 1, u_count - 1, scale, out);
}

void products_sse2(const Product& p, const RowPair* pairs, std::size_t count) {
  products<2>(p, pairs, count);
}
void planes_sse2(const double* row, std::size_t u_count, std::size_t plane, double* out) {
  planes(row, u_count, plane, out);
}
void normals_sse2(const double* row, const double* below, const double* above, std::size_t u_count,
                  std::size_t plane, double scale, float* out) {
  normals(row, below, above, u_count, plane, scale, out);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define PDEFACE_X86_KERNELS 1
[[gnu::target("avx2")]] void products_avx2(const Product& p, const RowPair* pairs, std::size_t count) {
  products<4>(p, pairs, count);
}
[[gnu::target("avx2")]] void planes_avx2(const double* row, std::size_t u_count, std::size_t plane,
                                         double* out) {
  planes(row, u_count, plane, out);
}
[[gnu::target("avx2")]] void normals_avx2(const double* row, const double* below, const double* above,
                                          std::size_t u_count, std::size_t plane, double scale, float* out) {
  normals(row, below, above, u_count, plane, scale, out);
}
[[gnu::target("avx512f")]] void products_avx512(const Product& p, const RowPair* pairs, std::size_t count) {
  products<kMaxLanes>(p, pairs, count);
}
[[gnu::target("avx512f")]] void planes_avx512(const double* row, std::size_t u_count, std::size_t plane,
                                              double* out) {
  planes(row, u_count, plane, out);
}
[[gnu::target("avx512f")]] void normals_avx512(const double* row, const double* below, const double* above,
                                               std::size_t u_count, std::size_t plane, double scale,
                                               float* out) {
  normals(row, below, above, u_count, plane, scale, out);
}
#endif

} // namespace

namespace detail {
struct MesherKernels {
  void (*products)(const Product&, const RowPair*, std::size_t);
  void (*planes)(const double*, std::size_t, std::size_t, double*);
  void (*normals)(const double*, const double*, const double*, std::size_t, std::size_t, double, float*);
};
} // namespace detail

namespace {

// The widest kernels this processor runs with at most `max_lanes` doubles a vector (0: any).
const detail::MesherKernels* pick_kernels(std::size_t max_lanes) {
  static const detail::MesherKernels sse2{products_sse2, planes_sse2, normals_sse2};
#if defined(PDEFACE_X86_KERNELS)
  static const detail::MesherKernels avx2{products_avx2, planes_avx2, normals_avx2},
      avx512{products_avx512, planes_avx512, normals_avx512};
  static const bool has_avx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2") != 0);
  static const bool has_avx512 = (__builtin_cpu_init(), __builtin_cpu_supports("avx512f") != 0);
  if (has_avx512 && (max_lanes == 0 || max_lanes >= 8)) return &avx512;
  if (has_avx2 && (max_lanes == 0 || max_lanes >= 4)) return &avx2;
#else
  (void)max_lanes;
#endif
  return &sse2;
}

} // namespace

GridMesher::GridMesher(const Surface& surface, std::size_t u_count, std::size_t v_count,
                       const MesherOptions& options)
    : kernels_(pick_kernels(options.max_lanes)), u_count_(u_count), v_count_(v_count),
      columns_(surface.columns_) {
  const AffineMap& map = options.map;
  if (u_count < 2 || v_count < 2) throw std::invalid_argument("pde: a grid needs at least 2 points each way");
  if (!map.linear.allFinite() || !map.offset.allFinite())
    throw std::invalid_argument("pde: the map of a mesh must be finite");
  reversed_ = map.linear.determinant() < 0;

  // A_n(u_i) = (linear · piece coefficients of column n) · basis_n(t_i), + offset for n = 0 (cos 0v = 1).
  stride_ = (3 * u_count + kMaxLanes - 1) / kMaxLanes * kMaxLanes;
  coefficients_.assign(columns_ * stride_, 0.0);
  std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> mapped;
  for (const Surface::Piece& piece : surface.pieces_)
    mapped.emplace_back(map.linear * piece.coefficients);
  std::vector<Eigen::Vector4d> basis(static_cast<std::size_t>(surface.frequency(columns_ - 1)) + 1);
  const std::vector<double> us = detail::spread(surface.u_max(), u_count);
  for (std::size_t i = 0; i < u_count; ++i) {
    const Surface::Piece& piece = surface.piece_at(us[i]);
    const auto& c = mapped[static_cast<std::size_t>(&piece - surface.pieces_.data())];
    detail::mode_basis_powers(surface.a_, piece.length, (us[i] - piece.start) / piece.length, basis);
    for (std::size_t n = 0; n < columns_; ++n) {
      Vec3 value = c.middleCols<4>(static_cast<Eigen::Index>(4 * n)) *
                   basis[static_cast<std::size_t>(surface.frequency(n))];
      if (n == 0) value += map.offset;
      std::copy(value.data(), value.data() + 3,
                coefficients_.begin() + static_cast<std::ptrdiff_t>(n * stride_ + 3 * i));
    }
  }

  // cos(n v_h) with v_h = πh/(v_count − 1) is the cosine of π·(nh mod P)/(v_count − 1), P = 2(v_count − 1):
  // one period of P cosines serves every column.
  const std::size_t period = 2 * (v_count - 1), half = (v_count + 1) / 2;
  std::vector<double> period_cosines(period);
  for (std::size_t m = 0; m < v_count; ++m)
    period_cosines[m] =
        std::cos(std::numbers::pi * static_cast<double>(m) / static_cast<double>(v_count - 1));
  for (std::size_t m = v_count; m < period; ++m)
    period_cosines[m] = period_cosines[period - m];
  cosines_.resize(half * columns_);
  for (std::size_t h = 0; h < half; ++h)
    for (std::size_t n = 0, m = 0; n < columns_;
         ++n, m = m + h < period ? m + h : m + h - period) // m = nh mod P
      cosines_[h * columns_ + n] = period_cosines[m];

  // The normals' scale: a power of two near 1/(typical cross product of neighbouring points' differences),
  // from the largest coefficient E (the surface's size, offset included): about (2E/u_count)(2E/v_count).
  const double largest =
      Eigen::Map<const Eigen::ArrayXd>(coefficients_.data(), static_cast<Eigen::Index>(coefficients_.size()))
          .abs()
          .maxCoeff();
  const double typical = 4 * largest * largest / static_cast<double>(u_count * v_count);
  if (typical > 0 && std::isfinite(typical)) {
    int exponent = 0;
    (void)std::frexp(typical, &exponent);
    normal_scale_ = std::ldexp(1.0, std::clamp(-exponent, -1000, 1000));
  }
}

void GridMesher::rows(std::size_t first, std::size_t count, std::span<Vec3> positions,
                      std::span<Vec3f> normals) const {
  const RowBlock block{first, count, positions, normals};
  rows(std::span(&block, 1));
}

void GridMesher::rows(std::span<const RowBlock> blocks) const {
  // Where every row asked for goes, and the rows beside them that normals need (made into `beside`).
  std::vector<double*> row(v_count_, nullptr);
  const std::size_t width = 3 * u_count_;
  for (const RowBlock& b : blocks) {
    if (b.first > v_count_ || b.count > v_count_ - b.first)
      throw std::invalid_argument("pde: rows outside the grid");
    if (b.positions.size() != b.count * u_count_ ||
        (!b.normals.empty() && b.normals.size() != b.count * u_count_))
      throw std::invalid_argument("pde: rows need u_count points per row");
    for (std::size_t k = 0; k < b.count; ++k) {
      if (row[b.first + k]) throw std::invalid_argument("pde: a row asked for twice");
      row[b.first + k] = b.positions.data()->data() + k * width;
    }
  }
  std::vector<std::size_t> missing;
  for (const RowBlock& b : blocks)
    if (!b.normals.empty() && b.count > 0)
      for (const std::size_t k :
           {b.first > 0 ? b.first - 1 : b.first, std::min(b.first + b.count, v_count_ - 1)})
        if (!row[k] && std::ranges::find(missing, k) == missing.end()) missing.push_back(k);
  std::vector<double> beside(missing.size() * width);
  for (std::size_t m = 0; m < missing.size(); ++m)
    row[missing[m]] = beside.data() + m * width;

  std::vector<RowPair> pairs;
  for (std::size_t h = 0; h < (v_count_ + 1) / 2; ++h) {
    const std::size_t mirror = v_count_ - 1 - h;
    const RowPair pair{h, row[h], mirror != h ? row[mirror] : nullptr};
    if (pair.low || pair.high) pairs.push_back(pair);
  }
  const detail::MesherKernels& k = *kernels_;
  k.products({coefficients_.data(), stride_, columns_, width, cosines_.data()}, pairs.data(), pairs.size());
  for (const RowBlock& b : blocks)
    if (!b.normals.empty()) normals_of(row, b.first, b.count, b.normals.data()->data());
}

void GridMesher::normals_of(std::span<double* const> row, std::size_t first, std::size_t count,
                            float* out) const {
  // Each row turned into planes once (a ring of three: the row, and the rows below and above).
  const detail::MesherKernels& k = *kernels_;
  const std::size_t plane = (u_count_ + kMaxLanes - 1) / kMaxLanes * kMaxLanes;
  std::vector<double> ring(std::size_t{9} * plane);              // three rows of three planes
  std::array<std::size_t, 3> held{v_count_, v_count_, v_count_}; // the row in each slot of the ring
  const auto planes_of = [&](std::size_t r) {
    double* slot = ring.data() + (r % 3) * 3 * plane;
    if (held[r % 3] != r) {
      k.planes(row[r], u_count_, plane, slot);
      held[r % 3] = r;
    }
    return slot;
  };
  for (std::size_t r = first; r < first + count; ++r) {
    const double* below = planes_of(r == 0 ? 0 : r - 1);
    const double* above = planes_of(r + 1 == v_count_ ? r : r + 1);
    const double* middle = planes_of(r);
    if (reversed_) std::swap(below, above); // X_u × (−X_v): the mapped surface's side
    k.normals(middle, below, above, u_count_, plane, normal_scale_, out + (r - first) * u_count_ * 3);
  }
}

void GridMesher::triangles(std::size_t first, std::size_t count, std::span<Triangle> out) const {
  if (first > v_count_ - 1 || count > v_count_ - 1 - first)
    throw std::invalid_argument("pde: cell rows outside the grid");
  const std::size_t per_row = 2 * (u_count_ - 1);
  if (out.size() != count * per_row) throw std::invalid_argument("pde: 2 (u_count - 1) triangles a row");
  if (count == 0) return;
  // Cell row first + k is cell row `first` with every index plus k·u_count: one pattern, then a vectorised
  // add per row.
  static_assert(sizeof(Triangle) == 3 * sizeof(std::uint32_t), "triangles are written as plain indices");
  const auto nu = static_cast<std::uint32_t>(u_count_);
  const auto base = static_cast<std::uint32_t>(first * u_count_);
  std::uint32_t* const pattern = out.data()->data();
  for (std::uint32_t i = 0; i + 1 < nu; ++i) { // counter-clockwise in (u, v): normals along X_u × X_v
    const std::uint32_t below = base + i, above = below + nu;
    const std::uint32_t corners[6] = {below, below + 1, above + 1, below, above + 1, above};
    std::copy(corners, corners + 6, pattern + std::size_t{6} * i);
  }
  const std::size_t values = 3 * per_row;
  for (std::size_t k = 1; k < count; ++k) {
    std::uint32_t* const row = pattern + k * values;
    const auto offset = static_cast<std::uint32_t>(k * u_count_);
    for (std::size_t v = 0; v < values; ++v)
      row[v] = pattern[v] + offset;
  }
}

Mesh GridMesher::displaced_mesh(std::span<const double> offsets, double scale, Units units) const {
  if (offsets.size() != vertex_count()) throw std::invalid_argument("pde: one offset per vertex");
  Mesh mesh = this->mesh(units);
  double* const p = mesh.positions.data()->data();
  const float* const n = mesh.normals.data()->data();
  for (std::size_t v = 0; v < offsets.size(); ++v) {
    const double d = offsets[v] * scale;
    p[3 * v] = p[3 * v] + d * static_cast<double>(n[3 * v]);
    p[3 * v + 1] = p[3 * v + 1] + d * static_cast<double>(n[3 * v + 1]);
    p[3 * v + 2] = p[3 * v + 2] + d * static_cast<double>(n[3 * v + 2]);
  }
  std::vector<double*> row(v_count_);
  for (std::size_t r = 0; r < v_count_; ++r)
    row[r] = p + r * 3 * u_count_;
  normals_of(row, 0, v_count_, mesh.normals.data()->data());
  return mesh;
}

Mesh GridMesher::mesh(Units units) const {
  Mesh mesh;
  mesh.units = units;
  mesh.positions.resize(vertex_count());
  mesh.normals.resize(vertex_count());
  mesh.triangles.resize(triangle_count());
  rows(0, v_count_, mesh.positions, mesh.normals);
  triangles(0, v_count_ - 1, mesh.triangles);
  return mesh;
}

} // namespace pdeface::pde
