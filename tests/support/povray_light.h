// A POV-Ray light as the SDL importer makes one (decay kPovRay, no fade), for the tests of what
// `filmback convert` writes for it.
#pragma once

#include "core/math/constants.h"
#include "core/scene/scene.h"

namespace fb::test {

// Shines down its own -Z; its colour (0.8, 0.5, 0.3) times pi, as POV-Ray's `color` is scaled.
inline Light povray_light(LightType type, const Transform& world_from_light) {
  Light l;
  l.name = "light";
  l.type = type;
  l.decay = LightDecay::kPovRay;
  l.intensity = Rgb(0.8f, 0.5f, 0.3f) * float(kPi);
  l.world_from_light = world_from_light;
  return l;
}

}  // namespace fb::test
