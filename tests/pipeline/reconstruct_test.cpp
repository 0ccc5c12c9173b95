// The method end to end on the built-in sample face: the surface goes through the curves, lands in the
// scan's own frame and units, and the fidelity measures see what they should.

#include "pdeface/align/frame.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface/metrics/fidelity.hpp"
#include "pdeface/pipeline/preview.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <numbers>

namespace pdeface::pipeline {
namespace {

const Mesh& face() {
  static const Mesh mesh = sample_face();
  return mesh;
}

// Computed once per process: the suites using it run in one process each (tests/CMakeLists.txt).
const align::Alignment& alignment() {
  static const align::Alignment a = align::align_scan(face(), std::nullopt, "sample").value();
  return a;
}

const Reconstruction& spline() {
  static const Reconstruction r = reconstruct(face(), alignment()).value();
  return r;
}

TEST(Reconstruct, TheSurfaceGoesThroughEveryCurve) {
  const Reconstruction& r = spline();
  ASSERT_EQ(r.profiles.curves.size(), 28U);
  const std::size_t k = r.profiles.k;
  std::vector<double> vs(k);
  for (std::size_t i = 0; i < k; ++i)
    vs[i] = std::numbers::pi * static_cast<double>(i) / static_cast<double>(k - 1);
  const pde::Grid on_curves = r.surface.evaluate(r.surface.knots(), vs);
  double worst = 0.0;
  for (std::size_t j = 0; j < 28; ++j)
    for (std::size_t i = 0; i < k; ++i)
      worst = std::max(worst, (on_curves(j, i) - r.profiles.curves[j].points[i]).norm());
  EXPECT_LT(worst, 1e-9 * 200.0); // relative to a face's size
  // Physical spacing by default: the knots follow the planes' x.
  const auto& c = r.profiles.curves;
  const double scale = r.surface.u_max() / (c.back().x - c.front().x);
  for (std::size_t j = 0; j < 28; ++j)
    EXPECT_NEAR(r.surface.knots()[j], (c[j].x - c.front().x) * scale, 1e-9) << j;
}

TEST(Reconstruct, TheMeshCoversTheCurvesAtAboutOneMillimetre) {
  const Reconstruction& r = spline();
  const slice::ProfileSet& p = r.profiles;
  EXPECT_NEAR((p.border[0] + p.border[1]) / static_cast<double>(r.grid.u - 1), 1.0, 0.05);
  EXPECT_NEAR((p.height_range[1] - p.height_range[0]) / static_cast<double>(r.grid.v - 1), 1.0, 0.05);
  ASSERT_EQ(r.canonical.vertex_count(), r.grid.u * r.grid.v);
  EXPECT_EQ(r.canonical.triangle_count(), 2 * (r.grid.u - 1) * (r.grid.v - 1));
  EXPECT_EQ(r.canonical.normals.size(), r.canonical.vertex_count());
  EXPECT_EQ(r.canonical.units, Units::Millimetres);
  Box box;
  for (const Vec3& q : r.canonical.positions)
    box.extend(q);
  EXPECT_NEAR(box.min.x(), -p.border[0], 1e-9);
  EXPECT_NEAR(box.max.x(), p.border[1], 1e-9);
  EXPECT_NEAR(box.min.y(), p.height_range[0], 1.0);
  EXPECT_NEAR(box.max.y(), p.height_range[1], 1.0);
  // Normals face the viewer (+z) on the whole face.
  std::size_t forward = 0;
  for (const Vec3f& n : r.canonical.normals)
    forward += n.z() > 0 ? 1 : 0;
  EXPECT_EQ(forward, r.canonical.normals.size());

  const Result<Reconstruction> coarse = reconstruct(face(), alignment(), {.resolution = Resolution{0, 21}});
  ASSERT_TRUE(coarse) << coarse.error().message;
  EXPECT_EQ(coarse->grid.v, 21U);
  EXPECT_NEAR(static_cast<double>(coarse->grid.u - 1) / 20.0,
              (p.border[0] + p.border[1]) / (p.height_range[1] - p.height_range[0]), 0.1);
  const Result<Reconstruction> exact = reconstruct(face(), alignment(), {.resolution = Resolution{7, 9}});
  ASSERT_TRUE(exact);
  EXPECT_EQ(exact->canonical.vertex_count(), 63U);
  const Result<Reconstruction> huge =
      reconstruct(face(), alignment(), {.resolution = Resolution{3000, 3000}}, "face.ply");
  ASSERT_FALSE(huge);
  EXPECT_EQ(huge.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(huge.error().message.find("3000 x 3000 grid"), std::string::npos) << huge.error().message;
}

// The same face moved, turned and stated in metres: the reconstruction moves with it, vertex by vertex.
TEST(Reconstruct, TheMeshLandsInTheScansFrameAndUnits) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Vec3(0.2, 1.0, -0.3).normalized()).toRotationMatrix();
  const Vec3 shift(0.4, -1.2, 0.25);
  const auto move = [&](const Vec3& mm) -> Vec3 { return turn * (mm / 1000.0) + shift; };
  Mesh metres = face();
  for (Vec3& p : metres.positions)
    p = move(p);
  metres.units = Units::Metres;
  // The same landmarks, moved: the frames then agree exactly and so must the surfaces.
  align::Landmarks given = alignment().landmarks;
  for (auto& p : given.points)
    if (p) p = move(*p);
  given.units = Units::Metres;
  const Result<align::Alignment> moved = align::align_scan(metres, given);
  ASSERT_TRUE(moved) << moved.error().message;
  const Result<Reconstruction> r = reconstruct(metres, *moved);
  ASSERT_TRUE(r) << r.error().message;

