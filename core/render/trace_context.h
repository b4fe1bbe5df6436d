// The host side of the integrator ABI: fb_scene_api's functions and the per-thread context they
// run on. One context per worker batch; it counts the rays it traces for the summary line.
#pragma once

#include <cstdint>
#include <vector>

#include <filmback/plugin_abi.h>

#include "core/accel/render_geometry.h"
#include "core/render/global_medium_segment.h"
#include "core/render/light_sampler.h"
#include "core/render/sampler.h"
#include "core/shading/surface_arena.h"
#include "core/texture/ray_footprint.h"

struct fb_trace_context {
  const fb::RenderGeometry* geometry = nullptr;
  const fb::LightSampler* lights = nullptr;
  const fb::Sampler* sampler = nullptr;
  const fb::RenderMedia* media = nullptr;  // none: the scene has no global medium
  std::vector<fb::SampleKey> paths;        // one per ray of the current batch
  fb::SurfaceArena surfaces;               // of the hits the current batch traces (fb_hit.surface)
  // The integrator's fb_hit size (fb_integrator_api.hit_size): smaller when it was built against
  // an older header, whose records the host writes and reads no further (plugin_abi.h, "Growth").
  uint32_t hit_size = sizeof(fb_hit);
  std::vector<fb_hit> full_hits;  // a batch traced at this host's size, for such an integrator
  // Texture footprints (core/texture/ray_footprint.h). The render loop's batch of camera rays
  // (known by its address, which integrators pass on to intersect_batch) has one differential
  // per ray; every other ray, and all of them when `differentials` is empty, the camera's
  // spread. `footprint.differential` stays null: the spread and the scale are what it holds.
  const fb_ray* camera_rays = nullptr;
  std::vector<fb::RayDifferential> differentials;
  fb::FootprintSource footprint;
  uint64_t rays_traced = 0;
};

namespace fb {

const fb_scene_api& host_scene_api();

}  // namespace fb
