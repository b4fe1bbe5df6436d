// Solids as Embree 3 user geometry: Embree's BVH decides which solids a ray may meet, and
// RenderSolid::first_hit intersects them exactly.
#pragma once

#include "core/accel/solid_intersect.h"

typedef struct RTCDeviceTy* RTCDevice;  // <embree3/rtcore.h>
typedef struct RTCSceneTy* RTCScene;

namespace fb {

// Attaches `solid` (which must outlive the scene) as geometry `id`: one user primitive whose
// bounds are solid.bounds(), widened to the floats around them.
void attach_solid(RTCDevice device, RTCScene scene, const RenderSolid& solid, unsigned id);

}  // namespace fb
