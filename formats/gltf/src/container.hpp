#pragma once
// The two containers of glTF: a `.gltf` JSON document, or a `.glb` (12-byte header, a JSON chunk, an
// optional BIN chunk). The GLB's header and chunk headers are checked here, with exact byte offsets,
// before tinygltf sees them: tinygltf reports "Invalid glTF binary." without saying where, and reads up to
// 8 bytes past a BIN chunk whose length ends exactly at the end of the file.

#include "pdeface/core/result.hpp"

#include <cstdint>
#include <optional>
#include <string_view>

namespace pdeface::gltf {

struct Container {
  std::string_view bytes;              //!< the whole GLB (without trailing bytes), or the JSON document
  std::string_view json;               //!< the JSON text
  std::uint64_t json_offset = 0;       //!< where `json` starts in the file
  std::optional<std::string_view> bin; //!< the GLB's BIN chunk data
  std::uint64_t bin_offset = 0;        //!< where the BIN data starts in the file
  bool glb = false;

  //! Where byte `offset` of the JSON text is in the file: a byte offset in a GLB, a line and column in a
  //! `.gltf` (both 1-based).
  [[nodiscard]] Location json_location(std::uint64_t offset) const;
};

//! Splits `bytes` into JSON and BIN. Errors: `Empty`, `BadMagic` (neither "glTF" nor a JSON object),
//! `UnsupportedVersion` (byte 4), `Truncated` (at the end of the data), `Malformed` (at the chunk header).
[[nodiscard]] Result<Container> split_container(std::string_view bytes, std::string_view source,
                                                Notes* notes);

} // namespace pdeface::gltf
