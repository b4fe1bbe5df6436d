// Integrator `path`: unidirectional path tracing with next-event estimation (Kajiya 1986;
// Veach 1997 ch. 9). Surfaces scatter as the host prepared them at each hit (fb_scene_api's
// bsdf_eval and bsdf_sample: glTF's metallic-roughness model, or Blender's materials as Cycles
// renders them); light comes from punctual lights, lights with a size (which rays pass through),
// emissive triangles and the world (uniform, or an environment image that light sampling also
// picks). Emission found by BSDF sampling and by light sampling is combined with the power
// heuristic; delta lights are reached by light sampling only. Russian roulette from bounce
// `rr_depth` on (Cycles' rule, below) keeps it unbiased. `clamp`, off by default, scales each
// sample's radiance down so that its largest component is at most the clamp (pbrt 4e's RGBFilm
// maxComponentValue): fireflies are bounded at the price of a bias. `passes` (what --passes sets:
// Blender's pass names, comma-separated) adds those render passes of the first hit as further
// channels (filmback/render_passes.h); none by default, and then none is computed. A scene's
// medium (fb_scene_api::medium_segment: POV-Ray's fog as the absorbing, emitting medium it maps
// to) adds its light along every segment and dims what lies beyond, shadow rays included. An
// object's interior medium (fb_scene::media, POV-Ray's media) absorbs, emits (in closed form) and
// scatters isotropically (a free flight from the mean extinction, next-event estimation at the
// collision); shadow rays of such a scene pass through the clear surfaces that hold media.
#include <filmback/geometry.h>
#include <filmback/interior_media.h>
#include <filmback/plugin_sdk.h>
#include <filmback/render_passes.h>
#include <filmback/sampling.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

using fb::Rgb;
using fb::Vec3f;

// Surfaces a shadow ray passes through in a scene with media before it counts as blocked (a bound
// on untrusted scenes).
constexpr int kMostMediumShadowSurfaces = 64;
// Clear boundaries (fb::is_clear_boundary) a path crosses in all, which are not bounces.
constexpr int kMostBoundaryCrossings = 256;
constexpr float kIsotropicPhase = 0.25f * std::numbers::inv_pi_v<float>;  // 1 / (4 pi) sr^-1

constexpr fb_param_desc kParams[] = {
    {"max_depth", FB_PARAM_INT, "8", "", nullptr, 0, 1024,
     "most bounces a path takes (0: emitters only, 1: direct light)"},
    {"rr_depth", FB_PARAM_INT, "1", "", nullptr, 1, 1024,
     "bounces before Russian roulette may end a path (1: from the first bounce, as Cycles)"},
    {"clamp", FB_PARAM_FLOAT, "0", "W/sr/m^2", nullptr, 0, HUGE_VAL,
     "largest component a sample's radiance may have (scaled down to it: biased); 0 is off"},
    {"passes", FB_PARAM_STRING, "", "", nullptr, 0, 0,
     "Blender render passes of the first hit to add as channels, comma-separated (--passes)"},
};
constexpr auto kMaxDepth = fb::param<int>(kParams, "max_depth");
constexpr auto kRrDepth = fb::param<int>(kParams, "rr_depth");
constexpr auto kClamp = fb::param<float>(kParams, "clamp");
constexpr auto kPasses = fb::param<const char*>(kParams, "passes");

