// Every scan in ../shared/faces (skipped when absent) reconstructs at 10 % and at 30 %, and at 10 % every
// scan's face, cheek to cheek (the face mask: chin to forehead, across to 1.3 × the outer eye corners or to
// where the face turns away in front of the ears), is covered: 97 % or more of the scan's face within 1 mm
// of the reconstruction, the reconstruction 0.25 mm or less from the scan on average there, and none of its
// area facing away from the viewer (no fold).

#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/pipeline/report.hpp"

#include "pdeface_test.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace pdeface::pipeline {
namespace {

class EveryScan : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryScan, ReconstructsAndCoversItsFace) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Result<formats::LoadedMesh> scan = formats::read_mesh(path);
  ASSERT_TRUE(scan) << scan.error().to_string();
  const Result<align::Alignment> alignment = align::align_scan(scan->mesh, std::nullopt, GetParam());
  ASSERT_TRUE(alignment) << alignment.error().to_string();
  const CanonicalScan canonical = canonical_scan(scan->mesh, *alignment);
  for (double ratio : {0.10, 0.30}) {
    ReconstructOptions options;
    options.profiles.ratio = ratio;
    const Result<Reconstruction> r = reconstruct(canonical, options, GetParam());
    ASSERT_TRUE(r) << ratio << ": " << r.error().to_string();
    const Result<metrics::Fidelity> f = metrics::measure_fidelity(canonical.mesh, r->profiles, r->canonical);
    ASSERT_TRUE(f) << ratio << ": " << f.error().to_string();
    std::printf("%s at %.0f %%: coverage %.1f %%, mask -> reconstruction %.3f mm, reconstruction -> scan "
                "%.3f mm, profile error %.3f mm, %zu holes filled (%.1f %%)\n",
                GetParam(), 100 * ratio, 100 * f->coverage.share, f->coverage.distance.mean,
                f->surface.b_to_a.mean, f->mean_profile_error, r->profiles.holes(),
                100 * r->profiles.filled_fraction);
    if (ratio != 0.10) continue;
    const Result<metrics::FaceYardstick> yardstick =
        metrics::FaceYardstick::make(canonical.mesh, r->profiles);
    ASSERT_TRUE(yardstick) << yardstick.error().to_string();
    const Result<metrics::SelfCheck> check = metrics::self_check(*yardstick, r->canonical);
    ASSERT_TRUE(check) << check.error().to_string();
    EXPECT_TRUE(check->passed()) << check->summary();
    EXPECT_GE(check->coverage, 0.97);
    EXPECT_LE(check->mean_mm, 0.25);
    EXPECT_EQ(check->facing_away, 0.0);
    EXPECT_LE(f->coverage.distance.mean, 0.5);
  }
}

// A lossless copy of the scan (its raw files, gzipped or not: float32 positions, as read) measures 0 both
// ways: every sample of the scan's face is a point of its own surface, and the copy's samples lie on it.
TEST_P(EveryScan, LosslessCopiesMeasureZero) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Result<formats::LoadedMesh> scan = formats::read_mesh(path);
  ASSERT_TRUE(scan) << scan.error().to_string();
  CompareOptions options;
  options.draco_bits.clear();
  options.budgets.clear();
  options.budgets_at_pde = false;
  options.ratios.clear();
  options.pde_budgets.clear();
  options.colour = false; // the raw rows alone
  options.threads = 1;
  const Result<ScanReport> report = compare_scan(scan->mesh, GetParam(), options);
  ASSERT_TRUE(report) << report.error().to_string();
  ASSERT_GE(report->variants.size(), 4U);
  for (const Variant& v : report->variants) {
    ASSERT_TRUE(v.fidelity) << v.name << ": " << v.failure;
    const metrics::MeshFidelity& f = *v.fidelity;
    EXPECT_EQ(f.coverage.share, 1.0) << v.name;
    EXPECT_LE(f.coverage.distance.max, 1e-4) << v.name << " mask -> mesh";
    EXPECT_LE(f.to_scan.max, 1e-4) << v.name << " mesh -> scan";
    EXPECT_GT(f.coverage.distance.samples, 1000U) << v.name;
    EXPECT_GT(f.to_scan.samples, 1000U) << v.name;
  }
}

INSTANTIATE_TEST_SUITE_P(SharedFaces, EveryScan, ::testing::ValuesIn(test::kSharedScans),
                         test::FileParamName());

} // namespace
} // namespace pdeface::pipeline
