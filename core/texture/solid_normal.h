// Evaluates POV-Ray's normal patterns (core/scene/solid_texture.h, SolidNormal) as POV-Ray 3.7's
// Perturb_Normal does (source/core/material/normal.cpp): the surface normal, taken into the
// pattern's space and made unit, gains a perturbation there and goes back to world space. The
// result bends the shading normal only; the geometry stays as it is (docs/pov.md "Normals").
#pragma once

#include <vector>

#include <filmback/vec.h>

#include "core/scene/solid_texture.h"

namespace fb {

// The unit normal `world_normal` bent by `normal` at `world_point`: unit, or `world_normal` itself
// where the bent one degenerates.
Vec3d perturbed_normal(const SolidNormal& normal, Vec3d world_point, Vec3d world_normal);

// The pieces, exposed for tests.
namespace solid {

// What POV-Ray adds to the unit pattern-space normal at `pattern_point` (already warped by the
// pattern's turbulence): bumps amount DNoise(p); dents noise(p)^3 amount DNoise(p); wrinkles
// amount sum_i |DNoise(2^i p)| / 2^i; ripples and waves a radial sine from each wave source;
// any other pattern -5 amount (0.02 / accuracy) sum_k h(p + accuracy v_k) v_k over the four
// corners v_k of a tetrahedron, h the pattern's value through the slope_map: about
// -(0.4 / 3) amount times the gradient of h.
Vec3d normal_perturbation(const SolidNormal& normal, Vec3d pattern_point);
// The slope_map's height at a pattern value: POV-Ray's Hermite cubic between the entries about
// it, the end entries' heights beyond them; the value itself for an empty map.
double slope_height(const std::vector<SolidSlopeStop>& map, double value);

}  // namespace solid
}  // namespace fb
