// Rays leaving a surface never meet it again, at any scale from 1e-3 m to 1e4 m
// (scenes/hard/README.md, "self-intersection"): new rays leave hit points by the hit's
// floating-point error bound (fb::offset_ray_origin, pbrt 4e section 6.8.6), not by a fixed
// epsilon. The scene is a nearly coplanar floor (a grid lifted by up to 1 um, facet slopes below
// 1e-5) and a convex icosphere off its edge, lit by a point light 5 cm above the floor: light
// reaches most of the floor at grazing angles, and nothing shadows anything.
#include <gtest/gtest.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <numbers>
#include <random>

#include <filmback/geometry.h>

#include "core/accel/render_geometry.h"
#include "core/math/constants.h"
#include "core/util/error.h"
#include "hard_case.h"

namespace fb {
namespace {

using test::report_case;

// The same shot `scale` times larger: geometry, camera, light positions and clip range scale, and
// the light's intensity by scale^2, so that irradiance E = I cos(theta) / d^2 stays the same.
Scene scaled(const Scene& scene, double scale) {
  Scene s = scene;
  const Transform grow = Transform::scale({scale, scale, scale});
  for (MeshInstance& instance : s.instances)
    instance.world_from_object = grow * instance.world_from_object;
  const auto move = [&](Transform& t) {
    t = Transform::translate(t.translation() * (scale - 1)) * t;
  };
  for (SceneCamera& camera : s.cameras) {
    move(camera.world_from_camera);
    camera.physical.clip_near_m *= scale;
    camera.physical.clip_far_m *= scale;
  }
  for (Light& light : s.lights) {
    move(light.world_from_light);
    light.intensity = light.intensity * float(scale * scale);
  }
  return s;
}

// How a new ray's origin leaves a hit: by its error bound (the renderer's way), by a fixed
// distance along the normal, or not at all (the last two are the controls that show acne).
enum class Offset { kErrorBound, kFixed1e4m, kNone };

Vec3f leave(Offset how, Vec3f p, Vec3f error, Vec3f n, Vec3f w) {
  switch (how) {
    case Offset::kErrorBound:
      return offset_ray_origin(p, error, n, w);
    case Offset::kFixed1e4m:
      return p + n * (dot(w, n) > 0.f ? 1e-4f : -1e-4f);
    default:
      return p;
  }
}

// Of `rays` primary rays at the floor and the ball from the camera and from a grazing viewpoint,
// the shadow rays towards the light and the bounce rays leaving into the upper hemisphere (more
// than 1e-4 rad above the surface, ten times the floor's steepest facet) that meet the surface
// they left: there is nothing else in their way.
struct Wrong {
  size_t shadow = 0, bounce = 0, traced = 0;
};

Wrong count_wrong(const Scene& scene, Offset how, int rays) {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);  // as every tracing thread of a render does
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  const Vec3d camera = scene.cameras.at(0).world_from_camera.translation();
  const Transform render_from_world = Transform::translate(-camera);
  const RenderGeometry geometry(scene, render_from_world, ShotTimes{}, MotionTolerance{});
  const Vec3f light(render_from_world.point(scene.lights.at(0).world_from_light.translation()));
  const double scale = length(camera) / std::sqrt(18.0);  // the camera is at (0, 3, 3) x scale
  const Vec3d ball =
      render_from_world.point(test::instance_named(scene, "ball").world_from_object.translation());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Wrong wrong;
  for (const Vec3d eye_world : {camera, Vec3d{-5, 0.03, 0.5} * scale}) {
    const Vec3d eye = render_from_world.point(eye_world);
    for (int i = 0; i < rays; ++i) {
      // Half of the rays aim at the floor, half at the ball.
      const Vec3d target = i % 2 ? Vec3d{2 * u(rng), 0, 2 * u(rng)} * scale - camera
                                 : ball + normalize(Vec3d{u(rng), u(rng), u(rng)}) * 0.5 * scale;
      fb_ray ray{};
      Vec3f(eye).store(ray.origin);
      Vec3f(normalize(target - eye)).store(ray.direction);
      ray.t_max = HUGE_VALF;
      fb_hit hit;
      if (!geometry.intersect(ray, hit)) continue;
      Vec3f n(hit.geometric_normal);
      if (dot(n, Vec3f(ray.direction)) > 0.f) n = -n;
      const Vec3f p(hit.position), error(hit.position_error);
      Vec3f to_light = light - p;
      const float distance = length(to_light);
      to_light = to_light / distance;
      if (dot(to_light, n) > 0.f) {
        fb_ray shadow{};
        leave(how, p, error, n, to_light).store(shadow.origin);
        to_light.store(shadow.direction);
        shadow.t_max = distance * (1.f - 1e-4f);  // as the path integrator stops short
        wrong.shadow += geometry.occluded(shadow);
        ++wrong.traced;
      }
      Vec3f w{float(u(rng)), float(u(rng)), float(u(rng))};
      w = normalize(w);
      if (dot(w, n) < 0.f) w = -w;
      if (dot(w, n) > 1e-4f) {
        fb_ray bounce{};
        leave(how, p, error, n, w).store(bounce.origin);
        w.store(bounce.direction);
        bounce.t_max = HUGE_VALF;
        fb_hit next;
        wrong.bounce += geometry.intersect(bounce, next) && next.material == hit.material;
        ++wrong.traced;
      }
    }
  }
  return wrong;
}

const double kScales[] = {1e-3, 1e-2, 0.1, 1, 10, 100, 1e3, 1e4};

TEST(SelfIntersection, RaysLeavingBySurfaceErrorBoundsNeverMeetTheirSurfaceAtAnyScale) {
  const Scene scene = test::load_hard_scene("self_intersection.gltf");
  for (double scale : kScales) {
    const test::Stopwatch clock;
    const Wrong w = count_wrong(scaled(scene, scale), Offset::kErrorBound, 4000);
    EXPECT_GT(w.traced, 10000u);
    report_case("self_intersection at " + number_text(scale) + " m", 0,
                double(w.shadow + w.bounce) / double(w.traced), 0,
                "fraction of shadow and bounce rays meeting the surface they left",
                clock.seconds());
  }
}

// The controls: the same rays without an offset, and with a fixed 0.1 mm one, do meet their own
// surfaces (acne) — the count above can fail.
TEST(SelfIntersection, WithoutErrorBoundsTheSameRaysShowAcne) {
  const Scene scene = test::load_hard_scene("self_intersection.gltf");
  for (double scale : kScales) {
    const Wrong none = count_wrong(scaled(scene, scale), Offset::kNone, 1000);
    EXPECT_GT(none.shadow + none.bounce, 0u) << "no offset at " << scale << " m";
    const Wrong fixed = count_wrong(scaled(scene, scale), Offset::kFixed1e4m, 1000);
    std::printf("[   hard   ] control at %g m: no offset %.3g, fixed 0.1 mm %.3g of rays wrong\n",
                scale, double(none.shadow + none.bounce) / double(none.traced),
                double(fixed.shadow + fixed.bounce) / double(fixed.traced));
    if (scale >= 1e3) {
      EXPECT_GT(fixed.shadow + fixed.bounce, 0u) << "fixed 0.1 mm at " << scale;
    }
  }
}

// Rendered: the floor's radiance is L = rho / pi * I cos(theta) / d^2 (direct light, one
// bounce); acne would show as dark speckle. Each pixel is compared with that radiance averaged
// over its footprint (box filter, 8 x 8 points), at 1 mm, 1 m and 10 km.
TEST(SelfIntersection, GrazingLitFloorRendersItsAnalyticRadianceAtEveryScale) {
  const Scene scene = test::load_hard_scene("self_intersection.gltf");
  const float rho = scene.materials.at(0).base_color.x;
  for (double scale : {1e-3, 1.0, 1e4}) {
    const Scene s = scaled(scene, scale);
    const test::TimedRender r = test::render_timed(s, test::box_filtered(64, "path:max_depth=1"));
    const Vec3d light = s.lights.at(0).world_from_light.translation();
    const double intensity = s.lights.at(0).intensity.x;
    // Inside the floor (the plane y = 0), away from its edge by more than its 1 um relief.
    const auto on_floor = [&](const test::WorldRay& ray) -> std::optional<Vec3d> {
      const double t = -ray.origin.y / ray.direction.y;
      const Vec3d p = ray.origin + ray.direction * t;
      if (t > 0 && std::abs(p.x) < 1.99 * scale && std::abs(p.z) < 1.99 * scale) return p;
      return std::nullopt;
    };
    const auto radiance = [&](Vec3d p) {
      const Vec3d to_light = light - p;
      const double d2 = dot(to_light, to_light);
      return rho / kPi * intensity * (to_light.y / std::sqrt(d2)) / d2;
    };
    const double worst =
        test::footprint_error(s, r.result.image, 1, 8, 1, on_floor, radiance).worst;
    report_case("grazing floor at " + number_text(scale) + " m", r.result.stats.dropped_samples,
                worst, 0.01, "worst |pixel / analytic radiance - 1| on the floor", r.seconds);
  }
}

}  // namespace
}  // namespace fb
