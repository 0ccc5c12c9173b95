#pragma once
// Little-endian fields, LEB128 varints and zigzag integers: writing them (core's `ByteWriter`), and
// reading them with every read checked against the bytes that remain (the first failure is kept, with its
// byte offset; the bytes themselves are decoded by core's `load_le`).

#include "pdeface/core/bytes.hpp"
#include "pdeface/core/result.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

namespace pdeface::pdef::detail {

[[nodiscard]] constexpr std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
[[nodiscard]] constexpr std::int64_t unzigzag(std::uint64_t u) {
  return static_cast<std::int64_t>(u >> 1) ^ -static_cast<std::int64_t>(u & 1);
}

//! Core's little-endian writer, with zigzag varints for signed values.
class Writer : public ByteWriter {
public:
  void svarint(std::int64_t v) { varint(zigzag(v)); }
};

//! Reads fields from `bytes`, which start at `base` in the file (for offsets in errors). After the first
//! failure every read returns 0 and `error()` holds what went wrong first.
class Reader {
public:
  Reader(std::string_view bytes, std::size_t base, std::string_view source)
      : bytes_(bytes), base_(base), source_(source) {}

  [[nodiscard]] bool ok() const { return !error_; }
  [[nodiscard]] const Error& error() const { return *error_; }
  [[nodiscard]] std::size_t offset() const { return base_ + pos_; } //!< in the file
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }
  [[nodiscard]] bool at_end() const { return pos_ == bytes_.size(); }
  [[nodiscard]] std::string_view source() const { return source_; }

  //! Records a failure at `at` (a file offset) unless one is recorded already; returns false.
  bool fail(ErrorCode code, std::string message, std::size_t at) {
    if (!error_) error_ = make_error(code, std::move(message), std::string(source_), Location::at_byte(at));
    return false;
  }
  bool fail_here(ErrorCode code, std::string message) { return fail(code, std::move(message), offset()); }

  std::uint8_t u8(std::string_view what) {
    if (!need(1, what)) return 0;
    return static_cast<std::uint8_t>(bytes_[pos_++]);
  }
  std::uint32_t u32(std::string_view what) { return little_endian<std::uint32_t>(what); }
  std::uint64_t u64(std::string_view what) { return little_endian<std::uint64_t>(what); }
  float f32(std::string_view what) { return std::bit_cast<float>(u32(what)); }
  double f64(std::string_view what) { return std::bit_cast<double>(u64(what)); }

  //! An unsigned LEB128 varint of at most `max_bytes` bytes (5: 32 bits, 10: 64 bits) in its shortest form;
  //! longer or padded encodings are `Malformed`.
  std::uint64_t varint(std::string_view what, int max_bytes = 5) {
    const std::size_t start = offset();
    std::uint64_t v = 0;
    for (int i = 0; i < max_bytes; ++i) {
      if (!need(1, what)) return 0;
      const auto b = static_cast<std::uint8_t>(bytes_[pos_++]);
      if (i == max_bytes - 1 && max_bytes == 5 && b > 0x0f)
        return fail(ErrorCode::Malformed, std::string(what) + ": varint above 32 bits", start), 0;
      v |= std::uint64_t{b & 0x7fu} << (7 * i);
      if ((b & 0x80) == 0) {
        if (b == 0 && i > 0)
          return fail(ErrorCode::Malformed, std::string(what) + ": varint not in its shortest form", start),
                 0;
        return v;
      }
    }
    return fail(ErrorCode::Malformed,
                std::string(what) + ": varint longer than " + std::to_string(max_bytes) + " bytes", start),
           0;
  }
  std::int64_t svarint(std::string_view what, int max_bytes = 5) { return unzigzag(varint(what, max_bytes)); }

  //! The bytes not read yet (not consumed).
  [[nodiscard]] std::string_view rest() const { return error_ ? std::string_view{} : bytes_.substr(pos_); }

  std::string_view take(std::size_t n, std::string_view what) {
    if (!need(n, what)) return {};
    const std::string_view out = bytes_.substr(pos_, n);
    pos_ += n;
    return out;
  }

private:
  template <typename Unsigned> Unsigned little_endian(std::string_view what) {
    if (!need(sizeof(Unsigned), what)) return 0;
    const auto v = load_le<Unsigned>(bytes_, pos_);
    pos_ += sizeof(Unsigned);
    return v;
  }
  bool need(std::size_t n, std::string_view what) {
    if (error_) return false;
    if (n <= remaining()) return true;
    return fail(ErrorCode::Truncated,
                std::string(what) + ": the data ends " + std::to_string(n - remaining()) + " byte" +
                    (n - remaining() == 1 ? "" : "s") + " short",
                offset());
  }

  std::string_view bytes_;
  std::size_t base_ = 0;
  std::size_t pos_ = 0;
  std::string_view source_;
  std::optional<Error> error_;
};

} // namespace pdeface::pdef::detail
