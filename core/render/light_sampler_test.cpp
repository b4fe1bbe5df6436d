#include "core/render/light_sampler.h"

#include <gtest/gtest.h>

#include <map>

namespace fb {
namespace {

Light point_light(double watts_per_sr, Vec3d at) {
  Light light;
  light.intensity = Rgb(float(watts_per_sr), float(watts_per_sr), float(watts_per_sr));
  light.world_from_light = Transform::translate(at);
  return light;
}

// Every value u can take (multiples of 2^-24) chooses each light exactly as often as its pdf says
// (so the estimator is exact over the grid), however dim a light is beside the others and wherever
// it is in the list.
TEST(LightSampler, ChoiceFrequenciesEqualTheirProbabilitiesOnTheSampleGrid) {
  for (bool dim_first : {true, false}) {
    Scene scene;
    const Light bright = point_light(1e9, {0, 10, 0}), dim = point_light(1e-3, {0, 1, 0});
    scene.lights = dim_first ? std::vector{dim, bright} : std::vector{bright, dim};
    const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
    const LightSampler sampler(scene, Transform(), geometry, 0.0);
    std::map<float, std::pair<uint32_t, float>> chosen;  // by distance: times chosen, pdf
    constexpr uint32_t kGrid = 1u << 24;
    for (uint32_t k = 0; k < kGrid; ++k) {
      const float u[3] = {float(k) * 0x1p-24f, 0.5f, 0.5f};
      fb_light_sample s;
      ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
      auto& [times, pdf] = chosen[s.distance];
      ++times;
      pdf = s.pdf;
    }
    ASSERT_EQ(chosen.size(), 2u) << "both lights must be reachable";
    for (const auto& [distance, entry] : chosen)
      EXPECT_EQ(double(entry.first), double(entry.second) * kGrid)
          << "light at " << distance << " m, "
          << (dim_first ? "dim light first" : "dim light last");
  }
}

TEST(LightSampler, LightsWithoutPowerAreNeverChosen) {
  Scene scene;
  scene.lights = {point_light(0, {0, 1, 0}), point_light(2, {0, 2, 0})};
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const LightSampler sampler(scene, Transform(), geometry, 0.0);
  for (float u0 : {0.f, 0.25f, 0.999f}) {
    const float u[3] = {u0, 0, 0};
    fb_light_sample s;
    ASSERT_TRUE(sampler.sample({0, 0, 0}, u, s));
    EXPECT_FLOAT_EQ(s.radiance[0], 2.f / 4.f);  // the 2 W/sr light at 2 m
    EXPECT_EQ(s.pdf, 1.f);
  }
}

}  // namespace
}  // namespace fb
