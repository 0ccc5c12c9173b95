// Every scan in ../shared/faces (meshes and the point cloud), aligned by detection, gives the 28 profiles
// and the 4 evaluation profiles, where a person expects them, holes filled.

#include "pdeface/align/detect.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/profile_error.hpp"
#include "pdeface/slice/profiles.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>

namespace pdeface::slice {
namespace {

using align::Landmark;

double distance_to(const Vec3& p, const std::vector<Vec3>& line) {
  return metrics::distance_to_polylines(p, std::span(&line, 1));
}

// A real scan moved into the canonical frame by detected landmarks.
struct Canonical {
  Mesh mesh;
  align::Landmarks landmarks;
  align::FaceFrame frame;
};

Result<Canonical> read_canonical(const std::filesystem::path& path) {
  Result<formats::LoadedMesh> scan = formats::read_mesh(path);
  if (!scan) return scan.error();
  Result<align::Detection> found = align::detect_landmarks(scan->mesh);
  if (!found) return found.error();
  return Canonical{align::to_canonical(scan->mesh, found->frame),
                   align::to_canonical(found->landmarks, found->frame), found->frame};
}

class RealScan : public ::testing::TestWithParam<const char*> {};

TEST_P(RealScan, Gives28ProfilesAndTheEvaluationProfiles) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Result<Canonical> scan = read_canonical(path);
  ASSERT_TRUE(scan) << scan.error().to_string();
  const align::Landmarks& landmarks = scan->landmarks;

  Result<ProfileSet> set = extract_profiles(scan->mesh, landmarks, scan->frame);
  ASSERT_TRUE(set) << set.error().to_string();
  ASSERT_EQ(set->curves.size(), 28U);
  ASSERT_EQ(set->evaluation.size(), 4U);
  EXPECT_EQ(set->k, 30U);
  for (const ProfileCurve& c : set->curves) {
    EXPECT_EQ(c.raw.front().y(), c.extent[0]) << c.feature;
    EXPECT_EQ(c.raw.back().y(), c.extent[1]) << c.feature;
    EXPECT_EQ(c.points.size(), set->k);
    EXPECT_NEAR(c.points.front().y(), c.extent[0], 1e-9) << c.feature; // the fitted curve keeps its extent
    EXPECT_NEAR(c.points.back().y(), c.extent[1], 1e-9) << c.feature;
    EXPECT_GE(c.surface_points, 20U) << c.feature; // real sections, not a few filled points
    for (const auto& h : c.holes)
      EXPECT_LE(h[1] - h[0], set->max_hole_mm + 1e-9) << c.feature;
    // A profile is a function of height: samples never double back (the surface would fold).
    for (std::size_t k = 1; k < c.points.size(); ++k)
      EXPECT_GE(c.points[k].y(), c.points[k - 1].y()) << c.feature << ", point " << k;
  }
  // The middle curves reach from below the mouth to above the eyes; holes are a small part of the face.
  for (const ProfileCurve* c : {&set->curves[13], &set->curves[14]}) {
    EXPECT_LT(c->extent[0],
              std::min(landmarks[Landmark::MouthLeft]->y(), landmarks[Landmark::MouthRight]->y()) - 10.0);
    EXPECT_GT(c->extent[1], landmarks[Landmark::EyeInnerLeft]->y() + 10.0);
  }
  EXPECT_LT(set->filled_fraction, 0.15);
  EXPECT_GT(set->mask_coverage, 0.85);
  // Where a person expects them: the outer eye corner joints pass the outer eye corners, the symmetry
  // profile's front-most point is the nose tip, the eye line passes all four corners.
  for (auto [joint, corner] : {std::pair{3U, Landmark::EyeOuterRight},
                               {24U, Landmark::EyeOuterLeft},
                               {9U, Landmark::EyeInnerRight},
                               {18U, Landmark::EyeInnerLeft}})
    EXPECT_LT(distance_to(*landmarks[corner], set->curves[joint].raw), 6.0) << align::name(corner);
  const auto& symmetry = set->evaluation[0].points;
  const Vec3 front = *std::max_element(symmetry.begin(), symmetry.end(),
                                       [](const Vec3& a, const Vec3& b) { return a.z() < b.z(); });
  EXPECT_LT(front.norm(), 3.0);
  for (Landmark corner :
       {Landmark::EyeOuterRight, Landmark::EyeOuterLeft, Landmark::EyeInnerRight, Landmark::EyeInnerLeft})
    EXPECT_LT(distance_to(*landmarks[corner], set->evaluation[1].points), 9.0) << align::name(corner);
  // The fitted curves stay on the raw ones (mean over all points, at the default 10 %).
  double sum = 0.0;
  std::size_t n = 0;
  for (const ProfileCurve& c : set->curves)
    for (const Vec3& p : c.points) {
      sum += distance_to(p, c.raw);
      ++n;
    }
  EXPECT_LT(sum / static_cast<double>(n), 1.0);
}

TEST(RealScanFit, ArcLengthFitsBetterThanHeight) {
  // docs/slice.md's comparison on facefuns_f18 at 10 % (K = 30, spline samples evenly in the parameter):
  // the raw points' mean distance to the fitted spline and the K points' largest distance to the raw
  // profile, by arc length against by height.
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  const Result<Canonical> scan = read_canonical(path);
  ASSERT_TRUE(scan) << scan.error().to_string();
  const align::Landmarks& landmarks = scan->landmarks;
  std::array<double, 2> raw_mean{}, k_max{};
  for (Parameter parameter : {Parameter::ArcLength, Parameter::Height}) {
    Result<ProfileSet> set =
        extract_profiles(scan->mesh, landmarks, scan->frame,
                         {.parameter = parameter, .sampling = Sampling::Parameter, .fit = Fit::Spline});
    ASSERT_TRUE(set) << set.error().to_string();
    const auto i = static_cast<std::size_t>(parameter == Parameter::Height);
    std::size_t n = 0;
    for (const ProfileCurve& c : set->curves) {
      const std::vector<Vec3> dense =
          fit_spline(c.raw, {.parameter = parameter, .controls = set->k})->resample(4000);
      for (const Vec3& p : c.raw) {
        raw_mean[i] += distance_to(p, dense);
        ++n;
      }
      for (const Vec3& p : c.points)
        k_max[i] = std::max(k_max[i], distance_to(p, c.raw));
    }
    raw_mean[i] /= static_cast<double>(n);
  }
  EXPECT_LT(raw_mean[0], 0.2);
  EXPECT_LT(raw_mean[0], 0.8 * raw_mean[1]);
  EXPECT_LT(k_max[0], 1.5);
  EXPECT_LT(k_max[0], k_max[1]);
  std::printf("raw -> spline mean %.3f vs %.3f mm, K points -> raw max %.2f vs %.2f mm\n", raw_mean[0],
              raw_mean[1], k_max[0], k_max[1]);
}

INSTANTIATE_TEST_SUITE_P(Faces, RealScan, ::testing::ValuesIn(test::kSharedScans), test::FileParamName());

} // namespace
} // namespace pdeface::slice
