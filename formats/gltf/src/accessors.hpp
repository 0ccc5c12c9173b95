#pragma once
// Reading accessors of a loaded tinygltf model. tinygltf checks none of the indices, offsets, strides and
// counts that lead from an accessor to bytes, so a hostile file could make a naive reader read out of
// bounds; here every one is checked against the data itself, and every value read (finite; indices in
// range). Errors are located at the byte of the file where the bad value is, when the data lies in the
// GLB's BIN chunk.

#include "container.hpp"

#include "pdeface/core/result.hpp"

#include <tiny_gltf.h>

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace pdeface::gltf {

//! An attribute's values as floats, `components` per element.
struct Floats {
  std::vector<float> values;
  int components = 0;

  [[nodiscard]] std::size_t count() const { return components ? values.size() / components : 0; }
  [[nodiscard]] const float* operator[](std::size_t i) const { return values.data() + i * components; }
};

class Accessors {
public:
  //! `file_views`: buffer views the file declares; tinygltf appends one per decoded Draco stream after
  //! them, tightly packed whatever it records as their stride.
  Accessors(const tinygltf::Model& model, const Container& container, std::size_t file_views,
            std::string_view source)
      : model_(model), container_(container), file_views_(file_views), source_(source) {}

  //! Accessor `index` of an attribute: float, or (signed or unsigned) byte or short components, converted as
  //! glTF says when `normalized`. `what` names it in errors ("meshes[0].primitives[0] POSITION").
  //! Errors: `Malformed`, `UnsupportedFormat` (sparse), `NonFinite`.
  [[nodiscard]] Result<Floats> floats(int index, std::string_view what) const;

  //! Accessor `index` of indices (unsigned byte, short or int scalars), each below `vertices`.
  //! Errors: `Malformed`, `IndexOutOfRange`.
  [[nodiscard]] Result<std::vector<std::uint32_t>> indices(int index, std::size_t vertices,
                                                           std::string_view what) const;

private:
  struct Span;
  [[nodiscard]] Result<Span> span(int index, std::string_view what) const;
  [[nodiscard]] Error error(ErrorCode code, std::string message,
                            std::optional<std::uint64_t> byte = {}) const;

  const tinygltf::Model& model_;
  const Container& container_;
  std::size_t file_views_;
  std::string_view source_;
};

} // namespace pdeface::gltf
