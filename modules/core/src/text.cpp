#include "pdeface/core/text.hpp"

#include <fmt/format.h>
#include <utf8.h>

#include <cstdint>
#include <iterator>

namespace pdeface {

std::string excerpt(std::string_view text, std::size_t max_bytes) {
  const std::string valid = valid_utf8(text.substr(0, max_bytes + 4)); // a character cut at the end too
  std::string out;
  bool cut = false;
  for (auto it = valid.begin(); it != valid.end();) {
    const auto start = it;
    const std::uint32_t c = utf8::next(it, valid.end());
    const std::string piece = c < 0x20 || c == 0x7f ? fmt::format("\\x{:02x}", c) : std::string(start, it);
    if (out.size() + piece.size() > max_bytes) {
      cut = true;
      break;
    }
    out += piece;
  }
  if (cut || text.size() > max_bytes + 4) out += "...";
  return out;
}

std::string excerpt_list(std::span<const std::string> items, std::size_t max_items) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < max_items; ++i)
    out += (i == 0 ? "" : ", ") + excerpt(items[i]);
  if (items.size() > max_items) out += fmt::format(" and {} more", items.size() - max_items);
  return out;
}

std::string valid_utf8(std::string_view text) {
  if (utf8::is_valid(text.begin(), text.end())) return std::string(text);
  std::string out;
  out.reserve(text.size());
  utf8::replace_invalid(text.begin(), text.end(), std::back_inserter(out));
  return out;
}

std::string clean_name(std::string_view name) {
  const std::string valid = valid_utf8(name.substr(0, kMaxNameBytes + 4));
  std::string out;
  for (auto it = valid.begin(); it != valid.end();) {
    const auto start = it;
    const std::uint32_t c = utf8::next(it, valid.end());
    if (out.size() + static_cast<std::size_t>(it - start) > kMaxNameBytes) break;
    if (c < 0x20 || c == 0x7f)
      out += ' ';
    else
      out.append(start, it);
  }
  const std::size_t first = out.find_first_not_of(' ');
  if (first == std::string::npos) return {};
  return out.substr(first, out.find_last_not_of(' ') - first + 1);
}

bool is_valid_utf8(std::string_view text) { return utf8::is_valid(text.begin(), text.end()); }

} // namespace pdeface
