#include "importers/pov/sdl/evaluate.h"

#include "importers/pov/sdl/parser.h"

namespace fb::pov {

Scene evaluate_pov(const EvaluateOptions& options) {
  sdl::Parser parser(options);
  return parser.run();
}

}  // namespace fb::pov
