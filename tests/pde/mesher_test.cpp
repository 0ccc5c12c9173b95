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
