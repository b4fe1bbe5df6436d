// A julia fractal's mesh (core/tessellate/tessellate_julia.h): every vertex on the set's boundary
// (the inside test flips across it along its normal, within float rounding of the set's size),
// normals pointing out of the set, and every edge shared by two triangles (closed).
#include "core/tessellate/tessellate_julia.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <utility>

#include "core/tessellate/tessellate.h"

namespace fb {
namespace {

TEST(TessellateJulia, VerticesOnTheBoundaryFacingOutInAClosedMesh) {
  JuliaFractal julia;  // objects/fractal1.pov's first set
  const double c[4] = {-0.083, 0, -0.83, -0.025};
  for (int i = 0; i < 4; ++i)
    julia.c[i] = c[i];
  julia.max_iteration = 8;
  julia_fractal_set_bounds(julia);
  Solid s;
  s.kind = SolidKind::kJuliaFractal;
  s.name = "julia";
  s.julia = std::make_shared<const JuliaFractal>(julia);
  TessellationOptions options;
  options.relative_tolerance = 2e-3;
  const TriangleMesh mesh = tessellate(s, options);
  ASSERT_GT(mesh.triangle_count(), 1000u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // float positions: a few float ulps of the bounding radius
  const double eps = 1e-5 * julia.radius;
  size_t flipped = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3d p(mesh.positions[v]), n(mesh.normals[v]);
    ASSERT_NEAR(length(n), 1, 1e-5) << v;
    EXPECT_FALSE(julia_fractal_contains(julia, p + n * eps)) << v;
    flipped += julia_fractal_contains(julia, p - n * eps);
  }
  // Inward along the normal is inside, save where the set is thinner than eps.
  EXPECT_GT(flipped, 0.99 * double(mesh.positions.size()));
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e)
      ++edges[{mesh.indices[t + size_t(e)], mesh.indices[t + size_t(e + 1) % 3]}];
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << edge.first << " " << edge.second;
  }
}

}  // namespace
}  // namespace fb
