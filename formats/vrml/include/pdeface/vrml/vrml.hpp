#pragma once
//! \file
//! VRML 1.0 and VRML 2.0/97 reader, VRML 2.0 writer.
//!
//! The reader merges every `IndexedFaceSet` and `PointSet` of the scene graph into one mesh, with each
//! node's accumulated `Transform` applied, polygons fan-triangulated. Nodes it does not need are parsed
//! and skipped. No maintained VRML library exists in Debian, so this parser is ours.

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::vrml {

//! Parses a VRML 1.0 or 2.0 document. Texture coordinates are per corner (`texCoordIndex` with seams),
//! else per vertex. VRML 2.0: the first Shape's `Appearance` is the material (`diffuseColor` as the base
//! colour when there is no texture, 1 − `transparency` as alpha) and its `ImageTexture` url the image,
//! obtained through `resolve` (see `resolve_image`: a missing file is a note). Errors carry the line and
//! column of the offending token (a corrupt image: its byte).
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr,
                                const Resolver& resolve = {});

struct WriteOptions {
  int precision = 9;       //!< significant digits per coordinate (9 round-trips a float exactly)
  std::string texture_url; //!< the image file written beside, named by the `ImageTexture` (empty: none)
};

//! A VRML 2.0 document: one `Shape` with an `IndexedFaceSet` (or a `PointSet` for a point cloud), with
//! normals, colours and texture coordinates when the mesh has them (per corner: a `texCoordIndex`), and
//! the material as an `Appearance` (`Material` `diffuseColor`, `ImageTexture` naming `texture_url`).
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::vrml
