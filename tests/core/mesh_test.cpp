#include "pdeface/core/image.hpp"
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
  // What is kept, as new indices: the strip's vertices first, then the lone triangle's; nothing when every
  // piece is large enough.
  constexpr std::uint32_t kGone = kDroppedVertex;
  EXPECT_EQ(kept_component_vertices(m, 0.2), (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, kGone}));
  EXPECT_EQ(kept_component_vertices(m, 0.5),
            (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5, kGone, kGone, kGone, kGone}));
  EXPECT_TRUE(kept_component_vertices(m, 0.1).empty());
  EXPECT_EQ(drop_small_components(m, 0.1).vertex_count(), 10U);
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

// ---- texture coordinates per corner, materials, images -------------------------------------------------

namespace pdeface {
namespace {

// Two triangles sharing the edge 0-2, the second giving vertex 0 a coordinate of its own: a seam.
Mesh seam_square() {
  Mesh m = test::unit_square();
  m.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5F, 0.5F}};
  m.texcoord_triangles = m.triangles;
  m.texcoord_triangles[1][0] = 4;
  return m;
}

TEST(CornerTexcoords, ValidateChecksBothForms) {
  EXPECT_TRUE(validate(seam_square()).ok());
  Mesh m = seam_square();
  m.texcoord_triangles.pop_back();
  Result<void> r = validate(m, "m");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "1 texture coordinate triangles for 2 triangles");
  m = seam_square();
  m.texcoord_triangles[1][2] = 5;
  r = validate(m, "m");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::IndexOutOfRange);
  EXPECT_EQ(r.error().message, "triangle 1 refers to texture coordinate 5 of 5");
  m = seam_square();
  m.texcoord_triangles.clear(); // 5 per-vertex coordinates for 4 vertices
  EXPECT_EQ(validate(m).error().message, "5 texture coordinates for 4 vertices");
}

TEST(CornerTexcoords, SplittingOnlyTheSeamVertices) {
  const Mesh m = seam_square();
  std::size_t split = 0;
  const Mesh v = with_vertex_texcoords(m, &split);
  EXPECT_EQ(split, 1u);
  ASSERT_TRUE(validate(v).ok());
  EXPECT_FALSE(v.has_corner_texcoords());
  EXPECT_EQ(v.vertex_count(), 5u);
  EXPECT_EQ(v.positions[4], m.positions[m.triangles[1][0]]) << "the copy shares the position";
  EXPECT_EQ(corner_texcoords(v), corner_texcoords(m));
  EXPECT_EQ(v.triangles[0], m.triangles[0]) << "the first corner keeps the vertex";
  // Welding undoes it.
  std::size_t merged = 0;
  const Mesh w = weld_texcoord_seams(v, &merged);
  EXPECT_EQ(merged, 1u);
  ASSERT_TRUE(validate(w).ok());
  EXPECT_EQ(w.positions, m.positions);
  EXPECT_EQ(w.triangles, m.triangles);
  EXPECT_EQ(corner_texcoords(w), corner_texcoords(m));
  // Per-vertex coordinates and meshes without any are left as they are.
  EXPECT_EQ(with_vertex_texcoords(v).positions.size(), 5u);
  EXPECT_EQ(weld_texcoord_seams(test::unit_square()).positions.size(), 4u);
}

TEST(CornerTexcoords, CroppingAndDroppingPiecesKeepTheCorners) {
  Mesh m = seam_square();
  const std::size_t n = m.vertex_count();
  // A far triangle of its own, dropped as a small piece.
  m.positions.insert(m.positions.end(), {Vec3(10, 10, 0), Vec3(11, 10, 0), Vec3(10, 11, 0)});
  m.triangles.insert(m.triangles.begin(),
                     Triangle{static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n + 1),
                              static_cast<std::uint32_t>(n + 2)});
  m.texcoord_triangles.insert(m.texcoord_triangles.begin(), Triangle{0, 0, 0});
  m.material = Material{.name = "skin", .base_color = Vec4f::Ones(), .base_color_image = {}};
  ASSERT_TRUE(validate(m).ok());
  const Mesh kept = drop_small_components(m, 0.6); // 3 of 7 vertices: fewer than 0.6 × 7
  ASSERT_TRUE(validate(kept).ok());
  EXPECT_EQ(kept.triangle_count(), 2u);
  EXPECT_EQ(corner_texcoords(kept), corner_texcoords(seam_square()));
  EXPECT_TRUE(kept.material);
}

TEST(Images, HeadersAreReadWithoutDecoding) {
  // PNG: signature, IHDR 3 × 2.
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\0\0\x03\0\0\0\x02\x08\x02\0\0\0\0\0\0\0", 33);
  Result<ImageInfo> info = inspect_image(png, "p.png");
  ASSERT_TRUE(info.ok()) << info.error().to_string();
  EXPECT_EQ(info->mime_type, "image/png");
  EXPECT_EQ(info->width, 3u);
  EXPECT_EQ(info->height, 2u);
  // JPEG: SOI, an APP0 segment, then SOF0 of 2400 × 1600.
  std::string jpeg("\xFF\xD8\xFF\xE0\x00\x04xx\xFF\xC0\x00\x08\x08\x06\x40\x09\x60\x03", 19);
  info = inspect_image(jpeg, "j.jpg");
  ASSERT_TRUE(info.ok()) << info.error().to_string();
  EXPECT_EQ(info->mime_type, "image/jpeg");
  EXPECT_EQ(info->width, 2400u);
  EXPECT_EQ(info->height, 1600u);
  // A bomb: 65535 × 65535 declared in a few bytes.
  jpeg[13] = jpeg[14] = jpeg[15] = jpeg[16] = '\xFF';
  Result<ImageInfo> bomb = inspect_image(jpeg, "j.jpg");
  ASSERT_FALSE(bomb.ok());
  EXPECT_EQ(bomb.error().code, ErrorCode::CountTooLarge);
  EXPECT_EQ(bomb.error().where.byte, 13u);
  // Cut inside the APP0 segment; a scan before any frame; not an image.
  EXPECT_EQ(inspect_image(jpeg.substr(0, 6), "j.jpg").error().code, ErrorCode::Truncated);
  EXPECT_EQ(inspect_image(std::string("\xFF\xD8\xFF\xDA\x00\x02", 6), "j.jpg").error().code,
            ErrorCode::Malformed);
  EXPECT_EQ(inspect_image("GIF89a", "g.gif").error().code, ErrorCode::UnsupportedFormat);
  png[19] = '\0'; // width 0
  EXPECT_EQ(inspect_image(png, "p.png").error().code, ErrorCode::Malformed);
  EXPECT_EQ(inspect_image(png.substr(0, 20), "p.png").error().code, ErrorCode::Truncated);
}

TEST(Images, ResolvingNotesWhatIsMissing) {
  Notes notes;
  Result<Image> image = resolve_image({}, "face.jpg", "f.obj", &notes);
  ASSERT_TRUE(image.ok());
  EXPECT_TRUE(image->bytes.empty());
  EXPECT_EQ(image->uri, "face.jpg");
  ASSERT_EQ(notes.size(), 1u);
  const Resolver gif = [](std::string_view) -> Result<std::string> { return std::string("GIF89a"); };
  image = resolve_image(gif, "face.gif", "f.obj", &notes);
  ASSERT_TRUE(image.ok());
  EXPECT_TRUE(image->bytes.empty());
  EXPECT_EQ(notes.size(), 2u);
}

} // namespace
} // namespace pdeface
