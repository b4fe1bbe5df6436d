// Blender's render passes (docs/blender.md, "Passes"): which ones filmback writes beside the
// beauty, their channels as Blender's multi-layer EXR names them ("ViewLayer.Depth.Z"), how the
// film resolves each, and their values at a camera ray's first hit. One table for the host (which
// checks --passes and picks each channel's filtering) and for integrators (which compute them).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "plugin_abi.h"
#include "vec.h"

namespace fb {

// How the film resolves a pass's channels: the pixel filter's weighted mean (as the beauty), or
// the nearest of the pixel's samples (a depth averaged with the background would be a depth where
// nothing is).
enum class PassFiltering { kWeightedMean, kNearest };

struct RenderPass {
  const char* name;      // Blender's pass name, as --passes takes it
  const char* channels;  // Blender's channel letters, one per channel
  PassFiltering filtering;
};

// Blender 3.4's names (a Cycles render written with `blender -b` to a multi-layer EXR; the two
// Denoising passes from Blender's source, as Debian's Blender has no OpenImageDenoise).
inline constexpr RenderPass kRenderPasses[] = {
    {"Depth", "Z", PassFiltering::kNearest},
    {"Normal", "XYZ", PassFiltering::kWeightedMean},
    {"DiffCol", "RGB", PassFiltering::kWeightedMean},
    {"GlossCol", "RGB", PassFiltering::kWeightedMean},
    {"Emit", "RGB", PassFiltering::kWeightedMean},
    {"Denoising Albedo", "RGB", PassFiltering::kWeightedMean},
    {"Denoising Normal", "XYZ", PassFiltering::kWeightedMean},
};

inline constexpr const char* kViewLayer = "ViewLayer";  // Blender's default view layer
inline constexpr float kMissDepthM = 1e10f;             // Cycles' depth where nothing was hit

inline const RenderPass* find_render_pass(std::string_view name) {
  for (const RenderPass& pass : kRenderPasses)
    if (name == pass.name) return &pass;
  return nullptr;
}

// "ViewLayer.<pass>.<channel>", Blender's multi-layer EXR channel name.
inline std::string pass_channel_name(std::string_view pass, char channel) {
  return std::string(kViewLayer) + "." + std::string(pass) + "." + channel;
}

// The filtering of a channel named as pass_channel_name() names it; anything else (the beauty, an
// integrator's own channels) is a weighted mean.
inline PassFiltering channel_filtering(std::string_view channel) {
  for (const RenderPass& pass : kRenderPasses)
    for (const char* c = pass.channels; *c; ++c)
      if (channel == pass_channel_name(pass.name, *c)) return pass.filtering;
  return PassFiltering::kWeightedMean;
}

// The values of `pass` at a camera ray's first hit (hit.t infinite: a miss), written to out[0..),
// one per channel. As Cycles 3.4 defines them (kernel/film/data_passes.h, denoising_passes.h):
//  - Depth: the hit's depth along the view axis (camera_z_depth), kMissDepthM for a miss;
//  - Normal: the world-space shading normal (normal map applied), 0 for a miss;
//  - DiffCol, GlossCol: the summed weights of the surface's diffuse and glossy closures
//    (fb_scene_api::closure_weight; for a principled surface the diffuse one is base colour x
//    (1 - metallic) x (1 - transmission), the glossy one white, its Fresnel not included);
//  - Emit: the radiance the surface emits towards the camera (front faces, or both if two-sided);
//  - Denoising Albedo: the textured base colour (Cycles sums its closures' albedos, which for a
//    principled surface is near it);
//  - Denoising Normal: as Normal, in world space; the host turns the resolved pixels into Cycles'
//    camera space (core/render/blender_layers.h), which the integrator does not know.
// Unlike Cycles' Denoising passes, these do not follow rays through perfectly specular surfaces.
inline void first_hit_pass_values(const RenderPass& pass, const fb_scene& scene,
                                  fb_trace_context* context, const fb_ray& ray, const fb_hit& hit,
                                  float* out) {
  const std::string_view name = pass.name;
  const bool miss = std::isinf(hit.t);
  if (name == "Depth") {
    out[0] = miss ? kMissDepthM : dot(Vec3f(hit.position), Vec3f(scene.view_axis));
    return;
  }
  Vec3f v{};
  if (!miss) {
    if (name == "Normal" || name == "Denoising Normal") {
      v = Vec3f(hit.shading_normal);
    } else if (name == "DiffCol" || name == "GlossCol") {
      float weight[3];
      scene.api->closure_weight(context, &hit,
                                name == "DiffCol" ? FB_CLOSURE_DIFFUSE : FB_CLOSURE_GLOSSY, weight);
      v = Vec3f(weight);
    } else if (name == "Emit") {
      const bool front = dot(Vec3f(hit.geometric_normal), Vec3f(ray.direction)) <= 0.f;
      if (front || scene.materials[hit.material].double_sided) v = Vec3f(hit.emission);
    } else if (name == "Denoising Albedo") {
      v = Vec3f(hit.base_color);
    }
  }
  v.store(out);
}

// The passes named in a comma-separated list, in the table's order; unknown names are skipped
// (the host refuses them before an integrator sees the list).
inline std::vector<const RenderPass*> parse_render_passes(std::string_view list) {
  std::vector<const RenderPass*> passes;
  for (const RenderPass& pass : kRenderPasses) {
    for (size_t start = 0; start <= list.size();) {
      const size_t comma = std::min(list.find(',', start), list.size());
      if (list.substr(start, comma - start) == pass.name) {
        passes.push_back(&pass);
        break;
      }
      start = comma + 1;
    }
  }
  return passes;
}

}  // namespace fb
