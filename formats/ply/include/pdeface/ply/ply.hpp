#pragma once
//! \file
//! PLY (ASCII and binary, with or without faces), OFF and STL, read and written through OpenMesh's IO.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::ply {

//! Parses a PLY document; a file with only a vertex element becomes a point cloud.
//! Errors name the byte offset (binary) or line (ASCII) where the data goes wrong.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  bool binary = true; //!< binary little-endian; false writes ASCII
};

[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::ply

namespace pdeface::off {

[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);
[[nodiscard]] Result<std::string> write(const Mesh& mesh, Notes* notes = nullptr);

} // namespace pdeface::off

namespace pdeface::stl {

//! ASCII or binary STL; coincident corners are merged into shared vertices.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  bool binary = true;
};

[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::stl
