#pragma once
//! \file
//! OFF (ASCII) read and written through OpenMesh's IO, after our own validator: errors give the line and
//! column. OpenMesh calls are serialised by one mutex shared with PLY and STL: the reader is safe to call
//! from any thread, but the part inside OpenMesh runs one at a time. Nothing is ever printed.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::off {

//! Parses ASCII OFF (comments allowed); polygons fan-triangulated. COFF colours are read (r g b [a] after
//! the coordinates, and after NOFF's normals: integers 0..255, or reals 0..1 when written with a '.' or an
//! exponent; a vertex without them is an error at its line); NOFF normals are dropped with a note, as are
//! values after a face's indices. Units come from a `# units mm` comment. Binary OFF and 4D/nD OFF are
//! refused.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);
//! Writes OFF (positions and faces, 9 significant digits), COFF with r g b a as integers 0..255 when the
//! mesh has colours, and a `# units mm` comment when known; other attributes are dropped with a note.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, Notes* notes = nullptr);

} // namespace pdeface::off
