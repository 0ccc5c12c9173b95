// The self-check every result passes before it is written: measured against the scan on a face mask that
// the landmarks and the scan give, not the curves' own region, and refused when it is off.

#include "pdeface/align/frame.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include <gtest/gtest.h>

namespace pdeface::pipeline {
namespace {

struct SampleFace {
  CanonicalScan scan;
  Reconstruction right;
};

// Computed once per process: the suites using it run in one process each (tests/CMakeLists.txt).
const SampleFace& sample() {
  static const SampleFace s = [] {
    const Mesh face = sample_face();
    const Result<align::Alignment> alignment = align::align_scan(face);
    EXPECT_TRUE(alignment) << alignment.error().to_string();
    CanonicalScan canonical = canonical_scan(face, *alignment);
    Result<Reconstruction> r = reconstruct(canonical, {}, "sample");
    EXPECT_TRUE(r) << r.error().to_string();
    return SampleFace{std::move(canonical), *std::move(r)};
  }();
  return s;
}

TEST(SelfCheck, AFaithfulReconstructionPasses) {
  const SampleFace& s = sample();
  const Result<metrics::SelfCheck> c =
      metrics::checked(s.scan.mesh, s.right.profiles, s.right.canonical, {}, false, "sample");
  ASSERT_TRUE(c) << c.error().to_string();
  EXPECT_TRUE(c->passed()) << c->summary();
  EXPECT_LT(c->mean_mm, 0.1);
  EXPECT_GT(c->coverage, 0.99);
  EXPECT_EQ(c->facing_away, 0.0);
}

// The slicing forced onto the wrong region (the landmarks it slices by moved 45 mm up the face, the
// mask left where the face is): the surface is faithful to the scan where it lies, but it is not the face.
TEST(SelfCheck, SlicingOntoTheWrongRegionIsRefused) {
  const SampleFace& s = sample();
  CanonicalScan moved = s.scan;
  for (auto& l : moved.landmarks.points)
    if (l) *l += Vec3(0.0, 45.0, 0.0);
  const Result<Reconstruction> wrong = reconstruct(moved, {}, "sample");
  ASSERT_TRUE(wrong) << wrong.error().to_string();
  const Result<metrics::SelfCheck> c =
      metrics::checked(s.scan.mesh, s.right.profiles, wrong->canonical, {}, false, "sample");
  ASSERT_FALSE(c) << c->summary() << " " << c->coverage;
  EXPECT_EQ(c.error().code, ErrorCode::SelfCheck);
  EXPECT_EQ(c.error().source, "sample");
  EXPECT_NE(c.error().message.find("of the face within 1 mm <"), std::string::npos) << c.error().message;
  // Forced, the figures come back with the failures.
  const Result<metrics::SelfCheck> forced =
      metrics::checked(s.scan.mesh, s.right.profiles, wrong->canonical, {}, true, "sample");
  ASSERT_TRUE(forced);
  EXPECT_FALSE(forced->passed());
  EXPECT_LT(forced->coverage, 0.75);
}

// A fold: a band of the surface flipped over (its triangles' winding reversed where it turns back), and a
// surface moved 3 mm off the scan: each fails on its own measure.
TEST(SelfCheck, AFoldAndASurfaceOffTheScanFail) {
  const SampleFace& s = sample();
  Mesh folded = s.right.canonical;
  std::size_t flipped = 0;
  for (Triangle& t : folded.triangles) {
    const Vec3 c = (folded.positions[t[0]] + folded.positions[t[1]] + folded.positions[t[2]]) / 3.0;
    if (c.y() > 10.0 && c.y() < 20.0 && std::abs(c.x()) < 30.0) {
      std::swap(t[1], t[2]);
      ++flipped;
    }
  }
  ASSERT_GT(flipped, 100U);
  const double away = metrics::facing_away(folded, s.right.profiles.mask);
  EXPECT_GT(away, 0.01);
  EXPECT_EQ(metrics::facing_away(s.right.canonical, s.right.profiles.mask), 0.0);
  Result<metrics::SelfCheck> c = metrics::checked(s.scan.mesh, s.right.profiles, folded, {}, true, "sample");
  ASSERT_TRUE(c);
  ASSERT_EQ(c->failures.size(), 1U) << c->summary();
  EXPECT_NE(c->failures[0].find("faces away from the viewer"), std::string::npos);

  Mesh off = s.right.canonical;
  for (Vec3& p : off.positions)
    p.z() += 3.0;
  c = metrics::checked(s.scan.mesh, s.right.profiles, off, {}, true, "sample");
  ASSERT_TRUE(c);
  EXPECT_NE(c->summary().find("mean distance to the scan"), std::string::npos) << c->summary();
  EXPECT_GT(c->mean_mm, 2.0);
}

// `encode` checks the file it wrote on a coarser grid than `metrics::checked` (a sample every 1 mm each way,
// no evaluation profiles): its figures agree with the full check's on the decoded file, and a file of 4
// curves (about 3 mm from the scan on average) is refused, or with `force` returned with its failures.
TEST(SelfCheck, EncodeChecksWhatItWroteAndRefusesAFileOffTheScan) {
  const Mesh face = sample_face();
  const Result<align::Alignment> alignment = align::align_scan(face);
  ASSERT_TRUE(alignment) << alignment.error().to_string();
  EncodeRequest request{.profiles = {.ratio = 0.1}, .source = "sample"};
  const Result<EncodeOutcome> good = encode_aligned(face, *alignment, request);
  ASSERT_TRUE(good) << good.error().to_string();
  ASSERT_TRUE(good->check);
  EXPECT_TRUE(good->check->passed()) << good->check->summary();
  const Result<pdef::Face> decoded = pdef::decode(good->encoded.bytes);
  ASSERT_TRUE(decoded);
  const Result<Mesh> mesh = pdef::to_mesh(*decoded);
  ASSERT_TRUE(mesh);
  const CanonicalScan canonical = canonical_scan(face, *alignment);
  const Result<metrics::SelfCheck> full = metrics::checked(
      canonical.mesh, good->profiles, align::to_canonical(*mesh, alignment->frame), {}, false, "sample");
  ASSERT_TRUE(full) << full.error().to_string();
  EXPECT_NEAR(good->check->mean_mm, full->mean_mm, 0.01 + 0.1 * full->mean_mm);
  EXPECT_NEAR(good->check->coverage, full->coverage, 0.01);
  EXPECT_EQ(good->check->facing_away, full->facing_away);

  request.profiles.planes.curves = 4;
  const Result<EncodeOutcome> bad = encode_aligned(face, *alignment, request);
  ASSERT_FALSE(bad) << bad->check->summary();
  EXPECT_EQ(bad.error().code, ErrorCode::SelfCheck);
  EXPECT_EQ(bad.error().source, "sample");
  EXPECT_NE(bad.error().message.find("mean distance to the scan"), std::string::npos) << bad.error().message;
  request.force = true;
  const Result<EncodeOutcome> forced = encode_aligned(face, *alignment, request);
  ASSERT_TRUE(forced) << forced.error().to_string();
  ASSERT_TRUE(forced->check);
  EXPECT_FALSE(forced->check->passed());
  EXPECT_GT(forced->check->mean_mm, 1.0);
}

} // namespace
} // namespace pdeface::pipeline
