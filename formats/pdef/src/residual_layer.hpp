#pragma once
// Reading a version 3 file's residual layer (residual.cpp), for `decode` (pdef.cpp).

#include "pdeface/core/result.hpp"
#include "pdeface/pdef/residual.hpp"

#include <cstdint>
#include <string_view>

namespace pdeface::pdef::detail {

inline constexpr std::uint8_t kVersionResidual = 3;
//! The layer's first byte: its kind. 1: offsets (the CDF 9/7 wavelet and bit-planes); 2: offsets and a
//! trim.
inline constexpr std::uint8_t kLayerOffsets = 1;
inline constexpr std::uint8_t kLayerTrimmed = 2;

//! The layer that starts at `offset` of `bytes` (the file, or the prefix of it that a reader has).
//! Errors (with their byte offsets): `UnsupportedFormat` for an unknown kind, `Malformed` and
//! `CountTooLarge` for bad fields, `ChecksumMismatch` for a damaged header or a damaged whole stream.
[[nodiscard]] Result<Residual> read_residual(std::string_view bytes, std::size_t offset,
                                             std::string_view source);

} // namespace pdeface::pdef::detail
