#include "pdeface/align/detect.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

#include <Eigen/Geometry>

#include <random>

namespace pdeface::align {
namespace {

double degrees_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / 3.141592653589793;
}

Mesh transformed(Mesh m, const Eigen::Matrix3d& r, const Vec3& t, double scale) {
  for (Vec3& p : m.positions)
    p = scale * (r * p) + t;
  for (Vec3f& n : m.normals)
    n = r.cast<float>() * n;
  m.units = Units::Unknown;
  return m;
}

class SampleInAnyPose : public ::testing::TestWithParam<int> {};

TEST_P(SampleInAnyPose, FindsTheNoseAndTheFrame) {
  std::mt19937 rng(static_cast<unsigned>(GetParam()));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d r =
      Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  const Vec3 t(300 * u(rng), 300 * u(rng), 1000 + 300 * u(rng));
  const Mesh face = sample_face();
  const Mesh scan = transformed(face, r, t, 1.0);

  auto found = detect_landmarks(scan);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  const Vec3 true_tip = r * Vec3(0, 0, sample_face_height(0, 0)) + t;
  EXPECT_LT((*found->landmarks[Landmark::NoseTip] - true_tip).norm(), 3.0);
  // The canonical axes, seen in the scan, are the sample's own axes rotated by r.
  EXPECT_LT(degrees_between(found->frame.axis_in_scan(0), r * Vec3::UnitX()), 5.0);
  EXPECT_LT(degrees_between(found->frame.axis_in_scan(1), r * Vec3::UnitY()), 8.0);
  EXPECT_LT(degrees_between(found->frame.axis_in_scan(2), r * Vec3::UnitZ()), 8.0);
  EXPECT_GT(found->confidence, 0.5);
  EXPECT_EQ(found->landmarks.count(), kLandmarkCount);
  // Corners within 5 mm of where the sample face has them (their hollows are 5 mm wide).
  const SampleFaceLandmarks truth = sample_face_landmarks();
  const std::pair<Landmark, Vec3> corners[] = {
      {Landmark::EyeInnerLeft, truth.eye_inner_left}, {Landmark::EyeInnerRight, truth.eye_inner_right},
      {Landmark::EyeOuterLeft, truth.eye_outer_left}, {Landmark::EyeOuterRight, truth.eye_outer_right},
      {Landmark::MouthLeft, truth.mouth_left},        {Landmark::MouthRight, truth.mouth_right}};
  for (const auto& [landmark, where] : corners)
    EXPECT_LT((*found->landmarks[landmark] - (r * where + t)).norm(), 5.0) << name(landmark);
}

INSTANTIATE_TEST_SUITE_P(RandomRotations, SampleInAnyPose, ::testing::Range(1, 7));

TEST(Detect, UpsideDownAndInMetres) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(3.14159265358979, Vec3::UnitZ()).toRotationMatrix();
  const Mesh scan = transformed(sample_face(), r, Vec3(0.1, 0.2, 0.9), 0.001);
  auto found = detect_landmarks(scan);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  EXPECT_EQ(found->frame.scan_units, Units::Metres);
  EXPECT_DOUBLE_EQ(found->frame.scale, 1000.0);
  EXPECT_LT(degrees_between(found->frame.axis_in_scan(1), -Vec3::UnitY()), 8.0); // up is down in the scan
  const Vec3 tip = found->frame.to_canonical(*found->landmarks[Landmark::NoseTip]);
  EXPECT_LT(tip.norm(), 1e-9);
}

TEST(Detect, PointCloudsToo) {
  const Mesh cloud = to_mesh(to_point_cloud(sample_face()));
  auto found = detect_landmarks(cloud);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  EXPECT_LT((*found->landmarks[Landmark::NoseTip] - Vec3(0, 0, sample_face_height(0, 0))).norm(), 3.0);
}

// Shapes with symmetry planes but no nose: a sphere cap, a flat sheet, a box.
TEST(Detect, NoFaceInShapesWithoutANose) {
  Mesh cap;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      if (x * x + y * y < 90.0 * 90.0)
        cap.positions.emplace_back(x, y, std::sqrt(100.0 * 100.0 - x * x - y * y));
    }
  Mesh sheet;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 120; ++j)
      sheet.positions.emplace_back(1.5 * i, 1.5 * j, 0.0);
  for (const Mesh* shape : {&cap, &sheet}) {
    auto found = detect_landmarks(*shape);
    ASSERT_FALSE(found.ok());
    EXPECT_EQ(found.error().code, ErrorCode::NoFace);
    EXPECT_NE(found.error().message.find("no face found"), std::string::npos) << found.error().message;
  }
}

// Closed shapes with corners and rims: a box (its corners stand out like a nose tip, and it is very
// symmetric) and a capped cylinder. Their "noses" have no eyes or mouth around them.
TEST(Detect, NoFaceInABoxOrACylinder) {
  Mesh box;
  for (int i = 0; i <= 30; ++i)
    for (int j = 0; j <= 30; ++j)
      for (int face = 0; face < 6; ++face) {
        const double u = -1.0 + i / 15.0, v = -1.0 + j / 15.0;
        const Vec3 p = face == 0   ? Vec3(-1, u, v)
                       : face == 1 ? Vec3(1, u, v)
                       : face == 2 ? Vec3(u, -1, v)
                       : face == 3 ? Vec3(u, 1, v)
                       : face == 4 ? Vec3(u, v, -1)
                                   : Vec3(u, v, 1);
        box.positions.push_back(Vec3(120.0 * p.x(), 80.0 * p.y(), 60.0 * p.z()));
      }
  Mesh cylinder;
  for (int i = 0; i < 90; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 90.0;
    for (int k = 0; k <= 60; ++k)
      cylinder.positions.emplace_back(70.0 * std::cos(a), 70.0 * std::sin(a), -100.0 + 200.0 * k / 60.0);
    for (int r = 0; r < 24; ++r)
      for (double z : {-100.0, 100.0})
        cylinder.positions.emplace_back(70.0 * r / 24.0 * std::cos(a), 70.0 * r / 24.0 * std::sin(a), z);
  }
  for (const Mesh* shape : {&box, &cylinder}) {
    auto found = detect_landmarks(*shape);
    ASSERT_FALSE(found.ok()) << "confidence " << found->confidence;
    EXPECT_EQ(found.error().code, ErrorCode::NoFace);
    // A true message: detection was given no landmarks, and every cue's value is there.
    EXPECT_EQ(found.error().message.find("landmarks given"), std::string::npos) << found.error().message;
    EXPECT_NE(found.error().message.find("no face found"), std::string::npos) << found.error().message;
  }
}

TEST(Detect, NoFaceInAWholeSphere) {
  Mesh sphere;
  for (int i = 1; i < 60; ++i)
    for (int j = 0; j < 120; ++j) {
      const double theta = 3.14159265358979 * i / 60.0, phi = 3.14159265358979 * j / 60.0;
      sphere.positions.emplace_back(90.0 * std::sin(theta) * std::cos(phi),
                                    90.0 * std::sin(theta) * std::sin(phi), 90.0 * std::cos(theta));
    }
  auto found = detect_landmarks(sphere);
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.error().code, ErrorCode::NoFace);
}

TEST(Detect, AHandfulOfPointsIsNoFace) {
  Mesh tiny;
  for (int i = 0; i < 10; ++i)
    tiny.positions.emplace_back(i, i * i, 0.5 * i);
  auto found = detect_landmarks(tiny);
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.error().code, ErrorCode::NoFace);
  EXPECT_EQ(found.error().message, "no face found: 10 points are too few to hold one");
}

} // namespace
} // namespace pdeface::align
