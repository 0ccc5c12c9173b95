#pragma once
//! \file
//! Draco `.drc` reader and writer (through libdraco), meshes and point clouds.
//!
//! Decoding untrusted bytes is safe: before libdraco sees them, the header, the metadata block and the
//! element counts are checked against the size of the data, so a hostile file fails fast with an error
//! instead of making libdraco allocate gigabytes (see third_party_notes/draco.md).
//!
//! The namespace is `pdeface::drc` (the file extension), not `draco`: `::draco` is libdraco's, and a
//! `pdeface::draco` would hide it from all code inside `pdeface` (the folder, the header path and the
//! target keep the name: `formats/draco`, `pdeface/draco/draco.hpp`, `pdeface::draco`).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <string>
#include <string_view>

namespace pdeface::drc {

//! The most elements (points, faces) Draco data may claim per byte. Real scans hold 0.3-2 per byte; the
//! most compressible data we could make (a flat grid quantised to 1 bit) 71. libdraco allocates ~30 bytes
//! per claimed element before reading any, so this bounds what hostile data can make it allocate.
inline constexpr std::size_t kMaxElementsPerByte = 128;

//! Decodes a Draco mesh or point cloud (bitstream 2.2 for meshes, 2.3 for point clouds, as written by
//! Draco 1.4 and later): positions, normals, colours (uint8/uint16/float, RGB or RGBA) and texture
//! coordinates, one value per point; points that differ in their texture coordinate only (a seam split by
//! the writer) are welded, the texture coordinates becoming per corner (`weld_texcoord_seams`). Units are
//! read from the geometry metadata entry "units" when present.
//! Errors: `Empty`, `BadMagic` (byte 0), `UnsupportedVersion` (byte 5), `Truncated`, `Malformed`,
//! `CountTooLarge` (at the byte of the count), `NonFinite`, `IndexOutOfRange`.
[[nodiscard]] Result<Mesh> read(std::string_view bytes, std::string_view source, Notes* notes = nullptr);

//! The most quantisation bits `check` accepts for positions, normals and texture coordinates. libdraco
//! takes up to 30, but its encoder allocates about 4 * 2^bits bytes whatever the mesh (76 MB and 0.5 s at
//! 24 bits, 4 GB and 30 s at 30); and 24 bits already resolve float32 values (24-bit significand).
inline constexpr int kMaxQuantizationBits = 24;

struct WriteOptions {
  int position_bits = 14; //!< quantisation of positions, 1..kMaxQuantizationBits (Draco's tool: 11)
  int normal_bits = 10;   //!< octahedral quantisation of normals, 2..kMaxQuantizationBits
  int color_bits = 8;     //!< colours as normalised unsigned integers of 8 or 16 bits (RGBA)
  int texcoord_bits = 12; //!< quantisation of texture coordinates, 1..kMaxQuantizationBits
  int level = 7;          //!< compression level 0..10 (Draco speed = 10 - level); 0 keeps the vertex order
};

//! Checks the options' ranges up front. Errors: `InvalidArgument`, naming the option and its range.
[[nodiscard]] Result<void> check(const WriteOptions& options);

//! Encodes a mesh (or, without triangles, a point cloud); per-corner texture coordinates split their seam
//! vertices (`with_vertex_texcoords`); the material is not kept. Positions are quantised (the maximum error
//! per axis is half a step, step = largest bounding-box side / (2^position_bits - 1)); a note says how large
//! in the mesh's units. Units are written as the geometry metadata entry "units".
//! Errors: `InvalidArgument` (options), `Empty` (no vertices), errors of `validate`, `Malformed` when
//! libdraco refuses the mesh.
[[nodiscard]] Result<std::string> write(const Mesh& mesh, const WriteOptions& options = {},
                                        Notes* notes = nullptr);

} // namespace pdeface::drc
