// POV-Ray 3.7 scenes (.pov): the SDL evaluator (importers/pov/sdl) runs the scene's program, then
// the converters turn what it built into an fb::Scene (docs/pov.md).
#pragma once

#include <filesystem>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/import_scene.h"

namespace fb {

// Throws InputError "file:line:column: what" (with the include chain) for a scene POV-Ray would
// refuse too, or one that exceeds the evaluator's limits.
Scene import_pov(const std::filesystem::path& file, const ImportOptions& options,
                 Diagnostics& diagnostics);

}  // namespace fb
