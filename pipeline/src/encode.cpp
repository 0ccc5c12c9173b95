#include "pdeface/pipeline/encode.hpp"
#include "encode_check.hpp"
#include "encode_residual.hpp"
#include "encode_texture.hpp"

#include "pdeface/core/text.hpp"
#include "pdeface/pdef/mesh.hpp"
#include "pdeface/pipeline/reconstruct.hpp"

namespace pdeface::pipeline {

pdef::Face to_face(const slice::ProfileSet& profiles, const pde::Surface& surface,
                   const pde::Options& options) {
  pdef::Face face;
  face.curves = to_curves(profiles);
  for (const slice::ProfileCurve& c : profiles.curves) {
    face.planes.push_back(c.x);
    face.filled.push_back(c.filled);
  }
  face.frame = profiles.frame;
  face.pde = options;
  face.pde.smoothing = surface.smoothing();
  face.pde.modes = surface.modes();
  return face;
}

Result<EncodeOutcome> encode_request(Mesh scan, const EncodeRequest& request) {
  Result<align::Alignment> alignment = align::align_from(scan, request.landmarks, request.source);
  if (!alignment) return alignment.error();
  return encode_aligned(std::move(scan), *std::move(alignment), request);
}

Result<SlicedScan> slice_and_solve(const CanonicalScan& canonical, const EncodeRequest& request) {
  auto named = [&](Error e) { return with_source(std::move(e), request.source); };
  Result<slice::ProfileSet> profiles = extract_profiles(canonical, request.profiles);
  if (!profiles) return named(std::move(profiles).error());
  Result<pde::Surface> surface = surface_from(*profiles, request.pde, request.source);
  if (!surface) return named(std::move(surface).error());
  return SlicedScan{*std::move(profiles), *std::move(surface)};
}

Result<EncodeOutcome> encode_sliced(const CanonicalScan& canonical, align::Alignment alignment,
                                    const SlicedScan& sliced, const EncodeRequest& request,
                                    ResidualGrids* grids) {
  auto named = [&](Error e) { return with_source(std::move(e), request.source); };
  EncodeOutcome out{std::move(alignment), sliced.profiles, {}, {}};
  out.face = to_face(out.profiles, sliced.surface, request.pde);
  out.face.name = clean_name(request.name); // a .pdef name is printable UTF-8, at most 1024 bytes
  if (request.store_landmarks)
    for (std::size_t i = 0; i < align::kLandmarkCount; ++i)
      if (const std::optional<Vec3>& p = canonical.landmarks.points[i])
        out.face.landmarks.push_back({std::string(align::name(static_cast<align::Landmark>(i))), *p});
  if (request.texture.wanted) {
    Result<TexturedFace> textured =
        make_texture(canonical.mesh, sliced.surface, request.texture, request.source);
    if (!textured) return named(std::move(textured).error());
    out.face.texture = std::move(textured->texture);
    out.texture = textured->outcome;
  }
  Result<pdef::Encoded> encoded = pdef::encode(out.face, request.encoding);
  if (!encoded) return named(std::move(encoded).error());
  out.encoded = *std::move(encoded);
  if (request.residual.wanted()) {
    Result<ResidualOutcome> layer = add_residual(canonical, out, request.residual, request.source, grids);
    if (!layer) return named(std::move(layer).error());
    out.residual = *std::move(layer);
  }
  return out;
}

Result<EncodeOutcome> encode_aligned(Mesh scan, align::Alignment alignment, const EncodeRequest& request) {
  const CanonicalScan canonical = canonical_scan(std::move(scan), alignment);
  Result<SlicedScan> sliced = slice_and_solve(canonical, request);
  if (!sliced) return std::move(sliced).error();
  Result<EncodeOutcome> made = encode_sliced(canonical, std::move(alignment), *sliced, request);
  if (!made) return made;
  EncodeOutcome out = *std::move(made);
  auto named = [&](Error e) { return with_source(std::move(e), request.source); };
  if (!request.check) return out;
  // What a reader gets: the file's bytes decoded and meshed, back in the canonical frame.
  Result<pdef::Face> decoded = pdef::decode(out.encoded.bytes, request.source);
  if (!decoded) return named(std::move(decoded).error());
  Result<Mesh> mesh = pdef::to_mesh(*decoded, std::nullopt, request.source);
  if (!mesh) return named(std::move(mesh).error());
  Result<metrics::SelfCheck> check = encode_check(
      canonical.mesh, out.profiles, align::to_canonical(*std::move(mesh), out.alignment.frame),
      out.residual ? with_scans_folds(*request.check, canonical.mesh, out.profiles.mask) : *request.check,
      request.force, request.source);
  if (!check) return check.error();
  out.check = *std::move(check);
  return out;
}

} // namespace pdeface::pipeline
