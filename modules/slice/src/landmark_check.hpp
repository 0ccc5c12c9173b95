#pragma once
// Landmarks a stage needs: missing ones are bad data (a landmark file without them, a detection that
// found none), so the answer is a `NoFace` error naming them, never an exception.

#include "pdeface/align/landmarks.hpp"
#include "pdeface/core/result.hpp"

#include <fmt/format.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace pdeface::slice::detail {

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
