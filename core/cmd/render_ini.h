// `filmback render scene.ini` and `render scene.pov --ini FILE` (docs/pov.md ".ini files"): a
// POV-Ray .ini's options into the render command, where the command line has not set them.
#pragma once

#include "core/cmd/commands.h"

namespace fb {

// Whether the scene argument names an .ini (`scene.ini`, `scene.ini[Section]`).
bool names_pov_ini(const std::filesystem::path& scene);

// Reads the .ini the command names (its scene, or --ini) and fills what the command line left
// unset: the scene, resolution, samples, frames, outputs, library folders, declarations and the
// animation the clock follows. Its warnings go to `warnings`. Throws InputError for a bad .ini,
// UsageError for an .ini given twice.
void apply_pov_ini(RenderCommand& c, std::vector<std::string>& warnings);

// filmback's samples per pixel for POV-Ray's antialiasing (docs/pov.md ".ini files").
uint32_t samples_for_pov_antialias(bool antialias, uint32_t depth);

}  // namespace fb
