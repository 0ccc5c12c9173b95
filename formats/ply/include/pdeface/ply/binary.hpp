#pragma once
//! \file
//! Binary PLY written in pieces: the bytes `ply::write` gives a triangle mesh with positions and, optionally,
//! normals (no colours, no texture coordinates), made a block of vertices or triangles at a time, so that a
//! writer can stream a mesh it never holds whole (a decoded `.pdef` at a million vertices: 60 MB as a
//! `Mesh`, 50 MB as PLY). No OpenMesh: plain little-endian records.

#include "pdeface/core/mesh.hpp"

#include <cstddef>
#include <span>
#include <string>

namespace pdeface::ply {

//! What such a file holds.
struct BinaryLayout {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  bool normals = false; //!< float nx ny nz after float x y z
  Units units = Units::Unknown;
};

//! The header, through `end_header\n`: as `write` makes it (`comment units` when the units are known).
[[nodiscard]] std::string binary_header(const BinaryLayout& layout);

//! The whole file's size in bytes.
[[nodiscard]] std::size_t binary_size(const BinaryLayout& layout);

//! Appends the vertex records of `positions` (rounded to float32, as `write` does) and, unless `normals`
//! is empty, their normals.
//! \throw std::invalid_argument when `normals` is neither empty nor as long as `positions`
void append_binary_vertices(std::string& out, std::span<const Vec3> positions,
                            std::span<const Vec3f> normals);

//! Appends the face records of `triangles`: the count 3 (uchar), then the indices (int32).
void append_binary_triangles(std::string& out, std::span<const Triangle> triangles);

} // namespace pdeface::ply
