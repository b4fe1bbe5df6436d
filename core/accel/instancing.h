// Which meshes the render keeps as one object-space copy traced through Embree instances, rather
// than flattening each of their instances into render-space triangles (docs/architecture.md,
// "Instances"). Shared by the geometry (core/accel/render_geometry.cpp) and by the memory estimate
// that must agree with it before anything is built (core/render/memory_estimate.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/scene.h"

namespace fb {

enum class Instancing {
  kRepeated,  // a mesh that two or more instances use (the default: one use traces faster flat)
  kNever,     // every instance flattened (the reference the instanced path is tested against)
  kAlways,    // every mesh that can be, even one used once
};

// Per mesh of `scene`: whether it is instanced under `policy`. Never a mesh without triangles, an
// emissive one (light sampling needs its triangles in render space, one emitter per copy) or one
// whose material has a solid pattern (it is evaluated at render-space positions inside Embree's
// alpha filter, which sees only the object-space copy).
std::vector<bool> instanced_meshes(const Scene& scene, Instancing policy);

}  // namespace fb
