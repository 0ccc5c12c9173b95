// Pose invariance: a scan turned by a random rotation (any axis, any angle) and shifted, then aligned,
// lands on the same canonical mesh as the scan aligned from its own pose: vertex by vertex within 1 mm RMS.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"

#include "pdeface_test.hpp"

#include <Eigen/Geometry>

#include <random>

namespace pdeface::align {
namespace {

// RMS distance between the vertices of the scan mapped by two frames (in mm).
double rms_between(const Mesh& scan_a, const FaceFrame& a, const Mesh& scan_b, const FaceFrame& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < scan_a.vertex_count(); ++i)
    sum += (a.to_canonical(scan_a.positions[i]) - b.to_canonical(scan_b.positions[i])).squaredNorm();
  return std::sqrt(sum / static_cast<double>(scan_a.vertex_count()));
}

void expect_pose_invariant(const Mesh& scan, int poses, unsigned seed) {
  auto reference = detect_landmarks(scan);
  ASSERT_TRUE(reference.ok()) << reference.error().to_string();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double size = bounding_box(scan).diagonal();
  for (int k = 0; k < poses; ++k) {
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    const Vec3 t = size * Vec3(u(rng), u(rng), u(rng));
    Mesh turned = scan;
    for (Vec3& p : turned.positions)
      p = r * p + t;
    auto found = detect_landmarks(turned);
    ASSERT_TRUE(found.ok()) << "pose " << k << ": " << found.error().to_string();
    const double rms = rms_between(scan, reference->frame, turned, found->frame);
    EXPECT_LT(rms, 1.0) << scan.name << ", pose " << k;
    std::printf("%s pose %d: %.3f mm RMS\n", scan.name.c_str(), k, rms);
  }
}

TEST(PoseInvariance, SampleFace) { expect_pose_invariant(sample_face(), 6, 7); }

class PoseInvarianceReal : public ::testing::TestWithParam<const char*> {};

TEST_P(PoseInvarianceReal, RealScan) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  auto scan = formats::read_mesh(path);
  ASSERT_TRUE(scan.ok()) << scan.error().to_string();
  expect_pose_invariant(scan->mesh, 6, 11);
}

INSTANTIATE_TEST_SUITE_P(SharedFaces, PoseInvarianceReal,
                         ::testing::Values("facefuns_f18.ply", "facefuns_f56_points.ply", "james.obj",
                                           "ict_07.wrl", "stfaces_neutral.wrl", "fran_cut.wrl"),
                         test::FileParamName());

} // namespace
} // namespace pdeface::align
