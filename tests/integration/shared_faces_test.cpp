// Every real scan in ../shared/faces reads with the counts its MANIFEST.md gives; skipped when absent.

#include "pdeface/core/summary.hpp"
#include "pdeface/formats/formats.hpp"

#include "pdeface_test.hpp"

namespace pdeface {
namespace {

struct Expected {
  const char* file;
  formats::Format format;
  std::size_t vertices;
  std::size_t triangles;
};

// From ../shared/faces/MANIFEST.md.
constexpr Expected kScans[] = {
    {"facefuns_f18.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_f36.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_f56.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_m26.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_m46.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_m66.ply", formats::Format::Ply, 30204, 59697},
    {"facefuns_example.obj", formats::Format::Obj, 30204, 59697},
    {"facefuns_f36.glb", formats::Format::Glb, 30204, 59697},
    {"facefuns_m46.drc", formats::Format::Draco, 30204, 59697},
    {"facefuns_f56_points.ply", formats::Format::Ply, 30204, 0},
    {"fran_cut.wrl", formats::Format::Vrml, 2205, 4224},
    {"stfaces_neutral.wrl", formats::Format::Vrml, 7118, 14037},
    {"james.obj", formats::Format::Obj, 6393, 12228},
    {"meshmonk_demoface.obj", formats::Format::Obj, 25524, 50660},
    {"demosthenes.obj", formats::Format::Obj, 8394, 16719},
    {"bust_man_wreath.obj", formats::Format::Obj, 15757, 31514},
    {"ict_00.obj", formats::Format::Obj, 8969, 17569},
    {"ict_01.ply", formats::Format::Ply, 8421, 16434},
    {"ict_02.glb", formats::Format::Glb, 9409, 18460},
    {"ict_03.wrl", formats::Format::Vrml, 7836, 15169},
    {"ict_04.obj", formats::Format::Obj, 9409, 18460},
    {"ict_05.ply", formats::Format::Ply, 9409, 18460},
    {"ict_06.glb", formats::Format::Glb, 8652, 16891},
    {"ict_07.wrl", formats::Format::Vrml, 9002, 17602},
};

class SharedFace : public ::testing::TestWithParam<Expected> {};

TEST_P(SharedFace, ReadsWithTheManifestCounts) {
  const Expected& e = GetParam();
  PDEFACE_FACE_OR_SKIP(path, e.file);
  auto loaded = formats::read_mesh(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  EXPECT_EQ(loaded->format, e.format);
  EXPECT_EQ(loaded->mesh.vertex_count(), e.vertices);
  EXPECT_EQ(loaded->mesh.triangle_count(), e.triangles);
  EXPECT_TRUE(validate(loaded->mesh).ok());
}

INSTANTIATE_TEST_SUITE_P(Manifest, SharedFace, ::testing::ValuesIn(kScans),
                         [](const auto& param_info) { return test::test_name(param_info.param.file); });

// The facefuns scans share one topology: a face open at the back with 2 boundary loops.
TEST(SharedFaces, FacefunsTopology) {
  PDEFACE_FACE_OR_SKIP(path, "facefuns_f18.ply");
  auto loaded = formats::read_mesh(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().to_string();
  const MeshSummary s = summarize(loaded->mesh);
  EXPECT_EQ(s.topology.boundary_loops, 2U);
  EXPECT_EQ(s.topology.non_manifold_triangles, 0U);
}

// The same scan in four formats gives the same geometry (Draco within its quantisation step).
TEST(SharedFaces, OneScanManyFormatsSameBox) {
  PDEFACE_FACE_OR_SKIP(ply, "facefuns_f36.ply");
  PDEFACE_FACE_OR_SKIP(glb, "facefuns_f36.glb");
  auto a = formats::read_mesh(ply);
  auto b = formats::read_mesh(glb);
  ASSERT_TRUE(a.ok() && b.ok());
  const Box ba = bounding_box(a->mesh), bb = bounding_box(b->mesh);
  EXPECT_TRUE(ba.min.isApprox(bb.min, 1e-6));
  EXPECT_TRUE(ba.max.isApprox(bb.max, 1e-6));
}

} // namespace
} // namespace pdeface
