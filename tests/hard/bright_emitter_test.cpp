// An emitter a million times brighter than the rest (scenes/hard/README.md, "bright emitter"): no
// sample turns non-finite, direct light stays unbiased, and the path integrator's optional clamp
// (path:clamp=X, docs/cli.md) bounds every sample, fireflies included, at the price of a bias.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "hard_case.h"
#include "support/polygon_irradiance.h"

namespace fb {
namespace {

using test::report_case;

// The world-space corners of the emissive square at node `node`, in order.
std::vector<Vec3d> square(const Scene& scene, const std::string& node) {
  const MeshInstance& instance = test::instance_named(scene, node);
  std::vector<Vec3d> corners;
  for (const Vec3f& p : scene.meshes[instance.mesh].positions)
    corners.push_back(instance.world_from_object.point(Vec3d(p)));
  return corners;
}

// Pixels that see only the floor (y = 0, within x < 1.5 m, away from the plate) against
// rho / pi (E_panel + E_tile), Lambert's polygon irradiance averaged over the pixel (box filter).
// Light sampling picks the panel once in 401 (by power), so its share is the noisy one: at 256
// samples a pixel is within about 1.5 %.
test::PixelError floor_error(const Scene& scene, const Image& image) {
  const double rho = scene.materials.at(0).base_color.x;
  const std::vector<Vec3d> panel = square(scene, "panel"), tile = square(scene, "tile");
  const double panel_l = scene.materials.at(1).emission.x,
               tile_l = scene.materials.at(2).emission.x;
  const auto on_floor = [](const test::WorldRay& r) -> std::optional<Vec3d> {
    const double t = -r.origin.y / r.direction.y;
    const Vec3d p = r.origin + r.direction * t;
    if (t > 0 && p.x > -3 && p.x < 1.5 && std::abs(p.z) < 3) return p;
    return std::nullopt;
  };
  return test::footprint_error(scene, image, 0, 4, rho / kPi, on_floor, [&](Vec3d p) {
    return test::polygon_irradiance(panel, panel_l, p, {0, 1, 0}) +
           test::polygon_irradiance(tile, tile_l, p, {0, 1, 0});
  });
}

bool all_finite(const Image& image) {
  for (float v : image.pixels)
    if (!std::isfinite(v)) return false;
  return true;
}

RenderOptions options(const char* integrator, uint64_t seed, uint32_t spp = 64) {
  RenderOptions o = test::box_filtered(spp, integrator);
  o.seed = seed;
  return o;
}

TEST(BrightEmitter, NothingTurnsNonFiniteAndDirectLightIsUnbiased) {
  const Scene scene = test::load_hard_scene("bright_emitter.gltf");
  const test::TimedRender r = test::render_timed(scene, options("path:max_depth=1", 0, 256));
  EXPECT_TRUE(all_finite(r.result.image));
  const test::PixelError e = floor_error(scene, r.result.image);
  const uint64_t non_finite = r.result.stats.dropped_samples;
  report_case("bright emitter, worst pixel", non_finite, e.worst, 0.03,
              "worst |floor pixel / rho/pi (E_panel + E_tile) - 1|", r.seconds);
  report_case("bright emitter, mean", non_finite, std::abs(e.mean), 0.003,
              "|mean of floor pixel / analytic - 1|", r.seconds);
}

// Every sample's largest component is at most the clamp, so with a box filter (positive weights)
// every pixel is too; the mirror's caustic, which only rare paths reach, stops flickering between
// seeds. Off (the default) is the unclamped, unbiased estimate above, bit for bit.
TEST(BrightEmitter, ClampBoundsEverySampleAndIsOffByDefault) {
  const Scene scene = test::load_hard_scene("bright_emitter.gltf");
  constexpr double kClamp = 4;
  const test::TimedRender on1 = test::render_timed(scene, options("path:clamp=4", 1)),
                          on2 = test::render_timed(scene, options("path:clamp=4", 2)),
                          off1 = test::render_timed(scene, options("path", 1)),
                          off2 = test::render_timed(scene, options("path", 2)),
                          zero = test::render_timed(scene, options("path:clamp=0", 1));
  EXPECT_EQ(zero.result.image.pixels, off1.result.image.pixels);
  double brightest = 0, flicker_on = 0, flicker_off = 0;
  for (size_t i = 0; i < on1.result.image.pixels.size(); ++i) {
    brightest = std::max(brightest, double(on1.result.image.pixels[i]));
    flicker_on = std::max(
        flicker_on, double(std::abs(on1.result.image.pixels[i] - on2.result.image.pixels[i])));
    flicker_off = std::max(
        flicker_off, double(std::abs(off1.result.image.pixels[i] - off2.result.image.pixels[i])));
  }
  const uint64_t non_finite = on1.result.stats.dropped_samples + on2.result.stats.dropped_samples +
                              off1.result.stats.dropped_samples + off2.result.stats.dropped_samples;
  const double seconds = on1.seconds + on2.seconds + off1.seconds + off2.seconds + zero.seconds;
  report_case("clamp 4, brightest pixel", non_finite, std::max(0.0, brightest / kClamp - 1), 1e-6,
              "max(0, brightest pixel / clamp - 1)", seconds);
  report_case("clamp 4, fireflies", non_finite, flicker_on / flicker_off, 0.1,
              "largest seed-to-seed pixel change, clamped / unclamped", seconds);
}

}  // namespace
}  // namespace fb
