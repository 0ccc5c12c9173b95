// Detection on every scan of ../shared/faces (skipped when absent), in the scan's own pose and units and
// in poses, units and resolutions the folder does not have: rescaled to arbitrary units, turned x-up,
// decimated and subdivided. Structural checks where the truth is known without hand-placed points: eye
// and mouth corners of the ICT faces at the ends of their holes, the nose tip the front-most point near
// the midline.

#include "pdeface/align/detect.hpp"
#include "pdeface/core/file.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/obj/obj.hpp"

#include <fmt/format.h>

#include "pdeface_test.hpp"

#include <Eigen/Geometry>

#include <map>
#include <set>
#include <unordered_map>

namespace pdeface::align {
namespace {

Mesh load(const std::filesystem::path& path) {
  auto scan = formats::read_mesh(path);
  EXPECT_TRUE(scan.ok()) << scan.error().to_string();
  return scan.ok() ? scan->mesh : Mesh{};
}

Mesh transformed(Mesh m, const Eigen::Matrix3d& r, double scale) {
  for (Vec3& p : m.positions)
    p = scale * (r * p);
  m.normals.clear();
  m.units = Units::Unknown;
  return m;
}

// Vertices on an edge that only one triangle has: the rims of the mesh's holes.
std::vector<Vec3> boundary_vertices(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  std::set<std::uint32_t> on;
  for (const auto& [edge, count] : uses)
    if (count == 1) on.insert({edge.first, edge.second});
  std::vector<Vec3> out;
  for (std::uint32_t v : on)
    out.push_back(m.positions[v]);
  return out;
}

double nearest(const Vec3& p, const std::vector<Vec3>& points) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& q : points)
    best = std::min(best, (p - q).norm());
  return best;
}

// Every landmark found; the eye and mouth corners mirror each other across x = 0 within 8 mm.
void expect_a_symmetric_face(const Detection& found, const std::string& what, double mouth_tilt = 8.0) {
  EXPECT_GE(found.confidence, 0.7) << what;
  EXPECT_EQ(found.landmarks.count(), kLandmarkCount) << what;
  const Landmarks c = to_canonical(found.landmarks, found.frame);
  for (auto [l, r] : {std::pair{Landmark::EyeInnerLeft, Landmark::EyeInnerRight},
                      {Landmark::EyeOuterLeft, Landmark::EyeOuterRight},
                      {Landmark::MouthLeft, Landmark::MouthRight}}) {
    if (!c.has(l) || !c.has(r)) continue;
    EXPECT_LT(std::abs(c[l]->x() + c[r]->x()), 8.0) << what << ": " << name(l);
    EXPECT_LT(std::abs(c[l]->y() - c[r]->y()), l == Landmark::MouthLeft ? mouth_tilt : 8.0)
        << what << ": " << name(l);
    EXPECT_GT(c[l]->x(), 5.0) << what << ": " << name(l); // the face's left is +x
  }
  // Above the nose the eyes, below it the mouth, the chin below that.
  EXPECT_GT(c[Landmark::EyeInnerLeft]->y(), 15.0) << what;
  EXPECT_LT(c[Landmark::MouthLeft]->y(), -15.0) << what;
  EXPECT_LT(c[Landmark::FaceBottom]->y(), c[Landmark::MouthLeft]->y()) << what;
}

// The nose tip is the front-most point of the scan near the midline (within 1.5 mm).
void expect_the_tip_in_front(const Mesh& scan, const Detection& found, const std::string& what) {
  double front = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : scan.positions) {
    const Vec3 q = found.frame.to_canonical(p);
    if (std::abs(q.x()) < 8.0 && std::abs(q.y()) < 12.0) front = std::max(front, q.z());
  }
  EXPECT_LT(front, 1.5) << what;
}

class EveryScan : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryScan, IsAConfidentSymmetricFace) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Mesh scan = load(path);
  auto found = detect_landmarks(scan);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  // ict_05's mouth is pulled up on one side (an expression): its corners are 8-14 mm apart in height.
  expect_a_symmetric_face(*found, GetParam(), std::string(GetParam()) == "ict_05.ply" ? 16.0 : 8.0);
  expect_the_tip_in_front(scan, *found, GetParam());
  std::printf("%s: confidence %.2f (symmetry %.2f mm, nose %.1f mm, fit %.1f mm), %.4g mm/unit (%s)\n",
              GetParam(), found->confidence, found->symmetry_rms_mm, found->nose_prominence_mm,
              found->fit_rms_mm, found->frame.scale, std::string(to_string(found->frame.scan_units)).c_str());
}

