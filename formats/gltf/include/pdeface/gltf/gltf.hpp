#pragma once
//! \file
//! glTF 2.0 (`.gltf` with data-URI buffers, and `.glb`) reader and writer, through tinygltf.
//!
//! Reading untrusted bytes is safe and touches no file: external buffers are refused, images are never
//! decoded, and every index, offset and count that tinygltf takes on trust is checked first (see
//! third_party_notes/tinygltf.md). Units are known only from our marker `asset.extras.units` ("mm", ...):
//! glTF says metres, but scanners write millimetres into it.

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/draco/draco.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace pdeface::gltf {

//! Merges every triangle (or point) primitive of the default scene (else scene 0, else every root node)
//! into one mesh, node transforms applied (normals by the inverse transpose; mirroring transforms flip the
//! winding). Modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN and POINTS; lines are skipped with a note.
//! Attributes POSITION, NORMAL, COLOR_0 (RGB gets alpha 1) and TEXCOORD_0, float or normalised integers
//! (`KHR_mesh_quantization`); others are dropped with a note, as is an attribute only some primitives have.
//! `KHR_draco_mesh_compression` primitives are decoded through Draco.
//! Errors: `Empty`, `BadMagic`, `UnsupportedVersion`, `Truncated` and `Malformed` (GLB: at the byte of the
//! header or chunk; JSON syntax: at the line and column of a `.gltf`, the byte of a `.glb`),
//! `UnsupportedFormat` (external buffers, sparse accessors, required extensions we cannot honour),
//! `IndexOutOfRange` and `NonFinite` (at the byte of the value when it lies in the GLB's BIN chunk).
//! The material of the first primitive that has one: its name, `baseColorFactor` and `baseColorTexture`
//! (TEXCOORD_0 only), the image embedded (a buffer view, a data URI) or, for an external `uri`, obtained
//! through `resolve` (without one, or when it fails, a note: the image keeps its uri only). Images are
//! never decoded, only their headers checked (`inspect_image`). Texture coordinates are turned from glTF's
//! top-left origin to ours (v' = 1 − v), and vertices that repeat another's position, normal and colour (a
//! writer's split at texture seams) are welded, their texture coordinates becoming per corner.
//! Errors, also: those of `inspect_image` for an embedded image (at its byte in a GLB).
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr,
                                const Resolver& resolve = {});

struct WriteOptions {
  bool binary = true; //!< GLB; false writes a `.gltf` JSON document with the buffer as a data URI
  std::optional<drc::WriteOptions> draco; //!< set: compress the primitive with KHR_draco_mesh_compression
};

//! A GLB (or .gltf) that the Khronos glTF validator accepts without errors: one mesh, one primitive (mode
//! TRIANGLES, or POINTS for a point cloud), one node, one scene. POSITION as float32 (with min and max; a
//! note tells how far doubles were rounded); NORMAL of unit length (computed with `vertex_normals` for a
//! mesh without normals; +z for vertices on no triangle); COLOR_0 as normalised unsigned bytes when every
//! channel is a multiple of 1/255, else as floats (RGBA); TEXCOORD_0 (v' = 1 − v; per-corner texture
//! coordinates split their seam vertices, `with_vertex_texcoords`); the material (base colour factor, not
//! metallic, fully rough) with its JPEG or PNG image embedded as a buffer view; indices u16 below 65535
//! vertices, else u32. With `options.draco`, triangle meshes are compressed with `KHR_draco_mesh_compression`
//! (point clouds, which the extension cannot hold, are written uncompressed with a note).
//! Errors: `InvalidArgument` (Draco options), `Empty`, those of `validate` and of the Draco encoder.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::gltf
