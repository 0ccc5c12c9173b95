// The .pdef codec on a synthetic face: what survives a round trip (exactly, or within the stated error),
// the encoder's guarantees about the decoded surface, determinism, and faces it refuses.

#include "pdeface/metrics/surface_distance.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pdef/pdef.hpp"

#include "pdef_support.hpp"

#include <gtest/gtest.h>

namespace pdeface::pdef {
namespace {

using test::synthetic_face;

double max_sample_distance(const Face& a, const Face& b) {
  double worst = 0;
  for (std::size_t j = 0; j < a.curve_count(); ++j)
    worst = std::max(worst, (a.curves.samples[j] - b.curves.samples[j]).rowwise().norm().maxCoeff());
  return worst;
}

// The largest distance from the surface of `b` to that of `a`, measured on meshes: b on a fine grid, a on a
// finer one (its chords lie within ~1e-4 mm of the surface here).
double surface_distance(const Face& a, const Face& b) {
  const pde::Surface sa = surface_of(a).value(), sb = surface_of(b).value();
  const Mesh ma = sa.mesh(241, 481), mb = sb.mesh(121, 241);
  const metrics::SurfaceDistance to_a(ma);
  double worst = 0;
  for (const Vec3& p : mb.positions)
    worst = std::max(worst, to_a.distance(p));
  return worst;
}

TEST(Pdef, LossyKeepsEverySampleAndTheSurfaceWithinTheMaximumError) {
  const Face face = synthetic_face();
  for (const double e : {0.01, 0.05, 0.2}) {
    const Result<Encoded> encoded = encode(face, {.max_error_mm = e});
    ASSERT_TRUE(encoded) << encoded.error().to_string();
    const Result<Face> back = decode(encoded->bytes, "synthetic.pdef");
    ASSERT_TRUE(back) << back.error().to_string();
    const double samples = max_sample_distance(face, *back);
    EXPECT_LE(samples, e) << e;
    // What the encoder reports includes the float32 frame's part (in the scan's frame): a few nanometres.
    EXPECT_LE(samples, encoded->max_sample_error) << e;
    EXPECT_GE(samples + 1e-5, encoded->max_sample_error) << e;
    EXPECT_LE(encoded->max_surface_error, e) << e;
    // Measured independently of the encoder's own check (meshes and exact point-triangle distances).
    EXPECT_LE(surface_distance(face, *back), e * 1.01) << e;
    EXPECT_GT(samples, e / 10) << e; // it did use the error it was given
  }
}

TEST(Pdef, ASmallerErrorCostsMoreBytes) {
  const Face face = synthetic_face(28, 30);
  std::size_t previous = 0;
  for (const double e : {0.2, 0.05, 0.01}) {
    const Result<Encoded> encoded = encode(face, {.max_error_mm = e});
    ASSERT_TRUE(encoded) << encoded.error().to_string();
    EXPECT_GT(encoded->bytes.size(), previous) << e;
    previous = encoded->bytes.size();
  }
  const Result<Encoded> lossless = encode(face, {.lossless = true});
  ASSERT_TRUE(lossless);
  EXPECT_GT(lossless->bytes.size(), previous);
}

TEST(Pdef, EverythingButTheSamplesSurvivesExactly) {
  Face face = synthetic_face();
  face.name = "synthetic face";
  face.landmarks = {{"nose_tip", Vec3(0.1, 0.2, 18.3)}, {"chin", Vec3(0.0, -68.0, 2.5)}};
  const Result<Encoded> encoded = encode(face);
  ASSERT_TRUE(encoded);
  const Result<Face> back = decode(encoded->bytes);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->curve_count(), face.curve_count());
  EXPECT_EQ(back->sample_count(), face.sample_count());
  EXPECT_EQ(back->filled, face.filled);
  EXPECT_EQ(back->pde.smoothing, face.pde.smoothing); // bit for bit: never recomputed
  EXPECT_EQ(back->pde.modes, face.pde.modes);
  EXPECT_EQ(back->pde.scheme, face.pde.scheme);
  EXPECT_EQ(back->pde.spacing, face.pde.spacing);
  EXPECT_EQ(back->pde.remainder, face.pde.remainder);
  EXPECT_EQ(back->frame.scan_units, Units::Centimetres);
  EXPECT_LT((back->frame.rotation - face.frame.rotation).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((back->frame.translation - face.frame.translation).norm(), 1e-4);
  EXPECT_FLOAT_EQ(static_cast<float>(back->frame.scale), static_cast<float>(face.frame.scale));
  EXPECT_EQ(back->name, face.name);
  ASSERT_EQ(back->landmarks.size(), 2U);
  EXPECT_EQ(back->landmarks[1].name, "chin");
  EXPECT_LE((back->landmarks[0].position - face.landmarks[0].position).cwiseAbs().maxCoeff(),
            back->storage.step_mm / 2);
  EXPECT_FALSE(back->storage.lossless);
  for (std::size_t j = 0; j < back->curve_count(); ++j) {
    EXPECT_NEAR(back->planes[j], face.planes[j], back->storage.plane_step_mm / 2);
    EXPECT_TRUE((back->curves.samples[j].col(0).array() == back->planes[j]).all())
        << j; // a curve lies in its plane
  }
}

TEST(Pdef, LosslessIsExact) {
  Face face = synthetic_face();
  face.curves.samples[2](3, 0) += 1e-13; // a sample off its plane by rounding, as the slicer's are
  face.landmarks = {{"nose_tip", Vec3(0.1, 0.2, 18.3)}};
  const Result<Encoded> encoded = encode(face, {.lossless = true});
  ASSERT_TRUE(encoded);
  const Result<Face> back = decode(encoded->bytes);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_TRUE(back->storage.lossless);
  for (std::size_t j = 0; j < face.curve_count(); ++j)
    EXPECT_TRUE(back->curves.samples[j] == face.curves.samples[j]) << j;
  EXPECT_EQ(back->planes, face.planes);
  EXPECT_TRUE(back->frame.rotation == face.frame.rotation);
  EXPECT_TRUE(back->frame.translation == face.frame.translation);
  EXPECT_EQ(back->frame.scale, face.frame.scale);
  EXPECT_TRUE(back->landmarks[0].position == face.landmarks[0].position);
  // The same surface, bit for bit, in the scan's frame.
  const Mesh a = to_mesh(face).value(), b = to_mesh(*back).value();
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(Pdef, EncodingADecodedFileGivesTheSameBytes) {
  Face face = synthetic_face(28, 30);
  face.name = "again";
  face.landmarks = {{"nose_tip", Vec3(0.1, 0.2, 18.3)}};
  for (const EncodeOptions& options :
       {EncodeOptions{}, EncodeOptions{.max_error_mm = 0.013}, EncodeOptions{.lossless = true}}) {
    const std::string first = encode(face, options).value().bytes;
    EXPECT_EQ(encode(face, options).value().bytes, first); // deterministic
    const Face back = decode(first).value();
    EXPECT_EQ(encode(back, options).value().bytes, first) << options.max_error_mm << options.lossless;
    // A coarser error keeps the finer grid the decoded face is on.
    if (!options.lossless) {
      EXPECT_EQ(encode(back, {.max_error_mm = 0.1}).value().bytes, first);
    }
  }
}

TEST(Pdef, TheMeshIsInTheScansFrameAndUnits) {
  const Face face = synthetic_face();
  const Result<Mesh> mesh = to_mesh(face, Resolution{30, 40});
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), 30U * 40U);
  EXPECT_EQ(mesh->units, Units::Centimetres);
  ASSERT_EQ(mesh->normals.size(), mesh->vertex_count());
  const pde::Surface s = surface_of(face).value();
  const Mesh canonical = s.mesh(30, 40);
  for (std::size_t i = 0; i < canonical.positions.size(); i += 97) {
    const Vec3 back = face.frame.scale * (face.frame.rotation * mesh->positions[i]) + face.frame.translation;
    EXPECT_LT((back - canonical.positions[i]).norm(), 1e-9) << i;
    const Vec3f n = face.frame.rotation.cast<float>() * mesh->normals[i];
    EXPECT_LT((n - canonical.normals[i]).norm(), 1e-5F) << i;
  }
  // About 1 mm between points by default; u × v and v-only resolutions.
  const std::array<double, 2> size = face_size(face);
  EXPECT_EQ(to_mesh(face).value().vertex_count(),
            grid_for(size[0], size[1], 1.0).u * grid_for(size[0], size[1], 1.0).v);
  EXPECT_EQ(to_mesh(face, Resolution{0, 50}).value().vertex_count(),
            grid_for(size[0], size[1], std::size_t{50}).u * 50);
  const Result<Mesh> huge = to_mesh(face, Resolution{4000, 4000});
  ASSERT_FALSE(huge);
  EXPECT_EQ(huge.error().code, ErrorCode::InvalidArgument);
}

TEST(Pdef, CurvesRunningDownwardsStillMesh) {
  // Not what the slicer makes (chin to forehead), but a file may hold it: the default grid stays sane.
  Face face = synthetic_face();
  for (pde::Curve& c : face.curves.samples)
    c = c.colwise().reverse().eval();
  const Result<Mesh> mesh = to_mesh(face);
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertex_count(), grid_for(face_size(face)[0], 0.0, 1.0).u * 2);
}

