// The names users write for the enumerators of a choice (a model, a route, a
// quadrature rule, a reading): one table per enumeration, next to it, from
// which its parse and print functions and the case schema's rows are made,
// so that each name is spelled once.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

#include "gearimpact/error.hpp"

namespace gearimpact {

template <typename E>
struct NamedValue {
  E value;
  std::string_view name;     // as case files, flags and outputs write it
  std::string_view meaning;  // for the docs and for messages
};

// "a, b, c": every name of the table, in its order.
template <typename E, std::size_t N>
std::string names_text(const std::array<NamedValue<E>, N>& table) {
  std::string text;
  for (const NamedValue<E>& entry : table) {
    if (!text.empty()) text += ", ";
    text += std::string(entry.name);
  }
  return text;
}

// The name of `value`; a value the table lacks is a programming error.
template <typename E, std::size_t N>
std::string name_of(const std::array<NamedValue<E>, N>& table, E value) {
  for (const NamedValue<E>& entry : table) {
    if (entry.value == value) return std::string(entry.name);
  }
  throw std::logic_error("a value without a name in its table");
}

// The value named `name`; otherwise InputError naming `field` with the names.
template <typename E, std::size_t N>
E value_named(const std::array<NamedValue<E>, N>& table, std::string_view name,
              std::string_view field) {
  for (const NamedValue<E>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  throw InputError(std::string(field), std::string(name), "one of " + names_text(table));
}

}  // namespace gearimpact
