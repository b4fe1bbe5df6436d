// An instanced scene renders the image its flattened twin renders (core/accel/instancing.h): the
// five spheres of tests/support/instanced_scene.h (rotated and scaled, mirrored, nested, moving
// under an open shutter), once as one mesh used five times (instanced) and once with a copy of
// the mesh per instance (each used once: flattened).
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/render_job.h"
#include "support/instanced_scene.h"
#include "support/plugins.h"

namespace fb {
namespace {

Image render(const Scene& scene, uint64_t seed) {
  RenderOptions options;
  options.width = 96, options.height = 64, options.samples_per_pixel = 16;
  options.integrator = "path:max_depth=3";
  options.background = Rgb{1.f, 1.f, 1.f};  // a uniform sky lights the spheres and their bounces
  options.shutter_s = Vec2d{0.0, 1.0};
  options.seed = seed;
  options.show_progress = false;
  const RenderJob job(scene, options, test::loader());
  return job.run().image;
}

double mean_absolute_difference(const Image& a, const Image& b) {
  double sum = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      for (uint32_t c = 0; c < 3; ++c)
        sum += std::abs(double(a.at(x, y, c)) - double(b.at(x, y, c)));
  return sum / (3.0 * a.width * a.height);
}

// The noise floor is the same render with another seed: the two paths differ only by float
// roundings in where a ray meets a triangle, so their images must agree 1000 times more closely
// than two seeds do (measured: 8.6 million times, 2e-10 against 1.7e-3; a few rays take another
// bounce direction where a rounding flips a comparison).
TEST(InstancedRender, InstancesRenderTheFlattenedImage) {
  const Scene instanced = test::five_spheres();
  Scene flattened = instanced;
  for (size_t i = 1; i < flattened.instances.size(); ++i) {
    flattened.meshes.push_back(flattened.meshes[0]);
    flattened.instances[i].mesh = uint32_t(flattened.meshes.size() - 1);
  }
  const Image a = render(instanced, 1), b = render(flattened, 1), c = render(instanced, 2);
  const double floor = mean_absolute_difference(a, c), difference = mean_absolute_difference(a, b);
  std::printf("instanced vs flattened %.3g, seed 1 vs seed 2 %.3g (ratio %.0f)\n", difference,
              floor, floor / difference);
  EXPECT_GT(floor, 0.0);
  EXPECT_LT(difference, floor / 1000);
}

}  // namespace
}  // namespace fb