INSTANTIATE_TEST_SUITE_P(SharedFaces, EveryScan,
                         ::testing::Values("facefuns_example.obj", "facefuns_f18.ply", "facefuns_f36.glb",
                                           "facefuns_f36.ply", "facefuns_f56.ply", "facefuns_f56_points.ply",
                                           "facefuns_m26.ply", "facefuns_m46.drc", "facefuns_m46.ply",
                                           "facefuns_m66.ply", "ict_00.obj", "ict_01.ply", "ict_02.glb",
                                           "ict_03.wrl", "ict_04.obj", "ict_05.ply", "ict_06.glb",
                                           "ict_07.wrl", "james.obj", "meshmonk_demoface.obj",
                                           "stfaces_neutral.wrl", "demosthenes.obj", "bust_man_wreath.obj",
                                           "fran_cut.wrl"),
                         test::FileParamName());

// Units: the facefuns and james scans state none; the face says millimetres. The ICT faces are in
// centimetres, the bust on its pedestal (0.605 tall) and the Cyberware patch in metres; demosthenes is in no
// standard unit (a 2.69-unit bust: 0.35-0.7 m tall, so 130-260 mm a unit).
TEST(SharedFacesScale, FromTheFaceItself) {
  const std::pair<const char*, Units> cases[] = {
      {"facefuns_f18.ply", Units::Millimetres}, {"ict_00.obj", Units::Centimetres},
      {"james.obj", Units::Millimetres},        {"demosthenes.obj", Units::Unknown},
      {"bust_man_wreath.obj", Units::Metres},   {"fran_cut.wrl", Units::Metres}};
  for (const auto& [file, units] : cases) {
    PDEFACE_FACE_OR_SKIP(path, file);
    auto found = detect_landmarks(load(path));
    ASSERT_TRUE(found.ok()) << file << ": " << found.error().to_string();
    EXPECT_EQ(found->frame.scan_units, units) << file;
    if (units != Units::Unknown)
      EXPECT_DOUBLE_EQ(found->frame.scale, millimetres_per(units)) << file;
    else {
      EXPECT_GT(found->frame.scale, 130.0) << file;
      EXPECT_LT(found->frame.scale, 260.0) << file;
    }
  }
}

// The ICT faces have no eyeballs: their eye corners are the ends of the eye holes, and their mouth
// corners the ends of the mouth slit (within 0.5 mm of a hole's rim, and as far apart as the hole).
class IctHoles : public ::testing::TestWithParam<const char*> {};

TEST_P(IctHoles, CornersAtTheEndsOfTheHoles) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Mesh scan = load(path);
  auto found = detect_landmarks(scan);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  const std::vector<Vec3> rims = boundary_vertices(scan);
  for (Landmark l : {Landmark::EyeInnerLeft, Landmark::EyeInnerRight, Landmark::EyeOuterLeft,
                     Landmark::EyeOuterRight, Landmark::MouthLeft, Landmark::MouthRight})
    EXPECT_LT(found->frame.scale * nearest(*found->landmarks[l], rims), 0.5) << name(l);
  const Landmarks c = to_canonical(found->landmarks, found->frame);
  // An eye hole 20-40 mm long, a mouth 40-70 mm wide.
  for (auto [inner, outer] : {std::pair{Landmark::EyeInnerLeft, Landmark::EyeOuterLeft},
                              {Landmark::EyeInnerRight, Landmark::EyeOuterRight}}) {
    const double length = (*c[outer] - *c[inner]).norm();
    EXPECT_GT(length, 20.0) << name(inner);
    EXPECT_LT(length, 40.0) << name(inner);
  }
  const double mouth = (*c[Landmark::MouthLeft] - *c[Landmark::MouthRight]).norm();
  EXPECT_GT(mouth, 40.0);
  EXPECT_LT(mouth, 70.0);
}

INSTANTIATE_TEST_SUITE_P(SharedFaces, IctHoles,
                         ::testing::Values("ict_00.obj", "ict_02.glb", "ict_05.ply", "ict_07.wrl"),
                         test::FileParamName());

