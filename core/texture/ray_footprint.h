// A ray's footprint on the surface it hits, for filtered texture lookups (ray differentials: Igehy
// 1999, "Tracing Ray Differentials"; pbrt-v4 §10.1). Camera rays carry exact differentials: the
// rays through the raster positions one pixel right and one pixel down, asked of the camera plugin
// with the same lens sample and time, so every projection and lens distortion is covered. Other
// rays use pbrt-v4's approximation (CameraBase::Approximate_dp_dxy): the footprint the camera's
// narrowest pixel would have at the hit's distance from the camera. The result is the change of
// each texture coordinate set per raster pixel, which OpenImageIO turns into a MIP level and an
// anisotropic filter (core/texture/texture_images.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include <filmback/vec.h>

#include "core/texture/surface_point.h"

namespace fb {

// The neighbours of a camera ray in render space, as offsets from it: the ray through raster
// position (x + 1, y) starts at origin + dx_origin and points along direction + dx_direction
// (directions as the camera made them, not necessarily unit).
struct RayDifferential {
  Vec3f dx_origin{}, dx_direction{}, dy_origin{}, dy_direction{};
};

// The camera's narrowest pixel (pbrt-v4's minPosDifferential and minDirDifferential): how far
// apart neighbouring camera rays start (m) and how far their unit directions differ (radians, for
// small angles). Both zero: no footprint, textures read at their finest level.
struct PixelSpread {
  float origin_m = 0.f;
  float direction_rad = 0.f;
  bool empty() const { return !(origin_m > 0.f) && !(direction_rad > 0.f); }
};

// What the footprint of a ray is computed from: its camera differential when it has one, otherwise
// the camera's spread at the hit's distance from the camera (the render-space origin). `scale`
// shrinks both for pixel supersampling: with n samples a pixel, each sample need only filter over
// about 1/sqrt(n) of a pixel, at most 8 times narrower (pbrt-v4's
// max(1/8, 1/sqrt(samplesPerPixel)), CameraBase::GenerateRayDifferential's scaling).
struct FootprintSource {
  const RayDifferential* differential = nullptr;
  PixelSpread spread{};
  float scale = 1.f;
  bool empty() const { return !differential && spread.empty(); }
  // For a batch of rays, `differential` points at one per ray: ray i's source.
  FootprintSource at(size_t i) const {
    return {differential ? differential + i : nullptr, spread, scale};
  }
};

// pbrt-v4's scale for `samples_per_pixel` (see FootprintSource::scale).
float footprint_scale(uint32_t samples_per_pixel);

// dp/dx and dp/dy: how far the hit at `position` on the plane of unit normal `normal` moves per
// raster pixel, for a ray from `ray_origin` along `ray_direction` (pbrt-v4
// SurfaceInteraction::ComputeDifferentials: the neighbouring rays met with the tangent plane).
// False, and no footprint, when the source is empty or the neighbours miss the plane.
bool position_differentials(const FootprintSource& source, Vec3f ray_origin, Vec3f ray_direction,
                            Vec3f position, Vec3f normal, Vec3f& dp_dx, Vec3f& dp_dy);

// Fills point.duv_dx and point.duv_dy for a hit on the triangle with corners p[3], vertices
// corner[3] of `data` (point.uv_sets texture coordinate sets): dp/dx written as a combination of
// the two edges (least squares, as pbrt-v4 solves for du/dx), carried to every set through its
// corners' coordinates. A degenerate triangle leaves them zero.
void set_texture_differentials(const Vec3f p[3], const uint32_t corner[3],
                               const VertexTextureData& data, Vec3f dp_dx, Vec3f dp_dy,
                               SurfacePoint& point);

}  // namespace fb
