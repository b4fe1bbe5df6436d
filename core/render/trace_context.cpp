#include "core/render/trace_context.h"

#include <cstring>

#include "core/plugin/abi_layout.h"

namespace fb {
namespace {

// Hit records live in the integrator's memory at its own size, c->hit_size (plugin_abi.h,
// "Growth"): an integrator built against an older header has shorter records, so the host traces
// into a record of its own size and copies the part the plugin knows, with the plugin's stride.
int intersect(fb_trace_context* c, const fb_ray* ray, fb_hit* hit) {
  ++c->rays_traced;
  if (c->hit_size == sizeof(fb_hit))
    return c->geometry->intersect(*ray, *hit, &c->surfaces, c->footprint);
  fb_hit full{};
  const bool found = c->geometry->intersect(*ray, full, &c->surfaces, c->footprint);
  std::memcpy(hit, &full, c->hit_size);
  return found ? 1 : 0;
}

void intersect_batch(fb_trace_context* c, const fb_ray* rays, size_t count, fb_hit* hits) {
  c->rays_traced += count;
  FootprintSource footprints = c->footprint;
  if (rays == c->camera_rays && count == c->differentials.size())
    footprints.differential = c->differentials.data();
  if (c->hit_size == sizeof(fb_hit)) {
    c->geometry->intersect_coherent(rays, count, hits, &c->surfaces, footprints);
    return;
  }
  c->full_hits.assign(count, fb_hit{});
  c->geometry->intersect_coherent(rays, count, c->full_hits.data(), &c->surfaces, footprints);
  auto* out = reinterpret_cast<unsigned char*>(hits);
  for (size_t i = 0; i < count; ++i)
    std::memcpy(out + i * c->hit_size, &c->full_hits[i], c->hit_size);
}

// A record the integrator hands back, read as this host's fb_hit: no further than the fields of
// the plugin's layout, the fields it lacks zero (surface NULL: no surface).
const fb_hit& host_hit(const fb_trace_context* c, const fb_hit* hit, fb_hit& copy) {
  if (c->hit_size == sizeof(fb_hit)) return *hit;
  copy = read_covered(hit, fields_end(kHitLayouts, c->hit_size), fb_hit{});
  return copy;
}

int occluded(fb_trace_context* c, const fb_ray* ray) {
  ++c->rays_traced;
  return c->geometry->occluded(*ray) ? 1 : 0;
}

int sample_light(fb_trace_context* c, const float position[3], const float u[3],
                 fb_light_sample* sample) {
  return c->lights->sample(Vec3f(position), u, *sample) ? 1 : 0;
}

float light_pdf(fb_trace_context* c, const float position[3], const fb_hit* hit) {
  fb_hit copy;
  return c->lights->pdf(Vec3f(position), host_hit(c, hit, copy));
}

void next_samples(fb_trace_context* c, size_t path, float* u, uint32_t count) {
  c->sampler->fill(c->paths[path], u, count);
}

void background(fb_trace_context* c, const float direction[3], float radiance[3], float* pdf) {
  c->lights->background(Vec3f(direction), *pdf).store(radiance);
}

const Surface* surface_of(const fb_trace_context* c, const fb_hit* hit) {
  fb_hit copy;
  return reinterpret_cast<const Surface*>(host_hit(c, hit, copy).surface);
}

void bsdf_eval(fb_trace_context* c, const fb_hit* hit, const float wi[3], float f_cos[3],
               float* pdf) {
  const Surface* surface = surface_of(c, hit);
  *pdf = 0.f;
  (surface ? surface->eval(Vec3f(wi), *pdf) : Rgb{}).store(f_cos);
}

int bsdf_sample(fb_trace_context* c, const fb_hit* hit, const float u[3], fb_bsdf_sample* out) {
  const Surface* surface = surface_of(c, hit);
  SurfaceSample s;
  if (!surface || !surface->sample(u, s)) return 0;
  s.wi.store(out->wi);
  s.weight.store(out->weight);
  out->pdf = s.pdf;
  out->flags = (s.delta ? uint32_t(FB_BSDF_DELTA) : 0u) |
               (s.transmission ? uint32_t(FB_BSDF_TRANSMISSION) : 0u);
  return 1;
}

uint32_t lights_crossed(fb_trace_context* c, const fb_ray* ray, float t_end,
                        fb_light_crossing* crossings, uint32_t capacity) {
  return c->lights->crossed(*ray, t_end, crossings, capacity);
}

int sample_lamp(fb_trace_context* c, uint32_t lamp, const float position[3], const float u[2],
                fb_light_sample* sample) {
  return c->lights->sample_lamp(lamp, Vec3f(position), u, *sample) ? 1 : 0;
}

void closure_weight(fb_trace_context* c, const fb_hit* hit, uint32_t kind, float weight[3]) {
  const Surface* surface = surface_of(c, hit);
  Rgb sum{};
  if (surface && kind <= FB_CLOSURE_TRANSMISSION)
    sum = surface->closure_weight(static_cast<ClosureKind>(kind));
  sum.store(weight);
}

int medium_segment(fb_trace_context* c, const fb_ray* ray, float t_end, int povray_blend,
                   float transmittance[3], float emitted[3]) {
  if (!c->media) return 0;
  const MediumSegment s = c->media->along(
      *ray, t_end, povray_blend ? MediumModel::kPovRayBlend : MediumModel::kPhysical);
  s.transmittance.store(transmittance);
  s.emitted.store(emitted);
  return 1;
}

}  // namespace

static_assert(uint32_t(ClosureKind::kDiffuse) == FB_CLOSURE_DIFFUSE &&
              uint32_t(ClosureKind::kGlossy) == FB_CLOSURE_GLOSSY &&
              uint32_t(ClosureKind::kTransmission) == FB_CLOSURE_TRANSMISSION);

const fb_scene_api& host_scene_api() {
  static const fb_scene_api api{sizeof(fb_scene_api),
                                intersect,
                                intersect_batch,
                                occluded,
                                sample_light,
                                light_pdf,
                                next_samples,
                                background,
                                bsdf_eval,
                                bsdf_sample,
                                lights_crossed,
                                sample_lamp,
                                closure_weight,
                                medium_segment};
  return api;
}

}  // namespace fb
