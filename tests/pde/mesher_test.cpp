// The grid mesher: the same points as `Surface::evaluate`, `triangulate`'s triangles and normals, rows made
// in any pieces the same to the bit, the map folded in, and every vector width giving the same bits.

#include "pdeface/pde/mesher.hpp"
#include "pdeface/pde/surface.hpp"

#include "synthetic_face.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <numbers>

namespace {

using namespace pdeface;
using namespace pdeface::pde;

const Surface& face_surface() {
  static const Surface s = Surface::build(face::profiles(30), {.modes = 12}).value(); // with the remainder
  return s;
}

// A similarity that turns, scales and moves (and, with `mirror`, reflects).
AffineMap similarity(bool mirror) {
  AffineMap map;
  map.linear = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix() / 25.4;
  if (mirror) map.linear.col(0) *= -1;
  map.offset = Vec3(12.5, -40, 300.25);
  return map;
}

double largest_coordinate(const Mesh& mesh) {
  double largest = 0;
  for (const Vec3& p : mesh.positions)
    largest = std::max(largest, p.cwiseAbs().maxCoeff());
  return largest;
}

TEST(PdeMesher, IsTheEvaluatedGridTriangulated) {
  const Surface& s = face_surface();
  for (const auto& [nu, nv] : {std::pair<std::size_t, std::size_t>{2, 2}, {37, 50}, {40, 31}}) {
    const Mesh expected = triangulate(s.evaluate(nu, nv), s.units());
    const Mesh mesh = GridMesher(s, nu, nv).mesh(s.units());
    ASSERT_EQ(mesh.vertex_count(), nu * nv);
    EXPECT_EQ(mesh.triangles, expected.triangles) << nu << " x " << nv;
    EXPECT_EQ(mesh.units, Units::Millimetres);
    const double scale = largest_coordinate(expected);
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      EXPECT_LT((mesh.positions[i] - expected.positions[i]).norm(), 1e-13 * scale) << i;
      EXPECT_LT((mesh.normals[i] - expected.normals[i]).norm(), 1e-6F) << i;
      EXPECT_NEAR(mesh.normals[i].norm(), 1.0F, 1e-6F) << i;
    }
  }
  // Surface::mesh is the mesher's.
  const Mesh mesh = s.mesh(20, 25), direct = GridMesher(s, 20, 25).mesh(s.units());
  EXPECT_TRUE(mesh.positions == direct.positions);
  EXPECT_TRUE(mesh.normals == direct.normals);
}

TEST(PdeMesher, RowsInAnyPiecesAreTheSameToTheBit) {
  const Surface& s = face_surface();
  for (const std::size_t nv : {7, 8}) { // a middle row of its own, and none
    const GridMesher mesher(s, 9, nv, {.map = similarity(false)});
    const Mesh whole = mesher.mesh();
    for (std::size_t first = 0; first < nv; ++first)
      for (std::size_t count = 1; first + count <= nv; ++count) {
        std::vector<Vec3> positions(count * 9);
        std::vector<Vec3f> normals(count * 9);
        mesher.rows(first, count, positions, normals);
        const auto from = static_cast<std::ptrdiff_t>(first * 9);
        EXPECT_TRUE(std::equal(positions.begin(), positions.end(), whole.positions.begin() + from))
            << first << " + " << count;
        EXPECT_TRUE(std::equal(normals.begin(), normals.end(), whole.normals.begin() + from))
            << first << " + " << count;
        std::vector<Vec3> alone(count * 9);
        mesher.rows(first, count, alone, {}); // positions only
        EXPECT_TRUE(alone == positions);
      }
    // A block and its mirror image in one call (as a streaming writer asks for them).
    for (std::size_t first = 0; first < nv / 2; ++first) {
      const std::size_t count = std::min<std::size_t>(2, nv / 2 - first), mirror = nv - first - count;
      std::vector<Vec3> low(count * 9), high(count * 9);
      std::vector<Vec3f> low_normals(count * 9), high_normals(count * 9);
      const GridMesher::RowBlock blocks[] = {{first, count, low, low_normals},
                                             {mirror, count, high, high_normals}};
      mesher.rows(blocks);
      const auto at = [&](std::size_t row) { return static_cast<std::ptrdiff_t>(row * 9); };
      EXPECT_TRUE(std::equal(low.begin(), low.end(), whole.positions.begin() + at(first)));
      EXPECT_TRUE(std::equal(high.begin(), high.end(), whole.positions.begin() + at(mirror)));
      EXPECT_TRUE(std::equal(low_normals.begin(), low_normals.end(), whole.normals.begin() + at(first)));
      EXPECT_TRUE(std::equal(high_normals.begin(), high_normals.end(), whole.normals.begin() + at(mirror)));
    }
    for (std::size_t first = 0; first + 1 < nv; ++first) {
      std::vector<Triangle> triangles(2 * 8);
      mesher.triangles(first, 1, triangles);
      EXPECT_TRUE(std::equal(triangles.begin(), triangles.end(),
                             whole.triangles.begin() + static_cast<std::ptrdiff_t>(first * 16)));
    }
  }
}

TEST(PdeMesher, TheMapIsFoldedIntoThePoints) {
  const Surface& s = face_surface();
  const Mesh plain = GridMesher(s, 30, 40).mesh();
  for (const bool mirror : {false, true}) {
    const AffineMap map = similarity(mirror);
    const Mesh mapped = GridMesher(s, 30, 40, {.map = map}).mesh(Units::Inches);
    EXPECT_EQ(mapped.units, Units::Inches);
    EXPECT_TRUE(mapped.triangles == plain.triangles);
    const double scale = largest_coordinate(mapped);
    const Eigen::Matrix3f turn = (map.linear * 25.4).cast<float>(); // the rotation (or reflection)
    for (std::size_t i = 0; i < plain.vertex_count(); ++i) {
      EXPECT_LT((mapped.positions[i] - (map.linear * plain.positions[i] + map.offset)).norm(), 1e-13 * scale);
      // The mapped surface's normals: turned with it, on the same side even when the map mirrors.
      EXPECT_LT((mapped.normals[i] - turn * plain.normals[i]).norm(), 2e-6F) << mirror << " " << i;
    }
  }
}

