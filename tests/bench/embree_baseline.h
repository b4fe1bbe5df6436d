// The reference the benchmark measures filmback against: the same scene and the same camera rays
// traced with nothing but rtcIntersect1, in the same 16x16 tiles on the same TBB arena. The
// Embree scene is built here from the TriangleMesh, not borrowed from filmback's RenderGeometry.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "core/scene/scene.h"

namespace fb::bench {

class EmbreeBaseline {
 public:
  // Geometry goes into the camera-centred space filmback renders in (docs/conventions.md), narrowed
  // to float after the same double-precision transform, so both sides trace identical rays
  // against identical triangles.
  EmbreeBaseline(const Scene& scene, const SceneCamera& camera, uint32_t width_px,
                 uint32_t height_px);
  ~EmbreeBaseline();
  EmbreeBaseline(const EmbreeBaseline&) = delete;
  EmbreeBaseline& operator=(const EmbreeBaseline&) = delete;

  // `samples_per_pixel` pinhole rays per pixel through the film positions filmback's box filter
  // (radius 0.5 px) samples with seed 0. Writes each pixel's depth along the view axis for sample
  // 0 (kMissDepth when the ray escapes) and returns the number of hits of all samples.
  uint64_t trace(std::vector<float>& depth_m, uint32_t samples_per_pixel) const;

  static constexpr float kMissDepth = 1e10f;  // as the aov integrator's Z channel

 private:
  uint32_t width_, height_;
  double fx_, fy_, cx_, cy_;  // raster = (cx + fx X / -Z, cy - fy Y / -Z)
  float render_from_camera_[3][3];
  std::vector<Vec3f> positions_;  // one element of padding: Embree reads 16 bytes per vertex
  std::vector<uint32_t> indices_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace fb::bench
