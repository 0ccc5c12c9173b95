#pragma once
// The binary range coder of the residual layer's streams (docs/pdef-format.md, "The stream": LZMA's, 11-bit
// probabilities adapted by 1/32 of the error, a 32-bit range renormalised a byte at a time), for the trim
// stream (trim.cpp). The same arithmetic as bitplane.cpp's own copy, which its speed work keeps inline.

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pdeface::pdef::detail::range {

inline constexpr std::uint32_t kProbabilityBits = 11;
inline constexpr std::uint32_t kProbabilityOne = 1u << kProbabilityBits;
inline constexpr std::uint32_t kAdaptShift = 5;
inline constexpr std::uint32_t kTop = 1u << 24;

class RangeEncoder {
public:
  int bit(std::uint16_t& p, int b) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p;
    if (b == 0) {
      range_ = bound;
      p = static_cast<std::uint16_t>(p + ((kProbabilityOne - p) >> kAdaptShift));
    } else {
      low_ += bound;
      range_ -= bound;
      p = static_cast<std::uint16_t>(p - (p >> kAdaptShift));
    }
    while (range_ < kTop) {
      range_ <<= 8;
      shift_low();
    }
    return b;
  }
  int even(int b) {
    range_ >>= 1;
    if (b != 0) low_ += range_;
    while (range_ < kTop) {
      range_ <<= 8;
      shift_low();
    }
    return b;
  }
  [[nodiscard]] static bool exhausted() { return false; }
  std::string finish() {
    for (int i = 0; i < 5; ++i)
      shift_low();
    if (out_.empty() || out_[0] != 0) throw std::logic_error("pdef: range coder's first byte is not 0");
    return out_.substr(1); // always 0: not stored
  }

private:
  void shift_low() {
    if (static_cast<std::uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
      const auto carry = static_cast<std::uint8_t>(low_ >> 32);
      std::uint8_t temp = cache_;
      do {
        out_.push_back(static_cast<char>(static_cast<std::uint8_t>(temp + carry)));
        temp = 0xFF;
      } while (--cache_size_ != 0);
      cache_ = static_cast<std::uint8_t>(low_ >> 24);
    }
    ++cache_size_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }
  std::uint64_t low_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
  std::uint8_t cache_ = 0;
  std::uint64_t cache_size_ = 1;
  std::string out_;
};

// Decodes the decisions that the bytes it has determine: once a renormalisation needs a byte beyond them it
// is exhausted, and every decision before that is the encoder's. Branch-free but for the renormalisation.
class RangeDecoder {
public:
  explicit RangeDecoder(std::string_view in) : in_(in) {
    for (int i = 0; i < 4; ++i)
      code_ = (code_ << 8) | next();
  }
  int bit(std::uint16_t& p, int /*unused*/) {
    const std::uint32_t bound = (range_ >> kProbabilityBits) * p;
    const bool one = code_ >= bound;
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(one);
    code_ -= bound & mask;
    range_ = one ? range_ - bound : bound;
    const std::uint32_t down = p - (p >> kAdaptShift), up = p + ((kProbabilityOne - p) >> kAdaptShift);
    p = static_cast<std::uint16_t>(one ? down : up);
    while (range_ < kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
    return one ? 1 : 0;
  }
  int even(int /*unused*/) {
    range_ >>= 1;
    const bool one = code_ >= range_;
    code_ -= one ? range_ : 0;
    while (range_ < kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next();
    }
    return one ? 1 : 0;
  }
  [[nodiscard]] bool exhausted() const { return exhausted_; }
  [[nodiscard]] std::size_t used() const { return std::min(pos_, in_.size()); }

private:
  std::uint32_t next() {
    if (pos_ >= in_.size()) {
      exhausted_ = true;
      ++pos_;
      return 0;
    }
    return static_cast<std::uint8_t>(in_[pos_++]);
  }
  std::string_view in_;
  std::size_t pos_ = 0;
  std::uint32_t code_ = 0;
  std::uint32_t range_ = 0xFFFFFFFFu;
  bool exhausted_ = false;
};

} // namespace pdeface::pdef::detail::range
