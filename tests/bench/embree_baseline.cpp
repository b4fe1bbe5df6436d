#include "tests/bench/embree_baseline.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "core/render/render_loop.h"  // kTileSize
#include "core/render/sampler.h"

namespace fb::bench {

EmbreeBaseline::EmbreeBaseline(const Scene& scene, const SceneCamera& camera, uint32_t width_px,
                               uint32_t height_px)
    : width_(width_px), height_(height_px) {
  const PhysicalCamera& c = camera.physical;
  if (c.projection != FB_PROJECTION_PERSPECTIVE || c.sensor_fit != FB_SENSOR_FIT_AUTO ||
      c.shift_x != 0 || c.shift_y != 0 || c.clip_near_m != 0 || std::isfinite(c.clip_far_m) ||
      width_px < height_px || scene.instances.size() != 1)
    throw std::invalid_argument(
        "the baseline handles one instance and a landscape pinhole without shift or clipping");
  // Horizontal fit: the sensor width spans the image width (Blender's AUTO fit, landscape). The
  // operations are those of filmback/camera_projection.h, so that the rays agree to the bit.
  const double extent = c.sensor_width_mm / c.focal_length_mm,
               aspect = double(width_px) / height_px;
  fx_ = width_px / extent;
  fy_ = height_px / (extent / aspect);
  cx_ = width_px / 2.0, cy_ = height_px / 2.0;
  const Transform rotation = camera.world_from_camera.without_scale_and_translation();
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      render_from_camera_[r][k] = float(rotation(r, k));

  const MeshInstance& instance = scene.instances.front();
  const TriangleMesh& mesh = scene.meshes[instance.mesh];
  const Transform render_from_object =
      Transform::translate(-camera.world_from_camera.translation()) * instance.world_from_object;
  if (render_from_object.determinant3x3() < 0) throw std::invalid_argument("mirrored instance");
  for (const Vec3f& p : mesh.positions)
    positions_.emplace_back(render_from_object.point(Vec3d(p)));
  positions_.emplace_back();
  indices_ = mesh.indices;

  device_ = rtcNewDevice(nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);  // as filmback: watertight; MEDIUM quality
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             positions_.data(), 0, sizeof(Vec3f), positions_.size() - 1);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(),
                             0, 3 * sizeof(uint32_t), indices_.size() / 3);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree build failed");
}

EmbreeBaseline::~EmbreeBaseline() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

uint64_t EmbreeBaseline::trace(std::vector<float>& depth_m, uint32_t samples_per_pixel) const {
  depth_m.resize(size_t(width_) * height_);
  const uint32_t tiles_x = (width_ + kTileSize - 1) / kTileSize;
  const uint64_t tiles = uint64_t(tiles_x) * ((height_ + kTileSize - 1) / kTileSize);
  const Sampler sampler(kDefaultSampler, 0, samples_per_pixel, width_, height_);
  std::atomic<uint64_t> hits{0};
  tbb::parallel_for(
      tbb::blocked_range<uint64_t>(0, tiles, 1),
      [&](const tbb::blocked_range<uint64_t>& range) {
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);  // Embree wants these in every tracing thread
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (uint64_t tile = range.begin(); tile != range.end(); ++tile) {
          const uint32_t x0 = uint32_t(tile % tiles_x) * kTileSize,
                         y0 = uint32_t(tile / tiles_x) * kTileSize;
          uint64_t tile_hits = 0;
          // The pixels' sample seeds, hashed once per tile as filmback's render loop does.
          DimensionSeed seeds[kTileSize][kTileSize];
          for (uint32_t y = y0; y < std::min(y0 + kTileSize, height_); ++y)
            for (uint32_t x = x0; x < std::min(x0 + kTileSize, width_); ++x)
              seeds[y - y0][x - x0] = sampler.seed(x, y, kFilterDimension);
          for (uint32_t s = 0; s < samples_per_pixel; ++s)
            for (uint32_t y = y0; y < std::min(y0 + kTileSize, height_); ++y)
              for (uint32_t x = x0; x < std::min(x0 + kTileSize, width_); ++x) {
                // The box filter's sample, (2u - 1) r with r = 0.5 px, at filmback's sample key.
                const Vec2f u = sampler.get_2d(seeds[y - y0][x - x0], s);
                const float film_x = float(x) + 0.5f + (2.f * u.x - 1.f) * 0.5f;
                const float film_y = float(y) + 0.5f + (2.f * u.y - 1.f) * 0.5f;
                const float cam_x = float((film_x - cx_) / fx_),
                            cam_y = float(-(film_y - cy_) / fy_);
                const float inv_length = 1.f / std::sqrt(cam_x * cam_x + cam_y * cam_y + 1.f);
                const float d[3] = {cam_x * inv_length, cam_y * inv_length, -inv_length};
                const auto& m = render_from_camera_;
                RTCRayHit rh;
                rh.ray.org_x = rh.ray.org_y = rh.ray.org_z = 0.f;  // the camera is the origin
                rh.ray.dir_x = m[0][0] * d[0] + m[0][1] * d[1] + m[0][2] * d[2];
                rh.ray.dir_y = m[1][0] * d[0] + m[1][1] * d[1] + m[1][2] * d[2];
                rh.ray.dir_z = m[2][0] * d[0] + m[2][1] * d[1] + m[2][2] * d[2];
                rh.ray.tnear = 0.f;
                rh.ray.tfar = INFINITY;
                rh.ray.time = 0.f;
                rh.ray.mask = 0xffffffffu;
                rh.ray.id = 0;
                rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene_, &context, &rh);
                const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                tile_hits += hit;
                // depth along the view axis = t cos(theta), cos(theta) = inv_length
                if (s == 0)
                  depth_m[size_t(y) * width_ + x] = hit ? rh.ray.tfar * inv_length : kMissDepth;
              }
          hits += tile_hits;
        }
      },
      tbb::simple_partitioner());
  return hits;
}

}  // namespace fb::bench