  // The reference: the original reconstruction with the original's given landmarks.
  const Result<Reconstruction> ref =
      reconstruct(face(), align::align_scan(face(), alignment().landmarks).value());
  ASSERT_TRUE(ref);
  EXPECT_EQ(r->scan.units, Units::Metres);
  ASSERT_EQ(r->scan.vertex_count(), ref->scan.vertex_count());
  double worst = 0.0;
  for (std::size_t i = 0; i < ref->scan.vertex_count(); ++i)
    worst = std::max(worst, (r->scan.positions[i] - move(ref->scan.positions[i])).norm());
  EXPECT_LT(worst, 1e-9); // metres
  // Normals turn with it.
  EXPECT_LT((r->scan.normals[100].cast<double>() - turn * ref->scan.normals[100].cast<double>()).norm(),
            1e-5);
}

TEST(Fidelity, IsZeroForTheScanItselfAndSeesAShift) {
  const Mesh canonical = align::to_canonical(face(), alignment().frame);
  const slice::ProfileSet& p = spline().profiles;
  const Result<metrics::Fidelity> same = metrics::measure_fidelity(canonical, p, canonical);
  ASSERT_TRUE(same) << same.error().message;
  for (double e : same->profile_error)
    EXPECT_LT(e, 1e-9);
  EXPECT_LT(same->curve_error, 1e-3); // the border planes are cut 1 µm inside
  EXPECT_LT(same->surface.both.max, 1e-9);

  Mesh shifted = canonical;
  for (Vec3& q : shifted.positions)
    q.z() += 1.0;
  const Result<metrics::Fidelity> off = metrics::measure_fidelity(canonical, p, shifted);
  ASSERT_TRUE(off) << off.error().message;
  for (double e : off->profile_error) { // 1 mm along z is 1 mm · cos(slope) from a sloped profile
    EXPECT_GT(e, 0.5);
    EXPECT_LE(e, 1.0 + 1e-9);
  }
  EXPECT_GT(off->curve_error, 0.5);
  EXPECT_LE(off->curve_error, 1.0 + 1e-9);
  EXPECT_GT(off->surface.both.mean, 0.5);
  EXPECT_LE(off->surface.both.mean, 1.0 + 1e-9);
  EXPECT_GT(off->surface.diagonal, 100.0);
}

// A reconstruction that stops short is measured where it exists; one with nothing on a plane is an error.
TEST(Fidelity, AShortReconstructionIsMeasuredWhereItExists) {
  const Mesh canonical = align::to_canonical(face(), alignment().frame);
  const slice::ProfileSet& p = spline().profiles;
  Mesh upper = canonical; // the face above the mouth only
  std::erase_if(upper.triangles, [&](const Triangle& t) {
    return std::ranges::any_of(t, [&](std::uint32_t v) { return canonical.positions[v].y() < -30.0; });
  });
  const Result<metrics::Fidelity> short_of = metrics::measure_fidelity(canonical, p, upper);
  ASSERT_TRUE(short_of) << short_of.error().message;
  EXPECT_LT(short_of->profile_error[0], 1e-9); // what there is lies on the original
  EXPECT_LT(short_of->surface.b_to_a.max, 1e-9);
  EXPECT_GT(short_of->surface.a_to_b.max, 10.0); // the scan's chin is far from it

  Mesh elsewhere = canonical;
  for (Vec3& q : elsewhere.positions)
    q.x() += 1000.0;
  const Result<metrics::Fidelity> none = metrics::measure_fidelity(canonical, p, elsewhere);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, ErrorCode::NoFace);
  EXPECT_NE(none.error().message.find("symmetry evaluation profile"), std::string::npos)
      << none.error().message;
}

