// Reconstructed surfaces written as GLB pass the Khronos glTF validator with no errors (skipped, saying
// why, without node or the validator; see tests/support/gltf_validator.hpp).

#include "pdeface/core/sample_face.hpp"
#include "pdeface/formats/formats.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

#include "gltf_validator.hpp"
#include "pdeface_test.hpp"

#include <gtest/gtest.h>

namespace pdeface::pipeline {
namespace {

void expect_valid_reconstruction(const Mesh& scan, const std::string& name) {
  PDEFACE_GLTF_VALIDATOR_OR_SKIP(node, validator);
  const Result<align::Alignment> a = align::align_scan(scan, std::nullopt, name);
  ASSERT_TRUE(a) << a.error().to_string();
  test::TempDir dir;
  for (pde::Scheme scheme : {pde::Scheme::Spline, pde::Scheme::Paper}) {
    const Result<Reconstruction> r = reconstruct(scan, *a, {.pde = {.scheme = scheme}}, name);
    ASSERT_TRUE(r) << r.error().to_string();
    const std::filesystem::path file = dir / (std::string(pde::to_string(scheme)) + ".glb");
    ASSERT_TRUE(formats::write_mesh(r->scan, file));
    SCOPED_TRACE(file.string());
    test::expect_valid_gltf(*node, *validator, file);
  }
}

TEST(ReconstructionGlb, SampleFacePassesTheValidator) {
  expect_valid_reconstruction(sample_face(), "sample");
}

TEST(ReconstructionGlb, RealScansPassTheValidator) {
  for (const char* name : {"facefuns_f18.ply", "facefuns_f56_points.ply", "stfaces_neutral.wrl"}) {
    SCOPED_TRACE(name);
    const auto path = test::face(name);
    if (!path) GTEST_SKIP() << "real scan " << name << " not found (set PDEFACE_DATA)";
    const Result<formats::LoadedMesh> scan = formats::read_mesh(*path);
    ASSERT_TRUE(scan) << scan.error().to_string();
    expect_valid_reconstruction(scan->mesh, name);
  }
}

} // namespace
} // namespace pdeface::pipeline
