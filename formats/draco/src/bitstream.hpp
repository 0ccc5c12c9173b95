#pragma once
// The part of a Draco bitstream libdraco trusts blindly, checked before libdraco sees it: the 11-byte
// header, the metadata block and the element counts that open the geometry data. libdraco 1.5.5 sizes
// its tables from those counts before reading any element (~25 bytes per claimed face or point: 2.3 GB
// for a 130-byte file claiming 10^8 faces), and its metadata decoder allocates an entry's claimed size
// before reading it, loops over claimed counts even after the data has ended, and recurses without limit.

#include "pdeface/core/result.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace pdeface::drc::bitstream {

inline constexpr std::size_t kHeaderSize = 11;

//! Where the checked bytes are: their source name and their offset in that source (nullopt when they
//! are not a slice of it).
struct Origin {
  std::string_view source;
  std::optional<std::uint64_t> base;

  [[nodiscard]] Location at(std::uint64_t offset) const {
    return base ? Location::at_byte(*base + offset) : Location{};
  }
  [[nodiscard]] Error error(ErrorCode code, std::string message, std::uint64_t offset) const {
    return make_error(code, std::move(message), std::string(source), at(offset));
  }
};

struct Header {
  bool mesh = false; //!< triangular mesh, else point cloud
  int method = 0;    //!< mesh: 0 sequential, 1 edgebreaker; point cloud: 0 sequential, 1 k-d tree
};

//! Checks the header, metadata and counts of `bytes`. Errors: `Empty`, `BadMagic`, `UnsupportedVersion`,
//! `Truncated`, `Malformed`, `CountTooLarge`, each at the byte where the problem starts.
[[nodiscard]] Result<Header> check(std::string_view bytes, const Origin& origin);

} // namespace pdeface::drc::bitstream
