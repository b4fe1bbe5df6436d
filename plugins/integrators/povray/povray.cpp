// Integrator `povray`: POV-Ray 3.7's classic ray tracer (source/core/render/trace.cpp,
// ComputeLightedTexture), so that a .pov scene renders as POV-Ray draws it rather than
// physically (docs/pov.md, "The povray integrator"). At each hit, from the finish as the scene
// wrote it (fb_povray_scene, plugin_abi.h): ambient and emission times the pigment; for every
// light (fb_scene_api::sample_lamp, no choice among lights) diffuse with brilliance, phong and
// specular highlights, shadowed by what lies between, seen through filter and transmit; then the
// refracted or straight-through ray weighted by the pigment's filter and transmit, and the
// reflected ray by reflection min/max, falloff, fresnel and metallic; down to max_trace_level,
// pruned below adc_bailout, the background or sky_sphere where a ray escapes; the scene's fog
// blended over every ray but the shadow rays (ComputeFog); an object's interior media over the
// part of a ray inside it (ComputeMedia: absorption and emission in closed form, the lights'
// light scattered in sampled along the segment). No light bounces
// between surfaces but by these mirror and refraction rays: POV-Ray's `ambient` stands in for it.
// A surface without a POV-Ray finish (another scene's) is lit as diffuse 1 in its base colour.
#include <filmback/geometry.h>
#include <filmback/interior_media.h>
#include <filmback/plugin_sdk.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "pov_lighting.h"

namespace {

using fb::Rgb;
using fb::Vec3f;
namespace lighting = fb::pov_lighting;

constexpr float kPovPi = 3.14159265f;
// Surfaces a shadow ray looks through before it is taken as blocked (a bound on untrusted scenes).
constexpr int kMostShadowSurfaces = 64;
// Straight-through (ior 1) rays do not count towards max_trace_level (POV-Ray's continued rays);
// this bounds how many a ray may still take.
constexpr int kMostContinuedRays = 256;
// The finish of surfaces a POV-Ray scene did not describe: diffuse 1 in the hit's base colour.
constexpr fb_pov_finish kPlainFinish = lighting::diffuse_finish(1.f);
// A host whose fb_povray_scene ends before colour_gamma and ambient_light: a linear scene.
constexpr size_t kPovGammaSize = offsetof(fb_povray_scene, ambient_light) + 3 * sizeof(float);

constexpr fb_param_desc kParams[] = {
    {"max_trace_level", FB_PARAM_INT, "0", "", nullptr, 0, 256,
     "deepest ray (the camera's is 1); 0: the scene's global_settings, else POV-Ray's 5"},
};
constexpr auto kMaxTraceLevel = fb::param<int>(kParams, "max_trace_level");

// One ray of the tree: where it starts, where it goes, its weight in the pixel, and the interior
// medium it starts in (a material index; FB_NONE: none, or not known, fb::segment_medium).
struct PovRay {
  fb_ray ray;
  int level;      // 1 for the camera's
  int continued;  // straight-through rays taken since the last counted level
  float weight;
  uint32_t medium = FB_NONE;
};

class PovRayTracer {
 public:
  static constexpr const char* kChannels[] = {"R", "G", "B"};

  explicit PovRayTracer(const fb_value* values) : max_trace_level_(kMaxTraceLevel(values)) {}

  void radiance(const fb_scene& scene, fb_trace_context* ctx, const fb_ray* rays, size_t count,
                float* values) const {
    const fb_hit* hits = fb::first_hits(scene, ctx, rays, count);
    Tracer tracer{scene, ctx, max_trace_level_};
    for (size_t i = 0; i < count; ++i)
      tracer.decoded(tracer.seen({rays[i], 1, 0, 1.f}, hits[i], i)).store(values + 3 * i);
  }

