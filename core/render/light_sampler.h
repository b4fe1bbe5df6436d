// Next-event estimation's half of the lights: picks a light (lamps, emissive triangles and the
// world alike) by its estimated power or, among lights with a place, by a light tree's estimate of
// what each brings to the shading point (core/render/light_choice.h), and a point on it. Lamps are
// the scene's Lights: delta lights (a point or spot without a radius, a sun without an angle,
// POV-Ray's lights) are reached by light sampling only; lights with a size
// (core/render/sized_lights.h: a point or spot light's disk, a sun's cone, an area light) are
// sampled by solid angle as Cycles 3.4 samples them and are also found by BSDF-sampled rays through
// crossed(), with the same density, for multiple importance sampling (docs/blender.md, "Lights and
// world").
#pragma once

#include <optional>
#include <variant>
#include <vector>

#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

#include "core/accel/render_geometry.h"
#include "core/math/transform.h"
#include "core/render/environment.h"
#include "core/render/light_choice.h"
#include "core/render/sized_lights.h"
#include "core/scene/scene.h"

namespace fb {

class LightSampler {
 public:
  // Lamps are placed at `frame_s` on the scene's timeline (they do not move within the shutter);
  // emissive triangles that move are left to BSDF sampling (EmissiveTriangle::moving). The world is
  // the scene's environment image, sampled as a light, or its uniform background;
  // `background_override` (the command line's) replaces both.
  LightSampler(const Scene& scene, const Transform& render_from_world,
               const RenderGeometry& geometry, double frame_s,
               std::optional<Rgb> background_override = {},
               LightSelection selection = LightSelection::kAuto);
  bool sample(Vec3f position, const float u[3], fb_light_sample& out) const;
  // fb_scene_api::sample_lamp: a point on lamp `index` (< lamp_count()) from `position`, without a
  // choice among lights (pdf 1 for a delta light); false for an index past the lamps. `u` NULL:
  // the lamp's centre (a POV-Ray area light's; u = (0.5, 0.5) for a light with a size).
  bool sample_lamp(uint32_t index, Vec3f position, const float u[2], fb_light_sample& out) const;
  float pdf(Vec3f position, const fb_hit& emitter_hit) const;
  // Radiance of the world arriving from direction -w (w: the escaping ray's direction), and the
  // solid-angle pdf with which sample() would have chosen w (0 for a uniform world, which only
  // BSDF sampling finds).
  Rgb background(Vec3f w, float& pdf) const;
  // fb_scene_api::lights_crossed: the lights with a size that `ray` passes through before t_end
  // (suns only when t_end is infinite), nearest first, each with the pdf sample() would have chosen
  // that point with from the ray's origin, the choice of the light included.
  uint32_t crossed(const fb_ray& ray, float t_end, fb_light_crossing* crossings,
                   uint32_t capacity) const;
  size_t lamp_count() const { return lamps_.size(); }
  size_t emissive_triangle_count() const { return emitters_.size(); }
  bool uses_tree() const { return choice_.uses_tree(); }

 private:
  struct Lamp {
    LightType type;
    Vec3f position;  // point, spot
    Vec3f axis;      // spot: where it shines; directional: towards the light
    Rgb intensity;
    SpotFalloff falloff;
    float cos_inner, cos_outer;
    float spot_smooth;  // SpotFalloff::kCycles: the width in cos(angle) of the fade
    // POV-Ray's semantics (Light's opt-in fields, docs/pov.md "Appearance").
    LightDecay decay;
    float fade_distance, fade_power;
    float spot_tightness;
    bool casts_shadows;
    Vec3f area_axis1, area_axis2;  // render space
    uint32_t area_size1, area_size2;
    bool area_circular, area_orient;
    // A light with a size; monostate for a delta light.
    std::variant<std::monostate, FacingDisk, SunDisk, AreaLight> size;
  };
  // The point of a POV-Ray area light's grid that u picks, seen from `position`.
  static Vec3f area_point(const Lamp& lamp, Vec3f position, const float u[2]);
  bool sample_delta(const Lamp& lamp, Vec3f position, const float u[2], fb_light_sample& out) const;
  // A point on a light with a size, from `position` (sampled) or along a ray (crossed).
  static bool sample_sized(const Lamp& lamp, Vec3f position, const float u[2],
                           SizedLightPoint& point);
  static bool cross_sized(const Lamp& lamp, const fb_ray& ray, float t_end, SizedLightPoint& point);
  static Rgb radiance(const Lamp& lamp, const SizedLightPoint& point);
  bool sample_triangle(uint32_t index, Vec3f position, const float u[2],
                       fb_light_sample& out) const;

  std::vector<Lamp> lamps_;
  std::vector<uint32_t> sized_;                    // the lamps with a size
  const std::vector<EmissiveTriangle>& emitters_;  // light index lamps_.size() + i
  const RenderGeometry& geometry_;                 // evaluates textured emission
  std::optional<EnvironmentLight> environment_;    // the last light index, when present
  Rgb background_;                                 // uniform world, when no environment
  const std::vector<Material>& materials_;
  LightChoice choice_;
};

}  // namespace fb