TEST(Fidelity, CoverageIsOfTheFaceTheLandmarksOutline) {
  const Mesh canonical = align::to_canonical(face(), alignment().frame);
  const slice::ProfileSet& p = spline().profiles;
  // The scan covers itself, the reconstruction nearly all of it.
  const Result<metrics::Coverage> itself = metrics::measure_coverage(canonical, p.mask, canonical);
  ASSERT_TRUE(itself) << itself.error().message;
  EXPECT_DOUBLE_EQ(itself->share, 1.0);
  EXPECT_LT(itself->distance.max, 1e-9);
  const Result<metrics::Fidelity> f = metrics::measure_fidelity(canonical, p, spline().canonical);
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_GE(f->coverage.share, 0.97);
  EXPECT_LT(f->coverage.distance.mean, 0.3);
  // Half a reconstruction covers about half the face.
  Mesh half = spline().canonical;
  std::erase_if(half.triangles, [&](const Triangle& t) { return half.positions[t[0]].x() > 0.0; });
  const Result<metrics::Coverage> some = metrics::measure_coverage(canonical, p.mask, half);
  ASSERT_TRUE(some);
  EXPECT_NEAR(some->share, 0.5, 0.05);
  // Surface hidden behind the face (a second layer 20 mm back, like the inside of a mouth) is not the
  // face: it changes nothing.
  Mesh layered = canonical;
  const auto n = static_cast<std::uint32_t>(layered.positions.size());
  for (std::size_t i = 0; i < n; ++i)
    layered.positions.push_back(canonical.positions[i] - Vec3(0, 0, 20));
  for (std::size_t t = 0; t < canonical.triangles.size(); ++t)
    layered.triangles.push_back(
        {canonical.triangles[t][0] + n, canonical.triangles[t][1] + n, canonical.triangles[t][2] + n});
  layered.normals.clear();
  layered.colors.clear();
  const Result<metrics::Coverage> behind = metrics::measure_coverage(layered, p.mask, spline().canonical);
  ASSERT_TRUE(behind);
  EXPECT_NEAR(behind->share, f->coverage.share, 0.005);
  // The mask is the landmarks', not the reconstruction's: a reconstruction that stops short of the chin
  // leaves the chin uncovered.
  Mesh short_of = spline().canonical;
  std::erase_if(short_of.triangles, [&](const Triangle& t) { return short_of.positions[t[0]].y() < -40.0; });
  const Result<metrics::Coverage> chinless = metrics::measure_coverage(canonical, p.mask, short_of);
  ASSERT_TRUE(chinless);
  EXPECT_LT(chinless->share, 0.9);
}

TEST(Fidelity, ReconstructionToScanLeavesOutTheHolesItFilled) {
  // A 24 mm hole in the cheek: the reconstruction spans it, the scan has nothing there to compare with.
  Mesh holed = face();
  std::erase_if(holed.triangles, [&](const Triangle& t) {
    const Vec3 c = (holed.positions[t[0]] + holed.positions[t[1]] + holed.positions[t[2]]) / 3.0;
    return std::hypot(c.x() + 30.0, c.y() + 5.0) < 12.0;
  });
  const Result<align::Alignment> a = align::align_scan(holed);
  ASSERT_TRUE(a) << a.error().message;
  const Result<Reconstruction> r = reconstruct(holed, *a);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GE(r->profiles.holes(), 3U);
  const Mesh canonical = align::to_canonical(holed, a->frame);
  const Result<metrics::Fidelity> f = metrics::measure_fidelity(canonical, r->profiles, r->canonical);
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_LT(f->surface.b_to_a.max, 3.0); // over the hole it would be up to 12 mm
  EXPECT_LT(f->surface.b_to_a.mean, 0.3);
  EXPECT_GE(f->coverage.share, 0.97);
}

