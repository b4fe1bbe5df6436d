// A POV-Ray pigment (pov_scene.h) as the scene model's solid texture (core/scene/solid_texture.h),
// with POV-Ray's defaults made explicit: the converter's textures (pov_appearance) and the SDL's
// pigment functions (function_compiler.cpp) both evaluate it.
#pragma once

#include "core/scene/solid_texture.h"
#include "importers/pov/pov_scene.h"

namespace fb::pov {

// A colour as written, decoded by `gamma` (POV-Ray's assumed_gamma).
Rgb decode(const Colour& c, double gamma);
// A pigment as a solid texture; `pov_from_input` takes the points it will be evaluated at
// (filmback's world for objects, the sky's own space for a sky_sphere) into POV-Ray's space.
SolidPattern to_solid(const Pigment& p, double gamma, const Transform& pov_from_input);

}  // namespace fb::pov
