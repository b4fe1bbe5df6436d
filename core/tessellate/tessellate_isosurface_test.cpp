// An isosurface's mesh (core/tessellate/tessellate_isosurface.h): vertices on the level set,
// faces within the tolerance of a sphere written as a function and facing out, a closed mesh
// where the container cuts the set, and an open one that is only the function's level.
#include "core/tessellate/tessellate_isosurface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "core/function/user_function.h"
#include "core/tessellate/tessellate.h"

namespace fb {
namespace {

// sqrt(x^2 + y^2 + z^2), or y alone
std::shared_ptr<const UserFunction> distance_or_height(bool height) {
  auto f = std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
  if (height) {
    f->push_parameter(1);
  } else {
    for (int i = 0; i < 3; ++i) {
      f->push_parameter(i);
      f->apply(FunctionOp::kSqr, 1);
      if (i) f->apply(FunctionOp::kAdd, 2);
    }
    f->apply(FunctionOp::kSqrt, 1);
  }
  f->finish();
  return f;
}

Solid isosurface_primitive(double threshold, bool height = false, bool open = false) {
  Isosurface iso;
  iso.function = distance_or_height(height);
  iso.threshold = threshold;
  Solid s;
  s.kind = SolidKind::kIsosurface;
  s.name = "iso";
  s.open = open;
  s.isosurface = std::make_shared<const Isosurface>(std::move(iso));
  return s;
}

Vec3d at(const TriangleMesh& mesh, size_t corner) {
  return Vec3d(mesh.positions[mesh.indices[corner]]);
}

TEST(TessellateIsosurface, SphereFunctionStaysWithinTheToleranceFacingOut) {
  const Solid s = isosurface_primitive(0.8);
  const TessellationOptions options;
  const TriangleMesh mesh = tessellate(s, options);
  ASSERT_GT(mesh.triangle_count(), 500u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3d p(mesh.positions[v]);
    EXPECT_NEAR(length(p), 0.8, 1e-6) << v;  // float positions
    EXPECT_GT(dot(Vec3d(mesh.normals[v]), p / length(p)), 1 - 1e-6) << v;
  }
  const double tolerance = tessellation_tolerance_m(s, options);
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3d a = at(mesh, t), b = at(mesh, t + 1), c = at(mesh, t + 2);
    const Vec3d middle = (a + b + c) / 3.0;
    EXPECT_LT(0.8 - length(middle), tolerance) << t;
    EXPECT_GT(dot(cross(b - a, c - a), middle), 0) << t;
  }
}

// The ball of radius 1.3 within the box -1 to 1: a closed mesh, every edge shared by two faces,
// the box's faces with the box's normals.
TEST(TessellateIsosurface, ContainerCutsAClosedMesh) {
  const TriangleMesh mesh = tessellate(isosurface_primitive(1.3), {});
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = mesh.indices[t + size_t(e)], b = mesh.indices[t + size_t(e + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [edge, uses] : edges)
    EXPECT_EQ(uses, 2) << edge.first << " " << edge.second;
  int on_wall = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3d p(mesh.positions[v]);
    if (std::abs(length(p) - 1.3) < 1e-5) continue;  // the ball's part
    const Vec3d n(mesh.normals[v]);
    ++on_wall;
    EXPECT_NEAR(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1, 1e-6) << v;
    EXPECT_NEAR(length(n), 1, 1e-6) << v;
    EXPECT_NEAR(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 1, 1e-6) << v;
  }
  EXPECT_GT(on_wall, 100);
}

TEST(TessellateIsosurface, OpenIsTheFunctionsLevelAlone) {
  const TriangleMesh mesh = tessellate(isosurface_primitive(0, true, true), {});
  ASSERT_GT(mesh.triangle_count(), 0u);
  double area = 0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3d a = at(mesh, t), b = at(mesh, t + 1), c = at(mesh, t + 2);
    const Vec3d n = cross(b - a, c - a);
    area += 0.5 * length(n);
    EXPECT_GT(n.y, 0) << t;  // facing +y, out of the set y < 0
    for (const Vec3d& p : {a, b, c})
      EXPECT_NEAR(p.y, 0, 1e-6) << t;
  }
  EXPECT_NEAR(area, 4, 1e-4);
}

}  // namespace
}  // namespace fb
