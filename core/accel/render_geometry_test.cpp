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

}  // namespace
}  // namespace fb
