// POV-Ray's built-in identifiers and functions in expressions (manual 3.3.1.x): constants such as
// pi and x, the render settings (clock, image_width ...), and the float, vector and string
// functions.
#pragma once

#include <optional>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

// The value of the built-in `keyword` (its arguments read from `parser`), or none if `keyword`
// is not a built-in.
std::optional<Value> builtin(Parser& parser, const Tok& keyword);

}  // namespace fb::pov::sdl
