#pragma once
//! \file
//! Wavefront OBJ reader and writer (our own code, one pass over the bytes).

#include "pdeface/core/image.hpp"
#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::obj {

//! Parses an OBJ document: `v` (optionally with `r g b`), `vt`, `vn`, and `f` in every corner form
//! (`v`, `v/vt`, `v//vn`, `v/vt/vn`, negative = relative), polygons of up to 255 corners fan-triangulated
//! from their first corner. Values are float32 precision (parsed exactly, then rounded). Texture coordinates
//! are per vertex when every corner of a vertex gives it the same one, else per corner (`texcoord_triangles`:
//! seams kept, vertices never split); when some corners have none they are dropped with a note. Normals are
//! kept when every corner of a vertex gives it the same one, else dropped with a note. Units come from a
//! `# units mm` comment, the name from the first `o`.
//!
//! The first `mtllib` is obtained through `resolve` (without one, or when it fails: a note, no material), and
//! in it the material the first `usemtl` names (else the first): `Kd` as the base colour when there is no
//! `map_Kd` (with one, the photo is the colour, as viewers show it), `d` as alpha, and `map_Kd`'s image
//! (relative to the library's folder; through `resolve`, see `resolve_image`). Errors carry the line and
//! column of the offending statement; an image that is there but corrupt or too large is an error
//! (`inspect_image`), one that is missing a note.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr,
                                const Resolver& resolve = {});

struct WriteOptions {
  //! Significant digits of each float32 value (1..17); 9 or more writes the shortest text that reads back
  //! as the same float.
  int precision = 9;
  //! The material library the OBJ refers to (`mtllib`, `usemtl`), written by `write_material_library`;
  //! empty: no material (with a note when the mesh has one).
  std::string material_library;
};

//! Writes `v x y z [r g b]`, `vn`, `vt`, then `f` with one index per attribute (texture coordinates per
//! corner: their own index, seams kept), a `# units` comment when the units are known and `o name` when the
//! mesh has a name. Alpha is dropped with a note.
//! Errors: `InvalidArgument` (precision), those of `validate`.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

//! The material library for `write`'s `material_library`: `newmtl`, `Kd` (the base colour), `d` (its alpha)
//! and `map_Kd image` when `image` is not empty. \pre mesh.material
[[nodiscard]] std::string write_material_library(const Mesh& mesh, std::string_view image);

//! The material's name as `newmtl` and `usemtl` write it: one token ("material_0" when it has none).
[[nodiscard]] std::string material_name(const Material& material);

} // namespace pdeface::obj
