#pragma once
// From a parsed scene to one mesh: traverse the graph with the accumulated transforms, fan-triangulate the
// face sets, keep per-vertex attributes where they map one-to-one onto vertices, and merge everything.

#include "context.hpp"
#include "scene.hpp"

#include "pdeface/core/mesh.hpp"

namespace pdeface::vrml::detail {

enum class Version { V1, V2 };

//! The merged mesh of every IndexedFaceSet and PointSet the scene draws. Fails with `Empty` if it draws
//! none with coordinates, `IndexOutOfRange` at the offending index, `CountTooLarge` if instancing
//! (`USE`) would multiply the geometry beyond what a scan can hold.
[[nodiscard]] Mesh build_mesh(const Scene& scene, Version version, Context& context);

} // namespace pdeface::vrml::detail
