// An extruded outline's mesh: on the surface within the tolerance, closed and wound outward (its
// volume by the divergence theorem is the outline's area), caps covering exactly the inside.
#include "core/tessellate/tessellate.h"

#include <gtest/gtest.h>

#include "support/outline_shapes.h"

namespace fb {
namespace {

// The outline's area by the shoelace formula over fine chords (even-odd: a hole's chords run
// either way, so each contour's area counts by its absolute value; the test outline's hole is
// the only nested contour).
double mixed_outline_area() {
  return 16 - 1.6 * 1.6 + [] {
    Outline d = test::mixed_outline();
    d.segments.erase(d.segments.begin(), d.segments.begin() + 8);
    double area = 0;
    for (const auto& [a, b] : test::chords(d, 4000))
      area += a.x * b.y - b.x * a.y;
    return std::abs(area) / 2;
  }();
}

TEST(TessellateOutline, MeshLiesOnTheSurfaceAndEnclosesTheOutlinesVolume) {
  const Outline outline = test::mixed_outline();
  const Solid s = test::outline_solid(outline, Transform::scale({1, 1, 3}));
  TessellationOptions options;
  options.relative_tolerance = 1e-4;
  const TriangleMesh mesh = tessellate(s, options);
  ASSERT_FALSE(mesh.indices.empty());
  // In object units: the scale by 3 in z is the largest stretch; x and y are not scaled.
  const double tolerance = tessellation_tolerance_m(s, options) / 3;
  double volume = 0, top_area = 0;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Vec3d a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    const Vec3d centre = (a + b + c) / 3.0, n = cross(b - a, c - a);
    volume += dot(a, cross(b, c)) / 6;
    if (std::abs(n.z) > 0 && a.z == 1 && b.z == 1 && c.z == 1) top_area += n.z / 2;
    // Walls: within the tolerance of the curves; caps: inside the outline.
    if (std::abs(n.z) < 1e-9 * length(n))
      EXPECT_LT(test::distance_to_curves(outline, {centre.x, centre.y}), tolerance);
    else
      EXPECT_TRUE(outline_contains(outline, {centre.x, centre.y}));
    for (const Vec3d& p : {a, b, c})
      EXPECT_TRUE(p.z == 0 || p.z == 1);
  }
  const double area = mixed_outline_area();
  EXPECT_NEAR(top_area, area, 1e-3 * area);
  EXPECT_NEAR(volume, area, 1e-3 * area);
}

// The conic sweep between z = 0.5 and 1.5: the mesh is the outline scaled by each vertex's z,
// closed and outward (volume = area (z1^3 - z0^3) / 3).
TEST(TessellateOutline, ConicMeshIsTheScaledSectionAndEnclosesItsVolume) {
  const Outline outline = test::mixed_outline();
  Solid s = test::outline_solid(outline);
  s.conic = true, s.radius0 = 0.5, s.radius1 = 1.5;
  TessellationOptions options;
  options.relative_tolerance = 1e-4;
  const TriangleMesh mesh = tessellate(s, options);
  ASSERT_FALSE(mesh.indices.empty());
  const double tolerance = tessellation_tolerance_m(s, options);
  double volume = 0;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Vec3d a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    volume += dot(a, cross(b, c)) / 6;
    const Vec3d centre = (a + b + c) / 3.0, n = cross(b - a, c - a);
    if (std::abs(n.z) < 0.999 * length(n)) {  // a wall: within the tolerance of the curve
      const Vec2d section{centre.x / centre.z, centre.y / centre.z};
      EXPECT_LT(test::distance_to_curves(outline, section) * centre.z, tolerance);
    }
  }
  const double area = mixed_outline_area();
  EXPECT_NEAR(volume, area * (1.5 * 1.5 * 1.5 - 0.5 * 0.5 * 0.5) / 3, 2e-3 * area);
}

TEST(TessellateOutline, OpenOutlineHasOnlyWalls) {
  Solid s = test::outline_solid(test::mixed_outline());
  s.open = true;
  const TriangleMesh mesh = tessellate(s, TessellationOptions{});
  ASSERT_FALSE(mesh.indices.empty());
  for (const Vec3f& n : mesh.normals)
    EXPECT_EQ(n.z, 0.f);
}

}  // namespace
}  // namespace fb