TEST(PdeMesher, EveryVectorWidthGivesTheSameBits) {
  for (const Curves& curves : {face::profiles(30), face::profiles(31)}) {
    const Surface s = Surface::build(curves).value();
    const Mesh widest = GridMesher(s, 53, 41, {.map = similarity(false)}).mesh();
    for (const std::size_t lanes : {2, 4, 8}) {
      const Mesh mesh = GridMesher(s, 53, 41, {.map = similarity(false), .max_lanes = lanes}).mesh();
      EXPECT_TRUE(mesh.positions == widest.positions) << lanes;
      EXPECT_TRUE(mesh.normals == widest.normals) << lanes;
    }
  }
}

TEST(PdeMesher, ADegenerateGridGetsZeroNormalsNotNaN) {
  // A map onto one point: every difference is 0, and no point has a normal.
  AffineMap collapse;
  collapse.linear.setZero();
  collapse.offset = Vec3(1, 2, 3);
  const Mesh mesh = GridMesher(face_surface(), 6, 5, {.map = collapse}).mesh();
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    EXPECT_EQ(mesh.positions[i], collapse.offset);
    EXPECT_EQ(mesh.normals[i], Vec3f::Zero());
  }
}

// The displaced mesh: every vertex moved along the mesh's own normal by its offset times the scale, then
// given the normals the mesher gives the moved grid (the same as a plain mesh's when nothing moved), in
// both orientations of the map.
TEST(PdeMesher, DisplacedMeshMovesAlongTheNormalsAndRemakesThem) {
  for (const bool mirror : {false, true}) {
    const GridMesher mesher(face_surface(), 41, 53, {.map = similarity(mirror)});
    const Mesh plain = mesher.mesh(Units::Millimetres);
    const std::vector<double> zero(mesher.vertex_count(), 0.0);
    const Mesh same = mesher.displaced_mesh(zero, 2.0, Units::Millimetres);
    EXPECT_EQ(same.positions, plain.positions);
    EXPECT_EQ(same.normals, plain.normals);
    EXPECT_EQ(same.triangles, plain.triangles);
    EXPECT_EQ(same.units, Units::Millimetres);
    std::vector<double> offsets(mesher.vertex_count());
    for (std::size_t v = 0; v < offsets.size(); ++v)
      offsets[v] = 0.3 * std::sin(0.05 * static_cast<double>(v));
    const Mesh moved = mesher.displaced_mesh(offsets, 0.5);
    double worst_normal = 0;
    for (std::size_t v = 0; v < offsets.size(); ++v) {
      const Vec3 expected = plain.positions[v] + (offsets[v] * 0.5) * plain.normals[v].cast<double>();
      EXPECT_LT((moved.positions[v] - expected).norm(), 1e-12) << v;
      worst_normal = std::max(worst_normal, std::abs(static_cast<double>(moved.normals[v].norm()) - 1));
    }
    EXPECT_LT(worst_normal, 1e-5);
    // The moved grid's normals are those of its own points: a mesher's normals of the moved positions.
    const std::size_t middle = 26 * 41 + 20;
    const Vec3 du = moved.positions[middle + 1] - moved.positions[middle - 1];
    const Vec3 dv = moved.positions[middle + 41] - moved.positions[middle - 41];
    const Vec3 n = du.cross(dv).normalized() * (mirror ? -1.0 : 1.0);
    EXPECT_GT(n.dot(moved.normals[middle].cast<double>()), 1 - 1e-6);
  }
  EXPECT_THROW((void)GridMesher(face_surface(), 5, 6).displaced_mesh(std::vector<double>(29), 1.0),
               std::invalid_argument);
}

TEST(PdeMesher, RefusesBadCalls) {
  const Surface& s = face_surface();
  EXPECT_THROW(GridMesher(s, 1, 5), std::invalid_argument);
  EXPECT_THROW(GridMesher(s, 5, 1), std::invalid_argument);
  AffineMap bad;
  bad.offset.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(GridMesher(s, 5, 5, {.map = bad}), std::invalid_argument);
  const GridMesher mesher(s, 5, 6);
  std::vector<Vec3> positions(5);
  std::vector<Vec3f> normals(5);
  EXPECT_THROW(mesher.rows(6, 1, positions, normals), std::invalid_argument);
  EXPECT_THROW(mesher.rows(5, 2, positions, normals), std::invalid_argument);
  EXPECT_THROW(mesher.rows(0, 1, std::span<Vec3>(positions).first(4), normals), std::invalid_argument);
  EXPECT_THROW(mesher.rows(0, 1, positions, std::span<Vec3f>(normals).first(4)), std::invalid_argument);
  std::vector<Vec3> more(5);
  const GridMesher::RowBlock twice[] = {{2, 1, positions, normals}, {2, 1, more, {}}};
  EXPECT_THROW(mesher.rows(twice), std::invalid_argument);
  std::vector<Triangle> triangles(8);
  EXPECT_THROW(mesher.triangles(5, 1, triangles), std::invalid_argument);
  EXPECT_THROW(mesher.triangles(0, 1, std::span<Triangle>(triangles).first(7)), std::invalid_argument);
  EXPECT_NO_THROW(mesher.triangles(4, 1, triangles));
}

} // namespace
