// Scans we have not tuned on: the shared scans made into what users bring (full heads with hair and a
// neck, busts on a plinth, a side or the chin cut short, holes, noise, a child's proportions, a smile, an
// open mouth), each in a random pose and in other units, reconstructed from the variant's file alone and
// judged against the truth (the modified face where it was made, in the canonical frame) by a measure
// written here, independent of the library's own: the cheek-to-cheek face (an ellipse from the chin to
// the forehead reaching 1.45 × the outer eye corners across), its front-most surface within 1 mm of the
// reconstruction, the reconstruction's distance to it, and the share of its area facing away.

#include "pdeface/compare/reconstruct.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/front_view.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/slice/face_mask.hpp"
#include "pdeface/slice/planes.hpp"

#include "pdeface_test.hpp"
#include "scan_variants.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <map>
#include <string>

namespace pdeface::compare {
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
  if (std::getenv("PDEFACE_UNCOVERED")) {
    std::map<std::pair<int, int>, int> bins;
    for (const Vec3& p : face)
      if (to_reconstruction.distance(p) > 1.0)
        ++bins[{static_cast<int>(std::floor(p.x() / 10)), static_cast<int>(std::floor(p.y() / 10))}];
    for (const auto& [k, n] : bins)
      if (n > 20)
        std::printf("  uncovered x %d..%d y %d..%d: %d\n", 10 * k.first, 10 * k.first + 10, 10 * k.second,
                    10 * k.second + 10, n);
  }
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
    if (cross.z() < 0.0) {
      away += 0.5 * cross.norm();
      if (std::getenv("PDEFACE_UNCOVERED"))
        std::printf("  away at (%.1f, %.1f, %.1f) n.z %.2f\n", centre.x(), centre.y(), centre.z(),
                    cross.normalized().z());
    }
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
  };
}

TEST(HeldOut, DISABLED_SharedWidths) {
  for (const char* name : test::kSharedScans) {
    std::optional<FaceScan> t = truth_of(name);
    if (!t) continue;
    const Result<Reconstruction> r = reconstruct(CanonicalScan{t->mesh, t->landmarks, {}}, {}, name);
    if (!r) continue;
    std::printf("%-24s", name);
    for (double w : {1.1, 1.3, 1.45})
      std::printf(" %.2f: %5.1f %%", w, 100 * judge(*t, r->canonical, w).coverage);
    const Judged j = judge(*t, r->canonical);
    std::printf("  face %5.1f %%  to scan %.3f  back %.2f %%\n", 100 * j.coverage, j.to_scan_mm,
                100 * j.back_facing);
  }
}

TEST(HeldOut, DISABLED_Table) {
  std::map<std::string, FaceScan> truths;
  for (const Case& c : cases()) {
    if (!truths.contains(c.scan)) {
      std::optional<FaceScan> t = truth_of(c.scan);
      if (!t) GTEST_SKIP() << c.scan << " is not available";
      truths.emplace(c.scan, std::move(*t));
    }
    const FaceScan truth = c.make(truths.at(c.scan));
    const test::Posed variant = test::posed(truth, c.seed, c.mm_per_unit, c.units);
    const std::string file = "/tmp/heldout_" + std::to_string(c.seed);
    (void)formats::write_mesh(variant.mesh, file + "_scan.ply");
    const Result<align::Alignment> alignment = align::align_scan(variant.mesh, std::nullopt, c.variant);
    if (!alignment) {
      std::printf("%-22s %-32s FAILED: %s\n", c.scan.c_str(), c.variant.c_str(),
                  alignment.error().to_string().c_str());
      continue;
    }
    const Result<Reconstruction> r = reconstruct(variant.mesh, *alignment, {}, c.variant);
    if (!r) {
      std::printf("%-22s %-32s FAILED: %s\n", c.scan.c_str(), c.variant.c_str(),
                  r.error().to_string().c_str());
      continue;
    }
    Mesh in_truth = r->scan;
    for (Vec3& p : in_truth.positions)
      p = variant.truth.to_canonical(p);
    const Judged j = judge(truth, in_truth);
    std::printf("%-22s %-32s coverage %5.1f %%  to scan %6.3f mm  back-facing %5.2f %%\n", c.scan.c_str(),
                c.variant.c_str(), 100 * j.coverage, j.to_scan_mm, 100 * j.back_facing);
    (void)formats::write_mesh(r->scan, file + "_recon.ply");
  }
}

} // namespace
} // namespace pdeface::compare