// ict_05 has an expression (the mouth pulled up on one side): the corners follow the slit, one higher.
TEST(SharedFacesExpression, AsymmetricSmileFollowsTheSlit) {
  PDEFACE_FACE_OR_SKIP(path, "ict_05.ply");
  auto found = detect_landmarks(load(path));
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  EXPECT_GE(found->confidence, 0.7);
  const Landmarks c = to_canonical(found->landmarks, found->frame);
  // Read off the preview: the face's left corner 8-14 mm higher than its right.
  const double rise = c[Landmark::MouthLeft]->y() - c[Landmark::MouthRight]->y();
  EXPECT_GT(rise, 6.0);
  EXPECT_LT(rise, 16.0);
  // The eyes, which the expression leaves alone, stay level.
  EXPECT_LT(std::abs(c[Landmark::EyeInnerLeft]->y() - c[Landmark::EyeInnerRight]->y()), 4.0);
}

// A scan in arbitrary units gives the same landmarks on the surface and the scale it was given
// (up to the face's size against the average face's, which both share).
TEST(SharedFacesScale, ArbitraryUnitsGiveTheSameFace) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  const Mesh scan = load(path);
  auto reference = detect_landmarks(scan);
  ASSERT_TRUE(reference.ok()) << reference.error().to_string();
  std::optional<double> relative;
  for (double factor : {0.00371, 3.7}) {
    auto found = detect_landmarks(transformed(scan, Eigen::Matrix3d::Identity(), factor));
    ASSERT_TRUE(found.ok()) << factor << ": " << found.error().to_string();
    EXPECT_EQ(found->frame.scan_units, Units::Unknown) << factor;
    // mm per unit: about 1 / factor (the face's own size decides the rest).
    const double ratio = found->frame.scale * factor;
    EXPECT_GT(ratio, 0.85) << factor;
    EXPECT_LT(ratio, 1.15) << factor;
    if (relative) {
      EXPECT_NEAR(ratio, *relative, 0.01 * *relative); // both the same face
    }
    relative = ratio;
    for (std::size_t i = 0; i < kLandmarkCount; ++i) {
      const Vec3 back = *found->landmarks.points[i] / factor; // mm, on the original scan
      EXPECT_LT((back - *reference->landmarks.points[i]).norm(), 2.0)
          << factor << ": " << name(static_cast<Landmark>(i));
    }
  }
}

// x up (the scan turned a quarter about its view axis) and upside down; the frame follows.
TEST(SharedFacesPose, XUpAndUpsideDown) {
  PDEFACE_FACE_OR_SKIP(path, "james.obj");
  const Mesh scan = load(path);
  auto reference = detect_landmarks(scan);
  ASSERT_TRUE(reference.ok());
  for (double angle : {-0.5 * 3.14159265358979, 3.14159265358979}) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
    auto found = detect_landmarks(transformed(scan, r, 1.0));
    ASSERT_TRUE(found.ok()) << found.error().to_string();
    expect_a_symmetric_face(*found, "turned");
    const Vec3 up = found->frame.axis_in_scan(1);
    EXPECT_GT(up.dot(r * reference->frame.axis_in_scan(1)), std::cos(2.0 * 3.14159265 / 180.0));
    EXPECT_LT((*found->landmarks[Landmark::NoseTip] - r * *reference->landmarks[Landmark::NoseTip]).norm(),
              1.0);
  }
}

// A bust turned so that its pedestal's corner, symmetric and pointed, passes the quick test for a face
// (a "nose", landmarks near the average face's) at the scale the bounding box suggests: the search must go
// on to the bust's own face, not give up when the corner fails the full check (it has no eye sockets).
TEST(SharedFacesPose, APedestalCornerDoesNotHideTheFace) {
  PDEFACE_FACE_OR_SKIP(path, "bust_man_wreath.obj");
  const Mesh bust = load(path);
  const Eigen::Matrix3d r{{-0.7795631764608477, 0.4252354807450397, 0.45984349492170484},
                          {-0.05259256718159325, 0.6871583206664327, -0.7246015899900701},
                          {-0.6241115892078296, -0.5890570670609282, -0.5133190976011455}};
  const Vec3 t(404.8048268374896, 371.44065598547405, -300.0811499569935);
  // Turned and moved, written as OBJ text with 9 digits and read back, as a user's file would be.
  std::string text;
  for (const Vec3& p : bust.positions) {
    const Vec3 q = r * p + t;
    text += fmt::format("v {:.9g} {:.9g} {:.9g}\n", q.x(), q.y(), q.z());
  }
  for (const Triangle& f : bust.triangles)
    text += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  const Result<Mesh> scan = obj::read(text, "turned bust");
  ASSERT_TRUE(scan.ok()) << scan.error().to_string();
  auto found = detect_landmarks(*scan);
  ASSERT_TRUE(found.ok()) << found.error().to_string();
  expect_a_symmetric_face(*found, "the turned bust");
  expect_the_tip_in_front(*scan, *found, "the turned bust");
}

