// Degenerate and coincident geometry (scenes/hard/README.md): zero-area triangles (a repeated
// vertex, collinear vertices, three equal vertices, a zero normal), among them emissive ones, leave
// no NaN and no trace, and the proper triangles around them render their analytic radiance; two
// surfaces in the same plane, triangulated differently, render deterministically, and either one
// reflects its own analytic radiance.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "core/math/constants.h"
#include "hard_case.h"
#include "support/polygon_irradiance.h"

namespace fb {
namespace {

using test::report_case;

// The world-space corners of instance `node`'s triangle `triangle`.
std::vector<Vec3d> corners(const Scene& scene, const std::string& node, size_t triangle) {
  const MeshInstance& instance = test::instance_named(scene, node);
  const TriangleMesh& mesh = scene.meshes[instance.mesh];
  std::vector<Vec3d> out;
  for (size_t k = 0; k < 3; ++k)
    out.push_back(
        instance.world_from_object.point(Vec3d(mesh.positions[mesh.indices[3 * triangle + k]])));
  return out;
}

// Irradiance on the plane z = -3 (normal +z) at p from the scene's point light.
double point_light_irradiance(const Scene& scene, Vec3d p) {
  const Light& bulb = scene.lights.at(0);
  const Vec3d to_light = bulb.world_from_light.translation() - p;
  const double d2 = dot(to_light, to_light);
  return bulb.intensity.x * (to_light.z / std::sqrt(d2)) / d2;
}

// Each pixel whose footprint lies on the 2 x 2 m square at z = -3 against rho / pi times the
// irradiance `irradiance(p)` averaged over the footprint (box filter, 4 x 4 points), in channel c.
test::PixelError error_on_the_square(const Scene& scene, const Image& image, size_t c, double rho,
                                     const std::function<double(Vec3d)>& irradiance) {
  const auto on_square = [](const test::WorldRay& r) -> std::optional<Vec3d> {
    const Vec3d p = r.origin + r.direction * ((-3 - r.origin.z) / r.direction.z);
    if (std::abs(p.x) < 1 && std::abs(p.y) < 1) return p;
    return std::nullopt;
  };
  return test::footprint_error(scene, image, c, 4, rho / kPi, on_square, irradiance);
}

TEST(DegenerateTriangles, LeaveNoTraceAndTheRestRendersItsAnalyticRadiance) {
  const Scene scene = test::load_hard_scene("degenerate_triangles.gltf");
  const test::TimedRender r =
      test::render_timed(scene, test::box_filtered(256, "path:max_depth=1"));
  // The lamp: its one proper triangle (the others have no area) of radiance L, by Lambert's
  // formula; the bulb by the inverse-square law.
  const std::vector<Vec3d> lamp = corners(scene, "lamp", 1);
  const double radiance = scene.materials.at(1).emission.x;
  const test::PixelError e = error_on_the_square(
      scene, r.result.image, 1, scene.materials.at(0).base_color.x, [&](Vec3d p) {
        return point_light_irradiance(scene, p) +
               test::polygon_irradiance(lamp, radiance, p, {0, 0, 1});
      });
  // 256 samples leave the lamp's sampling noise at about 0.4 % a pixel (0.6 % worst at 1024).
  const uint64_t non_finite = r.result.stats.dropped_samples;
  report_case("degenerate triangles, worst pixel", non_finite, e.worst, 0.03,
              "worst |pixel / analytic radiance - 1| on the square", r.seconds);
  report_case("degenerate triangles, mean", non_finite, std::abs(e.mean), 0.002,
              "|mean of pixel / analytic radiance - 1| over the square", r.seconds);
}

TEST(CoincidentSurfaces, RenderDeterministicallyAndEitherReflectsItsAnalyticRadiance) {
  const Scene scene = test::load_hard_scene("coincident_surfaces.gltf");
  const RenderOptions options = test::box_filtered(16, "path:max_depth=1");
  test::TimedRender runs[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    runs[threads - 1] = test::render_timed(scene, options);
  }
  EXPECT_EQ(runs[0].result.image.pixels, runs[1].result.image.pixels);
  // Albedos (0.6, 0.3, 0.3) and (0.3, 0.6, 0.3): whichever surface a sample meets, its blue is
  // 0.3 E / pi and its red + green 0.9 E / pi.
  const auto irradiance = [&](Vec3d p) { return point_light_irradiance(scene, p); };
  const Image& image = runs[1].result.image;
  Image red_green = image;
  for (size_t i = 0; i < image.pixels.size(); i += 3)
    red_green.pixels[i] = image.pixels[i] + image.pixels[i + 1];
  const double worst = std::max(error_on_the_square(scene, image, 2, 0.3, irradiance).worst,
                                error_on_the_square(scene, red_green, 0, 0.9, irradiance).worst);
  report_case("coincident surfaces",
              runs[0].result.stats.dropped_samples + runs[1].result.stats.dropped_samples, worst,
              0.01, "worst |pixel / analytic radiance - 1|, blue and red + green",
              runs[0].seconds + runs[1].seconds);
}

}  // namespace
}  // namespace fb
