// Command-line flags of the benchmarks: `--name=N` for a positive integer N.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/util/error.h"

namespace fb::bench {

// Whether `arg` is the flag `name` (e.g. "--res="); if so, its value into `value`. A value that
// is not a positive integer is a UsageError.
inline bool parse_flag(std::string_view arg, std::string_view name, uint32_t& value) {
  if (!arg.starts_with(name)) return false;
  arg.remove_prefix(name.size());
  const auto [end, error] = std::from_chars(arg.data(), arg.data() + arg.size(), value);
  if (error != std::errc() || end != arg.data() + arg.size() || value == 0)
    throw UsageError("bad value in '" + std::string(name) + std::string(arg) + "'");
  return true;
}

}  // namespace fb::bench
