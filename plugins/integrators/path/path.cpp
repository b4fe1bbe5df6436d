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
// to) adds its light along every segment and dims what lies beyond, shadow rays included.
#include <filmback/geometry.h>
#include <filmback/plugin_sdk.h>
#include <filmback/render_passes.h>
#include <filmback/sampling.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

using fb::Rgb;
using fb::Vec3f;

constexpr float kShadowEpsilon = 1e-4f;  // relative: shadow rays stop this short of the light

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

Rgb PathTracer::trace(const fb_scene& scene, fb_trace_context* ctx, size_t path, fb_ray ray,
                      fb_hit hit) const {
  const fb_scene_api& api = *scene.api;
  Rgb L{}, beta{1.f, 1.f, 1.f};
  float bsdf_pdf = 0.f;           // of the direction that produced `ray`
  bool delta = false;             // that direction came from a perfectly specular lobe
  float previous[3] = {0, 0, 0};  // where that direction was sampled
  const float time_s = ray.time_s;
  for (int depth = 0;; ++depth) {
    const bool found = depth == 0 ? !std::isinf(hit.t) : api.intersect(ctx, &ray, &hit) != 0;
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
        fb_ray shadow{};
        (above ? fb::offset_ray_origin(lifted, p_error, ng, ng)
               : fb::offset_ray_origin(p, p_error, ng, wi))
            .store(shadow.origin);
        wi.store(shadow.direction);
        shadow.t_max = std::isinf(ls.distance) ? HUGE_VALF : ls.distance * (1.f - kShadowEpsilon);
        shadow.time_s = time_s;
        // distance 0: a light that casts no shadows (fb_light_sample in plugin_abi.h).
        if (ls.distance == 0.f || !api.occluded(ctx, &shadow)) {
          // Where BSDF sampling never goes (pdf 0), light sampling takes the whole weight.
          const float weight = ls.is_delta ? 1.f : fb::power_heuristic(ls.pdf, pdf);
          const Rgb through =
              in_medium ? medium_transmittance(api, ctx, shadow, shadow.t_max) : Rgb{1.f, 1.f, 1.f};
          L += beta * Rgb(f) * Rgb(ls.radiance) * through * (weight / ls.pdf);
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

    if (depth + 1 >= rr_depth_) {
      // Cycles 3.4's rule (kernel/integrator/path_state.h, path_state_continuation_probability):
      // continue with probability min(1, sqrt(max throughput)). A survivor's throughput grows to
      // sqrt(beta) rather than to 1 as with min(1, beta), so a deep path that then finds a small
      // bright lamp brings a spike about 1 / sqrt(beta) times smaller; unbiased either way.
      float r;
      api.next_samples(ctx, path, &r, 1);
      const float survive = std::min(1.f, std::sqrt(fb::max_component(beta)));
      if (r >= survive) break;
      beta *= 1.f / survive;
    }
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