class PathTracer {
 public:
  explicit PathTracer(const fb_value* values)
      : max_depth_(kMaxDepth(values)),
        rr_depth_(kRrDepth(values)),
        clamp_(kClamp(values)),
        passes_(fb::parse_render_passes(kPasses(values))),
        channels_{"R", "G", "B"} {
    for (const fb::RenderPass* pass : passes_)
      for (const char* c = pass->channels; *c; ++c)
        channels_.push_back(fb::pass_channel_name(pass->name, *c));
  }
  const std::vector<std::string>& channel_names() const { return channels_; }
  void radiance(const fb_scene& scene, fb_trace_context* ctx, const fb_ray* rays, size_t count,
                float* values) const {
    const fb_hit* hits = fb::first_hits(scene, ctx, rays, count);
    const size_t stride = channels_.size();
    for (size_t i = 0; i < count; ++i) {
      float* v = values + stride * i;
      for (const fb::RenderPass* pass : passes_) {
        fb::first_hit_pass_values(*pass, scene, ctx, rays[i], hits[i], v + 3);
        v += std::char_traits<char>::length(pass->channels);
      }
      clamped(trace(scene, ctx, i, rays[i], hits[i])).store(values + stride * i);
    }
  }

 private:
  Rgb trace(const fb_scene& scene, fb_trace_context* ctx, size_t path, fb_ray ray,
            fb_hit hit) const;
  // The sample's radiance scaled by clamp / max(L) where that is below 1. A non-finite sample is
  // left for the film to drop and count.
  Rgb clamped(Rgb L) const {
    const float largest = fb::max_component(L);
    return clamp_ > 0.f && largest > clamp_ && std::isfinite(largest) ? L * (clamp_ / largest) : L;
  }
  int max_depth_;  // bounces; 0 shows emitters only
  int rr_depth_;
  float clamp_;                                // W sr^-1 m^-2; 0: off
  std::vector<const fb::RenderPass*> passes_;  // what `passes` asks for, in the table's order
  std::vector<std::string> channels_;          // R, G, B, then each pass's
};

// Emission leaving the hit towards -direction: front faces only, unless the material is two-sided.
Rgb emitted(const fb_material& m, const fb_hit& hit, Vec3f direction) {
  if (!m.double_sided && fb::dot(Vec3f(hit.geometric_normal), direction) > 0.f) return {};
  return Rgb(hit.emission);
}

// The share of the light that the scene's medium (POV-Ray's fog as the physical medium it maps
// to, docs/pov.md "Fog") lets through along `ray` up to `t_end`; 1 without one.
Rgb medium_transmittance(const fb_scene_api& api, fb_trace_context* ctx, const fb_ray& ray,
                         float t_end) {
  float transmittance[3], emitted[3];
  if (!api.medium_segment(ctx, &ray, t_end, 0, transmittance, emitted)) return {1.f, 1.f, 1.f};
  return Rgb(transmittance);
}

// Light from the lights with a size that the ray from the previous vertex passed through before
// `t_end` (fb_scene_api::lights_crossed), weighted against light sampling's choice of them, and
// dimmed by the medium before each when the scene has one (`in_medium`).
Rgb lights_on_the_way(const fb_scene_api& api, fb_trace_context* ctx, const fb_ray& ray,
                      float t_end, float bsdf_pdf, bool delta, bool in_medium) {
  fb_light_crossing crossings[8];
  const uint32_t n = api.lights_crossed(ctx, &ray, t_end, crossings, 8);
  Rgb L{};
  for (uint32_t i = 0; i < n; ++i) {
    const Rgb through =
        in_medium ? medium_transmittance(api, ctx, ray, crossings[i].t) : Rgb{1.f, 1.f, 1.f};
    L += Rgb(crossings[i].radiance) * through *
         (delta ? 1.f : fb::power_heuristic(bsdf_pdf, crossings[i].pdf));
  }
  return L;
}

// What a shadow ray lets through in a scene with interior media: each medium it crosses dims it
// by e^(-sigma_t d) (fb::segment_medium follows which one it is in), and a surface passes it only
// where it is clear, fully transmitting with ior 1 (a POV-Ray container such as `hollow` with
// `rgbt 1`), tinted by its colour; any other surface blocks it.
Rgb through_interior_media(const fb_scene& scene, fb_trace_context* ctx, const fb_ray& shadow) {
  return fb::shadow_ray_through(
      scene, ctx, shadow, kMostMediumShadowSurfaces,
      [](const fb_hit& hit) { return fb::is_clear_boundary(hit) ? Rgb(hit.base_color) : Rgb{}; },
      [](const fb_medium& m) { return Rgb(m.absorption) + Rgb(m.scattering); });
}

