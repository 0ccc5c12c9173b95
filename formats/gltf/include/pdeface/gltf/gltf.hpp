#pragma once
//! \file
//! glTF 2.0 (`.gltf` with embedded or data-URI buffers, and `.glb`) reader and GLB writer.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/draco/draco.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace pdeface::gltf {

//! Merges every triangle (or point) primitive of the default scene into one mesh, node transforms
//! applied; `KHR_draco_mesh_compression` primitives are decoded through Draco.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  bool binary = true; //!< GLB; false writes a `.gltf` JSON document with the buffer as a data URI
  std::optional<draco::WriteOptions> draco; //!< set: compress the primitive with KHR_draco_mesh_compression
};

//! A GLB (or .gltf) holding one mesh with positions, normals (computed when the mesh has none) and optional vertex
//! colours, which the Khronos glTF validator accepts without errors.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::gltf
