// The SDL functions that ask an object (POV-Ray 3.7 reference, "Functions"): trace(OBJECT, A, B
// [, NORMAL]), inside(OBJECT, P), min_extent(OBJECT), max_extent(OBJECT). Each reads its own
// arguments after its name; the geometry work is object_probe's.
#pragma once

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

Value trace_function(Parser& parser, const Tok& name);
Value inside_function(Parser& parser, const Tok& name);
Value extent_function(Parser& parser, const Tok& name);  // min_extent and max_extent

}  // namespace fb::pov::sdl
