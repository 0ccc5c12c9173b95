// Scans we have not tuned on: the shared scans made into what users bring (full heads with hair and a
// neck, busts on a plinth, a side or the chin cut short, holes, noise, a child's proportions, a smile, an
// open mouth), each in a random pose and in other units, reconstructed from the variant's file alone and
// judged against the truth (the modified face where it was made, in the canonical frame, with the
// landmarks it was made from), not against what the pipeline saw: the cheek-to-cheek face of the truth
// (`profile_planes`' mask on the truth's surface and landmarks: chin to forehead, across to 1.3 × the outer
// eye corners or to where the face turns away in front of the ears), its front-most surface within 1 mm of
// the reconstruction, the reconstruction's distance to it, and the share of its area facing away. The cases
// below the line were written after the method was settled on those above it.

#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/metrics/front_view.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/pipeline/reconstruct.hpp"
#include "pdeface/slice/face_mask.hpp"
#include "pdeface/slice/planes.hpp"

#include "pdeface_test.hpp"
#include "scan_variants.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>

namespace pdeface::pipeline {
namespace {

using test::FaceScan;

struct Judged {
  double coverage = 0.0;    // share of the face's front-most surface within 1 mm of the reconstruction
  double to_scan_mm = 0.0;  // mean reconstruction -> truth, inside the face where the truth has surface
  double back_facing = 0.0; // share of the reconstruction's area inside the face facing away
};

// The truth's face: from the chin to the forehead, across the cheeks to 1.45 × the outer eye corners or,
// nearer, to where the truth's face turns away from the viewer in front of the ears (`profile_planes`' mask
// of the truth's own surface and landmarks); `across` > 0: a plain ellipse that wide instead.
Judged judge(const FaceScan& truth, const Mesh& reconstruction, double across = 0.0) {
  Result<slice::FaceMask> mask = slice::face_mask(truth.landmarks, {.beyond_outer_corners = across});
  if (across <= 0.0) {
    const Result<slice::PlaneLayout> layout =
        slice::profile_planes(truth.mesh, truth.landmarks, {}, {.max_gap_mm = 45.0});
    EXPECT_TRUE(layout) << layout.error().to_string();
    if (!layout) return {};
    mask = layout->mask;
  }
  EXPECT_TRUE(mask) << mask.error().to_string();
  if (!mask) return {};
  const metrics::FrontView view(truth.mesh, -mask->half_width, mask->half_width,
                                mask->centre_y - mask->half_height, mask->centre_y + mask->half_height, 0.5);
  const std::vector<Vec3> face = view.samples([&](const Vec3& p) { return mask->contains(p); });
  Judged j;
  const metrics::SurfaceDistance to_reconstruction(reconstruction);
  std::size_t near = 0;
  for (const Vec3& p : face)
    near += to_reconstruction.distance(p) <= 1.0 ? 1 : 0;
  j.coverage = face.empty() ? 0.0 : static_cast<double>(near) / static_cast<double>(face.size());

  const metrics::SurfaceDistance to_truth(truth.mesh);
  double sum = 0.0;
  std::size_t n = 0;
  for (const Vec3& p : metrics::sample_surface(reconstruction, 0.5))
    if (mask->contains(p) && view.sees_surface(p.x(), p.y())) {
      sum += to_truth.distance(p);
      ++n;
    }
  j.to_scan_mm = n ? sum / static_cast<double>(n) : 1e9;
  double area = 0.0, away = 0.0;
  for (const Triangle& t : reconstruction.triangles) {
    const Vec3& a = reconstruction.positions[t[0]];
    const Vec3 cross = (reconstruction.positions[t[1]] - a).cross(reconstruction.positions[t[2]] - a);
    const Vec3 centre = (a + reconstruction.positions[t[1]] + reconstruction.positions[t[2]]) / 3.0;
    if (!mask->contains(centre)) continue;
    area += 0.5 * cross.norm();
    if (cross.z() < 0.0) away += 0.5 * cross.norm();
  }
  j.back_facing = area > 0.0 ? away / area : 1.0;
  return j;
}

// The shared scan as the truth: aligned by the library (it is judged on the shared scans elsewhere), moved
// into the canonical frame with its landmarks.
std::optional<FaceScan> truth_of(const std::string& name) {
  const std::optional<std::filesystem::path> path = test::face(name);
  if (!path) return std::nullopt;
  const Result<formats::LoadedMesh> scan = formats::read_mesh(*path);
  if (!scan) return std::nullopt;
  const Result<align::Alignment> alignment = align::align_scan(scan->mesh, std::nullopt, name);
  if (!alignment) return std::nullopt;
  const CanonicalScan canonical = canonical_scan(scan->mesh, *alignment);
  return FaceScan{canonical.mesh, canonical.landmarks};
}

struct Case {
  std::string scan;
  std::string variant;
  std::function<FaceScan(FaceScan)> make;
  double mm_per_unit;
  Units units;
  unsigned seed;
  //! A known limit (docs/align.md): detection may refuse it, cleanly (`NoFace`), but never reconstruct a
  //! wrong face from it.
  bool limit = false;
};

std::vector<Case> cases() {
  using namespace test;
  const auto head = [](FaceScan f) { return with_back_of_head(std::move(f)); };
  const auto bust = [](FaceScan f) { return on_pedestal(with_back_of_head(std::move(f))); };
  return {
      {"facefuns_f18.ply", "full head, arbitrary units", head, 4.3, Units::Unknown, 1},
      {"facefuns_m46.ply", "full head, m", head, 1000.0, Units::Metres, 2},
      {"james.obj", "full head, cm", head, 10.0, Units::Unknown, 3},
      {"facefuns_f36.ply", "bust on a plinth, arbitrary", bust, 2.7, Units::Unknown, 4},
      {"meshmonk_demoface.obj", "bust on a plinth, m", bust, 1000.0, Units::Unknown, 5},
      {"facefuns_m26.ply", "child bust, arbitrary",
       [](FaceScan f) { return on_pedestal(with_back_of_head(child_like(std::move(f)))); }, 1.9,
       Units::Unknown, 6},
      {"facefuns_f56.ply", "child face, mm", [](FaceScan f) { return child_like(std::move(f)); }, 1.0,
       Units::Millimetres, 7},
      {"facefuns_f18.ply", "smile, cm", [](FaceScan f) { return smiling(std::move(f)); }, 10.0,
       Units::Centimetres, 8},
      {"facefuns_m66.ply", "open mouth, mm", [](FaceScan f) { return open_mouth(std::move(f)); }, 1.0,
       Units::Unknown, 9},
      {"ict_04.obj", "smile + open mouth, cm", [](FaceScan f) { return open_mouth(smiling(std::move(f))); },
       10.0, Units::Unknown, 10},
      {"facefuns_f36.ply", "left side cut", [](FaceScan f) { return cut_side(std::move(f), 1.0); }, 1.0,
       Units::Millimetres, 11},
      {"meshmonk_demoface.obj", "right side cut, holes",
       [](FaceScan f) { return with_holes(cut_side(std::move(f), -1.0), 12); }, 1.0, Units::Unknown, 12},
      {"facefuns_m46.ply", "holes + noise 0.3 mm",
       [](FaceScan f) { return with_noise(with_holes(std::move(f), 13, 5), 0.3, 13); }, 1.0, Units::Unknown,
       13},
      {"facefuns_f56.ply", "chin cut, holes, m",
       [](FaceScan f) { return with_holes(cut_chin(std::move(f)), 14); }, 1000.0, Units::Metres, 14},
      {"ict_02.glb", "full head, holes, arbitrary",
       [](FaceScan f) { return with_holes(with_back_of_head(std::move(f)), 15); }, 0.37, Units::Unknown, 15},
      {"demosthenes.obj", "bust, other pose", [](FaceScan f) { return f; }, 0.01, Units::Unknown, 16},
      // ---- written after the method was settled on the cases above. Five of the eight failed at first;
      // fixed in the method, not here: holes showing the inside of a head fooled the landmarks' depth map,
      // a curve ended on the wall of a chin cut across, a capture hole merged with an eye hole was taken
      // for the eye. The known limit is the one not fixed.
      {"stfaces_neutral.wrl", "full head, holes, m",
       [](FaceScan f) { return with_holes(with_back_of_head(std::move(f)), 21, 3); }, 1000.0, Units::Metres,
       21},
      // A capture hole swallowed the child's left eye and its eye hole: found at a quick look (landmark
      // fit 6.7 mm), lost on the finer map the final landmarks are searched on.
      {"ict_06.glb", "child bust, holes, arbitrary",
       [](FaceScan f) { return with_holes(on_pedestal(with_back_of_head(child_like(std::move(f)))), 22); },
       0.21, Units::Unknown, 22, true},
      {"facefuns_f36.ply", "smile, noise 0.2 mm, cm",
       [](FaceScan f) { return with_noise(smiling(std::move(f)), 0.2, 23); }, 10.0, Units::Unknown, 23},
      {"james.obj", "open mouth, left side cut",
       [](FaceScan f) { return cut_side(open_mouth(std::move(f)), 1.0); }, 1.0, Units::Millimetres, 24},
      {"bust_man_wreath.obj", "holes, arbitrary", [](FaceScan f) { return with_holes(std::move(f), 25, 5); },
       37.0, Units::Unknown, 25},
      {"facefuns_m66.ply", "child, open mouth, m",
       [](FaceScan f) { return open_mouth(child_like(std::move(f))); }, 1000.0, Units::Metres, 26},
      {"ict_00.obj", "full head, chin cut, cm",
       [](FaceScan f) { return cut_chin(with_back_of_head(std::move(f))); }, 10.0, Units::Centimetres, 27},
      {"facefuns_f56_points.ply", "cloud, full head, arbitrary",
       [](FaceScan f) { return with_back_of_head(std::move(f)); }, 3.3, Units::Unknown, 28},
  };
}

class HeldOut : public ::testing::TestWithParam<std::size_t> {};

// Each variant, read as a user's file would be (its own pose and units, nothing of the truth), is found,
// reconstructed at 10 % and checked against the truth: 96 % of the cheek-to-cheek face within 1 mm (capture
// noise of 0.3 mm alone puts a few % of the truth's samples a millimetre off any smooth surface), the
// surface 0.25 mm from it on average, nothing folded; and its own self-check agrees that it passed.
TEST_P(HeldOut, ReconstructsTheWholeFaceFaithfully) {
  const Case c = cases()[GetParam()];
  static std::map<std::string, std::optional<FaceScan>> truths;
  if (!truths.contains(c.scan)) truths.emplace(c.scan, truth_of(c.scan));
  const std::optional<FaceScan>& original = truths.at(c.scan);
  if (!original) GTEST_SKIP() << c.scan << " is not in the shared faces (PDEFACE_DATA)";
  const FaceScan truth = c.make(*original);
  const test::Posed variant = test::posed(truth, c.seed, c.mm_per_unit, c.units);
  // PDEFACE_HELD_OUT=folder keeps each variant as a file there, to look at (pdeface reconstruct --preview).
  if (const char* keep = std::getenv("PDEFACE_HELD_OUT")) {
    ASSERT_TRUE(formats::write_mesh(variant.mesh, std::filesystem::path(keep) /
                                                      ("heldout_" + std::to_string(c.seed) + ".ply")));
  }
  const Result<align::Alignment> alignment = align::align_scan(variant.mesh, std::nullopt, c.variant);
  if (c.limit && !alignment) {
    EXPECT_EQ(alignment.error().code, ErrorCode::NoFace) << alignment.error().to_string();
    std::printf("%s, %s: refused (a known limit): %s\n", c.scan.c_str(), c.variant.c_str(),
                alignment.error().message.c_str());
    return;
  }
  ASSERT_TRUE(alignment) << alignment.error().to_string();
  const Result<Reconstruction> r = reconstruct(variant.mesh, *alignment, {}, c.variant);
  ASSERT_TRUE(r) << r.error().to_string();
  Mesh in_truth = r->scan;
  for (Vec3& p : in_truth.positions)
    p = variant.truth.to_canonical(p);
  const Judged j = judge(truth, in_truth);
  std::printf("%s, %s: coverage %.1f %%, to scan %.3f mm, facing away %.2f %%\n", c.scan.c_str(),
              c.variant.c_str(), 100 * j.coverage, j.to_scan_mm, 100 * j.back_facing);
  EXPECT_GE(j.coverage, 0.96); // the shared scans themselves are held to 97 % (every_scan_test.cpp)
  EXPECT_LE(j.to_scan_mm, 0.25);
  EXPECT_EQ(j.back_facing, 0.0);
  const CanonicalScan canonical = canonical_scan(variant.mesh, *alignment);
  const Result<metrics::SelfCheck> own =
      metrics::checked(canonical.mesh, r->profiles, r->canonical, {}, true, c.variant);
  ASSERT_TRUE(own);
  EXPECT_TRUE(own->passed()) << own->summary();
}

INSTANTIATE_TEST_SUITE_P(Variants, HeldOut, ::testing::Range<std::size_t>(0, cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& param) {
                           std::string name = cases()[param.param].scan + "_" + cases()[param.param].variant;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

} // namespace
} // namespace pdeface::pipeline

namespace pdeface::pipeline {
namespace {

TEST(HeldOut, DISABLED_SelfCheckFigures) {
  for (const char* name : test::kSharedScans) {
    std::optional<FaceScan> t = truth_of(name);
    if (!t) continue;
    const CanonicalScan canonical{t->mesh, t->landmarks, {}};
    std::printf("%-24s", name);
    for (double ratio : {0.05, 0.10, 0.30, 0.60}) {
      ReconstructOptions options;
      options.profiles.ratio = ratio;
      const Result<Reconstruction> r = reconstruct(canonical, options, name);
      if (!r) {
        std::printf(" %2.0f%%: failed", 100 * ratio);
        continue;
      }
      const Result<metrics::FaceYardstick> y = metrics::FaceYardstick::make(canonical.mesh, r->profiles);
      const Result<metrics::SelfCheck> c = metrics::self_check(*y, r->canonical);
      std::printf(" %2.0f%%: %.3f %5.1f %.3f%%", 100 * ratio, c->mean_mm, 100 * c->coverage,
                  100 * c->facing_away);
    }
    std::printf("\n");
  }
}

} // namespace
} // namespace pdeface::pipeline
