#pragma once
//! \file
//! Draco `.drc` reader and writer (through libdraco), meshes and point clouds.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::draco {

//! Decodes a Draco mesh or point cloud; positions, normals, colours and texture coordinates.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

struct WriteOptions {
  int position_bits = 14; //!< quantisation of positions, 1..30 (Draco's tool defaults to 11)
  int normal_bits = 10;
  int color_bits = 8;
  int texcoord_bits = 12;
  int level = 7;          //!< compression level 0..10; 0 keeps the vertex order
};

//! Checks the options' ranges up front. Errors: `InvalidArgument`.
[[nodiscard]] Result<void> check(const WriteOptions& options);

[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::draco
