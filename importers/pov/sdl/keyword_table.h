// The SDL reader's keyword tables: constexpr arrays of entries, each with a `name`, one line per
// keyword, where a long if-chain would hide which keywords a statement takes.
#pragma once

#include <cstddef>
#include <string_view>

namespace fb::pov::sdl {

// The entry of `table` named `keyword`, or null. A linear search: the tables are a few dozen
// short names.
template <typename Entry, std::size_t N>
constexpr const Entry* find_keyword(const Entry (&table)[N], std::string_view keyword) {
  for (const Entry& entry : table) {
    if (entry.name == keyword) return &entry;
  }
  return nullptr;
}

}  // namespace fb::pov::sdl
