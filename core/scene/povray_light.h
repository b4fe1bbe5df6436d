// POV-Ray's light attenuation (Attenuate_Light, docs/pov.md "Light sources") in double precision,
// for what works with LightDecay::kPovRay lights outside the render loop (the glTF writer's
// stand-ins for other viewers, importers/gltf/gltf_khr_stand_in.h).
#pragma once

#include "core/scene/scene.h"

namespace fb {

// The attenuation at distance_m from the light: 1 without fading (fade_power <= 0), else
// 2 / (1 + (d / fade_distance)^fade_power), or d^-fade_power for a zero fade_distance.
double povray_fading(const Light& light, double distance_m);

// A SpotFalloff::kPov spot's profile at cos_angle off its axis: cos^tightness times POV-Ray's
// cubic from 0 at the falloff cone to 1 at the radius cone; 0 behind the light.
double povray_spot_profile(const Light& light, double cos_angle);

}  // namespace fb
