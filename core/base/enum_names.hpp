#pragma once
// One name table per enumeration, feeding the JSON parsers, the schema's choices and the reports: an enum E is
// named by specializing `EnumNames<E>` with a `static constexpr std::array<std::pair<E, std::string_view>, N>
// table`. Names are snake_case, as the JSON spells them.
#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/errors.hpp"

namespace closurelab {

template <class E>
struct EnumNames;  // specialize: static constexpr std::array<std::pair<E, std::string_view>, N> table{...};

template <class E>
std::string name_of(E value) {
  for (const auto& [e, name] : EnumNames<E>::table)
    if (e == value) return std::string(name);
  return "?";
}

// The names, in table order (a schema's `choices`).
template <class E>
std::vector<std::string> names_of() {
  std::vector<std::string> names;
  for (const auto& entry : EnumNames<E>::table) names.emplace_back(entry.second);
  return names;
}

// The value named `name`; a ConfigError at `path` listing the choices otherwise.
template <class E>
E parse_name(std::string_view name, const std::string& path) {
  for (const auto& [e, n] : EnumNames<E>::table)
    if (n == name) return e;
  std::string choices;
  for (const auto& entry : EnumNames<E>::table) choices += (choices.empty() ? "" : ", ") + std::string(entry.second);
  throw ConfigError(path, "unknown value \"" + std::string(name) + "\" (choices: " + choices + ")");
}

}  // namespace closurelab
