// Every mesh scan in ../shared/faces (skipped when absent) at 10 %: its lossy .pdef (default error), the
// surface decoded from it against the one decoded from its lossless .pdef (both in the scan's frame,
// measured in mm with exact point-to-triangle distances, both ways), and the lossless file against the
// reconstruction's own mesh.

#include "pdeface/core/sample_face.hpp"
#include "pdeface/draco/draco.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pipeline/encode.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include "pdeface_test.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace pdeface::pdef {
namespace {

//! Every shared scan that is a mesh (the point cloud is the same face as facefuns_f56).
std::vector<const char*> mesh_scans() {
  std::vector<const char*> out;
  for (const char* name : test::kSharedScans)
    if (std::string_view(name) != "facefuns_f56_points.ply") out.push_back(name);
  return out;
}

struct Encoded2 {
  Face face;
  Encoded lossy;
  Encoded lossless;
  pipeline::CanonicalScan canonical;
};

Encoded2 encode_scan(const Mesh& scan, std::string_view name) {
  const Result<align::Alignment> alignment = align::align_scan(scan, std::nullopt, name);
  EXPECT_TRUE(alignment) << alignment.error().to_string();
  pipeline::CanonicalScan canonical = pipeline::canonical_scan(scan, *alignment);
  const pipeline::ReconstructOptions defaults;
  const Result<slice::ProfileSet> profiles = pipeline::extract_profiles(canonical, defaults.profiles);
  EXPECT_TRUE(profiles) << profiles.error().to_string();
  const pde::Surface surface = pipeline::surface_from(*profiles, defaults.pde).value();
  Face face = pipeline::to_face(*profiles, surface, defaults.pde);
  Result<Encoded> lossy = encode(face), lossless = encode(face, {.lossless = true});
  EXPECT_TRUE(lossy && lossless);
  return {std::move(face), *std::move(lossy), *std::move(lossless), std::move(canonical)};
}

// The two-sided distance (mm) between the surfaces of two decoded files, both on a grid of about 0.4 mm
// in the scan's frame.
double decoded_distance(const std::string& a, const std::string& b) {
  const Face fa = decode(a).value(), fb = decode(b).value();
  const std::array<double, 2> size = face_size(fa);
  const Resolution grid = grid_for(size[0], size[1], 0.4);
  const Mesh ma = to_mesh(fa, grid).value(), mb = to_mesh(fb, grid).value();
  const double mm_per_unit = fa.frame.scale;
  const Result<metrics::TwoSidedDistance> d =
      metrics::surface_distance(ma, mb, {.spacing = 0.4 / mm_per_unit});
  EXPECT_TRUE(d) << d.error().to_string();
  return d->both.max * mm_per_unit;
}

class PdefRealScans : public ::testing::TestWithParam<const char*> {};

TEST_P(PdefRealScans, LossyFileAndItsSurfaceAtTenPercent) {
  PDEFACE_FACE_OR_SKIP(path, GetParam());
  const Result<formats::LoadedMesh> scan = formats::read_mesh(path);
  ASSERT_TRUE(scan) << scan.error().to_string();
  const Encoded2 e = encode_scan(scan->mesh, GetParam());
  const double distance = decoded_distance(e.lossy.bytes, e.lossless.bytes);
  std::printf(
      "%s at 10 %%: %zu bytes lossy (step %.4f mm, samples within %.4f, surface within %.4f mm by the "
      "encoder's check; %.4f mm measured on the decoded meshes), %zu bytes lossless\n",
      GetParam(), e.lossy.bytes.size(), e.lossy.step_mm, e.lossy.max_sample_error, e.lossy.max_surface_error,
      distance, e.lossless.bytes.size());
  EXPECT_LE(e.lossy.max_surface_error, kDefaultMaxError);
  EXPECT_LE(distance, kDefaultMaxError);
  // A face in under a kilobyte (docs/pdef-format.md has the measured sizes: 855-952 bytes), with y as the
  // slicer's heights.
  EXPECT_LE(e.lossy.bytes.size(), 1024U);
  EXPECT_EQ(decode(e.lossy.bytes).value().storage.heights_stride, 3U);
}

INSTANTIATE_TEST_SUITE_P(SharedFaces, PdefRealScans, ::testing::ValuesIn(mesh_scans()),
                         test::FileParamName());

// The lossless file decodes to the reconstruction's mesh exactly: one code path from curves to mesh.
void expect_reconstruction(const Mesh& scan, std::string_view name) {
  const Encoded2 e = encode_scan(scan, name);
  const Result<pipeline::Reconstruction> r = pipeline::reconstruct(e.canonical, {}, name);
  ASSERT_TRUE(r) << r.error().to_string();
  const Face back = decode(e.lossless.bytes).value();
  const Result<Mesh> decoded = to_mesh(back);
  ASSERT_TRUE(decoded) << decoded.error().to_string();
  EXPECT_EQ(decoded->vertex_count(), r->scan.vertex_count()) << name;
  EXPECT_TRUE(decoded->positions == r->scan.positions) << name;
  EXPECT_TRUE(decoded->normals == r->scan.normals) << name;
  EXPECT_TRUE(decoded->triangles == r->scan.triangles) << name;
  EXPECT_EQ(decoded->units, r->scan.units) << name;
}

TEST(PdefReconstruction, LosslessFileDecodesToTheReconstructionsMesh) {
  expect_reconstruction(sample_face(), "sample face");
  for (const char* name : {"facefuns_f18.ply", "ict_03.wrl"}) {
    const auto path = test::face(name);
    if (!path) continue;
    const Result<formats::LoadedMesh> scan = formats::read_mesh(*path);
    ASSERT_TRUE(scan);
    expect_reconstruction(scan->mesh, name);
  }
}

// The size table of docs/pdef-format.md (run on purpose: --gtest_also_run_disabled_tests
// --gtest_filter='*Table*'): bytes of the .pdef of every ratio and maximum error, mean and largest over the
// scans given by PDEF_TABLE_SCANS (default: the six facefuns scans and the eight ICT faces), and Draco's
// sizes of the same scans (pdeface::drc at 11 and 14 bits, level 7).
TEST(PdefSizes, DISABLED_Table) {
  std::vector<std::string> names;
  if (const char* env = std::getenv("PDEF_TABLE_SCANS")) {
    std::string list = env;
    for (std::size_t at = 0; at < list.size();) {
      const std::size_t comma = std::min(list.find(',', at), list.size());
      names.push_back(list.substr(at, comma - at));
      at = comma + 1;
    }
  } else {
    names = {"facefuns_f18.ply", "facefuns_f36.ply", "facefuns_f56.ply", "facefuns_m26.ply",
             "facefuns_m46.ply", "facefuns_m66.ply", "ict_00.obj",       "ict_01.ply",
             "ict_02.glb",       "ict_03.wrl",       "ict_04.obj",       "ict_05.ply",
             "ict_06.glb",       "ict_07.wrl"};
  }
  const std::vector<double> ratios{0.05, 0.10, 0.15, 0.20, 0.30, 0.60};
  const std::vector<double> errors{0.01, 0.02, 0.05, 0.1, 0.2, 0.0}; // 0: lossless
  std::vector<std::vector<std::vector<double>>> bytes(ratios.size(),
                                                      std::vector<std::vector<double>>(errors.size()));
  std::vector<double> draco11, draco14;
  for (const std::string& name : names) {
    const auto path = test::face(name);
    if (!path) GTEST_SKIP() << name << " not found";
    const Mesh scan = formats::read_mesh(*path).value().mesh;
    draco11.push_back(
        static_cast<double>(drc::write(scan, {.position_bits = 11, .level = 7}).value().size()));
    draco14.push_back(
        static_cast<double>(drc::write(scan, {.position_bits = 14, .level = 7}).value().size()));
    const align::Alignment alignment = align::align_scan(scan, std::nullopt, name).value();
    const pipeline::CanonicalScan canonical = pipeline::canonical_scan(scan, alignment);
    for (std::size_t r = 0; r < ratios.size(); ++r) {
      pipeline::ReconstructOptions options;
      options.profiles.ratio = ratios[r];
      const slice::ProfileSet profiles = pipeline::extract_profiles(canonical, options.profiles).value();
      const pde::Surface surface = pipeline::surface_from(profiles, options.pde).value();
      const Face face = pipeline::to_face(profiles, surface, options.pde);
      for (std::size_t e = 0; e < errors.size(); ++e) {
        const Result<Encoded> encoded =
            encode(face, {.lossless = errors[e] == 0.0, .max_error_mm = errors[e] == 0.0 ? 1.0 : errors[e]});
        ASSERT_TRUE(encoded) << name << " " << ratios[r] << " " << errors[e];
        bytes[r][e].push_back(static_cast<double>(encoded->bytes.size()));
      }
    }
    std::fprintf(stderr, "%s done\n", name.c_str());
  }
  const auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (const double x : v)
      s += x;
    return s / static_cast<double>(v.size());
  };
  const auto most = [](const std::vector<double>& v) { return *std::ranges::max_element(v); };
  std::printf("\n| ratio (K) | 0.01 mm | 0.02 mm | 0.05 mm | 0.1 mm | 0.2 mm | lossless "
              "|\n|---|---|---|---|---|---|---|\n");
  for (std::size_t r = 0; r < ratios.size(); ++r) {
    std::printf("| %.0f %% (%.0f) |", 100 * ratios[r], 300 * ratios[r]);
    for (std::size_t e = 0; e < errors.size(); ++e)
      std::printf(" %.0f (%.0f) |", mean(bytes[r][e]), most(bytes[r][e]));
    std::printf("\n");
  }
  std::printf(
      "\nDraco, level 7: 11 bits %.0f (%.0f to %.0f), 14 bits %.0f (%.0f to %.0f) bytes over %zu scans\n",
      mean(draco11), *std::ranges::min_element(draco11), most(draco11), mean(draco14),
      *std::ranges::min_element(draco14), most(draco14), names.size());
}

} // namespace
} // namespace pdeface::pdef
