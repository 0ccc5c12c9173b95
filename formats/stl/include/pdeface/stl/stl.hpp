#pragma once
//! \file
//! STL (binary and ASCII) read by our own validator, which builds the mesh, and written through OpenMesh's
//! IO (behind the mutex PLY and OFF share). Errors give the byte offset in binary data, or the line and
//! column in text. Nothing is ever printed.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::stl {

//! ASCII or binary STL (decided by the size: 84 + 50 × facets means binary); equal corners are merged into
//! shared vertices, so vertices come back renumbered in the order corners first appear; facets two of whose
//! corners are the same point are skipped with a note. Read by our own code (OpenMesh merges corners up to
//! FLT_MIN apart), written through OpenMesh.
//! Units come from "units mm" in the binary header or the solid line, as our writer puts them.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  bool binary = true; //!< false writes ASCII
};

//! Writes facets with their normals; attributes are dropped with a note. Errors: `InvalidArgument` for a
//! point cloud.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::stl
