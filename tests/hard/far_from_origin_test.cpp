// A shot 1e5 m and 1e7 m from the world origin renders as the same shot at the origin
// (scenes/hard/README.md, "far from the origin"): render space is centred on the camera in double
// precision before anything is narrowed to float (docs/architecture.md, "Precision"), so the far
// shot's render-space data equals the origin shot's up to one float rounding. In float world
// coordinates 1e7 m would leave steps of 1 m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hard_case.h"

namespace fb {
namespace {

using test::load_hard_scene;
using test::render_timed;
using test::report_case;

// Mean squared difference over every pixel and colour channel.
double mean_square_difference(const Image& a, const Image& b) {
  double sum = 0;
  size_t n = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      for (size_t c = 0; c < 3; ++c, ++n) {
        const double d = double(a.at(x, y, c)) - b.at(x, y, c);
        sum += d * d;
      }
  return sum / double(n);
}

double max_difference(const Image& a, const Image& b) {
  double most = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    most = std::max(most, std::abs(double(a.pixels[i]) - b.pixels[i]));
  return most;
}

// Energy in the differences of neighbouring pixels: blocky rendering (vertices or hit points
// snapped to a coarse float grid) adds steps between pixels.
double high_frequency_energy(const Image& image) {
  double sum = 0;
  for (uint32_t y = 0; y + 1 < image.height; ++y)
    for (uint32_t x = 0; x + 1 < image.width; ++x)
      for (size_t c = 0; c < 3; ++c) {
        const double dx = double(image.at(x + 1, y, c)) - image.at(x, y, c);
        const double dy = double(image.at(x, y + 1, c)) - image.at(x, y, c);
        sum += dx * dx + dy * dy;
      }
  return sum;
}

TEST(FarFromOrigin, ShotsFarAwayEqualTheShotAtTheOriginWithinNoise) {
  RenderOptions options;
  options.samples_per_pixel = 16;  // every bounce (max_depth 8): camera, shadow and bounce rays
  const auto render = [&](const Scene& scene, uint64_t seed) {
    options.seed = seed;
    return render_timed(scene, options);
  };
  const Scene origin = load_hard_scene("far_origin.gltf");
  const test::TimedRender o1 = render(origin, 1), o2 = render(origin, 2);
  // The noise: two seeds at the origin differ by sqrt(2) sigma per pixel.
  const double sigma = std::sqrt(mean_square_difference(o1.result.image, o2.result.image) / 2);
  ASSERT_GT(sigma, 0.0);
  const double origin_energy = high_frequency_energy(o1.result.image);
  for (const char* file : {"far_1e5.gltf", "far_1e7.gltf"}) {
    const test::TimedRender far = render(load_hard_scene(file), 1);
    const uint64_t non_finite = far.result.stats.dropped_samples;
    // With the same seed the far shot is the origin's image up to the rounding of render-space
    // vertices (measured: bit-identical). Any pixel off by 4 standard errors would be acne, a
    // displaced edge or a blocky surface.
    report_case(std::string(file) + " per pixel", non_finite,
                max_difference(far.result.image, o1.result.image) / sigma, 4,
                "max |far - origin| per pixel, same seed, in noise standard deviations",
                far.seconds);
    report_case(std::string(file) + " blockiness", non_finite,
                std::abs(high_frequency_energy(far.result.image) / origin_energy - 1), 0.01,
                "|neighbour-difference energy far / origin - 1|", far.seconds);
  }
}

}  // namespace
}  // namespace fb
