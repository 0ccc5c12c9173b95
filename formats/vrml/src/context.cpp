#include "context.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace pdeface::vrml::detail {

void Context::add_note(std::string text) {
  const auto same =
      std::find_if(notes_.begin(), notes_.end(), [&](const auto& n) { return n.first == text; });
  if (same != notes_.end())
    ++same->second;
  else
    notes_.emplace_back(std::move(text), 1);
}

void Context::note(std::string_view text) { add_note(fmt::format(": {}", text)); }

void Context::note(const Position& at, std::string_view text) {
  add_note(fmt::format(":{}:{}: {}", at.line, at.column, text));
}

void Context::flush_notes(Notes* out) const {
  if (!out) return;
  const std::string_view source = source_.empty() ? std::string_view("<input>") : source_;
  for (const auto& [text, times] : notes_)
    out->push_back(times > 1 ? fmt::format("{}{} ({} times)", source, text, times)
                             : fmt::format("{}{}", source, text));
}

Position Context::locate(const IndexList& list, std::size_t k) const {
  Lexer lexer(bytes_, list.at);
  Token t = lexer.next();
  if (t.kind == TokenKind::OpenBracket) t = lexer.next();
  for (std::size_t i = 0; i < k; ++i)
    t = lexer.next();
  return t.at;
}

} // namespace pdeface::vrml::detail
