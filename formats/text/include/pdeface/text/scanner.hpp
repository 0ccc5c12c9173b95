#pragma once
//! \file
//! Tokens with their line and column, and strict number parsing, for the validators of text formats.
//! Internal to the format libraries (not installed).

#include "pdeface/core/mesh.hpp"
#include "pdeface/core/result.hpp"

#include <fast_float/fast_float.h>

#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>

namespace pdeface::text {

//! A run of non-blank characters and where it starts. `text` is empty at the end of a line or input.
struct Token {
  std::string_view text;
  std::uint64_t line = 0;   //!< 1-based
  std::uint64_t column = 0; //!< 1-based, in bytes
  std::size_t offset = 0;   //!< byte offset in the scanned text

  [[nodiscard]] bool empty() const noexcept { return text.empty(); }
  [[nodiscard]] Location location() const noexcept { return Location::at_line(line, column); }
};

//! Splits text into blank-separated tokens, counting lines. Blanks are space, tab, CR, VT, FF and LF.
class Scanner {
public:
  //! Scans `text` from `offset`, which is on line `line`.
  explicit Scanner(std::string_view text, std::size_t offset = 0, std::uint64_t line = 1)
      : text_(text), pos_(offset), line_(line), line_start_(offset) {}

  //! The next token, on this line or a later one; empty at the end of the input.
  Token next() {
    skip_blanks(true);
    return take();
  }
  //! The next token before the end of the current line; empty (and the line not left) if there is none.
  Token next_on_line() {
    skip_blanks(false);
    return take();
  }
  //! Moves to the start of the next line.
  void skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n')
      ++pos_;
    skip_newline();
  }
  //! Whether only blanks remain.
  [[nodiscard]] bool at_end() {
    skip_blanks(true);
    return pos_ >= text_.size();
  }
  [[nodiscard]] std::size_t offset() const noexcept { return pos_; }
  //! Where the scanner stands (after the last token taken).
  [[nodiscard]] Location here() const noexcept { return Location::at_line(line_, pos_ - line_start_ + 1); }

private:
  static bool is_blank(char c) noexcept {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  }

  void skip_newline() {
    if (pos_ < text_.size()) {
      ++pos_;
      ++line_;
      line_start_ = pos_;
    }
  }
  void skip_blanks(bool newlines) {
    while (pos_ < text_.size()) {
      if (is_blank(text_[pos_]))
        ++pos_;
      else if (newlines && text_[pos_] == '\n')
        skip_newline();
      else
        break;
    }
  }
  Token take() {
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n' && !is_blank(text_[pos_]))
      ++pos_;
    return {text_.substr(begin, pos_ - begin), line_, begin - line_start_ + 1, begin};
  }

  std::string_view text_;
  std::size_t pos_;
  std::uint64_t line_;
  std::size_t line_start_;
};

//! The whole token as a number ("1", "-2.5e3", "+0.5", "nan", "inf"), or nullopt if any of it is not.
//! Correctly rounded (fast_float) to `T` (float or double). Values beyond its range come back as
//! infinities: callers reject non-finite values.
template <class T = double> [[nodiscard]] inline std::optional<T> parse_real(std::string_view token) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  T value = 0;
  const auto [end, ec] = fast_float::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
  return value;
}

[[nodiscard]] inline std::optional<double> parse_double(std::string_view token) {
  return parse_real<double>(token);
}

//! The whole token as a decimal integer (optionally signed), or nullopt.
[[nodiscard]] inline std::optional<std::int64_t> parse_integer(std::string_view token) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
  return value;
}

//! The units stated by a comment's text "units mm" (after the comment marker), or nullopt.
[[nodiscard]] inline std::optional<Units> units_from_comment(std::string_view comment) {
  Scanner scan(comment);
  if (scan.next_on_line().text != "units") return std::nullopt;
  const std::optional<Units> units = units_from_string(scan.next_on_line().text);
  if (!units || !scan.next_on_line().empty()) return std::nullopt;
  return units;
}

} // namespace pdeface::text
