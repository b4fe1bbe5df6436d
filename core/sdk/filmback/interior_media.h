// Interior media for integrators (fb_medium in plugin_abi.h; docs/pov.md "Media"): which medium
// a ray travels in, followed across the surfaces it crosses, and the closed form of a homogeneous
// segment's transmittance and emission.
#pragma once

#include <cmath>
#include <cstdint>

#include <filmback/geometry.h>
#include <filmback/plugin_abi.h>
#include <filmback/vec.h>

namespace fb {

// The medium inside `material`'s surfaces, or nullptr.
inline const fb_medium* interior_medium(const fb_scene& scene, uint32_t material) {
  if (scene.media == nullptr || material >= scene.material_count) return nullptr;
  return scene.media[material].present ? &scene.media[material] : nullptr;
}

inline bool leaves_surface(const fb_hit& hit, const float direction[3]) {
  return hit.geometric_normal[0] * direction[0] + hit.geometric_normal[1] * direction[1] +
             hit.geometric_normal[2] * direction[2] >
         0.f;
}

// A surface a ray passes straight through, tinted by its base colour: fully transmitting with
// ior 1, as a POV-Ray container of media (`rgbt 1`) is. A microfacet BSDF cannot sample it (at
// ior 1 its refraction is a delta), so a path tracer crosses it itself.
inline bool is_clear_boundary(const fb_hit& hit) {
  return hit.transmission >= 0.999f && std::abs(hit.ior - 1.f) < 1e-3f;
}

// The medium (a material index, FB_NONE for none) of the segment of a ray that started in
// `inside` and ends at `hit`: `inside`, or, for a ray not known to be in one that leaves a surface
// holding a medium, that medium (a ray that started inside it: the camera's, a light's).
inline uint32_t segment_medium(const fb_scene& scene, uint32_t inside, const fb_hit& hit,
                               const float direction[3]) {
  if (inside != FB_NONE) return inside;
  return leaves_surface(hit, direction) && interior_medium(scene, hit.material) ? hit.material
                                                                                : FB_NONE;
}

// The medium a ray is in after it passes through the surface at `hit`, having travelled in
// `segment` (segment_medium) along `direction`: entering a surface that holds a medium puts it in
// that medium, leaving the one it is in puts it outside, other surfaces change nothing (a ray in a
// medium stays in it through an object inside; an inner medium replaces an outer one until the
// ray leaves it, and the outer one is not resumed then).
inline uint32_t medium_after_crossing(const fb_scene& scene, uint32_t segment, const fb_hit& hit,
                                      const float direction[3]) {
  if (!leaves_surface(hit, direction))
    return interior_medium(scene, hit.material) ? hit.material : segment;
  return hit.material == segment ? FB_NONE : segment;
}

// Along `length_m` of a homogeneous medium that attenuates by `sigma` (m^-1) and adds `emission`
// per metre: the share of the light from the far end that comes through, e^(-sigma d), and the
// light the segment adds, the integral of emission e^(-sigma s) over s in [0, d] =
// emission (1 - e^(-sigma d)) / sigma (emission d where sigma is 0).
struct HomogeneousSegment {
  Rgb transmittance{1.f, 1.f, 1.f};
  Rgb emitted{0.f, 0.f, 0.f};
};

inline HomogeneousSegment homogeneous_segment(Rgb sigma, Rgb emission, float length_m) {
  float transmittance[3] = {}, emitted[3] = {};
  for (int c = 0; c < 3; ++c) {
    const double s = sigma[c], d = length_m, x = s * d;
    transmittance[c] = float(std::exp(-x));
    // -expm1(-x) / s stays exact where s d is tiny
    emitted[c] = float(emission[c] * (x > 1e-12 ? -std::expm1(-x) / s : d));
  }
  return {Rgb(transmittance), Rgb(emitted)};
}

// What a shadow ray lets through on its way to a light, crossing surfaces and interior media:
// `passed(hit)` is what a surface lets through (0 where it blocks), `extinction(medium)` what a
// medium attenuates by (m^-1), each medium segment dimming by e^(-extinction d) (segment_medium
// follows which medium the ray is in; a light inside one is dimmed up to it). Past `most_surfaces`
// surfaces the ray counts as blocked (a bound on untrusted scenes). The shadow ray's direction is
// unit.
template <typename Passed, typename Extinction>
Rgb shadow_ray_through(const fb_scene& scene, fb_trace_context* context, const fb_ray& shadow,
                       int most_surfaces, Passed passed, Extinction extinction) {
  fb_ray ray = shadow;
  Rgb through{1.f, 1.f, 1.f};
  uint32_t inside = FB_NONE;
  const auto dim = [&](uint32_t medium, float length) {
    through *=
        homogeneous_segment(extinction(*interior_medium(scene, medium)), {}, length).transmittance;
  };
  for (int i = 0; i < most_surfaces; ++i) {
    fb_hit hit;
    if (!scene.api->intersect(context, &ray, &hit)) {
      if (inside != FB_NONE && std::isfinite(ray.t_max)) dim(inside, ray.t_max);
      return through;
    }
    const uint32_t medium = segment_medium(scene, inside, hit, ray.direction);
    if (medium != FB_NONE) dim(medium, hit.t);
    inside = medium_after_crossing(scene, medium, hit, ray.direction);
    through *= passed(hit);
    if (!(max_component(through) > 0.f)) return {};
    const Vec3f p(hit.position), d(ray.direction);
    offset_ray_origin(p, Vec3f(hit.position_error), Vec3f(hit.geometric_normal), d)
        .store(ray.origin);
    ray.t_max = shadow.t_max - dot(p - Vec3f(shadow.origin), d);
    if (!(ray.t_max > 0.f)) return through;
  }
  return {};
}

// A free flight through a homogeneous medium that attenuates by sigma_t and scatters sigma_s
// (m^-1), for a path tracer: the distance to a collision is drawn from the mean of sigma_t's
// channels, sigma_bar (pdf sigma_bar e^(-sigma_bar s)), with u in [0, 1). Either the path collides
// at distance_m < length_m and its throughput is multiplied by sigma_s e^(-sigma_t s) / pdf(s)
// (there it scatters), or it passes and is multiplied by e^(-sigma_t d) / e^(-sigma_bar d)
// (pbrt 4e section 14.1.2, with a single distance-sampling density for the three channels).
struct FreeFlight {
  bool collided = false;
  float distance_m = 0.f;
  Rgb weight{1.f, 1.f, 1.f};
};

inline FreeFlight free_flight(Rgb sigma_t, Rgb sigma_s, float length_m, float u) {
  const double sigma_bar = (double(sigma_t.x) + sigma_t.y + sigma_t.z) / 3.0;
  if (!(sigma_bar > 0.0)) return {};
  const double s = -std::log1p(-double(u)) / sigma_bar;
  const bool collided = s < length_m;
  const double at = collided ? s : double(length_m);
  const double pdf = collided ? sigma_bar * std::exp(-sigma_bar * s) : std::exp(-sigma_bar * at);
  float weight[3];
  for (int c = 0; c < 3; ++c) {
    const double through = std::exp(-double(sigma_t[c]) * at);
    weight[c] = float((collided ? sigma_s[c] * through : through) / pdf);
  }
  return {collided, float(at), Rgb(weight)};
}

}  // namespace fb
