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

//! The bytes of `count` vertex records (float x y z, and nx ny nz with `normals`).
[[nodiscard]] std::size_t binary_vertex_bytes(std::size_t count, bool normals);
//! The bytes of `count` face records (uchar 3, int i j k).
[[nodiscard]] std::size_t binary_triangle_bytes(std::size_t count);

//! Writes the vertex records of `positions` (rounded to float32, as `write` does) and, unless `normals` is
//! empty, their normals, at the start of `out`.
//! \throw std::invalid_argument when `normals` is neither empty nor as long as `positions`, or `out` is
//! shorter than `binary_vertex_bytes`
void put_binary_vertices(std::span<char> out, std::span<const Vec3> positions,
                         std::span<const Vec3f> normals);

//! Writes the face records of `triangles` at the start of `out`: the count 3, then the indices.
//! \throw std::invalid_argument when `out` is shorter than `binary_triangle_bytes`
void put_binary_triangles(std::span<char> out, std::span<const Triangle> triangles);

} // namespace pdeface::ply
