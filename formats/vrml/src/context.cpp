#include "context.hpp"

#include <fmt/format.h>

namespace pdeface::vrml::detail {

void Context::add_note(std::string text, bool positioned) {
  if (const auto found = index_.find(text); found != index_.end()) {
    ++notes_[found->second].second;
  } else if (positioned && positioned_ == kMaxPositionedNotes) {
    ++more_;
  } else {
    positioned_ += positioned ? 1 : 0;
    index_.emplace(text, notes_.size());
    notes_.emplace_back(std::move(text), 1);
  }
}

void Context::note(std::string_view text) { add_note(fmt::format(": {}", text), false); }

void Context::note(const Position& at, std::string_view text) {
  add_note(fmt::format(":{}:{}: {}", at.line, at.column, text), true);
}

void Context::flush_notes(Notes* out) const {
  if (!out) return;
  const std::string_view source = source_.empty() ? std::string_view("<input>") : source_;
  for (const auto& [text, times] : notes_)
    out->push_back(times > 1 ? fmt::format("{}{} ({} times)", source, text, times)
                             : fmt::format("{}{}", source, text));
  if (more_ > 0) out->push_back(fmt::format("{}: {} more notes like those above not shown", source, more_));
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
