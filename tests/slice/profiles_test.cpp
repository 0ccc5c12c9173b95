// The whole stage on the built-in sample face: layout, ranges, K, evaluation profiles, bad calls and
// scans that cannot supply a plane.

#include "pdeface/core/sample_face.hpp"
#include "pdeface/slice/face_mask.hpp"
#include "pdeface/slice/output.hpp"
#include "pdeface/slice/profiles.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace pdeface::slice {
namespace {

using align::Landmark;

// The sample face is drawn in the canonical frame already; its forehead and chin are added by hand.
align::Landmarks sample_landmarks() {
  const SampleFaceLandmarks s = sample_face_landmarks();
  align::Landmarks l;
  l.units = Units::Millimetres;
  l[Landmark::NoseTip] = s.nose_tip;
  l[Landmark::EyeInnerLeft] = s.eye_inner_left;
  l[Landmark::EyeInnerRight] = s.eye_inner_right;
  l[Landmark::EyeOuterLeft] = s.eye_outer_left;
  l[Landmark::EyeOuterRight] = s.eye_outer_right;
  l[Landmark::MouthLeft] = s.mouth_left;
  l[Landmark::MouthRight] = s.mouth_right;
  l[Landmark::FaceTop] = Vec3(0.0, 70.0, sample_face_height(0.0, 70.0));
  l[Landmark::FaceBottom] = Vec3(0.0, -80.0, sample_face_height(0.0, -80.0));
  return l;
}

Result<ProfileSet> extract(const Mesh& face, const ProfileOptions& options = {}) {
  return extract_profiles(face, sample_landmarks(), align::FaceFrame{}, options);
}

const Mesh& face() {
  static const Mesh mesh = sample_face({.holes = false});
  return mesh;
}

TEST(Profiles, SampleFaceGivesTheLayout) {
  Result<ProfileSet> set = extract(face());
  ASSERT_TRUE(set) << set.error().message;
  ASSERT_EQ(set->curves.size(), 28U);
  for (std::size_t j = 0; j < 28; ++j) {
    const ProfileCurve& c = set->curves[j];
    EXPECT_EQ(c.index, j);
    EXPECT_EQ(c.role, j % 3 == 0 ? PlaneRole::Joint : PlaneRole::Intermediate) << j;
    EXPECT_NEAR(c.x, -set->curves[27 - j].x, 1e-12) << j; // symmetric
    if (j > 0) {
      EXPECT_GT(c.x, set->curves[j - 1].x);
    }
    // Each curve spans its own extent, on its plane, ending exactly at it.
    EXPECT_EQ(c.raw.front().y(), c.extent[0]);
    EXPECT_EQ(c.raw.back().y(), c.extent[1]);
    for (const Vec3& p : c.raw)
      EXPECT_EQ(p.x(), c.x);
    ASSERT_EQ(c.points.size(), set->k);
    ASSERT_EQ(c.filled.size(), set->k);
    EXPECT_NEAR(c.points.front().y(), c.extent[0], 1e-9);
    EXPECT_NEAR(c.points.back().y(), c.extent[1], 1e-9);
    EXPECT_GE(c.extent[0], set->height_range[0]);
    EXPECT_LE(c.extent[1], set->height_range[1]);
    EXPECT_TRUE(c.holes.empty()) << j;
  }
  // Joints at the features: outer corners ±46, inner ±17, eye centres midway, nose sides at 0.4 · 17.
  EXPECT_EQ(set->curves[3].feature, "outer eye corner (right)");
  EXPECT_DOUBLE_EQ(set->curves[3].x, -46.0);
  EXPECT_DOUBLE_EQ(set->curves[6].x, -31.5);
  EXPECT_DOUBLE_EQ(set->curves[9].x, -17.0);
  EXPECT_DOUBLE_EQ(set->curves[12].x, -0.4 * 17.0);
  EXPECT_EQ(set->curves[12].feature, "nose side (right)");
  EXPECT_EQ(set->curves[27].feature, "face border (left)");
  // The border lies beyond the face mask, which lies beyond the outer eye corners.
  EXPECT_GT(set->mask.half_width, 1.1 * 46.0);
  EXPECT_NEAR(set->border_mm, 1.06 * set->mask.half_width, 1e-9);
  EXPECT_DOUBLE_EQ(set->curves[13].x, set->curves[12].x * 2.0 / 3.0 + set->curves[15].x / 3.0);
  // The middle curves reach from the chin to the forehead (the landmarks at -80 and 70), the border curves
  // less far: the extents follow the face's oval.
  EXPECT_LT(set->curves[13].extent[0], -80.0);
  EXPECT_GT(set->curves[13].extent[1], 70.0);
  EXPECT_GT(set->curves[0].extent[0], set->curves[13].extent[0] + 30.0);
  EXPECT_LT(set->curves[0].extent[1], set->curves[13].extent[1] - 30.0);
  EXPECT_GT(set->curves[0].extent[1] - set->curves[0].extent[0], 40.0);
  // K is the ratio of the paper's 300 reference points, whatever the scan's density.
  EXPECT_EQ(set->reference_points, 300U);
  EXPECT_EQ(set->k, 30U);
  EXPECT_GT(set->raw_points, 100U);
  EXPECT_GT(set->central_width_mm, 92.0); // longer along the surface than the 92 mm straight across
  EXPECT_DOUBLE_EQ(set->mask_coverage, 1.0);
  EXPECT_TRUE(set->missing.empty());
}

// Shared heights: point k of every curve at one relative height; local heights: neighbouring curves nearly
// so; parameter sampling: each curve its own.
TEST(Profiles, SamplingsLineUpPointKAsAsked) {
  Result<ProfileSet> set = extract(face(), {.ratio = 0.2, .sampling = Sampling::SharedHeights});
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_EQ(set->sampling, Sampling::SharedHeights);
  ASSERT_EQ(set->heights.size(), set->k);
  EXPECT_EQ(set->heights.front(), 0.0);
  EXPECT_EQ(set->heights.back(), 1.0);
  for (std::size_t i = 1; i < set->k; ++i)
    EXPECT_GT(set->heights[i], set->heights[i - 1]) << i;
  auto relative = [](const ProfileCurve& c, std::size_t i) {
    return (c.points[i].y() - c.extent[0]) / (c.extent[1] - c.extent[0]);
  };
  for (const ProfileCurve& c : set->curves) {
    ASSERT_EQ(c.points.size(), set->k);
    for (std::size_t i = 0; i < set->k; ++i)
      EXPECT_NEAR(relative(c, i), set->heights[i], 0.02) << c.index << " " << i; // the samples follow the fit
    EXPECT_EQ(c.points.front(), c.raw.front());
    EXPECT_EQ(c.points.back(), c.raw.back());
  }
  // How far apart point k of neighbouring curves lies, in relative height, on average.
  auto neighbour_spread = [&](const ProfileSet& p) {
    double spread = 0.0;
    for (std::size_t j = 1; j < p.curves.size(); ++j)
      for (std::size_t i = 0; i < p.k; ++i)
        spread += std::abs(relative(p.curves[j], i) - relative(p.curves[j - 1], i));
    return spread / static_cast<double>((p.curves.size() - 1) * p.k);
  };
  // Local heights line point k up the more, the wider their window across the face; each curve on its own
  // (a window of a tenth of a millimetre) the least.
  Result<ProfileSet> local = extract(face(), {.ratio = 0.2, .sampling = Sampling::LocalHeights});
  Result<ProfileSet> alone =
      extract(face(), {.ratio = 0.2, .sampling = Sampling::LocalHeights, .sampling_window_mm = 0.1});
  Result<ProfileSet> own = extract(face(), {.ratio = 0.2, .sampling = Sampling::Parameter});
  ASSERT_TRUE(local && alone && own);
  EXPECT_EQ(own->sampling, Sampling::Parameter);
  EXPECT_TRUE(own->heights.empty());
  EXPECT_LT(neighbour_spread(*set), 0.001);
  EXPECT_LT(neighbour_spread(*local), 0.7 * neighbour_spread(*alone));
  EXPECT_GT(neighbour_spread(*own), 0.001);
  std::printf(
      "point k of neighbouring curves, mean relative height apart: shared %.4f, local %.4f, each alone "
      "%.4f, own parameter %.4f\n",
      neighbour_spread(*set), neighbour_spread(*local), neighbour_spread(*alone), neighbour_spread(*own));
}

// Local heights are chosen at every third curve (the joints), the same for a mirrored pair, on a grid of
// 2^-h (h = ⌈log₂ K⌉ + 4), blended linearly in x between them, and the samples sit at exactly those heights:
// what lets a .pdef store a curve's heights as its extent and a few small integers (docs/slice.md).
TEST(Profiles, LocalHeightsAreTheAnchorsOnTheirGridBlended) {
  // The sample face, and the same with a bump on its left cheek (its sides' own heights then differ).
  Mesh lopsided_mesh = face();
  for (Vec3& p : lopsided_mesh.positions)
    p.z() += 4.0 * std::exp(-((p.x() - 35.0) * (p.x() - 35.0) + (p.y() - 10.0) * (p.y() - 10.0)) / 100.0);
  const Mesh& lopsided = lopsided_mesh;
  for (const auto& [mesh, ratio] :
       {std::pair{&face(), 0.1}, std::pair{&face(), 0.2}, std::pair{&lopsided, 0.1}}) {
    Result<ProfileSet> set = extract(*mesh, {.ratio = ratio});
    ASSERT_TRUE(set) << set.error().message;
    const std::size_t n = set->curves.size(), k = set->k;
    ASSERT_EQ((n - 1) % 3, 0U);
    const int bits = static_cast<int>(std::bit_width(k - 1)) + 4;
    const auto relative = [&](std::size_t j, std::size_t i) {
      const ProfileCurve& c = set->curves[j];
      return (c.points[i].y() - c.extent[0]) / (c.extent[1] - c.extent[0]);
    };
    for (std::size_t j = 0; j < n; ++j) {
      EXPECT_EQ(set->curves[j].points.front().y(), set->curves[j].extent[0]) << j;
      EXPECT_EQ(set->curves[j].points.back().y(), set->curves[j].extent[1]) << j;
      for (std::size_t i = 1; i < k; ++i)
        EXPECT_GT(relative(j, i), relative(j, i - 1)) << j << " " << i;
      for (std::size_t i = 1; i + 1 < k; ++i) {
        if (j % 3 == 0) { // an anchor: on the grid, as its mirror
          const double units = std::ldexp(relative(j, i), bits);
          EXPECT_NEAR(units, std::round(units), 1e-6) << j << " " << i;
          EXPECT_NEAR(relative(j, i), relative(n - 1 - j, i), 1e-12) << j << " " << i;
        } else { // between two anchors, blended by x
          const std::size_t a = j - j % 3, b = a + 3;
          const double w = (set->curves[j].x - set->curves[a].x) / (set->curves[b].x - set->curves[a].x);
          EXPECT_NEAR(relative(j, i), (1 - w) * relative(a, i) + w * relative(b, i), 1e-9) << j << " " << i;
        }
      }
    }
  }
}

TEST(Profiles, EvaluationProfilesLieInTheirPlanes) {
  Result<ProfileSet> set = extract(face());
  ASSERT_TRUE(set);
  ASSERT_EQ(set->evaluation.size(), 4U);
  const std::array<std::string, 4> names{"symmetry", "eyes", "diagonal_up", "diagonal_down"};
  const CurveRegion region = set->region();
  for (std::size_t i = 0; i < 4; ++i) {
    const EvaluationProfile& e = set->evaluation[i];
    EXPECT_EQ(e.name, names[i]);
    ASSERT_GT(e.points.size(), 50U);
    EXPECT_TRUE(e.gaps.empty());
    for (const Vec3& p : e.points) {
      EXPECT_NEAR(e.plane.normal.dot(p), e.plane.offset, 1e-9);
      EXPECT_TRUE(region.contains(p.x(), p.y())) << e.name << " " << p.transpose();
    }
    for (std::size_t k = 1; k < e.points.size(); ++k)
      EXPECT_LT(e.along.dot(e.points[k - 1]), e.along.dot(e.points[k]));
  }
  // The symmetry profile spans the region at x = 0, the eye line the border curves.
  EXPECT_NEAR(set->evaluation[0].points.front().y(), (*region.heights_at(0.0))[0], 1e-6);
  EXPECT_NEAR(set->evaluation[1].points.front().x(), -set->border[0], 0.1);
  EXPECT_NEAR(set->evaluation[1].points.back().x(), set->border[1], 0.1);
  EXPECT_DOUBLE_EQ(set->evaluation[1].plane.offset, 29.5); // the four eye corners' mean height
  // The symmetry profile's front-most point is the nose tip.
  const auto& symmetry = set->evaluation[0].points;
  const Vec3 tip = *std::max_element(symmetry.begin(), symmetry.end(),
                                     [](const Vec3& a, const Vec3& b) { return a.z() < b.z(); });
  EXPECT_NEAR(tip.y(), 0.0, 2.0);
}

TEST(Profiles, RatioAndPointsAreChecked) {
  for (double ratio : {0.04, 0.61, std::numeric_limits<double>::quiet_NaN()}) {
    Result<ProfileSet> set = extract(face(), {.ratio = ratio});
    ASSERT_FALSE(set) << ratio;
    EXPECT_EQ(set.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(set.error().message.find("5 % to 60 %"), std::string::npos) << set.error().message;
  }
  for (double ratio : {0.05, 0.60}) {
    Result<ProfileSet> set = extract(face(), {.ratio = ratio});
    ASSERT_TRUE(set) << set.error().message;
    EXPECT_NEAR(set->ratio, ratio, 0.002);
    EXPECT_EQ(set->k, static_cast<std::size_t>(std::lround(300 * ratio)));
  }
  Result<ProfileSet> three = extract(face(), {.points = 3});
  ASSERT_FALSE(three);
  EXPECT_EQ(three.error().code, ErrorCode::InvalidArgument);
  Result<ProfileSet> fifteen = extract(face(), {.points = 15});
  ASSERT_TRUE(fifteen);
  EXPECT_EQ(fifteen->k, 15U);
  EXPECT_EQ(fifteen->curves[5].points.size(), 15U);
}

TEST(Profiles, CurveCountsAreThreePatchesPlusOne) {
  for (std::size_t n : {0U, 3U, 25U, 27U, 29U}) {
    ProfileOptions o;
    o.planes.curves = n;
    Result<ProfileSet> set = extract(face(), o);
    ASSERT_FALSE(set) << n;
    EXPECT_EQ(set.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(set.error().message.find("3 · patches + 1"), std::string::npos);
  }
  for (std::size_t n : {4U, 10U, 16U, 34U}) {
    ProfileOptions o;
    o.planes.curves = n;
    Result<ProfileSet> set = extract(face(), o);
    ASSERT_TRUE(set) << n << ": " << set.error().message;
    ASSERT_EQ(set->curves.size(), n);
    EXPECT_NEAR(set->curves.back().x, set->border[1], 1e-12);
    EXPECT_NEAR(set->curves.front().x, -set->border[0], 1e-12);
  }
}

// Removes the triangles of a mesh whose centroid `cut` selects.
Mesh without(const Mesh& mesh, const auto& cut) {
  Mesh out = mesh;
  std::erase_if(out.triangles, [&](const Triangle& t) {
    return cut((out.positions[t[0]] + out.positions[t[1]] + out.positions[t[2]]) / 3.0);
  });
  return out;
}

TEST(Profiles, HolesAreFilledFromTheCurveAndItsNeighbours) {
  // A 30 mm hole on the forehead across the right inner eye corner's plane (x = -17), and an open mouth.
  const Mesh holed = without(face(), [](const Vec3& c) {
    return std::hypot(c.x() + 17.0, c.y() - 50.0) < 15.0 ||
           (std::abs(c.x()) < 18.0 && std::abs(c.y() + 30.5) < 4.0);
  });
  Result<ProfileSet> set = extract(holed);
  ASSERT_TRUE(set) << set.error().message;
  std::size_t filled_samples = 0;
  double squares = 0.0, worst = 0.0;
  std::size_t filled_points = 0;
  auto in_hole = [](const ProfileCurve& c, double y) {
    return std::ranges::any_of(c.holes, [&](const auto& h) { return y > h[0] && y < h[1]; });
  };
  for (const ProfileCurve& c : set->curves) {
    // Curves well inside a hole have it, curves clear of both have none (the cut's edge is ragged).
    if (std::abs(c.x + 17.0) < 12.0) {
      EXPECT_TRUE(in_hole(c, 50.0)) << c.feature;
    }
    if (std::abs(c.x) < 16.0) {
      EXPECT_TRUE(in_hole(c, -30.5)) << c.feature;
    }
    if (std::abs(c.x + 17.0) > 16.0 && std::abs(c.x) > 19.0) {
      EXPECT_TRUE(c.holes.empty()) << c.feature;
    }
    for (const auto& h : c.holes)
      EXPECT_LT(h[1] - h[0], 31.0);
    // The filled points lie near the face the holes took away (they cannot know its lips and brow): the
    // fill bends as little as it can, from the surface around it.
    for (const Vec3& p : c.raw)
      if (in_hole(c, p.y())) {
        const double d = std::abs(p.z() - sample_face_height(p.x(), p.y()));
        squares += d * d;
        worst = std::max(worst, d);
        ++filled_points;
      }
    for (std::size_t k = 0; k < c.points.size(); ++k)
      filled_samples += c.filled[k];
  }
  ASSERT_GT(filled_points, 200U);
  EXPECT_LT(std::sqrt(squares / static_cast<double>(filled_points)), 1.5);
  EXPECT_LT(worst, 3.5);
  EXPECT_GT(filled_samples, 10U);
  EXPECT_GE(set->holes(), 14U);
  EXPECT_GT(set->filled_fraction, 0.01);
  EXPECT_LT(set->filled_fraction, 0.1);
  EXPECT_NEAR(set->longest_hole_mm(), 30.0, 1.5);
  // A hole longer than may be filled ends the curves that cross it, and the forehead is reported missing.
  Result<ProfileSet> short_holes = extract(holed, {.max_hole_mm = 10.0});
  ASSERT_TRUE(short_holes) << short_holes.error().message;
  EXPECT_LT(short_holes->curves[9].extent[1], 40.0);
  ASSERT_FALSE(short_holes->missing.empty());
  EXPECT_NE(short_holes->missing.front().find("forehead"), std::string::npos) << short_holes->missing.front();
}

TEST(Profiles, AScanCutShortReconstructsWhatIsThereAndSaysWhatIsMissing) {
  // The chin cut off below y = -45, and the face's left side beyond x = 25.
  Result<ProfileSet> chin = extract(without(face(), [](const Vec3& c) { return c.y() < -45.0; }));
  ASSERT_TRUE(chin) << chin.error().message;
  for (const ProfileCurve& c : chin->curves)
    EXPECT_GE(c.extent[0], -45.5) << c.feature;
  ASSERT_EQ(chin->missing.size(), 1U);
  EXPECT_NE(chin->missing[0].find("the chin"), std::string::npos) << chin->missing[0];
  Result<ProfileSet> side = extract(without(face(), [](const Vec3& c) { return c.x() > 25.0; }));
  ASSERT_TRUE(side) << side.error().message;
  EXPECT_LE(side->border[1], 25.0);
  EXPECT_NEAR(side->border[0], 1.06 * side->mask.half_width, 1e-9);
  EXPECT_LE(side->curves.back().x, 25.0);
  ASSERT_FALSE(side->missing.empty());
  EXPECT_NE(side->missing.back().find("left side"), std::string::npos) << side->missing.back();
  EXPECT_LT(side->mask_coverage, 0.9);
  // Most of the face gone is refused, saying how much is there.
  Result<ProfileSet> most = extract(without(face(), [](const Vec3& c) { return c.x() > -15.0; }));
  ASSERT_FALSE(most);
  EXPECT_EQ(most.error().code, ErrorCode::NoFace);
  EXPECT_NE(most.error().message.find("most of the face is missing"), std::string::npos)
      << most.error().message;
}

TEST(Profiles, MissingLandmarksAreNamed) {
  align::Landmarks l = sample_landmarks();
  l[Landmark::EyeInnerLeft].reset();
  l[Landmark::FaceTop].reset();
  Result<ProfileSet> set = extract_profiles(face(), l, {});
  ASSERT_FALSE(set);
  // Bad data (a landmark file without them), not a bad call.
  EXPECT_EQ(set.error().code, ErrorCode::NoFace);
  EXPECT_NE(set.error().message.find("eye_inner_left, face_top"), std::string::npos) << set.error().message;
}

TEST(Profiles, PointCloudAgreesWithTheMesh) {
  Result<ProfileSet> mesh = extract(face());
  Result<ProfileSet> cloud = extract(to_mesh(to_point_cloud(face())));
  ASSERT_TRUE(mesh);
  ASSERT_TRUE(cloud) << cloud.error().message;
  EXPECT_TRUE(cloud->point_cloud);
  ASSERT_EQ(cloud->curves.size(), 28U);
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t j = 0; j < 28; ++j) {
    ASSERT_NEAR(cloud->curves[j].x, mesh->curves[j].x, 1e-9);
    EXPECT_NEAR(cloud->curves[j].extent[0], mesh->curves[j].extent[0], 2.0);
    EXPECT_NEAR(cloud->curves[j].extent[1], mesh->curves[j].extent[1], 2.0);
    for (const Vec3& p : cloud->curves[j].raw) {
      sum += std::pow(p.z() - sample_face_height(p.x(), p.y()), 2);
      ++n;
    }
  }
  EXPECT_LT(std::sqrt(sum / static_cast<double>(n)), 0.3);
}

TEST(Profiles, JsonHoldsWhatLaterStagesNeed) {
  Result<ProfileSet> set = extract(face());
  ASSERT_TRUE(set);
  const nlohmann::json j = nlohmann::json::parse(write_profiles_json(*set));
  EXPECT_EQ(j["format"], "pdeface-profiles");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["to_canonical"]["rotation"].size(), 3U);
  EXPECT_EQ(j["curves"].size(), 28U);
  EXPECT_EQ(j["curves"][3]["role"], "joint");
  EXPECT_EQ(j["curves"][3]["points"].size(), set->k);
  EXPECT_EQ(j["points_per_curve"], set->k);
  EXPECT_EQ(j["parameter"], "arc_length");
  EXPECT_EQ(j["sampling"], "local_heights");
  EXPECT_EQ(j["curves"][3]["extent"].size(), 2U);
  EXPECT_EQ(j["curves"][3]["holes"].size(), 0U);
  EXPECT_EQ(j["face_mask"]["half_width"], set->mask.half_width);
  EXPECT_EQ(j["mask_coverage"], 1.0);
  EXPECT_EQ(j["evaluation"].size(), 4U);
  EXPECT_EQ(j["evaluation"][0]["points"].size(), set->evaluation[0].points.size());
  const std::string svg = profiles_svg(face(), *set, {.title = "a <title> & more"});
  EXPECT_TRUE(svg.starts_with("<svg"));
  EXPECT_NE(svg.find("a &lt;title&gt; &amp; more"), std::string::npos);
  EXPECT_EQ(std::count(svg.begin(), svg.end(), '\n') > 40, true);
}

TEST(Profiles, SvgCaptionsFitThePicture) {
  // Every caption ends inside the picture's view box, estimated at 0.55 em a character (sans-serif);
  // the side view's caption once ran 40 units past the right edge.
  Result<ProfileSet> set = extract(face());
  ASSERT_TRUE(set);
  const std::string svg = profiles_svg(face(), *set, {.title = "facefuns_f18.ply: 28 curves, K = 27"});
  double box_x = 0.0, box_width = 0.0;
  ASSERT_EQ(std::sscanf(svg.c_str(), "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"%lf %*f %lf",
                        &box_x, &box_width),
            2);
  std::size_t texts = 0;
  for (std::size_t at = svg.find("<text "); at != std::string::npos; at = svg.find("<text ", at + 1)) {
    double x = 0.0, size = 0.0;
    ASSERT_EQ(std::sscanf(svg.c_str() + at, "<text x=\"%lf\" y=\"%*f\" font-size=\"%lf\"", &x, &size), 2);
    const std::size_t open = svg.find('>', at) + 1, close = svg.find("</text>", open);
    const std::string caption = svg.substr(open, close - open);
    EXPECT_LE(x + 0.55 * size * static_cast<double>(caption.size()), box_x + box_width) << caption;
    ++texts;
  }
  EXPECT_EQ(texts, 4U); // front, side (two lines), title
}

} // namespace
} // namespace pdeface::slice

