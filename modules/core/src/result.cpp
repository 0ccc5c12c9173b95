#include "pdeface/core/result.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pdeface {

std::string_view to_string(ErrorCode code) noexcept {
  switch (code) {
  case ErrorCode::Io: return "i/o error";
  case ErrorCode::Empty: return "empty";
  case ErrorCode::Truncated: return "truncated";
  case ErrorCode::Malformed: return "malformed";
  case ErrorCode::BadMagic: return "bad magic";
  case ErrorCode::UnsupportedVersion: return "unsupported version";
  case ErrorCode::UnsupportedFormat: return "unsupported format";
  case ErrorCode::IndexOutOfRange: return "index out of range";
  case ErrorCode::NonFinite: return "non-finite value";
  case ErrorCode::CountTooLarge: return "count too large";
  case ErrorCode::UndefinedName: return "undefined name";
  case ErrorCode::InvalidArgument: return "invalid argument";
  case ErrorCode::NoFace: return "no face";
  case ErrorCode::ChecksumMismatch: return "checksum mismatch";
  case ErrorCode::SelfCheck: return "self-check failed";
  }
  return "error";
}

Location Location::in_text(std::string_view text, std::uint64_t offset) {
  const std::string_view before = text.substr(0, std::min<std::uint64_t>(offset, text.size()));
  const std::size_t last_newline = before.rfind('\n');
  const auto line = static_cast<std::uint64_t>(std::ranges::count(before, '\n')) + 1;
  const std::uint64_t column =
      before.size() - (last_newline == std::string_view::npos ? 0 : last_newline + 1) + 1;
  return at_line(line, column);
}

std::string Error::to_string() const {
  std::string out = source.empty() ? std::string("<input>") : source;
  if (where.line != 0) {
    out += fmt::format(":{}", where.line);
    if (where.column != 0) out += fmt::format(":{}", where.column);
  } else if (where.byte) {
    out += fmt::format(": byte {}", *where.byte);
  }
  out += fmt::format(": {}: {}", pdeface::to_string(code), message);
  return out;
}

} // namespace pdeface
