#pragma once
// The VRML tokenizer: one pass over the bytes in memory, no allocation, tokens are views into the input.
//
// VRML 1.0 and 2.0 share the lexical rules this reader needs: whitespace is space, tab, CR, LF and the
// comma; `#` starts a comment that runs to the end of the line (except inside a string); strings are
// double-quoted with `\"` and `\\` escapes and may span lines; `{ } [ ]` are tokens of their own.
// Everything else is a "word": a run of characters up to the next delimiter. Numbers, names, `TRUE`,
// `ROUTE`'s `a.b` are all words; the parser decides what a word must be where it stands.

#include <fast_float/fast_float.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace pdeface::vrml::detail {

enum class TokenKind : std::uint8_t {
  End,          // no more input
  Word,         // a name, keyword or number
  String,       // "..." (text holds the characters between the quotes, escapes not resolved)
  OpenBrace,    // {
  CloseBrace,   // }
  OpenBracket,  // [
  CloseBracket, // ]
  BadString,    // a string the input ends inside of
};

//! Where a token starts. Lines and columns are 1-based; a column counts bytes from the line start.
struct Position {
  std::size_t offset = 0;
  std::size_t line = 1;
  std::size_t column = 1;
};

struct Token {
  TokenKind kind = TokenKind::End;
  std::string_view text;
  Position at;
};

inline constexpr std::uint8_t kSpace = 1;
inline constexpr std::uint8_t kDelimiter = 2;
inline constexpr std::array<std::uint8_t, 256> kCharClasses = [] {
  std::array<std::uint8_t, 256> c{};
  for (unsigned char s : {' ', '\t', '\r', '\n', ','})
    c[s] = kSpace | kDelimiter;
  for (unsigned char d : {'#', '"', '{', '}', '[', ']'})
    c[d] = kDelimiter;
  return c;
}();

class Lexer {
public:
  //! Lexes `bytes` from `start` (a position inside them, e.g. just after the header line).
  explicit Lexer(std::string_view bytes, Position start = {})
      : begin_(bytes.data()), p_(bytes.data() + start.offset), end_(bytes.data() + bytes.size()),
        line_(start.line), line_start_(p_ - (start.column - 1)) {}

  [[nodiscard]] Token next() {
    skip_space();
    Token t;
    t.at = position();
    if (p_ == end_) return t;
    const char* start = p_;
    switch (*p_) {
    case '{': t.kind = TokenKind::OpenBrace; break;
    case '}': t.kind = TokenKind::CloseBrace; break;
    case '[': t.kind = TokenKind::OpenBracket; break;
    case ']': t.kind = TokenKind::CloseBracket; break;
    case '"': return string(t);
    default: {
      const char* p = p_; // a local: through a member, every byte read could alias it and force a store
      while (p != end_ && !is(*p, kDelimiter))
        ++p;
      p_ = p;
      t.kind = TokenKind::Word;
      t.text = {start, static_cast<std::size_t>(p - start)};
      return t;
    }
    }
    ++p_;
    t.text = {start, 1};
    return t;
  }

  //! The fast path for long number lists: if the next token is a plain number of type T (a finite float,
  //! or a decimal integer in T's range) ending at a delimiter, consumes it and returns true. Otherwise it
  //! consumes nothing but space: the caller lexes the token with `next()` and reports what is wrong.
  template <class T> [[nodiscard]] bool number(T& value) {
    skip_space();
    const char* p = p_;
    if (p == end_) return false;
    const char* last = nullptr;
    if constexpr (std::is_floating_point_v<T>) {
      const fast_float::from_chars_result r = fast_float::from_chars(p, end_, value);
      if (r.ec != std::errc() || !std::isfinite(value)) return false;
      last = r.ptr;
    } else {
      const std::from_chars_result r = std::from_chars(p, end_, value);
      if (r.ec != std::errc()) return false;
      last = r.ptr;
    }
    if (last != end_ && !is(*last, kDelimiter)) return false;
    p_ = last;
    return true;
  }

  //! Where the next token (or the end of the input) is.
  [[nodiscard]] Position position() const {
    return {static_cast<std::size_t>(p_ - begin_), line_, static_cast<std::size_t>(p_ - line_start_) + 1};
  }

private:
  static bool is(char c, std::uint8_t cls) {
    return (kCharClasses[static_cast<unsigned char>(c)] & cls) != 0;
  }

  // Counts a line break at *p_ (LF, CR LF counted once at the LF, or a lone CR) and steps past it.
  void step_over_maybe_newline() {
    const char c = *p_++;
    if (c == '\n' || (c == '\r' && (p_ == end_ || *p_ != '\n'))) {
      ++line_;
      line_start_ = p_;
    }
  }

  void skip_space() {
    const char* p = p_;
    while (p != end_) {
      const char c = *p;
      if (is(c, kSpace)) {
        ++p;
        if (c == '\n' || (c == '\r' && (p == end_ || *p != '\n'))) { // CR LF counts once, at the LF
          ++line_;
          line_start_ = p;
        }
      } else if (c == '#') {
        while (p != end_ && *p != '\n' && *p != '\r')
          ++p;
      } else {
        break;
      }
    }
    p_ = p;
  }

  Token string(Token t) {
    const char* start = ++p_; // past the opening quote
    while (p_ != end_) {
      if (*p_ == '"') {
        t.kind = TokenKind::String;
        t.text = {start, static_cast<std::size_t>(p_ - start)};
        ++p_;
        return t;
      }
      if (*p_ == '\\' && p_ + 1 != end_) ++p_; // the escaped character cannot end the string
      step_over_maybe_newline();
    }
    t.kind = TokenKind::BadString;
    return t;
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  std::size_t line_;
  const char* line_start_;
};

} // namespace pdeface::vrml::detail