// How much of a light a shadow ray sees: all or nothing, or through interior media in a scene
// that has them; a light of distance 0 casts no shadows (fb_light_sample in plugin_abi.h).
Rgb shadow_visibility(const fb_scene& scene, fb_trace_context* ctx, const fb_ray& shadow,
                      float distance) {
  if (distance == 0.f) return {1.f, 1.f, 1.f};
  if (scene.media != nullptr) return through_interior_media(scene, ctx, shadow);
  return scene.api->occluded(ctx, &shadow) ? Rgb{} : Rgb{1.f, 1.f, 1.f};
}

// Light scattered towards the path at `point` in an interior medium, per unit sigma_s: a light
// sampled as from a surface, times the isotropic phase 1 / (4 pi), weighted against sampling the
// phase (power heuristic), and dimmed by the fog on the way when the scene has one.
Rgb light_at_medium_point(const fb_scene& scene, fb_trace_context* ctx, size_t path, Vec3f point,
                          float time_s, bool in_fog) {
  const fb_scene_api& api = *scene.api;
  float u[3], position[3];
  point.store(position);
  api.next_samples(ctx, path, u, 3);
  fb_light_sample ls;
  if (!api.sample_light(ctx, position, u, &ls) || !(ls.pdf > 0.f)) return {};
  const fb_ray shadow = fb::shadow_ray_to_light(point, ls.direction, ls.distance, time_s);
  Rgb through = shadow_visibility(scene, ctx, shadow, ls.distance);
  if (!(fb::max_component(through) > 0.f)) return {};
  if (in_fog) through *= medium_transmittance(api, ctx, shadow, shadow.t_max);
  const float weight = ls.is_delta ? 1.f : fb::power_heuristic(ls.pdf, kIsotropicPhase);
  return Rgb(ls.radiance) * through * (kIsotropicPhase * weight / ls.pdf);
}

// Cycles 3.4's rule (kernel/integrator/path_state.h, path_state_continuation_probability):
// continue with probability min(1, sqrt(max throughput)). A survivor's throughput grows to
// sqrt(beta) rather than to 1 as with min(1, beta), so a deep path that then finds a small bright
// lamp brings a spike about 1 / sqrt(beta) times smaller; unbiased either way.
bool survives_roulette(const fb_scene_api& api, fb_trace_context* ctx, size_t path, Rgb& beta) {
  float r;
  api.next_samples(ctx, path, &r, 1);
  const float survive = std::min(1.f, std::sqrt(fb::max_component(beta)));
  if (r >= survive) return false;
  beta *= 1.f / survive;
  return true;
}

