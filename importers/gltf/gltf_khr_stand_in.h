// How bright the KHR_lights_punctual stand-in of a POV-Ray light is (docs/pov.md "Conversion"):
// POV-Ray's point and spot lights do not fall off with distance (or fade by their own law), every
// standard glTF viewer applies the inverse-square law, so the stand-in's intensity is scaled to
// light what the camera sees as filmback lights it. The exact light stays in FILMBACK_povray.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <span>
#include <vector>

#include "core/math/transform.h"
#include "core/scene/scene.h"

namespace fb::gltf {

// A surface point a viewer's camera sees, with its unit geometric normal (either side).
struct ViewedPoint {
  Vec3d position;
  Vec3d normal;
};

// Where a grid of rays through the frame of `camera` (as written: KHR's yfov and aspect ratio, or
// xmag and ymag) first meets the scene's triangles. Misses are left out.
std::vector<ViewedPoint> viewed_points(const Scene& scene, const tinygltf::Camera& camera,
                                       const Transform& world_from_camera);

// khr_intensity_scale for each of the scene's lights (1 for those it leaves unchanged), over the
// viewed points nothing shadows from the light's centre (all of them for a shadowless light),
// seen through `camera` placed at world_from_camera; the viewer for the fallback is the camera.
std::vector<double> khr_intensity_scales(const Scene& scene, const tinygltf::Camera& camera,
                                         const Transform& world_from_camera);

// A spot's KHR_lights_punctual cone, 0 <= inner < outer <= pi/2. A POV-Ray spot's
// (SpotFalloff::kPov) sends the flux POV-Ray's profile sends (cos^tightness and the cubic from
// falloff to radius), F = integral of the profile over the solid angle / 2 pi, in a narrow ramp:
// inner 0.95 of the hard cone of that flux (1 - cos = F), outer where KHR's ramp makes up the rest.
// Viewers disagree on the ramp (KHR's t^2, Blender's smoothstep of spot_blend = 1 - inner/outer,
// three.js's smoothstep), and a narrow one leaves them little to disagree on. Other spots: their
// cone clamped.
struct KhrSpotCone {
  double inner_rad, outer_rad;
};
KhrSpotCone khr_spot_cone(const Light& light);

// The factor from the intensity I of a POV-Ray point or spot light (LightDecay::kPovRay: POV-Ray's
// fading a(d), 1 without it, and a spot's profile p) to the intensity of its stand-in, which
// follows the inverse-square law and KHR's cone ramp k, chosen so that the viewed points get the
// same direct light in sum (Lambert-weighted; `viewed`: the points the light reaches unshadowed):
//   s = sum_i w_i a(d_i) p_i / sum_i w_i k_i / d_i^2,  w_i = |cos| between normal and light.
// Without any viewed point the stand-in lights, s = a(d) d^2 at the distance d to `viewer` (the
// camera), and 1 without a viewer. Directional lights and lights that fall off physically get 1.
double khr_intensity_scale(const Light& light, std::span<const ViewedPoint> viewed,
                           std::optional<Vec3d> viewer);

}  // namespace fb::gltf
