#pragma once
//! \file
//! What pdeface::gltf shares with pdeface::drc to read and write `KHR_draco_mesh_compression`: the
//! encoder with the ids of the attributes it wrote, and the checked decoder. Not a stable API.

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"
#include "pdeface/draco/draco.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::drc::detail {

//! How an attribute's values are stored in the Draco data (integers are normalised).
enum class ValueType { Float, UnsignedByte, UnsignedShort };

//! One attribute of Draco data: its unique id (what glTF refers to), size and value type.
struct Attribute {
  int unique_id = -1; //!< -1: absent
  int components = 0;
  ValueType type = ValueType::Float;

  [[nodiscard]] bool present() const noexcept { return unique_id >= 0; }
};

struct Encoded {
  std::string bytes;
  Attribute position, normal, color, texcoord;
};

//! Encodes `mesh` (triangles, or a point cloud when it has none) with `options`; adds a note on the
//! position error. Errors: those of `check`, `validate` and libdraco.
[[nodiscard]] Result<Encoded> encode(const Mesh& mesh, const WriteOptions& options, Notes* notes);

struct Decoded {
  Mesh mesh;                         //!< the first attribute of each kind, one value per point
  std::vector<Attribute> attributes; //!< every attribute in the data, in Draco's order
};

//! Decodes untrusted Draco bytes, checking the bitstream before libdraco reads it and the decoded data
//! after. `base` is the offset of `bytes` in the file named `source` (errors give file offsets), or
//! nullopt when the bytes are not a slice of the file (a glTF data URI).
[[nodiscard]] Result<Decoded> decode(std::string_view bytes, std::string_view source,
                                     std::optional<std::uint64_t> base, Notes* notes);

//! A library's message in our error style: "Failed to decode geometry data.\n" becomes "failed to decode
//! geometry data"; at most 200 bytes of it, as `excerpt` quotes them (tinygltf quotes whole data URIs).
[[nodiscard]] std::string message_text(std::string message);

} // namespace pdeface::drc::detail