TEST(Preview, ShowsScanReconstructionAndTurnedView) {
  const Mesh canonical = align::to_canonical(face(), alignment().frame);
  const std::string svg = reconstruction_preview_svg(canonical, spline().canonical, spline().profiles,
                                                     {.title = "a <face> & more"});
  EXPECT_TRUE(svg.starts_with("<svg"));
  std::size_t images = 0;
  for (std::size_t at = svg.find("<image "); at != std::string::npos; at = svg.find("<image ", at + 1))
    ++images;
  EXPECT_EQ(images, 3U);
  EXPECT_NE(svg.find("a &lt;face&gt; &amp; more"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos); // the face mask
}

TEST(Fidelity, TheFaceRegionIsTheCurvesRegion) {
  const slice::ProfileSet& p = spline().profiles;
  const metrics::FaceRegion region = metrics::face_region(p, 10.0);
  for (const slice::ProfileCurve& c : p.curves)
    for (const Vec3& q : c.raw)
      EXPECT_TRUE(region.contains(q)) << c.feature << " " << q.transpose();
  // Each curve's extent bounds it, linearly in between; beyond the border curves nothing.
  const slice::ProfileCurve& border = p.curves.front();
  EXPECT_FALSE(region.contains(Vec3(border.x, border.extent[0] - 1.0, 0.0)));
  EXPECT_FALSE(region.contains(Vec3(border.x - 1.0, 0.5 * (border.extent[0] + border.extent[1]), 0.0)));
  EXPECT_TRUE(region.contains(Vec3(0.0, 0.0, 0.0)));
  EXPECT_LT(region.min_z, -10.0);
  EXPECT_GT(region.min_z, -150.0); // the back of a head is not in it
  EXPECT_FALSE(region.contains(Vec3(0.0, 0.0, -200.0)));
}

// On the sample face too, the default scheme is the most faithful.
TEST(Fidelity, SplineBeatsPaperAndPatch4OnTheSampleFace) {
  const Mesh canonical = align::to_canonical(face(), alignment().frame);
  std::map<pde::Scheme, double> mean;
  for (pde::Scheme s : {pde::Scheme::Spline, pde::Scheme::Paper, pde::Scheme::Patch4}) {
    const Result<Reconstruction> r =
        reconstruct(face(), alignment(), {.pde = {.scheme = s, .spacing = pde::Spacing::Physical}});
    ASSERT_TRUE(r) << r.error().message;
    const Result<metrics::Fidelity> f = metrics::measure_fidelity(canonical, r->profiles, r->canonical);
    ASSERT_TRUE(f) << f.error().message;
    mean[s] = f->surface.both.mean;
  }
  EXPECT_LE(mean[pde::Scheme::Spline], 0.5);
  EXPECT_LT(mean[pde::Scheme::Spline], mean[pde::Scheme::Paper]);
  EXPECT_LT(mean[pde::Scheme::Spline], mean[pde::Scheme::Patch4]);
}

TEST(Reconstruct, ErrorsNameTheScan) {
  const Result<Reconstruction> ratio =
      reconstruct(face(), alignment(), {.profiles = {.ratio = 0.9}}, "f.ply");
  ASSERT_FALSE(ratio);
  EXPECT_EQ(ratio.error().code, ErrorCode::InvalidArgument);
  EXPECT_EQ(ratio.error().source, "f.ply");
  const Result<Reconstruction> unstable =
      reconstruct(face(), alignment(), {.pde = {.scheme = pde::Scheme::Patch4, .smoothing = 50.0}}, "f.ply");
  ASSERT_FALSE(unstable);
  EXPECT_EQ(unstable.error().source, "f.ply");
  EXPECT_NE(unstable.error().message.find("patch4"), std::string::npos) << unstable.error().message;
}

} // namespace
} // namespace pdeface::pipeline
