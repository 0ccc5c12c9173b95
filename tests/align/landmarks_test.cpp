#include "pdeface/align/frame.hpp"
#include "pdeface/align/landmarks.hpp"

#include "pdeface_test.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <fstream>

namespace pdeface::align {
namespace {

TEST(Landmarks, NamesRoundTripAndMirror) {
  for (std::size_t i = 0; i < kLandmarkCount; ++i) {
    const auto l = static_cast<Landmark>(i);
    EXPECT_EQ(landmark_from_name(name(l)), l);
    EXPECT_EQ(mirrored(mirrored(l)), l);
  }
  EXPECT_EQ(mirrored(Landmark::EyeOuterLeft), Landmark::EyeOuterRight);
  EXPECT_EQ(mirrored(Landmark::NoseTip), Landmark::NoseTip);
  EXPECT_EQ(landmark_from_name("nose"), std::nullopt);
}

TEST(Landmarks, JsonRoundTrip) {
  Landmarks l;
  l.units = Units::Metres;
  l[Landmark::NoseTip] = Vec3(0.1, 0.2, 0.3);
  l[Landmark::MouthLeft] = Vec3(-1e-3, 2.5, 1.0 / 3.0);
  auto back = read_landmarks_json(write_landmarks_json(l), "l.json");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back->units, Units::Metres);
  EXPECT_EQ(back->count(), 2U);
  EXPECT_EQ(*(*back)[Landmark::MouthLeft], *l[Landmark::MouthLeft]); // exact: JSON numbers keep 17 digits
  EXPECT_FALSE(back->has(Landmark::FaceTop));
}

TEST(Landmarks, JsonErrorsSayWhereAndWhat) {
  auto syntax =
      read_landmarks_json("{\n  \"landmarks\": {\n    \"nose_tip\": [1, 2,, 3]\n  }\n}", "bad.json");
  ASSERT_FALSE(syntax);
  EXPECT_EQ(syntax.error().code, ErrorCode::Malformed);
  EXPECT_EQ(syntax.error().where.line, 3U);
  EXPECT_EQ(syntax.error().where.column, 23U); // the second comma
  EXPECT_EQ(syntax.error().source, "bad.json");

  auto unknown = read_landmarks_json(R"({"landmarks": {"nose": [1, 2, 3]}})", "x");
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().message.find("unknown landmark \"nose\""), std::string::npos);

  auto nan = read_landmarks_json(R"({"landmarks": {"nose_tip": [1, "a", 3]}})", "x");
  ASSERT_FALSE(nan);
  EXPECT_NE(nan.error().message.find("three finite numbers"), std::string::npos);

  EXPECT_EQ(read_landmarks_json("", "x").error().code, ErrorCode::Empty);
  EXPECT_EQ(read_landmarks_json(R"({"version": 2, "landmarks": {}})", "x").error().code,
            ErrorCode::UnsupportedVersion);
  EXPECT_EQ(read_landmarks_json(R"({"units": "furlong", "landmarks": {}})", "x").error().code,
            ErrorCode::Malformed);
}

TEST(Landmarks, MenpoLjsonOfJames) {
  PDEFACE_FACE_OR_SKIP(path, "james.ljson");
  std::ifstream in(path);
  const std::string bytes{std::istreambuf_iterator<char>(in), {}};
  auto l = read_landmarks(bytes, path.string()); // told apart from ours by content
  ASSERT_TRUE(l.ok()) << l.error().to_string();
  EXPECT_EQ(l->count(), 8U); // no forehead point in the iBUG 68
  // Points 37 (nose tip), 26 (the face's left outer eye corner, at +x), 48 (its right mouth corner).
  EXPECT_TRUE((*l)[Landmark::NoseTip]->isApprox(Vec3(-8.7, -30.7, 38.3), 1e-2));
  EXPECT_GT((*l)[Landmark::EyeOuterLeft]->x(), (*l)[Landmark::EyeOuterRight]->x());
  EXPECT_GT((*l)[Landmark::MouthLeft]->x(), (*l)[Landmark::MouthRight]->x());
}