 private:
  // The recursion for one batch: the scene, its settings and the thread's context.
  struct Tracer {
    Tracer(const fb_scene& s, fb_trace_context* c, int max_level)
        : scene(s), api(*s.api), ctx(c), povray(s.povray) {
      max_trace_level = max_level > 0       ? max_level
                        : povray != nullptr ? int(povray->max_trace_level)
                                            : 5;
      adc_bailout = povray != nullptr ? povray->adc_bailout : 1.f / 255.f;
      const bool has_gamma =
          povray != nullptr && povray->struct_size >= kPovGammaSize && povray->colour_gamma > 0.f;
      colour_gamma = has_gamma ? povray->colour_gamma : 1.f;
      // fb_pov_finish.ambient is the amount times the decoded ambient_light: times this, the
      // amount times ambient_light as written.
      if (has_gamma) {
        const auto scale = [&](float light) {
          return light > 0.f ? std::pow(light, 1.f / colour_gamma - 1.f) : 0.f;
        };
        ambient_in_scene_values = {scale(povray->ambient_light[0]), scale(povray->ambient_light[1]),
                                   scale(povray->ambient_light[2])};
      }
    }
    // POV-Ray computes in the scene's own colour values and decodes the pixel by assumed_gamma
    // (its output gamma, File_Gamma 1): a decoded colour taken back to them, and the pixel.
    Rgb in_scene_values(Rgb decoded_colour) const {
      return lighting::raised(decoded_colour, 1.f / colour_gamma);
    }
    Rgb decoded(Rgb pixel) const { return lighting::raised(pixel, colour_gamma); }
    Rgb trace(const PovRay& r, size_t path) const;
    Rgb seen(const PovRay& r, const fb_hit& hit, size_t path) const;
    Rgb shade(const PovRay& r, const fb_hit& hit, size_t path, uint32_t medium) const;
    Rgb through_medium(const PovRay& r, float t_end, const fb_medium& medium, Rgb behind) const;
    Rgb lamps_at(const float position[3], float time_s) const;
    Rgb light_through(const fb_ray& shadow, float distance) const;
    const fb_pov_finish& finish(uint32_t material) const {
      return povray && material < povray->finish_count && povray->finishes[material].present
                 ? povray->finishes[material]
                 : kPlainFinish;
    }

    const fb_scene& scene;
    const fb_scene_api& api;
    fb_trace_context* ctx;
    const fb_povray_scene* povray;
    int max_trace_level;
    float adc_bailout;
    float colour_gamma;
    Rgb ambient_in_scene_values{1.f, 1.f, 1.f};
  };

