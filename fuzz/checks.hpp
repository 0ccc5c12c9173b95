#pragma once
// What every fuzz target checks, whatever the bytes: an error is one short line of valid UTF-8 with a
// location inside the input; notes are few and short; a mesh read is valid and no larger than its bytes
// justify; and a mesh a writer accepts reads back with its own reader (docs/robustness.md).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/core/text.hpp"
#include "pdeface/formats/formats.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pdeface::fuzz {

//! A message: fixed words, numbers, and at most a few excerpts of the input.
inline constexpr std::size_t kMaxMessage = 512;
//! All the notes of one read or write together.
inline constexpr std::size_t kMaxNotes = 64 * 1024;
//! Vertices plus triangles a reader may make of `n` bytes: Draco's bound (the densest format), and room
//! for a `.pdef` surface, whose grid does not depend on the file's size.
inline constexpr std::size_t kFreeElements = 1 << 20;
inline constexpr std::size_t kElementsPerByte = 128;

[[noreturn]] inline void broken(const std::string& what) { throw std::logic_error(what); }

inline bool readable(std::string_view text) {
  return is_valid_utf8(text) &&
         std::ranges::none_of(text, [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

inline void check_error(const Error& e, std::size_t input_size) {
  if (e.message.empty()) broken("an error without a message");
  if (e.message.size() > kMaxMessage) broken("a message of " + std::to_string(e.message.size()) + " bytes");
  if (!readable(e.message)) broken("a message that is not one line of UTF-8: " + excerpt(e.message, 200));
  if (e.where.byte && *e.where.byte > input_size) broken("an error past the end of the input");
}

inline void check_notes(const Notes& notes) {
  std::size_t total = 0;
  for (const std::string& n : notes) {
    total += n.size();
    if (!readable(n)) broken("a note that is not one line of UTF-8: " + excerpt(n, 200));
  }
  if (total > kMaxNotes) broken("notes of " + std::to_string(total) + " bytes");
}

inline void check_mesh(const Mesh& mesh, std::size_t input_size) {
  if (Result<void> ok = validate(mesh); !ok) broken("an invalid mesh: " + ok.error().to_string());
  if (mesh.vertex_count() == 0) broken("a mesh without vertices");
  if (mesh.vertex_count() + mesh.triangle_count() > kFreeElements + kElementsPerByte * input_size)
    broken("a mesh larger than its bytes justify");
}

//! Writes `mesh` as `format` (with `options`) and reads it back: either the writer refuses with a clean
//! error, or its reader reads what it wrote, with as many triangles (and vertices, where the format keeps
//! them: not STL, which merges corners, nor Draco's edgebreaker, which drops vertices on no triangle).
inline void round_trip(const Mesh& mesh, formats::Format format, const formats::WriteOptions& options = {}) {
  const formats::FormatInfo& info = formats::info(format);
  const std::string name = "again" + std::string(info.extensions.front());
  Notes notes;
  Result<std::string> bytes = formats::encode_mesh(mesh, name, options, &notes);
  check_notes(notes);
  if (!bytes) return check_error(bytes.error(), SIZE_MAX);
  Result<formats::LoadedMesh> back = formats::read_mesh(*bytes, name, {.format = format}, &notes);
  if (!back) broken(std::string(info.name) + " writes what it cannot read: " + back.error().to_string());
  check_notes(notes);
  const Mesh& m = back->mesh;
  // STL keeps the triangles whose corners are three different points (as float32): it has no vertices,
  // only corners, merged where they are equal.
  std::size_t triangles = mesh.triangle_count();
  if (format == formats::Format::Stl)
    triangles = static_cast<std::size_t>(std::ranges::count_if(mesh.triangles, [&](const Triangle& t) {
      const Vec3f a = mesh.positions[t[0]].cast<float>(), b = mesh.positions[t[1]].cast<float>(),
                  c = mesh.positions[t[2]].cast<float>();
      return a != b && b != c && a != c;
    }));
  // glTF and Draco weld vertices that repeat another's position, normal and colour when there are texture
  // coordinates (a seam split); PLY writes a seam vertex once per texture coordinate.
  const bool welds =
      mesh.has_texcoords() &&
      (format == formats::Format::Glb || format == formats::Format::Gltf || format == formats::Format::Draco);
  const bool splits = mesh.has_corner_texcoords() && format == formats::Format::Ply;
  const bool merges = format == formats::Format::Stl ||
                      (format == formats::Format::Draco && options.draco_level > 0) ||
                      (format == formats::Format::Glb && options.draco_in_gltf) || welds || splits;
  if (m.triangle_count() != triangles && format != formats::Format::Draco && !options.draco_in_gltf)
    broken(std::string(info.name) + " changes the triangle count: " + std::to_string(mesh.triangle_count()) +
           " (" + std::to_string(triangles) + " expected) read back as " +
           std::to_string(m.triangle_count()));
  if (!merges && m.vertex_count() != mesh.vertex_count())
    broken(std::string(info.name) + " changes the vertex count: " + std::to_string(mesh.vertex_count()) +
           " read back as " + std::to_string(m.vertex_count()));
}

} // namespace pdeface::fuzz