TEST(Landmarks, LjsonWithImageLeftAndRightIsMappedOntoTheFacesOwn) {
  // A flat 68-point list (version 1 layout) of a face looking along +z: iBUG's "left eye" (36-41) is the
  // image's left, the face's right.
  std::string points;
  for (int i = 0; i < 68; ++i) {
    Vec3 p(0, 0, 0);
    if (i == 30) p = Vec3(0, 0, 20);
    if (i == 36) p = Vec3(-45, 35, -10);
    if (i == 39) p = Vec3(-15, 35, -10);
    if (i == 42) p = Vec3(15, 35, -10);
    if (i == 45) p = Vec3(45, 35, -10);
    if (i == 48) p = Vec3(-25, -30, -5);
    if (i == 54) p = Vec3(25, -30, -5);
    if (i == 8) p = Vec3(0, -80, -10);
    points += (i ? "," : "") + fmt::format("[{},{},{}]", p.x(), p.y(), p.z());
  }
  auto l = read_ljson(R"({"landmarks": {"points": [)" + points + "]}}", "flat.ljson");
  ASSERT_TRUE(l.ok()) << l.error().to_string();
  EXPECT_EQ(*(*l)[Landmark::EyeOuterLeft], Vec3(45, 35, -10));
  EXPECT_EQ(*(*l)[Landmark::MouthRight], Vec3(-25, -30, -5));
  EXPECT_EQ(*(*l)[Landmark::FaceBottom], Vec3(0, -80, -10));
}

TEST(Frame, RecoversAKnownPoseAndUnits) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())
                                .toRotationMatrix(); // canonical -> scan (rotation part)
  const Vec3 t(0.1, -0.2, 1.2);                      // metres
  Landmarks scan;
  scan.units = Units::Metres;
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    scan.points[i] = Vec3(r * (*canonical_template().points[i] / 1000.0) + t);
  auto frame = frame_from_landmarks(scan, Units::Metres);
  ASSERT_TRUE(frame.ok()) << frame.error().to_string();
  EXPECT_TRUE(frame->rotation.isApprox(r.transpose(), 1e-9));
  EXPECT_DOUBLE_EQ(frame->scale, 1000.0);
  for (std::size_t i = 0; i < kLandmarkCount; ++i)
    EXPECT_LT((frame->to_canonical(*scan.points[i]) - *canonical_template().points[i]).norm(), 1e-9);
  EXPECT_LT((frame->to_scan(Vec3(1, 2, 3)) - (r * Vec3(0.001, 0.002, 0.003) + t)).norm(), 1e-12);
}

TEST(Frame, RefusesTooFewOrCollinearLandmarks) {
  Landmarks l;
  EXPECT_EQ(frame_from_landmarks(l, Units::Millimetres).error().code, ErrorCode::InvalidArgument);
  l[Landmark::NoseTip] = Vec3(0, 0, 0);
  l[Landmark::FaceTop] = Vec3(0, 80, 0);
  l[Landmark::FaceBottom] = Vec3(0, -80, 0);
  auto r = frame_from_landmarks(l, Units::Millimetres);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("collinear"), std::string::npos);
}

TEST(Frame, DetectUnitsFromSize) {
  Mesh m;
  m.positions = {{0, 0, 0}, {0.15, 0.2, 0.1}};
  EXPECT_EQ(detect_units(m), Units::Metres);
  m.positions[1] = Vec3(15, 20, 10);
  EXPECT_EQ(detect_units(m), Units::Centimetres);
  m.positions[1] = Vec3(150, 200, 100);
  EXPECT_EQ(detect_units(m), Units::Millimetres);
  m.units = Units::Inches; // stated units win
  EXPECT_EQ(detect_units(m), Units::Inches);
}

TEST(Frame, AlignmentJsonIsReadableAsLandmarks) {
  Landmarks l = canonical_template();
  FaceFrame f;
  f.scale = 1000.0;
  const std::string text = write_alignment_json(l, f, 0.9);
  EXPECT_NE(text.find("\"to_canonical\""), std::string::npos);
  EXPECT_NE(text.find("\"confidence\": 0.9"), std::string::npos);
  auto back = read_landmarks(text, "a.json");
  ASSERT_TRUE(back.ok()) << back.error().to_string();
  EXPECT_EQ(back->count(), kLandmarkCount);
}

} // namespace
} // namespace pdeface::align
