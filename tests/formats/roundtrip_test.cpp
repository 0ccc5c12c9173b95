// Every pair of writable formats: A -> B -> A keeps the counts, and positions within the precision of
// the formats on the way (exact after float rounding for float formats; within half a quantisation step
// per axis for Draco).

#include "pdeface/formats/formats.hpp"

#include "format_test_support.hpp"
#include "pdeface/core/sample_face.hpp"
#include "pdeface_test.hpp"

#include <cmath>
#include <limits>

namespace pdeface::formats {
namespace {

constexpr std::array kWritable{".wrl", ".obj", ".ply", ".off", ".stl", ".glb", ".gltf", ".drc"};

// Largest per-axis error a format may add to positions of the given mesh (one float ulp of slack).
double tolerance(std::string_view ext, const Mesh& mesh, int draco_bits) {
  const Box box = bounding_box(mesh);
  const double ulp = 4.0 * std::numeric_limits<float>::epsilon() *
                     box.max.cwiseAbs().cwiseMax(box.min.cwiseAbs()).maxCoeff();
  if (ext == ".drc") return 0.5 * box.size().maxCoeff() / (std::ldexp(1.0, draco_bits) - 1.0) + ulp;
  return ulp;
}

Mesh through(const Mesh& mesh, std::string_view ext) {
  const std::string name = "roundtrip" + std::string(ext);
  auto bytes = encode_mesh(mesh, name);
  EXPECT_TRUE(bytes.ok()) << ext << ": " << bytes.error().to_string();
  if (!bytes) return {};
  auto back = read_mesh(*bytes, name);
  EXPECT_TRUE(back.ok()) << ext << ": " << back.error().to_string();
  return back ? back->mesh : Mesh{};
}

// Max over the vertices of `a` of the distance (per axis, L-inf) to the nearest vertex of `b`.
double max_nearest(const Mesh& a, const Mesh& b) {
  double worst = 0.0;
  for (const Vec3& p : a.positions) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3& q : b.positions)
      best = std::min(best, (p - q).cwiseAbs().maxCoeff());
    worst = std::max(worst, best);
  }
  return worst;
}

class RoundTrip : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(RoundTrip, KeepsCountsAndPositions) {
  const auto [a, b] = GetParam();
  const Mesh original = sample_face({.spacing_mm = 4.0}); // ~1,500 vertices: the brute-force check stays fast
  const Mesh in_a = through(original, a);
  const Mesh in_b = through(in_a, b);
  const Mesh back = through(in_b, a);
  ASSERT_EQ(back.vertex_count(), original.vertex_count());
  ASSERT_EQ(back.triangle_count(), original.triangle_count());
  const double tol = tolerance(a, original, 14) + tolerance(b, original, 14) + tolerance(a, original, 14);
  EXPECT_LE(max_nearest(original, back), tol) << a << " -> " << b << " -> " << a;
  EXPECT_LE(max_nearest(back, original), tol) << a << " -> " << b << " -> " << a;
}

std::string pair_name(const ::testing::TestParamInfo<RoundTrip::ParamType>& info) {
  return std::string(std::get<0>(info.param) + 1) + "_" + (std::get<1>(info.param) + 1);
}

INSTANTIATE_TEST_SUITE_P(AllPairs, RoundTrip,
                         ::testing::Combine(::testing::ValuesIn(kWritable), ::testing::ValuesIn(kWritable)),
                         pair_name);

TEST(RoundTrip, AttributesSurviveWhereBothFormatsHoldThem) {
  const Mesh original = sample_face({.spacing_mm = 4.0});
  for (const char* ext : kWritable) {
    const FormatInfo& fi = info(*format_from_path(std::string("x") + ext));
    const Mesh back = through(original, ext);
    EXPECT_EQ(back.has_colors(), fi.colors) << ext;
    EXPECT_EQ(back.has_normals(), fi.normals) << ext;
    if (fi.colors && back.has_colors()) {
      float worst = 0.0F;
      for (std::size_t i = 0; i < back.colors.size(); ++i)
        worst = std::max(worst, (back.colors[i] - original.colors[i]).cwiseAbs().maxCoeff());
      if (std::string_view(ext) != ".drc") {
        EXPECT_LE(worst, 0.5F / 255.0F + 1e-6F) << ext; // 8-bit colours at worst
      }
    }
  }
}

