#pragma once
// The coders `.pdef` uses, behind plain types (third-party types stay in entropy.cpp): Draco's rANS coder,
// zstd, and zlib's CRC-32.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface::pdef::detail {

//! Symbols coded by magnitude class (docs/pdef-format.md, "Coded integers"): values 0-3 are classes 0-3;
//! from 4 up, two classes per power of two, each followed by its value's lower bits. The classes are
//! coded by rANS (Draco's `RAnsEncoder`, 12-bit precision) with a table of their frequencies in half
//! octaves stored in front; the lower bits follow, packed.
[[nodiscard]] std::string encode_classes(std::span<const std::uint32_t> symbols);
//! Decodes exactly `out.size()` symbols from the start of `bytes`; the bytes used, or nullopt when the data
//! is not a valid stream of that many symbols.
[[nodiscard]] std::optional<std::size_t> decode_classes(std::string_view bytes, std::span<std::uint32_t> out);

//! A zstd frame of `bytes` at `level` (with the content size in its header).
[[nodiscard]] std::string zstd_compress(std::string_view bytes, int level);

//! The content of the zstd frame `frame`, which must be exactly `expected` bytes (checked in the frame's
//! header before anything is allocated) and must fill `frame` whole. Nullopt otherwise.
[[nodiscard]] std::optional<std::string> zstd_decompress(std::string_view frame, std::size_t expected);

//! The bytes of `values` (each `width` bytes long) regrouped by byte position: all first bytes, then all
//! second bytes, ... (float64 values of nearby numbers share their high bytes, which zstd then finds).
[[nodiscard]] std::string shuffle(std::string_view values, std::size_t width);
//! The inverse of `shuffle`.
[[nodiscard]] std::string unshuffle(std::string_view planes, std::size_t width);

//! CRC-32 (ISO-HDLC: zlib's `crc32`).
[[nodiscard]] std::uint32_t crc32(std::string_view bytes);

} // namespace pdeface::pdef::detail
