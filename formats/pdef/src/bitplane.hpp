#pragma once
// The residual layer's embedded coder (docs/pdef-format.md, "The residual layer"): wavelet coefficients as
// integers, coded bit-plane by bit-plane, most significant first, by an adaptive binary range coder, so that
// every prefix of the stream decodes to coarser coefficients.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pdef::detail {

//! The coefficients of a width × height image after `levels` wavelet levels, as integers (sign and
//! magnitude), coded from bit-plane `planes − 1` down to 0. Returns the whole stream.
[[nodiscard]] std::string encode_planes(const std::vector<std::int64_t>& coefficients, std::size_t width,
                                        std::size_t height, std::size_t levels, std::size_t planes);

//! What a prefix of a stream gave.
struct DecodedPlanes {
  std::vector<double> coefficients; //!< reconstructed, in units of the step
  std::size_t bytes_used = 0;       //!< of the stream (at most its size)
  bool complete = false;            //!< every plane decoded
  std::size_t lowest_plane = 0;     //!< the last plane reached (partly, unless complete)
};

//! Decodes `stream` (the whole stream or any prefix of it). Never fails: a prefix decodes to the
//! coefficients known from the decisions its bytes determine.
[[nodiscard]] DecodedPlanes decode_planes(std::string_view stream, std::size_t width, std::size_t height,
                                          std::size_t levels, std::size_t planes);

} // namespace pdeface::pdef::detail
