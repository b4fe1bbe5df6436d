// POV-Ray's light model as JSON, for the FILMBACK_povray extension (docs/pov.md "Conversion"):
// nodes[i].extensions.FILMBACK_povray.light carries what neither KHR_lights_punctual nor
// FILMBACK_blender can say (no inverse-square law, fade_distance and fade_power, the spotlight's
// cubic falloff and tightness, area-light grids, shadowless), so that a converted file lights its
// scene as filmback lit the .pov. The node's frame is the light's: it shines down its -Z.
#pragma once

#include <tiny_gltf.h>

#include "core/scene/scene.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// Whether the light follows POV-Ray's model (LightDecay::kPovRay), which the extension carries.
bool is_povray_light(const Light& light);

tinygltf::Value povray_light_json(const Light& light);

// The light with everything but its name, frame and node set from the JSON. Throws InputError
// naming the file and the JSON path of the first value out of range.
Light read_povray_light(const Fields& json);

}  // namespace fb::gltf
