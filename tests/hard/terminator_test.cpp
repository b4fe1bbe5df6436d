// The shadow terminator on a low-poly sphere with smooth normals (scenes/hard/README.md,
// "shadow terminator"): a 12 x 6 UV sphere whose vertex normals are the exact sphere's, lit by a
// sun from the side, must shade as its interpolated normals say, L = rho / pi * E * max(0, n.l),
// up to the terminator, without the flat facets' blocky shadow. The reference takes n from the
// renderer's own hit records at 6 x 6 points per pixel (box filter): it is the smooth shading of
// this very mesh, so what differs is the terminator.
#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <numbers>

#include "core/accel/render_geometry.h"
#include "core/math/constants.h"
#include "hard_case.h"

namespace fb {
namespace {

TEST(Terminator, LowPolySphereShadesAsItsSmoothNormalsUpToTheTerminator) {
  const Scene scene = test::load_hard_scene("terminator.gltf");
  const test::TimedRender r = test::render_timed(scene, test::box_filtered(64, "path:max_depth=1"));
  const Image& image = r.result.image;

  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  const SceneCamera& camera = scene.cameras.at(0);
  const Transform render_from_world = Transform::translate(-camera.world_from_camera.translation());
  const RenderGeometry geometry(scene, render_from_world, ShotTimes{}, MotionTolerance{});
  const Light& sun = scene.lights.at(0);
  const Vec3d l = normalize(sun.world_from_light.vector({0, 0, 1}));  // towards the sun
  const double scale = scene.materials.at(0).base_color.x / kPi * sun.intensity.x;  // rho E / pi
  double worst = 0;
  constexpr int n = 6;  // n x n rays per pixel
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      double expected = 0, facing = 1;
      bool covered = true;
      for (int j = 0; j < n && covered; ++j)
        for (int i = 0; i < n && covered; ++i) {
          const test::WorldRay w = test::pixel_ray(camera, image.width, image.height,
                                                   x + (i + 0.5) / n, y + (j + 0.5) / n);
          fb_ray ray{};
          Vec3f(render_from_world.point(w.origin)).store(ray.origin);
          Vec3f(w.direction).store(ray.direction);
          ray.t_max = HUGE_VALF;
          fb_hit hit;
          covered = geometry.intersect(ray, hit);
          const Vec3d normal(Vec3f(hit.shading_normal));
          const double cosine = dot(normal, l);
          facing = std::min(facing, -dot(normal, w.direction));
          expected += std::max(0.0, cosine);
        }
      // Where the interpolated normal turns away from the viewer (the silhouette), the
      // integrator bends it back (fb::ensure_valid_reflection): not what is measured here.
      if (!covered || facing < 0.25) continue;
      worst = std::max(worst, std::abs(image.at(x, y, 1) / scale - expected / (n * n)));
    }
  // Before shadow rays left from the lifted point (fb_hit.shadow_position), light below a facet's
  // plane was refused and the facets across the terminator went black: 0.134.
  test::report_case("terminator", r.result.stats.dropped_samples, worst, 0.01,
                    "worst |pixel - rho/pi E max(0, n.l)| / (rho/pi E), n interpolated", r.seconds);
}

}  // namespace
}  // namespace fb