namespace pdeface::slice {
namespace {

// Every point a mask takes lies in its box, also where rounding puts a point on the ellipse a hair past the
// half-axes (points on and just around its boundary): with the centre far below the top, y − centre_y
// rounds a point an ulp above centre_y + half_height back onto the ellipse (the box without its hair
// fails here).
TEST(FaceMaskBox, HoldsEveryPointTheMaskTakes) {
  const FaceMask mask{.centre_y = -60.0, .half_width = 71.1, .half_height = 70.0, .min_z = -40.0};
  const Box box = mask.box();
  std::size_t taken = 0;
  for (int i = 0; i < 20000; ++i) {
    const double t = 2.0 * std::numbers::pi * i / 20000.0;
    for (const double s : {0.999999, 1.0, 1.000000001}) {
      for (const double z : {-40.0, 0.0}) {
        const Vec3 p(s * mask.half_width * std::cos(t), mask.centre_y + s * mask.half_height * std::sin(t),
                     z);
        // Steps outwards, in x and in y (where y − centre_y can round back onto the ellipse).
        const double out_y = p.y() > mask.centre_y ? 1e9 : -1e9;
        const Vec3 q(std::nextafter(p.x(), 2.0 * p.x()), p.y(), z);
        const Vec3 r1(p.x(), std::nextafter(p.y(), out_y), z);
        const Vec3 r2(p.x(), std::nextafter(r1.y(), out_y), z);
        for (const Vec3& r : {p, q, r1, r2}) {
          if (!mask.contains(r)) continue;
          ++taken;
          EXPECT_TRUE((r.array() >= box.min.array()).all() && (r.array() <= box.max.array()).all()) << r;
        }
      }
    }
  }
  EXPECT_GT(taken, 100000U);
  EXPECT_FALSE(mask.contains(Vec3(0.0, mask.centre_y, -40.5)));
  EXPECT_LE(box.max.x(), mask.half_width * 1.00001); // a hair, not a margin
}

} // namespace
} // namespace pdeface::slice
