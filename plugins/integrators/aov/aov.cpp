// Integrator `aov`: what the camera ray hits, one ray per sample. Channels: the base colour at the
// hit as the host's surface shader evaluated it (albedo.R/G/B: fb_hit.base_color, textures and
// KHR_texture_transform applied, the value the path integrator's BSDF uses; not the material's
// untextured factor), the world-space shading normal (N.X/Y/Z) and the depth along the view axis
// (Z, as Blender's depth pass: not the distance along the ray). R, G, B show one of them, chosen by
// `show`. Rays that escape get albedo 0, normal 0 and depth 1e10 m, as in Cycles.
#include <filmback/plugin_sdk.h>
#include <filmback/vec.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>

namespace {

constexpr float kMissDepth = 1e10f;
enum class Show { kAlbedo, kNormal, kDepth };

constexpr fb_param_desc kParams[] = {
    {"show", FB_PARAM_STRING, "albedo", "", "albedo|normal|depth", 0, 0,
     "which AOV the R, G, B channels (and a PNG) show; normals as 0.5 + 0.5 n"},
};
constexpr auto kShow = fb::param<const char*>(kParams, "show");

class Aov {
 public:
  static constexpr const char* kChannels[] = {"R",        "G",   "B",   "albedo.R", "albedo.G",
                                              "albedo.B", "N.X", "N.Y", "N.Z",      "Z"};

  explicit Aov(const fb_value* values) {
    const char* show = kShow(values);
    show_ = std::strcmp(show, "normal") == 0  ? Show::kNormal
            : std::strcmp(show, "depth") == 0 ? Show::kDepth
                                              : Show::kAlbedo;
  }

  void radiance(const fb_scene& scene, fb_trace_context* ctx, const fb_ray* rays, size_t count,
                float* values) const {
    const fb_hit* hits = fb::first_hits(scene, ctx, rays, count);
    for (size_t i = 0; i < count; ++i)
      shade(scene, hits[i], values + i * std::size(kChannels));
  }

 private:
  void shade(const fb_scene& scene, const fb_hit& hit, float* v) const {
    if (std::isinf(hit.t)) {
      std::fill(v, v + std::size(kChannels), 0.f);
      v[9] = kMissDepth;
      return;
    }
    for (int c = 0; c < 3; ++c)
      v[3 + c] = hit.base_color[c], v[6 + c] = hit.shading_normal[c];
    v[9] = fb::dot(fb::Vec3f(hit.position), fb::Vec3f(scene.view_axis));
    for (int c = 0; c < 3; ++c) {
      switch (show_) {
        case Show::kAlbedo:
          v[c] = v[3 + c];
          break;
        case Show::kNormal:
          v[c] = 0.5f + 0.5f * v[6 + c];
          break;
        case Show::kDepth:
          v[c] = v[9];
          break;
      }
    }
  }

  Show show_;
};

constexpr fb_integrator_api kApi = fb::integrator_api<Aov>();
constexpr fb_plugin kPlugin =
    fb::describe("aov", "1.0.0", "Depth, normal and albedo of what camera rays hit", kParams, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
