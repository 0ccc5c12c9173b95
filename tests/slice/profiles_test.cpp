// The whole stage on the built-in sample face: layout, ranges, K, evaluation profiles, bad calls and
// scans that cannot supply a plane.

#include "pdeface/core/sample_face.hpp"
#include "pdeface/slice/output.hpp"
#include "pdeface/slice/profiles.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>

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
  const auto [lo, hi] = set->height_range;
  for (std::size_t j = 0; j < 28; ++j) {
    const ProfileCurve& c = set->curves[j];
    EXPECT_EQ(c.index, j);
    EXPECT_EQ(c.role, j % 3 == 0 ? PlaneRole::Joint : PlaneRole::Intermediate) << j;
    EXPECT_NEAR(c.x, -set->curves[27 - j].x, 1e-12) << j; // symmetric
    if (j > 0) {
      EXPECT_GT(c.x, set->curves[j - 1].x);
    }
    // Every curve spans exactly the same heights, on its plane.
    EXPECT_EQ(c.raw.front().y(), lo);
    EXPECT_EQ(c.raw.back().y(), hi);
    for (const Vec3& p : c.raw)
      EXPECT_EQ(p.x(), c.x);
    ASSERT_EQ(c.points.size(), set->k);
    EXPECT_NEAR(c.points.front().y(), lo, 0.5);
    EXPECT_NEAR(c.points.back().y(), hi, 0.5);
  }
  // Joints at the features: outer corners ±46, inner ±17, eye centres midway, nose wings at 0.65 · 17.
  EXPECT_EQ(set->curves[3].feature, "outer eye corner (right)");
  EXPECT_DOUBLE_EQ(set->curves[3].x, -46.0);
  EXPECT_DOUBLE_EQ(set->curves[6].x, -31.5);
  EXPECT_DOUBLE_EQ(set->curves[9].x, -17.0);
  EXPECT_DOUBLE_EQ(set->curves[12].x, -0.65 * 17.0);
  EXPECT_EQ(set->curves[27].feature, "face border (left)");
  EXPECT_GT(set->border_mm, 46.0);
  EXPECT_DOUBLE_EQ(set->curves[13].x, set->curves[12].x * 2.0 / 3.0 + set->curves[15].x / 3.0);
  // The height range reaches from below the mouth to above the eyes.
  EXPECT_LT(lo, -35.5);
  EXPECT_GT(hi, 35.0);
  EXPECT_EQ(set->k, static_cast<std::size_t>(std::lround(0.1 * static_cast<double>(set->reference_points))));
  EXPECT_GT(set->central_width_mm, 92.0); // longer along the surface than the 92 mm straight across
}

// Shared heights: point k of every curve at one height, from the bottom of the range to its top.
TEST(Profiles, SharedHeightsPutPointKOfEveryCurveAtOneHeight) {
  Result<ProfileSet> set = extract(face(), {.ratio = 0.2, .sampling = Sampling::SharedHeights});
  ASSERT_TRUE(set) << set.error().message;
  EXPECT_EQ(set->sampling, Sampling::SharedHeights);
  ASSERT_EQ(set->heights.size(), set->k);
  EXPECT_EQ(set->heights.front(), set->height_range[0]);
  EXPECT_EQ(set->heights.back(), set->height_range[1]);
  for (std::size_t i = 1; i < set->k; ++i)
    EXPECT_GT(set->heights[i], set->heights[i - 1]) << i;
  for (const ProfileCurve& c : set->curves) {
    ASSERT_EQ(c.points.size(), set->k);
    for (std::size_t i = 0; i < set->k; ++i)
      EXPECT_NEAR(c.points[i].y(), set->heights[i], 1e-3) << c.index << " " << i; // within the tabulation
    EXPECT_EQ(c.points.front(), c.raw.front());
    EXPECT_EQ(c.points.back(), c.raw.back());
  }
  // Parameter sampling (the default) does not line them up.
  Result<ProfileSet> own = extract(face(), {.ratio = 0.2});
  ASSERT_TRUE(own);
  EXPECT_EQ(own->sampling, Sampling::Parameter);
  EXPECT_TRUE(own->heights.empty());
  double spread = 0.0;
  for (const ProfileCurve& c : own->curves)
    spread = std::max(spread, std::abs(c.points[own->k / 2].y() - own->curves[14].points[own->k / 2].y()));
  EXPECT_GT(spread, 1.0);
}