  int max_trace_level_;
};

// POV-Ray's TraceRay: nothing past the deepest level or below the bailout weight.
Rgb PovRayTracer::Tracer::trace(const PovRay& r, size_t path) const {
  if (r.level > max_trace_level || r.weight < adc_bailout || r.continued > kMostContinuedRays)
    return {};
  fb_hit hit;
  if (!api.intersect(ctx, &r.ray, &hit)) hit.t = HUGE_VALF;
  return seen(r, hit, path);
}

// What the ray brings back through the scene's fog: POV-Ray's ComputeFog blends the fog's colour
// over the ray's colour by the fog's depth up to the hit, infinite where it escapes (POV-Ray's
// BOUND_HUGE). Shadow rays are not fogged (a light's media_attenuation is off by default).
Rgb PovRayTracer::Tracer::seen(const PovRay& r, const fb_hit& hit, size_t path) const {
  const bool found = !std::isinf(hit.t);
  const uint32_t medium =
      found ? fb::segment_medium(scene, r.medium, hit, r.ray.direction) : FB_NONE;
  Rgb colour = shade(r, hit, path, medium);
  if (medium != FB_NONE)
    colour = through_medium(r, hit.t, *fb::interior_medium(scene, medium), colour);
  float transmittance[3], emitted[3];
  if (!api.medium_segment(ctx, &r.ray, hit.t, 1, transmittance, emitted)) return colour;
  // The fog's colour was blended in decoded values: taken back to the scene's, near POV-Ray's.
  return colour * lighting::rgb(transmittance) + in_scene_values(lighting::rgb(emitted));
}

// POV-Ray's ComputeMedia over the ray's segment inside an object's media, up to its hit at
// `t_end`: what lies behind dimmed by e^(-extinction d), plus the light the medium sends along the
// ray, dimmed by the medium before it, summed as POV-Ray 3.7 sums it (method 3, no jitter): a
// left Riemann sum over `povray_points` points (docs/pov.md "Media": its emission matches
// POV-Ray's renders to their 16-bit rounding, where the closed form differs by up to 40 %). The
// light per metre at a point is emission plus scattering times each light's colour reaching it
// (isotropic: POV-Ray's phase weight is 1).
Rgb PovRayTracer::Tracer::through_medium(const PovRay& r, float t_end, const fb_medium& medium,
                                         Rgb behind) const {
  const Vec3f origin(r.ray.origin), direction(r.ray.direction);
  const float length = t_end * fb::length(direction);
  // Emission was decoded as a colour (the scattering is a rate, as written): back to the
  // scene's values, as the lamps' colours are.
  const Rgb emission = in_scene_values(Rgb(medium.emission)), scattering(medium.scattering);
  const Rgb extinction(medium.povray_extinction);
  const bool scatters = fb::max_component(scattering) > 0.f && scene.lamp_count > 0;
  const uint32_t points = std::max(medium.povray_points, 1u);
  Rgb sent{};
  for (uint32_t k = 0; k < points; ++k) {
    const float at = float(k) / float(points);
    Rgb source = emission;
    if (scatters) {
      float point[3];
      (origin + direction * (t_end * at)).store(point);
      source += scattering * lamps_at(point, r.ray.time_s);
    }
    sent += source * fb::homogeneous_segment(extinction, {}, length * at).transmittance;
  }
  sent *= length / float(points);
  return behind * fb::homogeneous_segment(extinction, {}, length).transmittance + sent;
}

// The lights' colours reaching a point in a medium, each through what lies between (POV-Ray
// lights a medium from each light's centre).
Rgb PovRayTracer::Tracer::lamps_at(const float position[3], float time_s) const {
  Rgb sum{};
  for (uint32_t lamp = 0; lamp < scene.lamp_count; ++lamp) {
    fb_light_sample centre;
    if (!api.sample_lamp(ctx, lamp, position, nullptr, &centre)) continue;
    const fb_ray shadow =
        fb::shadow_ray_to_light(Vec3f(position), centre.direction, centre.distance, time_s);
    sum += in_scene_values(lighting::rgb(centre.radiance) * (1.f / (kPovPi * centre.pdf))) *
           light_through(shadow, centre.distance);
  }
  return sum;
}

// What a shadow ray from a lit point brings of a light `distance` away: each surface between
// passes its pigment's filter and transmit (POV-Ray's ComputeShadowColour), and each interior
// medium it crosses dims it by e^(-extinction d); an opaque surface, or one without a POV-Ray
// finish, blocks it. A surface the host let through already by its coverage
// (fb_pov_finish.coverage) passes the rest of its transmit where it is found, so that the mean is
// POV-Ray's.
Rgb PovRayTracer::Tracer::light_through(const fb_ray& shadow, float distance) const {
  if (!(distance > 0.f)) return {1.f, 1.f, 1.f};  // a light nothing shadows
  return fb::shadow_ray_through(
      scene, ctx, shadow, kMostShadowSurfaces,
      [this](const fb_hit& hit) {
        const fb_pov_finish& f = finish(hit.material);
        return lighting::passed_through(f, in_scene_values(lighting::pigment_at_hit(f, hit))) /
               std::max(f.coverage, 1e-6f);
      },
      [](const fb_medium& m) { return Rgb(m.povray_extinction); });
}

// `medium`: the one the ray travelled in to the hit (fb::segment_medium), which a reflected ray
// stays in and a transmitted one leaves or changes as fb::medium_after_crossing says.
Rgb PovRayTracer::Tracer::shade(const PovRay& r, const fb_hit& hit, size_t path,
                                uint32_t medium) const {
  const Vec3f view(r.ray.direction);
  if (std::isinf(hit.t)) {
    float le[3], pdf;
    api.background(ctx, r.ray.direction, le, &pdf);
    return in_scene_values(lighting::rgb(le));
  }
  const fb_pov_finish& f = finish(hit.material);
  // POV-Ray turns the normal to face the ray; the geometric normal decides whether the ray enters
  // or leaves the object (nested interiors are not tracked: docs/pov.md).
  Vec3f ng(hit.geometric_normal), n(hit.shading_normal);
  const bool entering = dot(ng, view) < 0.f;
  if (!entering) ng = -ng, n = -n;
  if (dot(n, view) > 0.f) n = ng;  // a bent normal turned away from the viewer
  const float eta = entering ? f.ior : 1.f / std::max(f.ior, 1e-6f);  // n2 / n1
  const Vec3f p(hit.position), p_error(hit.position_error);
  const Rgb pigment = in_scene_values(lighting::pigment_at_hit(f, hit));
  const float opacity = 1.f - f.filter - f.transmit;  // POV-Ray 3.7's Opacity()

  Rgb colour = pigment *
               (lighting::rgb(f.ambient) * ambient_in_scene_values + lighting::rgb(f.emission)) *
               opacity;
  const float cos_view = -dot(view, n);
  const Rgb reflec = lighting::reflectivity(f, cos_view, eta, pigment);

  if (f.diffuse != 0.f || f.phong != 0.f || f.specular != 0.f) {
    for (uint32_t lamp = 0; lamp < scene.lamp_count; ++lamp) {
      // POV-Ray lights from the light's centre, and shadows an area light from its grid: one
      // grid point per sample here, so that the samples average the grid's visibility. A light
      // with a size (not POV-Ray's) lights from the point sampled on it.
      float u[2];
      api.next_samples(ctx, path, u, 2);
      fb_light_sample point, centre;
      if (!api.sample_lamp(ctx, lamp, hit.position, u, &point)) continue;
      if (!point.is_delta)
        centre = point;
      else if (!api.sample_lamp(ctx, lamp, hit.position, nullptr, &centre))
        continue;
      const Vec3f to_light(centre.direction), to_point(point.direction);
      const float cos_light = dot(n, to_light);
      if (cos_light < lighting::kHorizonCosine) continue;
      const fb_ray shadow = fb::shadow_ray_to_light(fb::offset_ray_origin(p, p_error, ng, to_point),
                                                    point.direction, point.distance, r.ray.time_s);
      // POV-Ray's lights have colour c where filmback's have intensity pi c (docs/pov.md).
      const Rgb light =
          in_scene_values(lighting::rgb(centre.radiance) * (1.f / (kPovPi * centre.pdf))) *
          light_through(shadow, point.distance);
      if (!(fb::max_component(light) > 0.f)) continue;
      colour += lighting::diffuse(f, cos_light, opacity, pigment, light) +
                lighting::phong(f, view, n, to_light, pigment, light) +
                lighting::specular(f, view, n, to_light, pigment, light);
    }
  }

  // Transmission: the pigment's filter and transmit, less what the host's coverage passed by.
  const Rgb see_through = lighting::passed_through(f, pigment);
  bool total_internal_reflection = false;
  const float transmitted_weight = fb::max_component(see_through);
  if (transmitted_weight > adc_bailout) {
    PovRay next{{},
                r.level + 1,
                0,
                r.weight * transmitted_weight,
                fb::medium_after_crossing(scene, medium, hit, r.ray.direction)};
    Vec3f direction = view;
    if (std::abs(eta - 1.f) < 1e-5f) {
      next.level = r.level, next.continued = r.continued + 1;  // straight on, not a new level
    } else if (const auto refracted = lighting::refracted(view, n, eta)) {
      direction = *refracted;
    } else {
      total_internal_reflection = true;
      direction = view - n * (2.f * dot(view, n));
      next.medium = medium;  // reflected back in
    }
    fb::offset_ray_origin(p, p_error, ng, direction).store(next.ray.origin);
    direction.store(next.ray.direction);
    next.ray.t_max = HUGE_VALF;
    next.ray.time_s = r.ray.time_s;
    const Rgb behind = trace(next, path);
    // Totally reflected light is not filtered (POV-Ray's ComputeLightedTexture).
    colour += total_internal_reflection ? behind : behind * see_through;
  }

  if (!total_internal_reflection && fb::max_component(reflec) > 0.f) {
    const float reflect_weight = f.reflection_fresnel
                                     ? fb::max_component(reflec)
                                     : std::max(fb::max_component(lighting::rgb(f.reflection_max)),
                                                fb::max_component(lighting::rgb(f.reflection_min)));
    Vec3f mirrored = view - n * (2.f * dot(view, n));
    // A bent normal may mirror the ray into the surface: mirror it on the geometric normal then.
    if (dot(mirrored, ng) < 0.f) mirrored = view - ng * (2.f * dot(view, ng));
    PovRay next{{}, r.level + 1, 0, r.weight * reflect_weight, medium};
    fb::offset_ray_origin(p, p_error, ng, mirrored).store(next.ray.origin);
    mirrored.store(next.ray.direction);
    next.ray.t_max = HUGE_VALF;
    next.ray.time_s = r.ray.time_s;
    Rgb seen = trace(next, path);
    if (f.reflection_exponent != 1.f) seen = lighting::raised(seen, f.reflection_exponent);
    colour += reflec * seen;
  }
  // The host keeps this hit with probability `coverage` and passes the ray on otherwise: divided
  // by it, the mean over samples is POV-Ray's colour.
  return colour / std::max(f.coverage, 1e-6f);
}

constexpr fb_integrator_api kApi = fb::integrator_api<PovRayTracer>();
constexpr fb_plugin kPlugin =
    fb::describe("povray", "1.0.0",
                 "POV-Ray 3.7's classic lighting: ambient, diffuse, phong, specular, shadows, "
                 "reflection and refraction from the scene's finishes",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
