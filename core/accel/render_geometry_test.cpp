#include "core/accel/render_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fb {
namespace {

// A grid of n x n quads in the plane z = 0: 2 n² triangles.
Scene grid_scene(uint32_t n) {
  Scene scene;
  TriangleMesh mesh;
  for (uint32_t y = 0; y <= n; ++y)
    for (uint32_t x = 0; x <= n; ++x)
      mesh.positions.push_back({float(x), float(y), 0.f});
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t i = y * (n + 1) + x;
      mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + n + 2, i, i + n + 2, i + n + 1});
    }
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, Transform(), "grid"});
  scene.materials.push_back({});
  return scene;
}

// live_bytes() is what `filmback bench` reports as geometry and BVH: at least the render-space
// vertices and indices, plus a BVH Embree reports through its memory monitor, and all of it given
// back when the geometry goes.
TEST(RenderGeometry, LiveBytesCountItsArraysAndTheBvhAndReturnWhenItIsDestroyed) {
  const Scene scene = grid_scene(100);
  const size_t before = RenderGeometry::live_bytes();
  const size_t arrays = scene.meshes[0].positions.size() * sizeof(Vec3f) +
                        scene.meshes[0].indices.size() * sizeof(uint32_t);
  {
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    const size_t held = RenderGeometry::live_bytes() - before;
    EXPECT_GT(held, arrays + 20000 * 16);  // Embree 3: tens of bytes of BVH per triangle
    EXPECT_LT(held, arrays + 20000 * 1000);
  }
  EXPECT_EQ(RenderGeometry::live_bytes(), before);
}

// A unit sphere as an analytic solid (POV-Ray's sphere), its material partly transparent.
Scene transparent_sphere(AlphaMode mode, float alpha) {
  Scene scene;
  Material m;
  m.alpha_mode = mode;
  m.alpha = alpha;
  scene.materials.push_back(m);
  Solid sphere;
  sphere.kind = SolidKind::kSphere;
  scene.solids.push_back(sphere);
  return scene;
}

// Rays from z = -5 through the sphere, spread over its middle (each crosses two surfaces).
fb_ray ray_through(int i, int n) {
  const float x = 0.5f * (float(i % n) / float(n) - 0.5f), y = 0.5f * (float(i / n) / n - 0.5f);
  return {{x, y, -5.f}, {0.f, 0.f, 1.f}, 0.f, INFINITY, 0.f};
}

// glTF's Alpha Coverage holds for analytic solids as for meshes (POV-Ray's transmit becomes
// alpha, docs/pov.md): BLEND lets each surface through with probability 1 - alpha, so a ray
// across the sphere meets its front with probability alpha, its back with (1 - alpha) alpha,
// and is occluded with 1 - (1 - alpha)^2; intersect and occluded agree ray by ray.
TEST(RenderGeometry, TransparentSolidsLetRaysThroughAsTheirCoverageSays) {
  const float alpha = 0.3f;
  const Scene scene = transparent_sphere(AlphaMode::kBlend, alpha);  // outlives the geometry
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const int n = 100, rays = n * n;
  int front = 0, back = 0, occluded = 0;
  for (int i = 0; i < rays; ++i) {
    const fb_ray ray = ray_through(i, n);
    fb_hit hit{};
    const bool found = geometry.intersect(ray, hit);
    if (found) (hit.position[2] < 0 ? front : back) += 1;
    occluded += geometry.occluded(ray);
    ASSERT_EQ(found, geometry.occluded(ray)) << "ray " << i;
  }
  // Binomial standard deviations: at most sqrt(0.25 / 10000) = 0.005; 4 of them.
  EXPECT_NEAR(front / double(rays), alpha, 0.02);
  EXPECT_NEAR(back / double(rays), (1 - alpha) * alpha, 0.02);
  EXPECT_NEAR(occluded / double(rays), 1 - (1 - alpha) * (1 - alpha), 0.02);
}

TEST(RenderGeometry, MaskedSolidsBelowTheCutoffAreNotThere) {
  for (const float alpha : {0.4f, 0.6f}) {
    const Scene scene = transparent_sphere(AlphaMode::kMask, alpha);
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    fb_hit hit{};
    EXPECT_EQ(geometry.intersect(ray_through(0, 1), hit), alpha >= 0.5f) << alpha;
    EXPECT_EQ(geometry.occluded(ray_through(0, 1)), alpha >= 0.5f) << alpha;
  }
}

}  // namespace
}  // namespace fb
