#include "pdeface/core/mesh.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/core/topology.hpp"
#include "test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pdeface {
namespace {

using test::unit_square;

TEST(Mesh, BoundingBox) {
  const Box box = bounding_box(unit_square());
  EXPECT_EQ(box.min, Vec3(0, 0, 0));
  EXPECT_EQ(box.max, Vec3(1, 1, 0));
  EXPECT_DOUBLE_EQ(box.diagonal(), std::sqrt(2.0));
  EXPECT_TRUE(bounding_box(Mesh{}).empty());
}

TEST(Mesh, VertexNormalsFollowWinding) {
  Mesh m = unit_square();
  for (const Vec3f& n : vertex_normals(m))
    EXPECT_TRUE(n.isApprox(Vec3f(0, 0, 1)));
  m.positions.emplace_back(5, 5, 5); // on no triangle
  EXPECT_EQ(vertex_normals(m).back(), Vec3f::Zero());
}

TEST(Mesh, ValidateFindsEachViolation) {
  EXPECT_TRUE(validate(unit_square()).ok());

  Mesh bad_index = unit_square();
  bad_index.triangles.push_back({0, 1, 4});
  auto r = validate(bad_index, "m");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(r.error().message, "triangle 2 refers to vertex 4 of 4");
  EXPECT_EQ(r.error().source, "m");

  Mesh nan = unit_square();
  nan.positions[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validate(nan).error().code, ErrorCode::NonFinite);

  Mesh colours = unit_square();
  colours.colors.resize(3);
  EXPECT_EQ(validate(colours).error().code, ErrorCode::Malformed);
}

TEST(Mesh, PointCloudForms) {
  const Mesh m = unit_square();
  PointCloud cloud = to_point_cloud(m);
  EXPECT_EQ(cloud.positions.size(), 4U);
  const Mesh back = to_mesh(std::move(cloud));
  EXPECT_TRUE(back.is_point_cloud());
  EXPECT_EQ(back.positions, m.positions);
}

TEST(Topology, SquareHasOneComponentAndOneLoop) {
  const Topology t = topology(unit_square());
  EXPECT_EQ(t.components, 1U);
  EXPECT_EQ(t.boundary_loops, 1U);
  EXPECT_EQ(t.unreferenced_vertices, 0U);
}

TEST(Topology, ClosedTetrahedronHasNoBoundary) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const Topology t = topology(m);
  EXPECT_EQ(t.components, 1U);
  EXPECT_EQ(t.boundary_loops, 0U);
}

TEST(Topology, CountsPiecesLooseVerticesAndNonManifoldTriangles) {
  Mesh m = unit_square();
  for (const Vec3& p : unit_square().positions)
    m.positions.push_back(p + Vec3(3, 0, 0));
  m.triangles.push_back({4, 5, 6});
  m.positions.emplace_back(9, 9, 9);        // loose vertex
  m.positions.emplace_back(0.5, -1.0, 1.0); // a third triangle on edge 0-1: non-manifold
  m.triangles.push_back({0, 1, 9});
  const Topology t = topology(m);
  EXPECT_EQ(t.components, 2U);
  EXPECT_EQ(t.boundary_loops, 2U);
  EXPECT_EQ(t.unreferenced_vertices, 3U); // vertex 7 of the second square, the loose one, and 9 (rejected)
  EXPECT_EQ(t.non_manifold_triangles, 1U);
}

} // namespace
} // namespace pdeface

namespace pdeface {
namespace {

TEST(Components, LabelsAndDroppingSmallPieces) {
  Mesh m;
  // A strip of 4 triangles (6 vertices), a lone triangle, and a loose vertex.
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},  {0, 1, 0},  {1, 1, 0},
                 {2, 1, 0}, {9, 9, 9}, {10, 9, 9}, {9, 10, 9}, {5, 5, 5}};
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {6, 7, 8}};
  m.colors.assign(m.positions.size(), Vec4f(1, 0, 0, 1));
  EXPECT_EQ(component_labels(m), (std::vector<std::uint32_t>{0, 0, 0, 0, 0, 0, 1, 1, 1, 2}));
  const Mesh big = drop_small_components(m, 0.5);
  EXPECT_EQ(big.vertex_count(), 6U);
  EXPECT_EQ(big.triangle_count(), 4U);
  EXPECT_EQ(big.colors.size(), 6U);
  EXPECT_TRUE(validate(big).ok());
  EXPECT_EQ(drop_small_components(m, 0.2).vertex_count(), 9U); // the loose vertex goes, the triangle stays
}

} // namespace
} // namespace pdeface

namespace pdeface {
namespace {

// A triangle whose first vertex is not the smallest root: the second union must link roots, not the
// vertex that the first union moved (a bug that split components and left dangling indices).
TEST(Components, UnionsLinkRootsWhateverTheOrder) {
  Mesh m;
  m.positions.assign(6, Vec3::Zero());
  m.triangles = {{3, 4, 5}, {5, 1, 2}, {2, 0, 3}};
  EXPECT_EQ(component_labels(m), (std::vector<std::uint32_t>(6, 0)));
  for (const Mesh& sample : {sample_face({.spacing_mm = 4.0})}) {
    const Mesh kept = drop_small_components(sample, 0.5);
    EXPECT_TRUE(validate(kept).ok());
    EXPECT_EQ(kept.vertex_count(), sample.vertex_count());
  }
}

} // namespace
} // namespace pdeface
