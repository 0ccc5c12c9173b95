#include "pdeface/core/result.hpp"

#include <fmt/format.h>

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
  }
  return "error";
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
