#pragma once
//! \file
//! Little-endian fields, the one reader and writer every binary format uses (`.pdef`, the Draco bitstream
//! check, GLB containers, binary STL and PLY): values loaded from and stored into bytes whatever the
//! machine's byte order, and a writer that appends them (with LEB128 varints) to a byte string.
//!
//! Loading does not check bounds (\pre: the bytes are there); each format's reader checks what remains
//! first and reports a shortfall its own way (with its offsets and words).

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace pdeface {

//! The unsigned integer of `sizeof(T)` bytes at `p`, least significant first. \pre p has that many bytes
template <std::unsigned_integral T> [[nodiscard]] constexpr T load_le(const char* p) noexcept {
  if (!std::is_constant_evaluated() && std::endian::native == std::endian::little) {
    T v; // one load on the machines we build for
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    v |= static_cast<T>(T{static_cast<std::uint8_t>(p[i])} << (8 * i));
  return v;
}
//! The same at `offset` in `bytes`. \pre offset + sizeof(T) <= bytes.size()
template <std::unsigned_integral T>
[[nodiscard]] constexpr T load_le(std::string_view bytes, std::size_t offset) noexcept {
  return load_le<T>(bytes.data() + offset);
}
//! An IEEE-754 binary32 / binary64 value stored little-endian.
[[nodiscard]] inline float load_le_f32(const char* p) noexcept {
  return std::bit_cast<float>(load_le<std::uint32_t>(p));
}
[[nodiscard]] inline double load_le_f64(const char* p) noexcept {
  return std::bit_cast<double>(load_le<std::uint64_t>(p));
}

//! Stores `v` at `out` least significant byte first. \pre out has sizeof(T) bytes
template <std::unsigned_integral T> constexpr void store_le(char* out, T v) noexcept {
  if (!std::is_constant_evaluated() && std::endian::native == std::endian::little) {
    std::memcpy(out, &v, sizeof v); // one store on the machines we build for
    return;
  }
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out[i] = static_cast<char>(static_cast<std::uint8_t>(v >> (8 * i)));
}
inline void store_le_f32(char* out, float v) noexcept { store_le(out, std::bit_cast<std::uint32_t>(v)); }

//! Appends little-endian fields to a byte string.
class ByteWriter {
public:
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) { put(v); }
  void u32(std::uint32_t v) { put(v); }
  void u64(std::uint64_t v) { put(v); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  //! An unsigned LEB128 varint: 7 bits a byte, least significant first, in its shortest form.
  void varint(std::uint64_t v) {
    while (v >= 0x80) {
      u8(static_cast<std::uint8_t>(v | 0x80));
      v >>= 7;
    }
    u8(static_cast<std::uint8_t>(v));
  }
  void bytes(std::string_view b) { out_.append(b); }

  [[nodiscard]] std::size_t size() const { return out_.size(); }
  [[nodiscard]] std::string& str() { return out_; }

private:
  template <std::unsigned_integral T> void put(T v) {
    char b[sizeof(T)];
    store_le(b, v);
    out_.append(b, sizeof(T));
  }
  std::string out_;
};

} // namespace pdeface
