#include "core/texture/surface_shader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/texture/solid_normal.h"
#include "core/texture/solid_pattern.h"

namespace fb {
namespace {

SolidPattern plain_colour(Rgb rgb, float filter, float transmit) {
  SolidPattern s;
  s.colour = {rgb, filter, transmit};
  return s;
}

fb_hit hit_facing_up() {
  fb_hit hit{};
  hit.shading_normal[1] = hit.geometric_normal[1] = 1.f;
  return hit;
}

// POV-Ray's layered textures worked by hand: a grey base (0.6) under a red layer with filter 0.3
// and transmit 0.2 (coverage 0.5, diffuse 0.5), under a clear layer (transmit 1) with a highlight.
TEST(SurfaceShader, LayersBlendByCoverageBottomUp) {
  Scene scene;
  Material base;
  base.base_color = {0.6f, 0.6f, 0.6f};
  base.specular = 0.f, base.roughness = 1.f, base.metallic = 0.f;
  Material red;
  red.base_color = {0.5f, 0.5f, 0.5f};
  red.base_color_pattern = plain_colour({1, 0, 0}, 0.3f, 0.2f);
  red.specular = 0.f, red.roughness = 1.f, red.metallic = 1.f;
  Material clear_coat;
  clear_coat.base_color_pattern = plain_colour({1, 1, 1}, 0.f, 1.f);
  clear_coat.specular = 0.8f, clear_coat.roughness = 0.2f, clear_coat.ior = 1.7f;
  base.layers = {red, clear_coat};
  scene.materials = {base};
  const SurfaceShader shader(scene);
  fb_hit hit = hit_facing_up();
  shader.shade(0, SurfacePoint{}, hit);
  // red over grey: 0.5 * (1, 0, 0) * 0.5 + 0.6 * ((1, 0, 0) * 0.3 + 0.2) = (0.55, 0.12, 0.12);
  // the clear coat lets all of it through.
  EXPECT_NEAR(hit.base_color[0], 0.55f, 1e-6f);
  EXPECT_NEAR(hit.base_color[1], 0.12f, 1e-6f);
  EXPECT_NEAR(hit.base_color[2], 0.12f, 1e-6f);
  EXPECT_NEAR(hit.metallic, 0.5f, 1e-6f);  // the red layer's covered half; the coat covers none
  // the coat's highlight shows although it covers nothing
  EXPECT_FLOAT_EQ(hit.specular, 0.8f);
  EXPECT_FLOAT_EQ(hit.roughness, 0.2f);
  EXPECT_FLOAT_EQ(hit.ior, 1.7f);
}

// POV-Ray's emission and a self-lit finish's ambient are times the pigment (docs/pov.md): a
// gradient pigment glows in its colour at the hit, not in its average.
TEST(SurfaceShader, EmissionIsTimesThePatternAtTheHit) {
  Scene scene;
  Material glow;
  glow.emission = {2.f, 2.f, 2.f};
  SolidPattern ramp;
  ramp.kind = SolidPatternKind::kGradient;
  ramp.gradient = {1, 0, 0};
  ramp.colour_map = {{0.f, {{0, 0, 0}, 0, 0}}, {1.f, {{1, 0.5f, 0.25f}, 0, 0}}};
  glow.base_color_pattern = ramp;
  scene.materials = {glow};
  const SurfaceShader shader(scene);
  for (const float x : {0.25f, 0.75f}) {
    SurfacePoint point;
    point.position = {x, 0.f, 0.f};
    const Rgb expected = evaluate_solid(ramp, Vec3d(point.position), nullptr).rgb * 2.f;
    const Rgb emitted = shader.emission(0, point);
    EXPECT_NEAR(emitted.x, expected.x, 1e-6f);
    EXPECT_NEAR(emitted.y, expected.y, 1e-6f);
    EXPECT_NEAR(emitted.z, expected.z, 1e-6f);
    EXPECT_NEAR(emitted.x, 2.f * x, 1e-5f);  // the ramp's red, not its mean
  }
}

TEST(SurfaceShader, NormalPatternBendsTheShadingNormalOnly) {
  Scene scene;
  Material m;
  SolidNormal bumps;
  bumps.pattern.kind = SolidPatternKind::kBumps;
  bumps.amount = 0.6;
  m.normal_pattern = bumps;
  scene.materials = {m, Material{}};
  // render space = world moved by -offset (as RenderGeometry places the camera at the origin)
  const Vec3d offset{10, 0, 0};
  const SurfaceShader shader(scene, Transform::translate(offset));
  SurfacePoint point;
  point.position = {0.3f, 0.f, 0.7f};
  fb_hit hit = hit_facing_up();
  shader.shade(0, point, hit);
  const Vec3d expected = perturbed_normal(bumps, Vec3d(point.position) + offset, Vec3d{0, 1, 0});
  EXPECT_NEAR(hit.shading_normal[0], expected.x, 1e-6);
  EXPECT_NEAR(hit.shading_normal[1], expected.y, 1e-6);
  EXPECT_NEAR(hit.shading_normal[2], expected.z, 1e-6);
  EXPECT_GT(std::abs(hit.shading_normal[0]) + std::abs(hit.shading_normal[2]), 1e-3f);
  // the smooth normal and the geometry stay as they were
  EXPECT_EQ(hit.smooth_normal[1], 1.f);
  EXPECT_EQ(hit.geometric_normal[1], 1.f);
  // a material without one leaves the normal alone
  fb_hit plain = hit_facing_up();
  shader.shade(1, point, plain);
  EXPECT_EQ(plain.shading_normal[1], 1.f);
}

}  // namespace
}  // namespace fb