TEST(Pdef, SectionsAddUpToTheFile) {
  Face face = synthetic_face();
  face.name = "n";
  const std::string bytes = encode(face).value().bytes;
  const Result<std::vector<Section>> parts = sections(bytes, "x.pdef");
  ASSERT_TRUE(parts);
  std::vector<std::string> names;
  std::size_t total = 0, offset = 0;
  for (const Section& s : *parts) {
    names.push_back(s.name);
    EXPECT_EQ(s.offset, offset) << s.name;
    offset += s.bytes;
    total += s.bytes;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"header", "face", "curves", "name", "checksum"}));
  EXPECT_EQ(total, bytes.size());
}

TEST(Pdef, FacesTheFormatCannotHoldAreRefused) {
  const auto code = [](const Face& f, EncodeOptions o = {}) { return encode(f, o).error().code; };
  EXPECT_EQ(code(synthetic_face(), {.max_error_mm = 0}), ErrorCode::InvalidArgument);
  EXPECT_EQ(code(synthetic_face(), {.max_error_mm = 1e9}), ErrorCode::InvalidArgument);
  Face f = synthetic_face();
  f.curves.samples.resize(3);
  f.planes.resize(3);
  f.filled.resize(3);
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument); // fewer than 4 curves
  f = synthetic_face();
  std::swap(f.planes[1], f.planes[2]);
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument); // planes not ascending
  f = synthetic_face();
  f.curves.samples[1](2, 2) = std::nan("");
  EXPECT_EQ(code(f), ErrorCode::NonFinite);
  f = synthetic_face();
  f.pde.smoothing.reset();
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument);
  f = synthetic_face();
  f.pde.modes = f.sample_count();
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument);
  f = synthetic_face(11, 12);
  f.pde.scheme = pde::Scheme::Paper;
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument); // 11 curves are not 3p + 1
  f = synthetic_face();
  f.name = std::string(kMaxName + 1, 'a');
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument);
  f = synthetic_face();
  f.landmarks = {{"bad\nname", Vec3::Zero()}};
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument);
  f = synthetic_face();
  f.frame.scale = 0;
  EXPECT_EQ(code(f), ErrorCode::InvalidArgument);
  f = synthetic_face();
  f.filled.pop_back();
  EXPECT_THROW((void)encode(f), std::invalid_argument); // a bad call, not bad data
}

TEST(Pdef, OtherSchemesAndOptionsRoundTrip) {
  Face face = synthetic_face(10, 16);
  face.pde.scheme = pde::Scheme::Patch4;
  face.pde.modes = 9;
  face.pde.remainder = false;
  face.pde.spacing = pde::Spacing::Uniform;
  for (const bool lossless : {false, true}) {
    const Face back = decode(encode(face, {.lossless = lossless}).value().bytes).value();
    EXPECT_EQ(back.pde.scheme, pde::Scheme::Patch4);
    EXPECT_EQ(back.pde.modes, 9U);
    EXPECT_FALSE(back.pde.remainder);
    EXPECT_EQ(back.pde.spacing, pde::Spacing::Uniform);
    EXPECT_TRUE(to_mesh(back));
  }
}

} // namespace
} // namespace pdeface::pdef
