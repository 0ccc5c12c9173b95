// A .pdef converted to binary PLY is streamed (never held as a mesh): the same bytes and the same errors as
// reading it as a mesh and writing that, and nothing left behind when it fails.

#include "pdeface/core/file.hpp"
#include "pdeface/formats/formats.hpp"

#include "pdef_support.hpp"

#include <gtest/gtest.h>

namespace pdeface {
namespace {

// What the mesh path writes: read_mesh, then write_mesh.
std::string through_a_mesh(const std::filesystem::path& in, const std::filesystem::path& out,
                           const formats::ReadOptions& options) {
  const Result<formats::LoadedMesh> loaded = formats::read_mesh(in, options);
  EXPECT_TRUE(loaded) << loaded.error().to_string();
  if (!loaded) return {};
  EXPECT_TRUE(formats::write_mesh(loaded->mesh, out));
  return test::slurp(out);
}

TEST(PdefStream, BinaryPlyIsTheMeshPathsBytes) {
  test::TempDir dir;
  const std::filesystem::path lossy = test::fixtures() / "pdef" / "sample_10.pdef";
  const std::filesystem::path lossless = test::fixtures() / "pdef" / "synthetic_lossless.pdef";
  struct Case {
    std::filesystem::path in;
    std::size_t u, v;
  };
  // Default grids, a tiny one, and one of many blocks (rows written 256 KiB at a time).
  for (const Case& c : {Case{lossy, 0, 0}, Case{lossless, 0, 0}, Case{lossy, 2, 2}, Case{lossy, 700, 650}}) {
    const formats::ReadOptions options{.surface_u = c.u, .surface_v = c.v};
    const Result<formats::ConvertReport> report = formats::convert(c.in, dir / "streamed.ply", options);
    ASSERT_TRUE(report) << report.error().to_string();
    const std::string streamed = test::slurp(dir / "streamed.ply"),
                      expected = through_a_mesh(c.in, dir / "mesh.ply", options);
    EXPECT_EQ(streamed.size(), expected.size()) << c.in << " " << c.u;
    EXPECT_TRUE(streamed == expected) << c.in << " " << c.u << " x " << c.v;
    EXPECT_EQ(report->from, formats::Format::Pdef);
    EXPECT_EQ(report->to, formats::Format::Ply);
    EXPECT_EQ(report->bytes_out, streamed.size());
    const Result<formats::LoadedMesh> back = formats::read_mesh(streamed, "streamed.ply");
    ASSERT_TRUE(back) << back.error().to_string();
    EXPECT_EQ(report->vertices, back->mesh.vertex_count());
    EXPECT_EQ(report->triangles, back->mesh.triangle_count());
    EXPECT_EQ(report->units, back->mesh.units);
    EXPECT_EQ(dir.entries(), 2U) << "no temporary file may be left";
  }
  EXPECT_EQ(formats::convert(lossy, dir / "streamed.ply", {.surface_u = 700, .surface_v = 650})->vertices,
            455000U);
}

TEST(PdefStream, ErrorsAreTheMeshPathsAndLeaveNothing) {
  test::TempDir dir;
  const std::string bytes = test::slurp(test::fixtures() / "pdef" / "sample_10.pdef");
  std::ofstream(dir / "cut.pdef", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const Result<formats::ConvertReport> cut = formats::convert(dir / "cut.pdef", dir / "out.ply");
  const Result<formats::LoadedMesh> as_mesh = formats::read_mesh(dir / "cut.pdef");
  ASSERT_FALSE(cut);
  ASSERT_FALSE(as_mesh);
  EXPECT_EQ(cut.error().to_string(), as_mesh.error().to_string());

  // A grid too large, and a folder that does not exist: the mesh path's errors.
  std::ofstream(dir / "face.pdef", std::ios::binary) << bytes;
  const formats::ReadOptions too_fine{.surface_u = 4000, .surface_v = 4000};
  const Result<formats::ConvertReport> refused =
      formats::convert(dir / "face.pdef", dir / "out.ply", too_fine);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().to_string(), formats::read_mesh(dir / "face.pdef", too_fine).error().to_string());
  const Result<formats::ConvertReport> nowhere = formats::convert(dir / "face.pdef", dir / "no" / "out.ply");
  ASSERT_FALSE(nowhere);
  EXPECT_EQ(nowhere.error().code, ErrorCode::Io);

  // Frames whose scale sends the surface beyond double's range: the map itself (refused by to_mesh), or
  // only the points (refused as write_mesh refuses them).
  for (const double scale : {1e-309, 1e-307}) {
    pdef::Face face = test::synthetic_face();
    face.frame.scale = scale;
    face.frame.translation = Vec3::Zero();
    const Result<pdef::Encoded> encoded = pdef::encode(face, {.lossless = true});
    ASSERT_TRUE(encoded) << encoded.error().to_string();
    std::ofstream(dir / "far.pdef", std::ios::binary) << encoded->bytes;
    const Result<formats::ConvertReport> far = formats::convert(dir / "far.pdef", dir / "out.ply");
    ASSERT_FALSE(far) << scale;
    EXPECT_EQ(far.error().code, ErrorCode::NonFinite);
    const Result<formats::LoadedMesh> far_mesh = formats::read_mesh(dir / "far.pdef");
    if (!far_mesh) {
      EXPECT_EQ(far.error().to_string(), far_mesh.error().to_string());
      continue;
    }
    const Result<std::size_t> written = formats::write_mesh(far_mesh->mesh, dir / "out.ply");
    ASSERT_FALSE(written);
    EXPECT_EQ(far.error().to_string(), written.error().to_string());
  }
  EXPECT_EQ(dir.entries(), 3U) << "only the three inputs: no output, no temporary file";
}

} // namespace
} // namespace pdeface
