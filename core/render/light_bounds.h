// What a light tree knows of a light, or of a node's lights together, to guess how much of their
// light reaches a shading point without looking at any of them: where they are (a box), how much
// they emit, and in which directions (a cone of normals widened by how far past a normal each
// emits). pbrt 4e §12.6.3, "LightBounds" and "Bounding Lights"; Cycles 3.5's light tree bounds its
// nodes the same way (kernel/light/tree.h, "bounding cone").
#pragma once

#include <filmback/vec.h>

namespace fb {

struct LightBounds {
  Vec3f lo{HUGE_VALF, HUGE_VALF, HUGE_VALF};  // render space, m
  Vec3f hi{-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
  // The light's peak radiant intensity, luminance in W/sr: I for a point or spot light, L A for an
  // area light or an emissive triangle (its intensity along its normal). With it the importance
  // below is the irradiance a point light of that intensity would bring at normal incidence.
  float intensity = 0.f;
  Vec3f axis{0.f, 0.f, 1.f};  // unit: the normals' cone
  float cos_theta_o = 1.f;    // the cone of normals' half-angle theta_o
  float cos_theta_e = 0.f;    // how far past a normal light still leaves, theta_e
  bool two_sided = false;     // emits along -axis as along axis

  bool empty() const { return !(intensity > 0.f); }
  Vec3f centre() const { return (lo + hi) * 0.5f; }
};

// Both lights' (or nodes') bounds: the box around both boxes, the summed intensity, the smallest
// cone around both cones (pbrt 4e §3.8.4, "Union(DirectionCone, DirectionCone)"), the larger
// theta_e.
LightBounds union_of(const LightBounds& a, const LightBounds& b);

// pbrt 4e §12.6.3, "LightBounds::Importance" (eq. 12.21 and the angles before it), without the
// receiving surface's cosine: the light sampler is not told the shading normal. An upper estimate
// of the light's contribution at `p`: intensity cos(theta') / d^2, where theta' is the angle
// between the cone's nearest normal and the direction to p, reduced by the box's angular radius
// seen from p, and d is p's distance from the box's centre, at least the box's half diagonal. It is
// 0 only where the lights send nothing: where theta' exceeds theta_e for every point of the box.
float importance(const LightBounds& bounds, Vec3f p);

// pbrt 4e §12.6.3, "EvaluateCost": the surface-area-orientation heuristic's measure of a node's
// bounds, intensity times the solid angle its emission can cover (M_omega) times the box's area,
// stretched by how thin the box is along the split axis `axis_index`.
float orientation_cost(const LightBounds& bounds, int axis_index);

}  // namespace fb
