#pragma once
//! \file
//! PLY (ASCII and binary, with or without faces) and OFF read and written through OpenMesh's IO; STL written
//! through it and read by our validator.
//!
//! Every input is checked by our own validator before OpenMesh sees it (OpenMesh hangs, crashes or misreads
//! silently on bad data); errors give the header line and column, the byte offset in binary data, or the
//! line and column in text. OpenMesh calls are serialised by one mutex: the readers are safe to call from
//! any thread, but the part inside OpenMesh runs one at a time. Nothing is ever printed.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::ply {

//! Parses a PLY document; a file with only a vertex element becomes a point cloud. Reads x y z, nx ny nz,
//! u v / s t / texture_u texture_v, red green blue [alpha] (uchar or float), and the faces'
//! vertex_indices (polygons fan-triangulated). Values are float32 precision. Other properties and elements
//! are skipped with a note; layouts OpenMesh cannot read are refused (`UnsupportedFormat`). Units come
//! from a `comment units mm` line.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  bool binary = true; //!< binary little-endian; false writes ASCII (9 significant digits)
};

//! Writes float x y z, float nx ny nz, float s t, uchar red green blue (alpha only when some alpha < 1),
//! faces as `list uchar int vertex_indices`, and `comment units mm` when the units are known.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::ply

namespace pdeface::off {

//! Parses ASCII OFF (comments allowed); polygons fan-triangulated. COFF/NOFF are accepted but their
//! colours and normals are dropped with a note, as are values after a face's indices. Units come from a
//! `# units mm` comment. Binary OFF and 4D/nD OFF are refused.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);
//! Writes plain OFF (positions and faces, 9 significant digits) and a `# units mm` comment when known;
//! other attributes are dropped with a note.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, Notes* notes = nullptr);

} // namespace pdeface::off

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
