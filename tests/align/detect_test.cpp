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
  for (Vec3& p : m.positions) p = scale * (r * p) + t;
  for (Vec3f& n : m.normals) n = r.cast<float>() * n;
  m.units = Units::Unknown;
  return m;
}

class SampleInAnyPose : public ::testing::TestWithParam<int> {};

TEST_P(SampleInAnyPose, FindsTheNoseAndTheFrame) {
  std::mt19937 rng(static_cast<unsigned>(GetParam()));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Matrix3d r = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
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
  std::printf("pose %d: confidence %.2f symmetry %.2f nose %.1f fit %.1f\n", GetParam(), found->confidence,
              found->symmetry_rms_mm, found->nose_prominence_mm, found->fit_rms_mm);
}

INSTANTIATE_TEST_SUITE_P(RandomRotations, SampleInAnyPose, ::testing::Range(1, 9));

} // namespace
} // namespace pdeface::align
