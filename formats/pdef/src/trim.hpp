#pragma once
// The residual layer's trim (docs/pdef-format.md, "The trim"): which cells of the layer's grid hold no
// surface, as a quadtree coded breadth first, coarse to fine, so that every prefix of its stream decodes to
// a coarser trim (the cells it does not decide are kept).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pdef::detail {

//! Codes `cells` (`across` × `down`, cell (x, y) at y·across + x, 1 trimmed): the whole stream, empty when
//! no cell is trimmed. \throw std::invalid_argument for sizes that do not match
[[nodiscard]] std::string encode_trim(const std::vector<std::uint8_t>& cells, std::size_t across,
                                      std::size_t down);

//! What a prefix of a trim stream gave.
struct DecodedTrim {
  std::vector<std::uint8_t> cells; //!< 1 trimmed, 0 kept or not decided
  bool complete = false;           //!< every block decided
};

//! Decodes `stream` (the whole stream or any prefix of it). Never fails.
[[nodiscard]] DecodedTrim decode_trim(std::string_view stream, std::size_t across, std::size_t down);

} // namespace pdeface::pdef::detail
