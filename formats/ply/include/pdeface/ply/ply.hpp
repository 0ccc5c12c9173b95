#pragma once
//! \file
//! PLY (ASCII and binary, with or without faces), read by our own code for the usual layouts (float
//! coordinates, uchar colours, int or uint face indices) and through OpenMesh's IO for the others, written
//! through OpenMesh's IO; OFF and STL, which use it too, are `pdeface/off/off.hpp` and `pdeface/stl/stl.hpp`.
//!
//! Every input is checked by our own code before any of it is used (OpenMesh hangs, crashes or misreads
//! silently on bad data); errors give the header line and column, the byte offset in binary data, or the
//! line and column in text. OpenMesh calls are serialised by one mutex (shared with OFF and STL): the reader
//! is safe to call from any thread; only the layouts OpenMesh reads run one at a time. Nothing is printed.

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::ply {

//! Parses a PLY document; a file with only a vertex element becomes a point cloud. Reads x y z, nx ny nz,
//! u v / s t / texture_u texture_v, red green blue [alpha] (uchar or float), and the faces'
//! vertex_indices (polygons fan-triangulated). Values are float32 precision. Other properties and elements
//! are skipped with a note; layouts OpenMesh cannot read are refused (`UnsupportedFormat`). Units come
//! from a `comment units mm` line. A `comment TextureFile name` (MeshLab's) names the image the texture
//! coordinates map into: obtained through `resolve` as the material's (see `resolve_image`).
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr,
                                const Resolver& resolve = {});

struct WriteOptions {
  bool binary = true;       //!< binary little-endian; false writes ASCII (9 significant digits)
  std::string texture_file; //!< the image written beside, named by `comment TextureFile` (empty: none)
};

//! Writes float x y z, float nx ny nz, float s t (per vertex: seam vertices split,
//! `with_vertex_texcoords`), uchar red green blue (alpha only when some alpha < 1), faces as `list uchar
//! int vertex_indices`, `comment units mm` when the units are known and `comment TextureFile` naming
//! `texture_file`. The material's colour is not kept.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::ply
