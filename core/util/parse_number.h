// The one reader of a number typed as text: plugin parameters and their defaults
// (core/plugin/params.cpp) and the command line's numeric options (core/cmd/render_command.cpp).
#pragma once

#include <optional>
#include <string_view>

namespace fb {

// The whole of `text` as one finite number in std::from_chars' general format ("1.5", "-2e-3";
// no leading '+' or white space, no "inf" or "nan"); nullopt otherwise.
std::optional<double> parse_number(std::string_view text);

}  // namespace fb