// The same face at 3k and 120k vertices: decimated by vertex clustering, subdivided 1:4.
Mesh decimated(const Mesh& m, double cell) {
  std::unordered_map<std::uint64_t, std::uint32_t> cluster;
  std::vector<Vec3> sum;
  std::vector<int> count;
  std::vector<std::uint32_t> of(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const Eigen::Vector3d k = (m.positions[i] / cell).array().floor();
    const std::uint64_t key =
        (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.x()) & 0x1FFFFF) << 42U) |
        (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.y()) & 0x1FFFFF) << 21U) |
        (static_cast<std::uint64_t>(static_cast<std::int64_t>(k.z()) & 0x1FFFFF));
    const auto [it, fresh] = cluster.emplace(key, static_cast<std::uint32_t>(sum.size()));
    if (fresh) {
      sum.emplace_back(Vec3::Zero());
      count.push_back(0);
    }
    sum[it->second] += m.positions[i];
    ++count[it->second];
    of[i] = it->second;
  }
  Mesh out;
  for (std::size_t c = 0; c < sum.size(); ++c)
    out.positions.push_back(sum[c] / count[c]);
  for (const Triangle& t : m.triangles) {
    const Triangle u{of[t[0]], of[t[1]], of[t[2]]};
    if (u[0] != u[1] && u[1] != u[2] && u[0] != u[2]) out.triangles.push_back(u);
  }
  return out;
}

Mesh subdivided(const Mesh& m) {
  Mesh out;
  out.positions = m.positions;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
  auto mid = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, fresh] =
        middle.emplace(std::minmax(a, b), static_cast<std::uint32_t>(out.positions.size()));
    if (fresh) out.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
    return it->second;
  };
  for (const Triangle& t : m.triangles) {
    const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

TEST(SharedFacesResolution, ThreeThousandToAHundredThousandVertices) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  const Mesh scan = load(path);
  auto reference = detect_landmarks(scan);
  ASSERT_TRUE(reference.ok());
  const Mesh coarse = decimated(scan, 4.5);
  const Mesh fine = subdivided(scan);
  ASSERT_LT(coarse.vertex_count(), 4000U);
  ASSERT_GT(fine.vertex_count(), 100000U);
  for (const Mesh* m : {&coarse, &fine}) {
    auto found = detect_landmarks(*m);
    ASSERT_TRUE(found.ok()) << m->vertex_count() << " vertices: " << found.error().to_string();
    expect_a_symmetric_face(*found, std::to_string(m->vertex_count()) + " vertices");
    // Stable landmarks within a few mm of where the full scan has them (4.5 mm clusters move them).
    for (Landmark l : {Landmark::NoseTip, Landmark::EyeInnerLeft, Landmark::EyeInnerRight,
                       Landmark::MouthLeft, Landmark::MouthRight})
      EXPECT_LT((*found->landmarks[l] - *reference->landmarks[l]).norm(), 4.0)
          << m->vertex_count() << " vertices: " << name(l);
  }
}

// Given landmarks on a scan that states no units: the scale comes from the landmarks.
TEST(SharedFacesScale, GivenLandmarksOnAUnitlessScan) {
  PDEFACE_FACE_OR_SKIP(obj, "james.obj");
  PDEFACE_FACE_OR_SKIP(ljson, "james.ljson");
  const Mesh scan = transformed(load(obj), Eigen::Matrix3d::Identity(), 0.01);
  auto given = read_ljson(read_file(ljson).value(), ljson.string());
  ASSERT_TRUE(given.ok());
  for (auto& p : given->points)
    if (p) *p *= 0.01;
  auto aligned = align_scan(scan, *given);
  ASSERT_TRUE(aligned.ok()) << aligned.error().to_string();
  EXPECT_EQ(aligned->frame.scan_units, Units::Unknown);
  EXPECT_GT(aligned->frame.scale, 85.0); // 100 mm a unit, give or take the face's size
  EXPECT_LT(aligned->frame.scale, 115.0);
  EXPECT_LT(aligned->frame.to_canonical(*aligned->landmarks[Landmark::NoseTip]).norm(), 1e-9);
}

} // namespace
} // namespace pdeface::align
