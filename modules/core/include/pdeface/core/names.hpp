#pragma once
//! \file
//! The names of an enum's values, one table per enum: what is printed and what is parsed (a value may have
//! aliases; the first name of a value is its own).

#include "pdeface/core/result.hpp"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pdeface {

template <class E> struct NamedValue {
  std::string_view name;
  E value;
};

//! The value `name` names, if any.
template <class E>
[[nodiscard]] constexpr std::optional<E> value_named(std::span<const NamedValue<E>> table,
                                                     std::string_view name) noexcept {
  for (const NamedValue<E>& n : table)
    if (n.name == name) return n.value;
  return std::nullopt;
}

//! The first name of `value` (empty if the table lacks it).
template <class E>
[[nodiscard]] constexpr std::string_view name_of(std::span<const NamedValue<E>> table, E value) noexcept {
  for (const NamedValue<E>& n : table)
    if (n.value == value) return n.name;
  return {};
}

//! Every name, aliases too, in the table's order (for a command line's list of choices).
template <class E> [[nodiscard]] std::vector<std::string> all_names(std::span<const NamedValue<E>> table) {
  std::vector<std::string> out;
  for (const NamedValue<E>& n : table)
    out.emplace_back(n.name);
  return out;
}

} // namespace pdeface
