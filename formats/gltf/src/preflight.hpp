#pragma once
// Checks of the glTF JSON made before tinygltf loads it, for what tinygltf does not check or reports
// without a location:
// - JSON syntax errors, located (tinygltf keeps only nlohmann's message);
// - nesting deeper than 64 levels (tinygltf converts `extras` and `extensions` recursively);
// - glTF version, required extensions we cannot honour, external buffer URIs (never read: a reader of
//   bytes in memory does not touch the file system), buffer views outside their buffer;
// - every `KHR_draco_mesh_compression` primitive. tinygltf decodes these while parsing, trusting indices
//   from the file (buffer view, accessors, Draco attribute ids) and the decoded data: a bad index reads out
//   of bounds, a missing attribute id dereferences null, an attribute of more than 4 components overflows
//   a 4-element array on the stack. So the Draco data is decoded first through pdeface::drc's checked
//   decoder and compared with what the primitive claims; only then may tinygltf decode it (again).

#include "container.hpp"

#include "pdeface/core/result.hpp"

#include <cstddef>
#include <string_view>

namespace pdeface::gltf {

struct Preflight {
  std::size_t buffer_views = 0; //!< buffer views in the file; tinygltf appends one per decoded Draco stream
};

[[nodiscard]] Result<Preflight> preflight(const Container& container, std::string_view source);

} // namespace pdeface::gltf
