#pragma once
//! \file
//! Wavefront OBJ reader (through tinyobjloader) and writer.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::obj {

//! Parses an OBJ document (`v`, `vn`, `vt`, `f` with any polygon size, vertex colours after `v x y z`).
//! Material libraries are not opened. Errors carry the line of the offending statement.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  int precision = 9; //!< significant digits per coordinate (9 round-trips a float exactly)
};

[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::obj
