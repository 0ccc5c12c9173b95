#include "pdeface/align/crop.hpp"
#include "pdeface/align/frame.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

namespace pdeface::align {
namespace {

TEST(Crop, KeepsTheFaceRegionOnly) {
  Mesh face = sample_face();
  Landmarks l = canonical_template();
  // A loose fragment far outside, and a "neck" below the chin.
  const auto base = static_cast<std::uint32_t>(face.positions.size());
  face.positions.insert(face.positions.end(), {{200, 0, 0}, {201, 0, 0}, {200, 1, 0}});
  face.colors.resize(face.positions.size(), Vec4f(1, 1, 1, 1));
  face.normals.resize(face.positions.size(), Vec3f(0, 0, 1));
  face.triangles.push_back({base, base + 1, base + 2});
  auto cut = crop_face(face, l);
  ASSERT_TRUE(cut.ok()) << cut.error().to_string();
  EXPECT_TRUE(validate(*cut).ok());
  EXPECT_LT(cut->vertex_count(), face.vertex_count());
  const Box box = bounding_box(*cut);
  EXPECT_GE(box.min.y(), l[Landmark::FaceBottom]->y());
  EXPECT_LE(box.max.y(), l[Landmark::FaceTop]->y());
  EXPECT_LE(box.max.x(), 48.0 + 22.0);
  EXPECT_EQ(cut->colors.size(), cut->vertex_count());
  EXPECT_GT(cut->vertex_count(), 8000U); // most of the face is there
}

TEST(Crop, NeedsTheBorderLandmarks) {
  Landmarks l = canonical_template();
  l[Landmark::FaceTop].reset();
  auto cut = crop_face(sample_face({.spacing_mm = 5.0}), l);
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(cut.error().message.find("face_top"), std::string::npos);
}

TEST(Crop, NothingInsideIsNoFace) {
  Mesh far = sample_face({.spacing_mm = 5.0});
  for (Vec3& p : far.positions)
    p.x() += 1000.0;
  auto cut = crop_face(far, canonical_template());
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().code, ErrorCode::NoFace);
}

} // namespace
} // namespace pdeface::align
