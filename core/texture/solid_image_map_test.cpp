#include "core/texture/solid_image_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/math/constants.h"

namespace fb {
namespace {

constexpr double kImageMapPositionTolerance = 1e-12;

void expect_position(const SolidImageMap& map, Vec3d p, double s, double t) {
  const std::optional<Vec2d> st = image_map_position(map, p);
  ASSERT_TRUE(st) << p.x << " " << p.y << " " << p.z;
  EXPECT_NEAR(st->x, s, kImageMapPositionTolerance) << p.x << " " << p.y << " " << p.z;
  EXPECT_NEAR(st->y, t, kImageMapPositionTolerance) << p.x << " " << p.y << " " << p.z;
}

// Planar (map_type 0): x across, y up the image whatever z; repeated every unit unless `once`,
// off which nothing is read. The image's top row (t = 0) is at the top of the unit square.
TEST(SolidImageMap, PlanarProjectsXAndYAlongZ) {
  SolidImageMap map;
  expect_position(map, {0.25, 0.75, 3}, 0.25, 0.25);
  expect_position(map, {0.25, 0.1, -7}, 0.25, 0.9);
  expect_position(map, {-0.75, 2.75, 0}, 0.25, 0.25);  // repeated
  map.once = true;
  expect_position(map, {0.25, 0.75, 3}, 0.25, 0.25);
  EXPECT_FALSE(image_map_position(map, {1.25, 0.75, 0}));
  EXPECT_FALSE(image_map_position(map, {0.25, -0.01, 0}));
}

// Spherical (map_type 1): longitude theta about y from +x towards +z across, latitude phi from
// the south pole up: s = theta / 2 pi, t = 1 - (1/2 + phi / pi), at any radius.
TEST(SolidImageMap, SphericalIsLongitudeAndLatitude) {
  SolidImageMap map;
  map.projection = SolidImageProjection::kSpherical;
  for (double theta : {0.3, 1.9, 4.0, 6.0})
    for (double phi : {-1.2, -0.4, 0.0, 0.7, 1.4})
      for (double r : {0.5, 3.0}) {
        const Vec3d p{r * std::cos(phi) * std::cos(theta), r * std::sin(phi),
                      r * std::cos(phi) * std::sin(theta)};
        expect_position(map, p, theta / (2 * kPi), 0.5 - phi / kPi);
      }
  EXPECT_FALSE(image_map_position(map, {0, 0, 0}));
}

// Cylindrical (map_type 2): the longitude across, y up (repeated every unit unless `once`).
TEST(SolidImageMap, CylindricalIsLongitudeAndHeight) {
  SolidImageMap map;
  map.projection = SolidImageProjection::kCylindrical;
  for (double theta : {0.3, 2.5, 5.5})
    for (double y : {0.1, 0.6, 0.95})
      expect_position(map, {2 * std::cos(theta), y, 2 * std::sin(theta)}, theta / (2 * kPi), 1 - y);
  expect_position(map, {1, 1.25, 0}, 0, 0.75);
  map.once = true;
  EXPECT_FALSE(image_map_position(map, {1, 1.25, 0}));
  EXPECT_FALSE(image_map_position(map, {0, 0.5, 0}));  // on the axis
}

// Torus (map_type 5): the longitude about y across; up the image, the angle beta about the tube
// (radius r about the circle of major_radius R), 0 on the inner equator and a quarter turn at
// the bottom: the point ((R - r cos beta) cos theta, -r sin beta, (R - r cos beta) sin theta).
TEST(SolidImageMap, TorusIsBothAnglesAboutTheTube) {
  SolidImageMap map;
  map.projection = SolidImageProjection::kTorus;
  map.major_radius = 2;
  for (double theta : {0.2, 3.0, 5.0})
    for (double beta : {0.1, 1.0, 2.5, 4.0, 6.0}) {
      const double ring = 2 - 0.5 * std::cos(beta);
      const Vec3d p{ring * std::cos(theta), -0.5 * std::sin(beta), ring * std::sin(theta)};
      expect_position(map, p, theta / (2 * kPi), 1 - beta / (2 * kPi));
    }
}

}  // namespace
}  // namespace fb
