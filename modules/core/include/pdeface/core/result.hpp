#pragma once
//! \file
//! Errors for bad *data* and the `Result<T>` that carries them.
//!
//! Library code never prints or exits: a reader that meets a malformed file returns an `Error` naming the
//! source and the line or byte offset. Bad *calls* (broken preconditions) throw `std::invalid_argument`.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace pdeface {

//! What kind of problem the data has; stable, so callers and tests can branch on it.
enum class ErrorCode {
  Io,                 //!< the file cannot be opened, read or written
  Empty,              //!< no bytes, or no geometry where geometry is required
  Truncated,          //!< the data ends before its own header says it should
  Malformed,          //!< a syntax or structure error
  BadMagic,           //!< the file does not start like the format it claims to be
  UnsupportedVersion, //!< a version of the format we do not read
  UnsupportedFormat,  //!< an extension or content we have no reader/writer for
  IndexOutOfRange,    //!< a face refers to a vertex that does not exist
  NonFinite,          //!< NaN or infinity where a coordinate is expected
  CountTooLarge,      //!< a declared count the data cannot possibly hold
  UndefinedName,      //!< a reference (e.g. VRML `USE`) to a name never defined
  InvalidArgument,    //!< an option value outside its range
  NoFace,             //!< a scan in which no face can be found
  ChecksumMismatch,   //!< the data's checksum does not match: it was damaged after it was written
  SelfCheck,          //!< a result measured against its input is off: refused rather than written
};

//! A short lowercase name for the code ("truncated", "bad magic", ...).
[[nodiscard]] std::string_view to_string(ErrorCode code) noexcept;

//! Where in the source an error was found. Text formats give a line (and column), binary formats a byte
//! offset; either may be absent when the library we read through cannot tell.
struct Location {
  std::uint64_t line = 0;   //!< 1-based; 0 = unknown
  std::uint64_t column = 0; //!< 1-based; 0 = unknown
  std::optional<std::uint64_t> byte;

  [[nodiscard]] static Location at_line(std::uint64_t line, std::uint64_t column = 0) {
    return {line, column, std::nullopt};
  }
  [[nodiscard]] static Location at_byte(std::uint64_t offset) { return {0, 0, offset}; }
  //! The line and column of byte `offset` of a text (for parsers that only know offsets).
  [[nodiscard]] static Location in_text(std::string_view text, std::uint64_t offset);
  [[nodiscard]] bool known() const noexcept { return line != 0 || byte.has_value(); }
};

//! One error: what, where and in which source.
struct Error {
  ErrorCode code = ErrorCode::Malformed;
  std::string message; //!< lowercase, no trailing period, no source name
  std::string source;  //!< file name (or another name for in-memory data)
  Location where;

  //! "face.wrl:12:5: malformed: expected '}'" or "scan.ply: byte 1234: truncated: ...".
  [[nodiscard]] std::string to_string() const;
};

[[nodiscard]] inline Error make_error(ErrorCode code, std::string message, std::string source = {},
                                      Location where = {}) {
  return Error{code, std::move(message), std::move(source), where};
}

//! `error` naming `source`, unless it names a source already: what a stage returns when it passes on the
//! error of a step that did not know the input's name.
[[nodiscard]] inline Error with_source(Error error, std::string_view source) {
  if (error.source.empty()) error.source = source;
  return error;
}

//! Non-fatal notes a reader or writer collects for the user ("colours dropped: STL cannot store them").
using Notes = std::vector<std::string>;

//! A value or an `Error`.
template <class T> class [[nodiscard]] Result {
public:
  Result(T value) : v_(std::move(value)) {}     // NOLINT(google-explicit-constructor): implicit by design
  Result(Error error) : v_(std::move(error)) {} // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool ok() const noexcept { return v_.index() == 0; }
  explicit operator bool() const noexcept { return ok(); }

  //! \pre ok()
  [[nodiscard]] T& value() & { return std::get<0>(v_); }
  [[nodiscard]] const T& value() const& { return std::get<0>(v_); }
  [[nodiscard]] T&& value() && { return std::get<0>(std::move(v_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  //! `*std::move(result)` moves the value out (as `std::optional` does); without this overload it bound
  //! to the `const&` one and copied.
  T&& operator*() && { return std::move(*this).value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  //! \pre !ok()
  [[nodiscard]] const Error& error() const& { return std::get<1>(v_); }
  [[nodiscard]] Error&& error() && { return std::get<1>(std::move(v_)); }

private:
  std::variant<T, Error> v_;
};

//! Success without a value, or an `Error`.
template <> class [[nodiscard]] Result<void> {
public:
  Result() = default;
  Result(Error error) : error_(std::move(error)) {} // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool ok() const noexcept { return !error_.has_value(); }
  explicit operator bool() const noexcept { return ok(); }
  //! \pre !ok()
  [[nodiscard]] const Error& error() const& { return *error_; }
  [[nodiscard]] Error&& error() && { return std::move(*error_); }

private:
  std::optional<Error> error_;
};

} // namespace pdeface
