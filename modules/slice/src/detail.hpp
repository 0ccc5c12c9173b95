#pragma once
// What the slicing stage's files share: naming a plane in messages, prefixing an error with where it
// happened, and the landmarks a step needs (missing ones are bad data, a landmark file without them or a
// detection that found none, so the answer is a `NoFace` error naming them, never an exception).

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/result.hpp"

#include <fmt/format.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace pdeface::slice::detail {

//! "plane 7 (x = -26.5 mm, patch 3, 1/3)".
inline std::string describe_plane(std::size_t index, double x, std::string_view feature) {
  return fmt::format("plane {} (x = {:.1f} mm, {})", index, x, feature);
}

//! `error` with `what` before its message.
inline Error about(std::string_view what, Error error) {
  error.message = fmt::format("{}: {}", what, error.message);
  return error;
}

inline Result<void> require_landmarks(const align::Landmarks& landmarks,
                                      std::initializer_list<align::Landmark> needed, std::string_view what) {
  std::string missing;
  for (align::Landmark l : needed)
    if (!landmarks.has(l)) missing += fmt::format("{}{}", missing.empty() ? "" : ", ", align::name(l));
  if (missing.empty()) return {};
  return make_error(ErrorCode::NoFace,
                    fmt::format("{} needs the landmarks {}, which the face's landmarks lack", what, missing));
}

} // namespace pdeface::slice::detail
