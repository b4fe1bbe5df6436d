// Instances traced as Embree instances against the same scene flattened (core/accel/instancing.h):
// each ray must find the same surface, placed, oriented and shaded alike, also for a mirrored
// instance, a nested one and one that moves while the shutter is open.
#include <gtest/gtest.h>

#include <cmath>

#include <filmback/geometry.h>

#include "core/accel/render_geometry.h"
#include "core/math/random.h"
#include "core/render/memory_estimate.h"
#include "support/instanced_scene.h"

namespace fb {
namespace {

const ShotTimes kShutter{0.0, 0.0, 1.0};  // frame at 0 s, open over [0, 1] s
const MotionTolerance kTolerance{1e-4, 1e-4};

// A ray from the origin through (x, y) of an image plane at z = -1, at a time across the shutter.
fb_ray camera_ray(int i, int n) {
  const float x = 1.2f * ((float(i % n) + 0.5f) / float(n) - 0.5f);
  const float y = 1.2f * ((float(i / n) + 0.5f) / float(n) - 0.5f);
  const Vec3f d = normalize(Vec3f{x, y, -1.f});
  return {{0, 0, 0}, {d.x, d.y, d.z}, 0.f, INFINITY, unit_float(uint32_t(pcg_hash(uint64_t(i))))};
}

float distance(const float a[3], const float b[3]) {
  return length(Vec3f(a) - Vec3f(b));
}

TEST(Instancing, RepeatedMeshesAreInstancedAndMeshesUsedOnceFlattened) {
  const Scene scene = test::five_spheres();
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 5u);
  EXPECT_EQ(RenderGeometry(scene, Transform(), kShutter, kTolerance).instanced_count(), 5u);
  EXPECT_EQ(RenderGeometry(scene, Transform(), kShutter, kTolerance, Instancing::kNever)
                .instanced_count(),
            0u);
  Scene once = scene;
  once.instances.resize(1);  // a mesh used once stays flat, as it was before instancing
  EXPECT_EQ(RenderGeometry(once, Transform(), kShutter, kTolerance).instanced_count(), 0u);
  EXPECT_EQ(RenderGeometry(once, Transform(), kShutter, kTolerance, Instancing::kAlways)
                .instanced_count(),
            1u);
}

// Every ray finds the same sphere at the same distance, with the same normals. The two paths
// differ only in where Embree meets the triangle (in object space through its float inverse
// matrix, or in render space), so distances and points agree to a few float roundings of the
// distance (kRelative, 2^-17: 64 ulps), never more: a wrong transform, winding or time is off by
// centimetres. Rays that graze a silhouette within that rounding may disagree about hitting at
// all: none of these 4096 do.
TEST(Instancing, InstancedHitsMatchTheFlattenedScene) {
  const Scene scene = test::five_spheres();
  const RenderGeometry flat(scene, Transform(), kShutter, kTolerance, Instancing::kNever);
  const RenderGeometry instanced(scene, Transform(), kShutter, kTolerance);
  ASSERT_EQ(instanced.instanced_count(), 5u);
  EXPECT_EQ(flat.triangle_count(), instanced.triangle_count());
  EXPECT_EQ(flat.moving_instance_count(), 1u);
  EXPECT_EQ(instanced.moving_instance_count(), 1u);
  constexpr float kRelative = 0x1p-17f;
  const int n = 64;
  int hits = 0, moving_hits = 0, mirrored_hits = 0;
  for (int i = 0; i < n * n; ++i) {
    const fb_ray ray = camera_ray(i, n);
    fb_hit a{}, b{};
    const bool found = flat.intersect(ray, a);
    ASSERT_EQ(found, instanced.intersect(ray, b)) << "ray " << i;
    ASSERT_EQ(found, instanced.occluded(ray)) << "ray " << i;
    if (!found) continue;
    ++hits;
    moving_hits += a.position[1] < -0.6f;
    mirrored_hits += a.position[0] < -0.6f && a.position[1] > -0.6f;
    EXPECT_NEAR(a.t, b.t, kRelative * a.t) << "ray " << i;
    EXPECT_LE(distance(a.position, b.position), kRelative * a.t) << "ray " << i;
    EXPECT_LE(distance(a.shadow_position, b.shadow_position), kRelative * a.t) << "ray " << i;
    EXPECT_GT(dot(Vec3f(a.geometric_normal), Vec3f(b.geometric_normal)), 1 - 1e-5f) << "ray " << i;
    EXPECT_GT(dot(Vec3f(a.shading_normal), Vec3f(b.shading_normal)), 1 - 1e-5f) << "ray " << i;
    // Outward on every sphere, the mirrored one too: the winding survives the mirror.
    EXPECT_LT(dot(Vec3f(b.geometric_normal), Vec3f(ray.direction)), 0.f) << "ray " << i;
    EXPECT_EQ(a.material, b.material);
    for (int k = 0; k < 3; ++k)
      EXPECT_GE(b.position_error[k], a.position_error[k]);
  }
  EXPECT_GT(hits, n * n / 8);  // the spheres fill part of the view, each of them some
  EXPECT_GT(moving_hits, 20);
  EXPECT_GT(mirrored_hits, 20);
}

// The position's error bound covers where Embree's instanced surface really is: a ray leaving a
// hit offset by it (pbrt 4e §6.8.6) never finds the surface it left. Outward from a convex
// sphere it meets nothing of that sphere; inward it crosses the sphere to its far side.
TEST(Instancing, RaysLeavingAnInstancedHitDoNotFindItAgain) {
  const Scene scene = test::five_spheres();
  const RenderGeometry instanced(scene, Transform(), kShutter, kTolerance);
  const int n = 64;
  int checked = 0;
  for (int i = 0; i < n * n; ++i) {
    const fb_ray ray = camera_ray(i, n);
    fb_hit hit{};
    if (!instanced.intersect(ray, hit)) continue;
    const Vec3f ng(hit.geometric_normal), p(hit.position), error(hit.position_error);
    for (const float side : {1.f, -1.f}) {
      const Vec3f w = ng * side;
      const Vec3f o = offset_ray_origin(p, error, ng, w);
      const fb_ray leaving{{o.x, o.y, o.z}, {w.x, w.y, w.z}, 0.f, INFINITY, ray.time_s};
      fb_hit next{};
      if (instanced.intersect(leaving, next))
        EXPECT_GT(next.t, 1e-3f) << "ray " << i << (side > 0 ? " outward" : " inward");
      else
        EXPECT_GT(side, 0.f) << "ray " << i
                             << ": an inward ray left the sphere without its far side";
    }
    ++checked;
  }
  EXPECT_GT(checked, n * n / 8);
}

// The memory estimate's cost of an instance (kBytesPerInstance) bounds what one holds: 10,000
// instances of a quad against 5,000, so that the quad's own copy cancels.
TEST(Instancing, EachInstanceHoldsNoMoreThanTheEstimateCounts) {
  const auto bytes_for = [](size_t count) {
    Scene scene;
    TriangleMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(quad);
    scene.materials.push_back({});
    for (size_t i = 0; i < count; ++i) {
      MeshInstance instance;
      instance.world_from_object = Transform::translate({double(i % 100), double(i / 100), -5});
      scene.instances.push_back(instance);
    }
    const size_t before = RenderGeometry::live_bytes();
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    EXPECT_EQ(geometry.instanced_count(), count);
    return double(RenderGeometry::live_bytes() - before);
  };
  const double per_instance = (bytes_for(10000) - bytes_for(5000)) / 5000;
  EXPECT_GT(per_instance, 256);  // its transform and normal transform at least
  EXPECT_LE(per_instance, kBytesPerInstance);
}

}  // namespace
}  // namespace fb
