#pragma once
//! \file
//! Text that came from a file, made safe to show: in an error message (a short excerpt), or in a name
//! written to a file that must be valid UTF-8 (glTF's JSON, a `.pdef` name, a JSON report).

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace pdeface {

//! The most bytes of input an error message or a note quotes (`excerpt`): a 200 MB token must not become a
//! 200 MB message.
inline constexpr std::size_t kMaxExcerpt = 60;

//! At most `max_bytes` of `text` (cut at a character boundary, "..." after a cut), valid UTF-8, control
//! characters written as `\xNN`: what a message may quote of a file's contents.
[[nodiscard]] std::string excerpt(std::string_view text, std::size_t max_bytes = kMaxExcerpt);

//! The most items a list in a message or a note names (`excerpt_list`).
inline constexpr std::size_t kMaxListed = 8;

//! "a, b, c": the first `max_items` of `items`, each an `excerpt`, then " and N more" when there are more.
[[nodiscard]] std::string excerpt_list(std::span<const std::string> items,
                                       std::size_t max_items = kMaxListed);

//! `text` as valid UTF-8: each invalid byte sequence replaced by U+FFFD (utfcpp's `replace_invalid`).
[[nodiscard]] std::string valid_utf8(std::string_view text);

//! The most bytes of a name `clean_name` keeps (a `.pdef` holds up to 1024).
inline constexpr std::size_t kMaxNameBytes = 1024;

//! A name that came from a file or a command line, as writers store it: valid UTF-8 (`valid_utf8`),
//! control characters (a newline would end an OBJ `o` line) as spaces, blanks at both ends trimmed, at most
//! `kMaxNameBytes` (cut at a character boundary).
[[nodiscard]] std::string clean_name(std::string_view name);

//! Whether `text` is valid UTF-8.
[[nodiscard]] bool is_valid_utf8(std::string_view text);

} // namespace pdeface
