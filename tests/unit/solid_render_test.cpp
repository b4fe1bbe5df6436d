// An analytic solid through the whole render path (RenderJob, Embree user geometry, the path
// integrator): an emissive sphere against its exact pixel coverage.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/render_job.h"
#include "support/plugins.h"

namespace fb {
namespace {

TEST(SolidRender, EmissiveSphereCoversItsAnalyticPixels) {
  constexpr uint32_t kWidth = 96, kHeight = 64;
  const Vec3d centre{0.3, -0.2, -5};
  const double radius = 0.5, focal_mm = 35, sensor_mm = 36;
  const float emission = 2.f;
  Scene scene;
  Material glow;
  glow.base_color = {0, 0, 0};
  glow.emission = {emission, emission, emission};
  scene.materials.push_back(glow);
  Solid sphere;
  sphere.kind = SolidKind::kSphere;
  sphere.name = "ball";
  sphere.world_from_object =
      Transform::translate(centre) * Transform::scale({radius, radius, radius});
  scene.solids.push_back(sphere);
  SceneCamera camera;  // at the origin looking down -Z; the 36 mm sensor spans the width
  camera.name = "camera";
  camera.physical.focal_length_mm = focal_mm;
  camera.physical.sensor_width_mm = sensor_mm;
  scene.cameras.push_back(camera);

  RenderOptions options;
  options.width = kWidth, options.height = kHeight, options.samples_per_pixel = 64;
  options.filter = "box";
  options.show_progress = false;
  const RenderResult result = RenderJob(scene, options, test::loader()).run();

  // The sphere is the cone of directions within asin(r / |c|) of its centre's. A pixel lies inside
  // when its four corners do (the cone meets the sensor plane in a convex ellipse) and outside when
  // its centre is farther from the cone than the pixel's half-diagonal; the others are covered in
  // part, estimated by 32 x 32 pinhole rays (a pinhole maps the sensor linearly).
  const double pixel_mm = sensor_mm / kWidth, half_angle = std::asin(radius / length(centre));
  const double half_diagonal = std::sqrt(0.5) * pixel_mm / focal_mm;
  const auto off_centre = [&](double px, double py) {  // angle from the sphere's centre
    const Vec3d d = normalize(
        Vec3d{(px - kWidth / 2.0) * pixel_mm, -(py - kHeight / 2.0) * pixel_mm, -focal_mm});
    return std::acos(std::min(1.0, dot(d, normalize(centre))));
  };
  double rendered_sum = 0, covered_sum = 0;
  int interior = 0, exterior = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const float value = result.image.at(x, y, 1);
      rendered_sum += value;
      bool inside = true;
      for (int corner = 0; corner < 4; ++corner)
        inside &= off_centre(x + corner % 2, y + corner / 2) < half_angle;
      if (inside) {
        ++interior;
        covered_sum += emission;
        ASSERT_FLOAT_EQ(value, emission) << x << "," << y;
        continue;
      }
      if (off_centre(x + 0.5, y + 0.5) > half_angle + half_diagonal) {
        ++exterior;
        ASSERT_EQ(value, 0.f) << x << "," << y;
        continue;
      }
      constexpr int kSub = 32;
      int hits = 0;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx)
          hits += off_centre(x + (sx + 0.5) / kSub, y + (sy + 0.5) / kSub) < half_angle;
      covered_sum += emission * hits / (kSub * kSub);
    }
  EXPECT_GT(interior, 100);
  EXPECT_GT(exterior, 1000);
  // Edge pixels: 64 samples each estimate a coverage; their sum over the ~80 edge pixels agrees
  // within a few per cent of one pixel's worth, far below 0.5 % of the disc's ~280 px.
  EXPECT_NEAR(rendered_sum, covered_sum, 0.005 * covered_sum);
}

}  // namespace
}  // namespace fb
