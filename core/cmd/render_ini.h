// `filmback render scene.ini` and `render scene.pov --ini FILE` (docs/pov.md ".ini files"): a
// POV-Ray .ini's options into the render command, where the command line has not set them.
#pragma once

#include "core/cmd/commands.h"
#include "core/util/diagnostics.h"

namespace fb {

// Reads the .ini the command names (its scene, or --ini) and fills what the command line left
// unset: the scene, resolution, samples, frames, outputs, library folders, declarations and the
// animation the clock follows. Its warnings go to `diagnostics`. Throws InputError for a bad .ini,
// UsageError for an .ini given twice.
void apply_pov_ini(RenderCommand& c, Diagnostics& diagnostics);

}  // namespace fb
