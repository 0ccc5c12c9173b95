#pragma once
// Number words to values: exact (fast_float is correctly rounded) and strict (the whole word must be the
// number, so "1.2.3" or "4x" is an error, never a silently shortened value).

#include "pdeface/text/scanner.hpp"

#include <charconv>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>

namespace pdeface::vrml::detail {

//! Parses a VRML float (`[+-]digits[.digits][e[+-]digits]`, also `inf`/`nan`, which callers reject as
//! non-finite). False if the word is not entirely a number.
template <class T> [[nodiscard]] inline bool parse_float(std::string_view word, T& value) {
  const std::optional<T> parsed = text::parse_real<T>(word);
  if (parsed) value = *parsed;
  return parsed.has_value();
}

//! Parses a VRML SFInt32: decimal or `0x` hexadecimal, optionally signed, within 32 bits.
[[nodiscard]] inline bool parse_int32(std::string_view word, std::int32_t& value) {
  const char* first = word.data();
  const char* last = first + word.size();
  bool negative = false;
  if (first != last && (*first == '+' || *first == '-')) negative = *first++ == '-';
  int base = 10;
  if (last - first > 2 && first[0] == '0' && (first[1] == 'x' || first[1] == 'X')) {
    first += 2;
    base = 16;
  }
  if (first == last || *first == '+' || *first == '-') return false;
  std::int64_t magnitude = 0;
  const std::from_chars_result r = std::from_chars(first, last, magnitude, base);
  if (r.ec != std::errc() || r.ptr != last) return false;
  const std::int64_t v = negative ? -magnitude : magnitude;
  // Hexadecimal values up to 0xFFFFFFFF are bit patterns (SFImage pixels, colours): keep their bits.
  if (base == 16 && !negative && v <= std::numeric_limits<std::uint32_t>::max()) {
    value = static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
    return true;
  }
  if (v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
    return false;
  value = static_cast<std::int32_t>(v);
  return true;
}

} // namespace pdeface::vrml::detail
