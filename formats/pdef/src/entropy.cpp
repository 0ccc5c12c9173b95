#include "entropy.hpp"

#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/compression/entropy/symbol_encoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <draco/core/macros.h>
#include <zlib.h>
#include <zstd.h>

#include <climits>
#include <limits>
#include <stdexcept>

namespace pdeface::pdef::detail {

std::string encode_symbols(std::span<const std::uint32_t> symbols) {
  if (symbols.empty()) return {};
  if (symbols.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("pdef: too many symbols for Draco's coder");
  draco::EncoderBuffer buffer;
  if (!draco::EncodeSymbols(symbols.data(), static_cast<int>(symbols.size()), 1, nullptr, &buffer))
    throw std::invalid_argument("pdef: Draco's symbol encoder failed");
  return {buffer.data(), buffer.size()};
}

bool decode_symbols(std::string_view bytes, std::span<std::uint32_t> out) {
  if (out.empty()) return bytes.empty();
  if (out.size() > std::numeric_limits<std::uint32_t>::max()) return false;
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size(), DRACO_BITSTREAM_VERSION(2, 2));
  if (!draco::DecodeSymbols(static_cast<std::uint32_t>(out.size()), 1, &buffer, out.data())) return false;
  return buffer.remaining_size() == 0;
}

std::string zstd_compress(std::string_view bytes, int level) {
  std::string out(ZSTD_compressBound(bytes.size()), '\0');
  const std::size_t n = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), level);
  if (ZSTD_isError(n) != 0U) throw std::invalid_argument(std::string("pdef: zstd: ") + ZSTD_getErrorName(n));
  out.resize(n);
  return out;
}

std::optional<std::string> zstd_decompress(std::string_view frame, std::size_t expected) {
  if (ZSTD_findFrameCompressedSize(frame.data(), frame.size()) != frame.size()) return std::nullopt;
  if (ZSTD_getFrameContentSize(frame.data(), frame.size()) != expected) return std::nullopt;
  std::string out(expected, '\0');
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), frame.data(), frame.size());
  if (ZSTD_isError(n) != 0U || n != expected) return std::nullopt;
  return out;
}

std::string shuffle(std::string_view values, std::size_t width) {
  const std::size_t n = values.size() / width;
  std::string out(values.size(), '\0');
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < width; ++b)
      out[b * n + i] = values[i * width + b];
  return out;
}

std::string unshuffle(std::string_view planes, std::size_t width) {
  const std::size_t n = planes.size() / width;
  std::string out(planes.size(), '\0');
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < width; ++b)
      out[i * width + b] = planes[b * n + i];
  return out;
}

std::uint32_t crc32(std::string_view bytes) {
  uLong crc = ::crc32(0L, Z_NULL, 0);
  while (!bytes.empty()) {
    const auto n = static_cast<uInt>(std::min<std::size_t>(bytes.size(), UINT_MAX));
    crc = ::crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), n);
    bytes.remove_prefix(n);
  }
  return static_cast<std::uint32_t>(crc);
}

} // namespace pdeface::pdef::detail