TEST(Profiles, EvaluationProfilesLieInTheirPlanes) {
  Result<ProfileSet> set = extract(face());
  ASSERT_TRUE(set);
  ASSERT_EQ(set->evaluation.size(), 4U);
  const std::array<std::string, 4> names{"symmetry", "eyes", "diagonal_up", "diagonal_down"};
  for (std::size_t i = 0; i < 4; ++i) {
    const EvaluationProfile& e = set->evaluation[i];
    EXPECT_EQ(e.name, names[i]);
    ASSERT_GT(e.points.size(), 50U);
    for (const Vec3& p : e.points)
      EXPECT_NEAR(e.plane.normal.dot(p), e.plane.offset, 1e-9);
    for (std::size_t k = 1; k < e.points.size(); ++k)
      EXPECT_LT(e.along.dot(e.points[k - 1]), e.along.dot(e.points[k]));
  }
  EXPECT_EQ(set->evaluation[0].points.front().y(), set->height_range[0]);
  EXPECT_EQ(set->evaluation[1].points.front().x(), -set->border_mm);
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
    EXPECT_NEAR(set->ratio, ratio, 0.01);
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
    EXPECT_NEAR(set->curves.back().x, set->border_mm, 1e-12);
    EXPECT_NEAR(set->curves.front().x, -set->border_mm, 1e-12);
  }
}

TEST(Profiles, AHoleAcrossAPlaneNamesIt) {
  // A 30 mm hole on the forehead across the right inner eye corner's plane (x = -17).
  Mesh holed = face();
  std::erase_if(holed.triangles, [&](const Triangle& t) {
    const Vec3 c = (holed.positions[t[0]] + holed.positions[t[1]] + holed.positions[t[2]]) / 3.0;
    return std::hypot(c.x() + 17.0, c.y() - 50.0) < 15.0;
  });
  Result<ProfileSet> set = extract(holed);
  ASSERT_FALSE(set);
  EXPECT_EQ(set.error().code, ErrorCode::NoFace);
  EXPECT_TRUE(set.error().message.starts_with("plane ")) << set.error().message;
  EXPECT_NE(set.error().message.find("mm long at y = 5"), std::string::npos) << set.error().message;
  EXPECT_NE(set.error().message.find("the scan has no surface between y = -80.0 and y = 70.0 mm"),
            std::string::npos)
      << set.error().message;
  // Bridging that long a hole is an option.
  ProfileOptions wide;
  wide.section.max_gap_mm = 40.0;
  EXPECT_TRUE(extract(holed, wide));
}

TEST(Profiles, MissingLandmarksAreNamed) {
  align::Landmarks l = sample_landmarks();
  l[Landmark::EyeInnerLeft].reset();
  l[Landmark::FaceTop].reset();
  Result<ProfileSet> set = extract_profiles(face(), l, {});
  ASSERT_FALSE(set);
  EXPECT_EQ(set.error().code, ErrorCode::InvalidArgument);
  EXPECT_NE(set.error().message.find("eye_inner_left"), std::string::npos) << set.error().message;
  // The forehead is not needed when the height range is given.
  l = sample_landmarks();
  l[Landmark::FaceTop].reset();
  ProfileOptions o;
  o.planes.height_range = std::array<double, 2>{-40.0, 50.0};
  Result<ProfileSet> given = extract_profiles(face(), l, {}, o);
  ASSERT_TRUE(given) << given.error().message;
  EXPECT_EQ(given->height_range, (std::array<double, 2>{-40.0, 50.0}));
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
    // The border reaches as far as the outline at the ends of the height range, which a cloud gives
    // only to about its spacing.
    ASSERT_NEAR(cloud->curves[j].x, mesh->curves[j].x, 3.0);
    for (const Vec3& p : cloud->curves[j].raw) {
      if (p.y() < mesh->height_range[0] || p.y() > mesh->height_range[1]) continue;
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
  EXPECT_EQ(j["sampling"], "parameter");
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
