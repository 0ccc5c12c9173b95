#pragma once
// What the parser and the mesh builder share: the input (for error locations), the notes, and the one
// way they stop on bad data.
//
// Errors are thrown as `Failure` inside the reader and caught at its boundary (`vrml::read`), which returns
// them as a `Result`. A recursive-descent parser that had to check a result after every token would be
// twice as long and slower on the happy path; nothing escapes the reader as an exception.

#include "lexer.hpp"
#include "scene.hpp"

#include "pdeface/core/result.hpp"

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pdeface::vrml::detail {

//! How deep `{`/`[` may nest, and how deep `USE` may chain groups, before the input is rejected: deep
//! enough for any real scene, shallow enough that hostile input cannot exhaust the stack.
inline constexpr std::size_t kMaxDepth = 1000;

struct Failure {
  Error error;
};

class Context {
public:
  Context(std::string_view bytes, std::string_view source) : bytes_(bytes), source_(source) {}

  [[nodiscard]] std::string_view bytes() const { return bytes_; }
  [[nodiscard]] std::string_view source() const { return source_; }

  [[noreturn]] void fail(ErrorCode code, const Position& at, std::string message) const {
    throw Failure{
        make_error(code, std::move(message), std::string(source_), Location::at_line(at.line, at.column))};
  }

  //! A note for the user, once per distinct text (repeats are counted, not listed).
  void note(std::string_view text);
  //! A note about the token at `at`. Past kMaxPositionedNotes of them, the rest are only counted: a
  //! file with a hundred thousand shapes should not give as many notes.
  void note(const Position& at, std::string_view text);
  //! Appends the notes, each prefixed with the source name, to `out`.
  void flush_notes(Notes* out) const;

  //! Where entry `k` of an index list is in the file (for an error naming that entry).
  [[nodiscard]] Position locate(const IndexList& list, std::size_t k) const;

private:
  void add_note(std::string text, bool positioned); // text starts with ": " or ":line:col: "

  std::string_view bytes_;
  std::string_view source_;
  static constexpr std::size_t kMaxPositionedNotes = 50;

  std::vector<std::pair<std::string, std::size_t>> notes_; // text, times noted
  std::unordered_map<std::string, std::size_t> index_;     // text -> position in notes_
  std::size_t positioned_ = 0;                             // positioned notes kept
  std::size_t more_ = 0;                                   // positioned notes past the limit
};

//! Quotes a token for a message: 'abc', or a readable name for the end of the input.
[[nodiscard]] std::string describe(const Token& token);

} // namespace pdeface::vrml::detail
