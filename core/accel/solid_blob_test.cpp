// The blob's intersection against its field (core/math/blob.h): a closed form for one component,
// then, for a blob of spheres and capsules under their own transforms with a negative component,
// hits on the threshold's level set, normals against finite differences, containment against the
// field, and no span missed that dense sampling of the field finds.
#include <gtest/gtest.h>

#include <cmath>

#include "core/accel/solid_intersect.h"
#include "core/math/blob.h"
#include "support/finite_difference.h"
#include "support/random_rays.h"
#include "support/solid_builders.h"

namespace fb {
namespace {

using test::kReach;
using test::primitive;

Solid blob_solid(Blob blob, const Transform& world_from_object = Transform()) {
  Solid s = primitive(SolidKind::kBlob, world_from_object);
  s.blob = std::move(blob);
  return s;
}

BlobComponent sphere(Vec3d centre, double radius, double strength,
                     const Transform& blob_from_component = Transform()) {
  return {blob_from_component.inverse(), centre, centre, radius, strength, false};
}

BlobComponent capsule(Vec3d a, Vec3d b, double radius, double strength,
                      const Transform& blob_from_component = Transform()) {
  return {blob_from_component.inverse(), a, b, radius, strength, true};
}

// Spheres and capsules merging, one squashed and turned, one capsule subtracting.
Blob mixed_blob() {
  Blob blob;
  blob.threshold = 0.6;
  blob.components = {
      sphere({0, 0, 0}, 1, 1),
      sphere({0.8, 0.3, 0}, 0.9, 1),
      sphere({0, 0, 0}, 1, 1.2,
             Transform::translate({-0.7, 0.2, 0.3}) * Transform::rotate({0.2, 0.3, 0.1, 0.9}) *
                 Transform::scale({0.5, 1.2, 0.8})),
      capsule({-1, -0.8, 0}, {1, -0.8, 0.4}, 0.5, 1.5),
      capsule({0, 0, -1}, {0, 0, 1}, 0.3, -1.2, Transform::translate({0.3, 0.2, 0})),
  };
  return blob;
}

TEST(SolidBlob, OneSphereComponentHasItsClosedForm) {
  // (1 - d^2 / 4)^2 = 0.25 at d = sqrt(2)
  Blob blob;
  blob.threshold = 0.25;
  blob.components = {sphere({1, 2, 3}, 2, 1)};
  const RenderSolid solid(blob_solid(blob), Transform(), kReach);
  const auto hit = solid.first_hit({1, 2, 10}, {0, 0, -1}, 0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 7 - std::sqrt(2.0), 1e-12);
  EXPECT_LT(length(hit->normal - Vec3d{0, 0, 1}), 1e-12);
  EXPECT_TRUE(solid.contains({1, 2, 3 + 1.41}));
  EXPECT_FALSE(solid.contains({1, 2, 3 + 1.42}));
  EXPECT_FALSE(solid.first_hit({1 + 1.42, 2, 10}, {0, 0, -1}, 0));
}

// Rays from 6 away towards the blob's middle, and points of its box (half-size 1.8).
test::RaysAtABox blob_rays() {
  return test::RaysAtABox(23, {0, 0, 0}, 6, 1.08);
}

TEST(SolidBlob, HitsLieOnTheThresholdAndNormalsMatchFiniteDifferences) {
  const Blob blob = mixed_blob();
  const RenderSolid solid(blob_solid(blob), Transform(), kReach);
  test::RaysAtABox rays = blob_rays();
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const auto [o, d] = rays.next();
    const auto hit = solid.first_hit(o, d, 0);
    if (!hit) continue;
    ++hits;
    const Vec3d p = hit->position;
    EXPECT_LT(blob_field(blob, p - d * 1e-9), blob.threshold) << "ray " << i;
    EXPECT_GE(blob_field(blob, p + d * 1e-9), blob.threshold) << "ray " << i;
    const double h = 1e-6;
    const auto f = [&](Vec3d q) { return blob_field(blob, q); };
    const Vec3d fd = test::central_difference_gradient(f, p, h);
    EXPECT_LT(length(hit->normal + normalize(fd)), 1e-5) << "ray " << i;
  }
  EXPECT_GT(hits, 150);
}

TEST(SolidBlob, ContainsAgreesWithTheField) {
  const Blob blob = mixed_blob();
  const RenderSolid solid(blob_solid(blob), Transform(), kReach);
  test::RaysAtABox points = blob_rays();
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3d p = points.in_box(1.8);
    const double f = blob_field(blob, p) - blob.threshold;
    if (std::abs(f) < 1e-9) continue;
    EXPECT_EQ(solid.contains(p), f >= 0) << p.x << " " << p.y << " " << p.z;
    inside += f >= 0;
  }
  EXPECT_GT(inside, 100);
}

// Where 8,000 samples of the field along the ray find the inside, the ray hits, no later.
TEST(SolidBlob, MissesNoSpanDenseSamplingFinds) {
  const Blob blob = mixed_blob();
  const RenderSolid solid(blob_solid(blob, Transform::scale({2, 2, 2})), Transform(), kReach);
  test::RaysAtABox rays = blob_rays();
  for (int i = 0; i < 300; ++i) {
    const auto [o, d] = rays.next();
    double first_inside = -1;
    for (int k = 0; k < 8000 && first_inside < 0; ++k) {
      const double t = 24.0 * k / 8000;
      if (blob_field(blob, (o * 2 + d * t) * 0.5) > blob.threshold + 1e-3) first_inside = t;
    }
    const auto hit = solid.first_hit(o * 2, d, 0);
    if (first_inside < 0) continue;
    ASSERT_TRUE(hit) << "ray " << i;
    EXPECT_LE(hit->t, first_inside) << "ray " << i;
  }
}

}  // namespace
}  // namespace fb