Rgb PathTracer::trace(const fb_scene& scene, fb_trace_context* ctx, size_t path, fb_ray ray,
                      fb_hit hit) const {
  const fb_scene_api& api = *scene.api;
  Rgb L{}, beta{1.f, 1.f, 1.f};
  float bsdf_pdf = 0.f;           // of the direction that produced `ray`
  bool delta = false;             // that direction came from a perfectly specular lobe
  float previous[3] = {0, 0, 0};  // where that direction was sampled
  const float time_s = ray.time_s;
  uint32_t inside = FB_NONE;  // the interior medium the ray starts in (fb::segment_medium)
  int crossings = 0;          // clear boundaries crossed
  bool batch_hit = true;      // `hit` is the camera ray's, traced with the batch
  for (int depth = 0;; ++depth) {
    const bool found = batch_hit ? !std::isinf(hit.t) : api.intersect(ctx, &ray, &hit) != 0;
    batch_hit = false;
    const float t_end = found ? hit.t : HUGE_VALF;
    // The scene's medium over the segment, if it has one: it adds its own light, and dims what
    // comes from further on (the absorbing, emitting medium POV-Ray's fog maps to).
    float segment_transmittance[3], segment_emitted[3];
    const bool in_medium =
        api.medium_segment(ctx, &ray, t_end, 0, segment_transmittance, segment_emitted) != 0;
    // Cycles' lights are not seen by the camera; BSDF-sampled rays find those with a size.
    if (depth > 0) L += beta * lights_on_the_way(api, ctx, ray, t_end, bsdf_pdf, delta, in_medium);
    if (in_medium) {
      L += beta * Rgb(segment_emitted);
      beta *= Rgb(segment_transmittance);
    }
    // An object's interior medium over the segment: its emission in closed form, and its
    // attenuation, in closed form too unless it scatters: then a free flight either passes to the
    // hit or scatters the path at a point inside.
    const uint32_t medium = found && scene.media != nullptr
                                ? fb::segment_medium(scene, inside, hit, ray.direction)
                                : FB_NONE;
    if (medium != FB_NONE) {
      const fb_medium& m = *fb::interior_medium(scene, medium);
      const Rgb sigma_t = Rgb(m.absorption) + Rgb(m.scattering);
      const float length = hit.t * fb::length(Vec3f(ray.direction));
      const fb::HomogeneousSegment segment =
          fb::homogeneous_segment(sigma_t, Rgb(m.emission), length);
      L += beta * segment.emitted;
      if (!(fb::max_component(Rgb(m.scattering)) > 0.f)) {
        beta *= segment.transmittance;
      } else {
        float u;
        api.next_samples(ctx, path, &u, 1);
        const fb::FreeFlight flight = fb::free_flight(sigma_t, Rgb(m.scattering), length, u);
        beta *= flight.weight;
        if (flight.collided) {
          if (depth >= max_depth_) break;
          const Vec3f point =
              Vec3f(ray.origin) + fb::normalize(Vec3f(ray.direction)) * flight.distance_m;
          L += beta * light_at_medium_point(scene, ctx, path, point, time_s, in_medium);
          float v[2];
          api.next_samples(ctx, path, v, 2);
          const Vec3f wi = fb::sample_uniform_sphere({v[0], v[1]});  // phase / pdf = 1
          bsdf_pdf = kIsotropicPhase;
          delta = false;
          point.store(previous);
          if (depth + 1 >= rr_depth_ && !survives_roulette(api, ctx, path, beta)) break;
          ray = {};
          point.store(ray.origin);
          wi.store(ray.direction);
          ray.t_max = HUGE_VALF;
          ray.time_s = time_s;
          inside = medium;
          continue;
        }
      }
    }
    // In a scene with media, a clear surface (a container's) is crossed straight on, into or out
    // of its medium, tinted by its colour: not a bounce, and the direction's pdf is unchanged.
    if (found && scene.media != nullptr && fb::is_clear_boundary(hit)) {
      if (++crossings > kMostBoundaryCrossings) break;
      beta *= Rgb(hit.base_color);
      inside = fb::medium_after_crossing(scene, medium, hit, ray.direction);
      const Vec3f d(ray.direction);
      fb::offset_ray_origin(Vec3f(hit.position), Vec3f(hit.position_error),
                            Vec3f(hit.geometric_normal), d)
          .store(ray.origin);
      if (std::isfinite(ray.t_max)) ray.t_max -= hit.t;  // a camera ray's far clip stays put
      --depth;
      continue;
    }
    if (!found) {
      float le[3], world_pdf = 0.f;
      api.background(ctx, ray.direction, le, &world_pdf);
      const float weight =
          depth == 0 || delta || world_pdf == 0.f ? 1.f : fb::power_heuristic(bsdf_pdf, world_pdf);
      L += beta * Rgb(le) * weight;
      break;
    }
    const fb_material& m = scene.materials[hit.material];
    const Vec3f wo_world = -Vec3f(ray.direction);
    if (fb::max_component(Rgb(hit.emission)) > 0.f) {
      const Rgb Le = emitted(m, hit, Vec3f(ray.direction));
      // Emission that light sampling does not know (hit.emitter == FB_NONE: the host registers
      // every emissive triangle today, but the ABI allows it) counts with full weight.
      const float weight = depth == 0 || delta || hit.emitter == FB_NONE
                               ? 1.f
                               : fb::power_heuristic(bsdf_pdf, api.light_pdf(ctx, previous, &hit));
      L += beta * Le * weight;
    }
    if (depth >= max_depth_) break;

    // The side the ray arrived from; the geometric normal decides which side that is.
    Vec3f ng(hit.geometric_normal), ns(hit.shading_normal);
    if (fb::dot(ng, wo_world) < 0.f) ng = -ng, ns = -ns;
    const Vec3f p(hit.position), p_error(hit.position_error);

    // Light arriving above the shading normal but below the flat facet (the terminator of a
    // coarse mesh with smooth normals) is not refused: its shadow ray leaves from the hit lifted
    // onto the smooth surface (fb_hit.shadow_position, Hanika 2021), on the side being shaded, and
    // the object itself decides whether it is in shadow.
    Vec3f lifted(hit.shadow_position);
    if (dot(lifted - p, ng) < 0.f) lifted = p;  // lifted towards the other side: not ours

    float u[3];
    api.next_samples(ctx, path, u, 3);
    fb_light_sample ls;
    if (api.sample_light(ctx, hit.position, u, &ls) && ls.pdf > 0.f) {
      const Vec3f wi(ls.direction);
      float f[3], pdf = 0.f;
      api.bsdf_eval(ctx, &hit, ls.direction, f, &pdf);
      if (fb::max_component(Rgb(f)) > 0.f) {
        const bool above = fb::dot(ns, wi) > 0.f;
        const fb_ray shadow =
            fb::shadow_ray_to_light(above ? fb::offset_ray_origin(lifted, p_error, ng, ng)
                                          : fb::offset_ray_origin(p, p_error, ng, wi),
                                    ls.direction, ls.distance, time_s);
        const Rgb visible = shadow_visibility(scene, ctx, shadow, ls.distance);
        if (fb::max_component(visible) > 0.f) {
          // Where BSDF sampling never goes (pdf 0), light sampling takes the whole weight.
          const float weight = ls.is_delta ? 1.f : fb::power_heuristic(ls.pdf, pdf);
          const Rgb through =
              in_medium ? medium_transmittance(api, ctx, shadow, shadow.t_max) : Rgb{1.f, 1.f, 1.f};
          L += beta * Rgb(f) * Rgb(ls.radiance) * visible * through * (weight / ls.pdf);
        }
      }
    }

    float v[3];
    api.next_samples(ctx, path, v, 3);
    fb_bsdf_sample s;
    if (!api.bsdf_sample(ctx, &hit, v, &s)) break;
    const Vec3f wi(s.wi);
    beta *= Rgb(s.weight);
    bsdf_pdf = s.pdf;
    delta = (s.flags & FB_BSDF_DELTA) != 0;
    p.store(previous);
    // Through the surface the ray leaves or enters a medium; reflected, it stays in this one.
    inside = (s.flags & FB_BSDF_TRANSMISSION) != 0
                 ? fb::medium_after_crossing(scene, medium, hit, ray.direction)
                 : medium;

    if (depth + 1 >= rr_depth_ && !survives_roulette(api, ctx, path, beta)) break;
    ray = {};
    fb::offset_ray_origin(p, p_error, ng, wi).store(ray.origin);
    wi.store(ray.direction);
    ray.t_max = HUGE_VALF;
    ray.time_s = time_s;
  }
  return L;
}

constexpr fb_integrator_api kApi = fb::integrator_api<PathTracer>();
constexpr fb_plugin kPlugin =
    fb::describe("path", "1.0.0",
                 "Path tracing with next-event estimation and MIS over the host's surfaces, "
                 "emission, lights and world",
                 kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
