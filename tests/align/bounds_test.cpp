// Landmark detection bounded in time and memory whatever the coordinates (issue 22, docs/robustness.md):
// a random soup spanning a kilometre ran for more than 300 s and grew past 3 GB; a scan scaled by 1e12
// ended in std::bad_alloc. Each now ends in a clear error (or the face) quickly.
#include "pdeface/align/detect.hpp"

#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

#include <random>

namespace pdeface::align {
namespace {

void expect_no_face(const Result<Detection>& d, std::string_view says = {}) {
  ASSERT_FALSE(d.ok()) << "found a face";
  EXPECT_EQ(d.error().code, ErrorCode::NoFace) << d.error().to_string();
  EXPECT_NE(d.error().message.find(says), std::string::npos) << d.error().message;
}

// 100 random vertices in [0, 1e6]^3 and 300 triangles between them (a 5.5 KB OBJ): the symmetry profile
// sampled every millimetre of triangles a kilometre long.
TEST(DetectBounds, ARandomSoupAKilometreWide) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1e6);
  std::uniform_int_distribution<std::uint32_t> pick(0, 99);
  Mesh soup;
  for (int i = 0; i < 100; ++i)
    soup.positions.emplace_back(u(rng), u(rng), u(rng));
  for (int i = 0; i < 300; ++i)
    soup.triangles.push_back({pick(rng), pick(rng), pick(rng)});
  expect_no_face(detect_landmarks(soup));
  soup.units = Units::Millimetres; // a kilometre in millimetres: no face scan is that large
  expect_no_face(detect_landmarks(soup), "spans 1.");
}

Mesh scaled(Mesh m, double by, Units units = Units::Unknown) {
  for (Vec3& p : m.positions)
    p *= by;
  m.units = units;
  return m;
}

TEST(DetectBounds, AFaceAtAbsurdScales) {
  const Mesh face = sample_face({.spacing_mm = 2.5, .colors = false});
  // Without units, the scale is the face's own: found, or no face, but in bounded time and memory.
  for (double by : {1e6, 1e12, 1e-12}) {
    const Result<Detection> d = detect_landmarks(scaled(face, by));
    if (!d) {
      EXPECT_EQ(d.error().code, ErrorCode::NoFace) << by << ": " << d.error().to_string();
    }
  }
  // Stated in millimetres, a face a kilometre wide is none.
  expect_no_face(detect_landmarks(scaled(face, 1e4, Units::Millimetres)), "more than any face scan");
  // Beyond what any unit makes of a face: refused before any search.
  expect_no_face(detect_landmarks(scaled(face, 1e300)), "which no face scan does");
}

// A point cloud at an absurd scale: each point was splatted over a disc thousands of cells wide.
TEST(DetectBounds, APointCloudAtAnAbsurdScale) {
  Mesh cloud = scaled(sample_face({.spacing_mm = 2.5, .colors = false}), 1e9);
  cloud.triangles.clear();
  const Result<Detection> d = detect_landmarks(cloud);
  if (!d) {
    EXPECT_EQ(d.error().code, ErrorCode::NoFace) << d.error().to_string();
  }
}

} // namespace
} // namespace pdeface::align