// A face with a photo: texture coordinates with a seam (per corner), a material and its image. What each
// format keeps of them, written with the files beside (`encode_files`) and read back through a resolver
// over those files:
//   VRML, OBJ, glTF, GLB  the coordinates per corner (seam kept, vertices as they were), the material, the
//   image PLY                   the coordinates per vertex (the seam vertex split: one vertex more), the
//   image Draco                 the coordinates (quantised to 12 bits; seam split, then welded on reading),
//   no material OFF, STL              none of it (notes say so)
TEST(RoundTrip, TextureSeamsMaterialAndImageWhereTheFormatHoldsThem) {
  Mesh face = sample_face({.spacing_mm = 6.0});
  face.texcoords.clear();
  for (const Vec3& p : face.positions)
    face.texcoords.emplace_back(static_cast<float>(p.x() / 256 + 0.5), static_cast<float>(p.y() / 256 + 0.5));
  face.texcoord_triangles = face.triangles;
  // A seam: the first corner of a triangle whose vertex other triangles share gets a coordinate of its own.
  std::vector<int> uses(face.vertex_count(), 0);
  for (const Triangle& t : face.triangles)
    for (std::uint32_t v : t)
      ++uses[v];
  const auto seam = std::ranges::find_if(face.triangles, [&](const Triangle& t) { return uses[t[0]] > 1; });
  face.texcoords.emplace_back(0.125F, 0.25F);
  face.texcoord_triangles[static_cast<std::size_t>(seam - face.triangles.begin())][0] =
      static_cast<std::uint32_t>(face.texcoords.size() - 1);
  const std::string png = *read_file(test::fixtures() / "obj" / "texture.png");
  face.material =
      Material{.name = "skin",
               .base_color = Vec4f::Ones(),
               .base_color_image = Image{.bytes = png, .mime_type = "image/png", .uri = "face.png"}};
  ASSERT_TRUE(validate(face).ok());
  const std::vector<Vec2f> corners = corner_texcoords(face);

  for (const char* ext : kWritable) {
    SCOPED_TRACE(ext);
    const std::string name = std::string("out/face") + ext;
    Notes notes;
    Result<std::vector<OutputFile>> files = encode_files(face, name, {}, &notes);
    ASSERT_TRUE(files.ok()) << files.error().to_string();
    const Resolver resolve = [&](std::string_view reference) -> Result<std::string> {
      for (const OutputFile& f : *files)
        if (f.path == std::filesystem::path("out") / std::string(reference)) return f.bytes;
      return make_error(ErrorCode::Io, "no such file", std::string(reference));
    };
    const Result<LoadedMesh> back = read_mesh(files->front().bytes, name, {.resolver = resolve});
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    const Mesh& m = back->mesh;
    const FormatInfo& fi = info(*format_from_path(name));
    const std::string_view e = ext;
    EXPECT_EQ(m.has_texcoords(), fi.texcoords);
    EXPECT_EQ(m.material.has_value(), fi.materials && e != ".drc");
    if (fi.materials) {
      ASSERT_TRUE(m.material && m.material->base_color_image);
      EXPECT_EQ(m.material->base_color_image->bytes, png) << "the image's bytes unchanged";
      EXPECT_EQ(m.material->base_color_image->mime_type, "image/png");
    }
    if (!fi.texcoords) {
      EXPECT_TRUE(test::has_note(notes, "texture coordinates dropped"));
      continue;
    }
    EXPECT_EQ(m.triangle_count(), face.triangle_count());
    if (e == ".drc") continue; // quantised and reordered by the edgebreaker
    EXPECT_EQ(m.vertex_count(), face.vertex_count() + (e == ".ply" ? 1 : 0)) << "PLY: the seam vertex split";
    EXPECT_EQ(m.has_corner_texcoords(), e != ".ply");
    EXPECT_EQ(corner_texcoords(m), corners);
  }
}

TEST(RoundTrip, PointCloudsStayPointClouds) {
  const Mesh cloud = to_mesh(to_point_cloud(sample_face({.spacing_mm = 4.0})));
  for (const char* ext : kWritable) {
    if (!info(*format_from_path(std::string("x") + ext)).point_clouds) continue;
    const Mesh back = through(cloud, ext);
    EXPECT_TRUE(back.is_point_cloud()) << ext;
    EXPECT_EQ(back.vertex_count(), cloud.vertex_count()) << ext;
  }
}

TEST(RoundTrip, UnitsAreKept) {
  Mesh face = sample_face({.spacing_mm = 6.0});
  for (Units units : {Units::Millimetres, Units::Metres}) {
    face.units = units;
    for (const char* ext : kWritable) {
      if (std::string_view(ext) == ".stl") continue; // binary STL has nowhere to say it
      EXPECT_EQ(through(face, ext).units, units) << ext << " " << to_string(units);
    }
  }
}

} // namespace
} // namespace pdeface::formats
