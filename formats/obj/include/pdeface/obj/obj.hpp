#pragma once
//! \file
//! Wavefront OBJ reader and writer (our own code, one pass over the bytes).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::obj {

//! Parses an OBJ document: `v` (optionally with `r g b`), `vt`, `vn`, and `f` in every corner form
//! (`v`, `v/vt`, `v//vn`, `v/vt/vn`, negative = relative), polygons of up to 255 corners fan-triangulated
//! from their first corner. Values are float32 precision (parsed exactly, then rounded). Per-corner texture
//! coordinates and normals are kept when every corner of a vertex gives it the same value, else dropped with
//! a note (vertices are never split). Units come from a `# units mm` comment, the name from the first `o`.
//! Material libraries are never opened. Errors carry the line and column of the offending statement.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  //! Significant digits of each float32 value (1..17); 9 or more writes the shortest text that reads back
  //! as the same float.
  int precision = 9;
};

//! Writes `v x y z [r g b]`, `vn`, `vt`, then `f` with one index per attribute, a `# units` comment when
//! the units are known and `o name` when the mesh has a name. Alpha is dropped with a note.
//! Errors: `InvalidArgument` (precision), those of `validate`.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::obj
