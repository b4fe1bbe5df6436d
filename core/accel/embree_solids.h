// Solids as Embree 3 user geometry: Embree's BVH decides which solids a ray may meet, and
// RenderSolid::first_hit intersects them exactly.
#pragma once

#include <cmath>
#include <optional>

#include "core/accel/solid_intersect.h"
#include "core/texture/surface_shader.h"

typedef struct RTCDeviceTy* RTCDevice;  // <embree3/rtcore.h>
typedef struct RTCSceneTy* RTCScene;

namespace fb {

// A solid as Embree's callbacks see it: the solid, and the shader that says whether a hit on a
// partly transparent material counts. Both must outlive the Embree scene.
struct EmbreeSolid {
  const RenderSolid* solid;
  const SurfaceShader* shader;
};

// The first hit in (t_min, t_max) that the hit material covers (SurfaceShader::covers, with a
// hash of the hit position and the ray's direction), skipping the surfaces a partly transparent
// material lets the ray through as Embree's filter skips them on meshes. Deterministic, and a hit
// before t_max is the one t_max = infinity gives: the renderer intersects again, uncut, to fill
// a hit record.
std::optional<SolidHit> first_covered_hit(const EmbreeSolid& solid, Vec3d origin, Vec3d direction,
                                          double t_min, double t_max = HUGE_VAL);

// Attaches `solid` as geometry `id`: one user primitive whose bounds are the solid's bounds(),
// widened to the floats around them.
void attach_solid(RTCDevice device, RTCScene scene, const EmbreeSolid& solid, unsigned id);

}  // namespace fb
