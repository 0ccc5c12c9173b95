#include "pdeface/core/sample_face.hpp"
#include "pdeface/core/topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace pdeface {
namespace {

TEST(SampleFace, IsAScanSizedFaceInMillimetres) {
  const Mesh m = sample_face();
  EXPECT_TRUE(validate(m).ok());
  EXPECT_GE(m.vertex_count(), 12000U); // the paper's range: 12k-51k vertices
  EXPECT_LE(m.vertex_count(), 51000U);
  EXPECT_EQ(m.units, Units::Millimetres);
  const Vec3 size = bounding_box(m).size();
  EXPECT_NEAR(size.x(), 170.0, 10.0); // a face is ~14-16 cm wide, ~17 cm to in front of the ears
  EXPECT_NEAR(size.y(), 205.0, 15.0); // and ~20 cm from chin to hairline
  EXPECT_EQ(m.normals.size(), m.vertex_count());
  EXPECT_EQ(m.colors.size(), m.vertex_count());
}

TEST(SampleFace, NoseTipIsTheFrontmostPointNearTheOrigin) {
  const Mesh m = sample_face();
  const auto tip = std::ranges::max_element(m.positions, {}, [](const Vec3& p) { return p.z(); });
  EXPECT_LT(std::abs(tip->x()), 2.0);
  EXPECT_LT(std::abs(tip->y()), 2.0);
  EXPECT_NEAR(sample_face_height(0, 0) - sample_face_height(40, 0), 33.0,
              5.0);                                                      // nose stands out of the cheeks
  EXPECT_LT(sample_face_height(32, 27), sample_face_height(32, 45));     // eye socket below the brow
  EXPECT_GT(sample_face_height(0, -24.5), sample_face_height(0, -30.5)); // upper lip above the mouth line
}

TEST(SampleFace, ScannerLikeTopology) {
  const Topology t = topology(sample_face());
  EXPECT_EQ(t.components, 1U);
  EXPECT_EQ(t.boundary_loops, 5U); // the outline and four holes
  EXPECT_EQ(t.non_manifold_triangles, 0U);
  EXPECT_EQ(topology(sample_face({.holes = false})).boundary_loops, 1U);
}

TEST(SampleFace, NormalsFaceTheViewer) {
  const Mesh m = sample_face();
  const auto towards = std::ranges::count_if(m.normals, [](const Vec3f& n) { return n.z() > 0.0F; });
  EXPECT_EQ(static_cast<std::size_t>(towards), m.vertex_count());
}

TEST(SampleFace, DeterministicAndSeeded) {
  const Mesh a = sample_face();
  const Mesh b = sample_face();
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  const Mesh c = sample_face({.seed = 7});
  EXPECT_NE(a.positions.size(), c.positions.size()); // another outline
  const Mesh flat = sample_face({.noise_mm = 0.0});
  for (const Vec3& p : flat.positions)
    ASSERT_DOUBLE_EQ(p.z(), sample_face_height(p.x(), p.y()));
}

TEST(SampleFace, RejectsBadOptions) {
  EXPECT_THROW((void)sample_face({.spacing_mm = 0.0}), std::invalid_argument);
  EXPECT_THROW((void)sample_face({.noise_mm = -1.0}), std::invalid_argument);
}

} // namespace
} // namespace pdeface
