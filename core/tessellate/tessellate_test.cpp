// Tessellated primitives stay within their tolerance of the exact surface, and are not needlessly
// finer than it.
#include "core/tessellate/tessellate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/math/sor.h"
#include "core/math/sphere_sweep.h"
#include "core/math/superellipsoid.h"
#include "core/scene/lathe.h"
#include "support/finite_difference.h"

namespace fb {
namespace {

// Distance from an object-space point inside the convex hull of the mesh to the exact surface.
double surface_distance(const Solid& s, Vec3d p) {
  const double rho = std::sqrt(p.x * p.x + p.y * p.y);
  switch (s.kind) {
    case SolidKind::kSphere:
      return std::abs(length(p) - 1);
    case SolidKind::kCylinder:
      return std::min({std::abs(1 - rho), std::abs(p.z), std::abs(1 - p.z)});
    case SolidKind::kCone: {
      const double k = s.radius1 - s.radius0,
                   side = (s.radius0 + k * p.z - rho) / std::sqrt(1 + k * k);
      return std::min({std::abs(side), std::abs(p.z), std::abs(1 - p.z)});
    }
    case SolidKind::kTorus:
      return std::abs(std::hypot(rho - 1, p.z) - s.radius1);
    case SolidKind::kLemon:  // the minor circle's arc, or a cap's plane
      return std::min({std::abs(std::hypot(rho + s.lemon.major, p.z) - 1),
                       std::abs(p.z - s.lemon.z_low), std::abs(p.z - s.lemon.z_high)});
    case SolidKind::kSor: {  // about y: the radial distance to the side, or to a cap's plane
      const double radial = std::sqrt(p.x * p.x + p.z * p.z);
      const SorSegment& seg = p.y < s.sor.front().y1 ? s.sor.front() : s.sor.back();
      const double side = std::abs(radial - std::sqrt(std::max(sor_radius_2(seg, p.y), 0.0)));
      return std::min({side, std::abs(p.y - s.sor.front().y0), std::abs(p.y - s.sor.back().y1)});
    }
    case SolidKind::kLathe: {  // about y: the profile's distance from (rho, y)
      const Vec2d q{std::sqrt(p.x * p.x + p.z * p.z), p.y};
      double nearest = HUGE_VAL;
      for (const OutlineSegment& seg : s.outline->segments) {
        const auto away = [&](double u) {
          const Vec2d c = segment_point(seg, u);
          return std::hypot(c.x - q.x, c.y - q.y);
        };
        // The nearest of 16 samples, then golden-section search about it: the distance has one
        // minimum that near for these gently curved profiles.
        constexpr int kSamples = 16;
        int best = 0;
        for (int i = 1; i <= kSamples; ++i)
          if (away(double(i) / kSamples) < away(double(best) / kSamples)) best = i;
        double a = std::max(best - 1, 0) / double(kSamples);
        double b = std::min(best + 1, kSamples) / double(kSamples);
        const double golden = (std::sqrt(5.0) - 1) / 2;
        for (int i = 0; i < 40; ++i) {  // to 1e-9 of the segment
          const double u1 = b - golden * (b - a), u2 = a + golden * (b - a);
          if (away(u1) < away(u2))
            b = u2;
          else
            a = u1;
        }
        nearest = std::min(nearest, away(0.5 * (a + b)));
      }
      return nearest;
    }
    case SolidKind::kSuperellipsoid: {  // |f| / |grad f|, to first order; gradient by differences
      const SuperellipsoidExponents e{s.radius0, s.radius1};
      const double h = 1e-7;
      const auto f = [&](Vec3d q) { return superellipsoid_value(e, q); };
      const Vec3d g = test::central_difference_gradient(f, p, h);
      return std::abs(f(p)) / length(g);
    }
    default:
      return std::abs(p.z);
  }
}

// The largest distance, in world metres, of points spread over every triangle.
double largest_error(const Solid& s, const TriangleMesh& mesh, double world_scale) {
  double worst = 0;
  constexpr int kSteps = 6;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Vec3d a(mesh.positions[mesh.indices[i]]), b(mesh.positions[mesh.indices[i + 1]]),
        c(mesh.positions[mesh.indices[i + 2]]);
    for (int u = 0; u <= kSteps; ++u)
      for (int v = 0; u + v <= kSteps; ++v) {
        const Vec3d p = a + (b - a) * (double(u) / kSteps) + (c - a) * (double(v) / kSteps);
        worst = std::max(worst, surface_distance(s, p) * world_scale);
      }
  }
  return worst;
}

// Triangles not wound counter-clockwise about their vertices' normals (none should be: they face
// out of the solid).
size_t wound_against_normals(const TriangleMesh& mesh) {
  size_t wrong = 0;
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    const Vec3f a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                c = mesh.positions[mesh.indices[i + 2]];
    const Vec3f n = mesh.normals[mesh.indices[i]] + mesh.normals[mesh.indices[i + 1]] +
                    mesh.normals[mesh.indices[i + 2]];
    wrong += !(dot(cross(b - a, c - a), n) > 0.f);
  }
  return wrong;
}

Solid shape(SolidKind kind, double scale, double radius0 = 1, double radius1 = 1) {
  Solid s;
  s.kind = kind;
  s.world_from_object = Transform::translate({4, -2, 7}) * Transform::rotate({0.3, 0.1, 0.2, 0.9}) *
                        Transform::scale({scale, scale, scale});
  s.radius0 = radius0, s.radius1 = radius1;
  return s;
}

TEST(Tessellate, CurvedPrimitivesStayWithinTheTolerance) {
  const double scale = 2.5;
  for (const Solid& s :
       {shape(SolidKind::kSphere, scale), shape(SolidKind::kCylinder, scale),
        shape(SolidKind::kCone, scale, 1.5, 0.5), shape(SolidKind::kTorus, scale, 1, 0.25)}) {
    for (double tolerance : {1e-2, 1e-3}) {
      TessellationOptions options;
      options.tolerance_m = tolerance, options.relative_tolerance = 0;
      const TriangleMesh mesh = tessellate(s, options);
      const double error = largest_error(s, mesh, scale);
      EXPECT_LE(error, tolerance) << int(s.kind);
      EXPECT_GT(error, tolerance / 8) << int(s.kind) << ": finer than it needs to be";
      for (size_t i = 0; i < mesh.normals.size(); ++i)  // the surface's unit normals
        ASSERT_NEAR(length(mesh.normals[i]), 1.f, 1e-6f);
    }
  }
}

// The parametric grid doubles until it meets the tolerance: from a rounded box to a star.
TEST(Tessellate, SuperellipsoidStaysWithinTheTolerance) {
  const double scale = 2.5;
  for (const auto& [e, n] : {std::pair{0.5, 0.5}, {2.5, 0.5}, {0.3, 1.5}}) {
    const Solid s = shape(SolidKind::kSuperellipsoid, scale, e, n);
    for (double tolerance : {1e-2, 1e-3}) {
      TessellationOptions options;
      options.tolerance_m = tolerance, options.relative_tolerance = 0;
      const TriangleMesh mesh = tessellate(s, options);
      const double error = largest_error(s, mesh, scale);
      EXPECT_LE(error, tolerance) << e << " " << n;
      EXPECT_GT(error, tolerance / 16) << e << " " << n << ": finer than it needs to be";
      for (size_t i = 0; i < mesh.positions.size(); ++i)  // vertices on the surface
        ASSERT_LT(surface_distance(s, Vec3d(mesh.positions[i])) * scale, 1e-5) << e << " " << n;
    }
  }
}

// A lemon's arc and caps within the tolerance, wound out of the solid; open: no caps.
TEST(Tessellate, LemonStaysWithinTheTolerance) {
  const double scale = 2.5;
  Solid s = shape(SolidKind::kLemon, scale);
  s.lemon = {0.3, -0.5, 0.6};
  for (bool open : {false, true}) {
    s.open = open;
    for (double tolerance : {1e-2, 1e-3}) {
      TessellationOptions options;
      options.tolerance_m = tolerance, options.relative_tolerance = 0;
      const TriangleMesh mesh = tessellate(s, options);
      ASSERT_GT(mesh.triangle_count(), 0u);
      const double error = largest_error(s, mesh, scale);
      EXPECT_LE(error, tolerance);
      EXPECT_GT(error, tolerance / 8) << "finer than it needs to be";
      EXPECT_EQ(wound_against_normals(mesh), 0u);
      const bool caps = std::any_of(mesh.normals.begin(), mesh.normals.end(),
                                    [](Vec3f n) { return std::abs(n.z) > 1 - 1e-6f; });
      EXPECT_EQ(caps, !open);
    }
  }
}

// A sor's profile, sampled per segment, and its caps, within the tolerance.
TEST(Tessellate, SorStaysWithinTheTolerance) {
  const double scale = 2.5;
  Solid s = shape(SolidKind::kSor, scale);
  s.sor = sor_from_points({{0.5, -0.5}, {0.8, 0}, {0.4, 0.5}, {1.0, 1.1}});
  for (double tolerance : {1e-2, 1e-3}) {
    TessellationOptions options;
    options.tolerance_m = tolerance, options.relative_tolerance = 0;
    const TriangleMesh mesh = tessellate(s, options);
    ASSERT_GT(mesh.triangle_count(), 0u);
    EXPECT_LE(largest_error(s, mesh, scale), tolerance);
    EXPECT_EQ(wound_against_normals(mesh), 0u);
  }
}

TEST(Tessellate, FacesPointOutOfTheSolid) {
  for (SolidKind kind :
       {SolidKind::kSphere, SolidKind::kBox, SolidKind::kCylinder, SolidKind::kCone,
        SolidKind::kTorus, SolidKind::kDisc, SolidKind::kSuperellipsoid}) {
    Solid s = shape(kind, 1, 1, kind == SolidKind::kDisc ? 0.5 : 0.3);
    TessellationOptions options;
    options.tolerance_m = 1e-2;
    const TriangleMesh mesh = tessellate(s, options);
    ASSERT_GT(mesh.triangle_count(), 0u);
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
      const Vec3f a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                  c = mesh.positions[mesh.indices[i + 2]];
      const Vec3f n = mesh.normals[mesh.indices[i]] + mesh.normals[mesh.indices[i + 1]] +
                      mesh.normals[mesh.indices[i + 2]];
      ASSERT_GT(dot(cross(b - a, c - a), n), 0.f) << int(kind) << " triangle " << i / 3;
    }
  }
}

TEST(Tessellate, HalfSpaceIsASquareAboutTheNearestPoint) {
  Solid s;
  s.kind = SolidKind::kHalfSpace;
  s.world_from_object = Transform::translate({0, 3, 0}) * Transform::scale({0.5, 0.5, 0.5});
  TessellationOptions options;
  options.plane_half_size_m = 100;
  options.plane_centre = {10, 20, 30};
  const TriangleMesh mesh = tessellate(s, options);
  ASSERT_EQ(mesh.triangle_count(), 2u);
  Bounds3d world;
  for (const Vec3f& p : mesh.positions)
    world.extend(s.world_from_object.point(Vec3d(p)));
  EXPECT_NEAR(world.lo.x, 10 - 100, 1e-9);
  EXPECT_NEAR(world.hi.y, 20 + 100, 1e-9);
  EXPECT_NEAR(world.lo.z, 0, 1e-9);
  EXPECT_NEAR(world.hi.z, 0, 1e-9);
}

TEST(Tessellate, SceneSolidsBecomeMeshes) {
  Scene scene;
  Solid pair;
  pair.kind = SolidKind::kUnion;
  pair.children = {shape(SolidKind::kSphere, 1), shape(SolidKind::kBox, 1)};
  pair.children[1].material = 1;
  pair.children[1].world_from_object =  // half in the sphere: what is inside is no surface
      Transform::translate({1, 0, 0}) * pair.children[1].world_from_object;
  Solid ground = shape(SolidKind::kHalfSpace, 1);
  Solid cut;
  cut.kind = SolidKind::kIntersection;
  cut.children = {shape(SolidKind::kSphere, 1), shape(SolidKind::kBox, 0.5)};
  cut.children[1].inverse = true;
  Solid nothing;  // two spheres 10 m apart have no common point
  nothing.kind = SolidKind::kIntersection;
  nothing.name = "nothing";
  nothing.children = {shape(SolidKind::kSphere, 1), shape(SolidKind::kSphere, 1)};
  nothing.children[1].world_from_object =
      Transform::translate({10, 0, 0}) * nothing.children[1].world_from_object;
  scene.solids = {pair, ground, cut, nothing};
  SceneCamera camera;
  camera.world_from_camera = Transform::translate({0, 0, 50});
  scene.cameras.push_back(camera);
  Diagnostics diagnostics;
  tessellate_solids(scene, TessellationOptions(), diagnostics);
  EXPECT_TRUE(scene.solids.empty());
  // The union's two materials, the ground, the cut sphere; the empty set is reported.
  ASSERT_EQ(scene.meshes.size(), 4u);
  ASSERT_EQ(scene.instances.size(), 4u);
  EXPECT_EQ(scene.meshes[0].material, 0u);
  EXPECT_EQ(scene.meshes[1].material, 1u);
  ASSERT_EQ(diagnostics.count(), 1u);
  EXPECT_NE(diagnostics.messages()[0].find("nothing"), std::string::npos);
  // The ground reaches at least the default half-size around the camera's foot on the plane.
  Bounds3d ground_bounds;
  for (const Vec3f& p : scene.meshes[2].positions)
    ground_bounds.extend(scene.instances[2].world_from_object.point(Vec3d(p)));
  const Vec3d foot = ground.world_from_object.point(
      ground.world_from_object.inverse().point({0, 0, 50}) * Vec3d{1, 1, 0});
  EXPECT_LT(min_component(ground_bounds.hi - foot), 1e4 * 1.0001);
  EXPECT_GT(max_component(ground_bounds.hi - foot), 1e4 * 0.9999);
}

// A lathe's profile (a Bézier bulge closed by a line), sampled per segment, within the
// tolerance, its faces and normals out of the solid.
TEST(Tessellate, LatheStaysWithinTheTolerance) {
  const double scale = 2.5;
  Solid s = shape(SolidKind::kLathe, scale);
  Outline profile;
  profile.segments = {cubic_bezier_segment({0.5, 0}, {1.5, 0.2}, {1.5, 0.8}, {0.5, 1}),
                      line_segment({0.5, 1}, {0.5, 0})};
  finish_outline(profile);
  s.outline = std::make_shared<const Outline>(profile);
  for (double tolerance : {1e-2, 2e-3}) {
    TessellationOptions options;
    options.tolerance_m = tolerance, options.relative_tolerance = 0;
    const TriangleMesh mesh = tessellate(s, options);
    ASSERT_GT(mesh.triangle_count(), 0u);
    const double error = largest_error(s, mesh, scale);
    EXPECT_LE(error, tolerance);
    EXPECT_GT(error, tolerance / 16) << "finer than it needs to be";
    EXPECT_EQ(wound_against_normals(mesh), 0u);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {  // the normals out of the solid
      const Vec3d p(mesh.positions[i]), n(mesh.normals[i]);
      if (p.y < 1e-3 || p.y > 1 - 1e-3) continue;  // at the corners, beside the other piece
      ASSERT_TRUE(lathe_contains(*s.outline, p - n * 1e-4)) << "vertex " << i;
      ASSERT_FALSE(lathe_contains(*s.outline, p + n * 1e-4)) << "vertex " << i;
    }
  }
}

// A sphere sweep's tubes and caps (a linear segment that narrows and a Catmull-Rom curve):
// every vertex on the sphere at its u, so never outside its own segment (min over u of
// |p - c(u)|^2 - r(u)^2 <= 0, within float rounding of the sweep's size) and, save where a tube
// bends tighter than its radius and folds into itself, on that segment's envelope (0 there);
// faces wound about the normals.
TEST(Tessellate, SphereSweepVerticesLieOnTheSweptSurface) {
  for (SweepSpline spline : {SweepSpline::kLinear, SweepSpline::kCatmullRom}) {
    Solid s = shape(SolidKind::kSphereSweep, 1);
    s.sweep = std::make_shared<const SphereSweep>(sphere_sweep_from_spheres(
        spline, {{-1.5, 0, 0}, {-0.5, 0.8, 0.2}, {0.5, -0.3, 0.4}, {1.5, 0.2, -0.5}},
        {0.5, 0.3, 0.4, 0.25}));
    TessellationOptions options;
    options.tolerance_m = 2e-3, options.relative_tolerance = 0;
    const TriangleMesh mesh = tessellate(s, options);
    ASSERT_GT(mesh.triangle_count(), 500u);
    EXPECT_EQ(wound_against_normals(mesh), 0u);
    // |p - c|^2 - r^2 with |p - c| = r off by float rounding (1e-7 of ~2 units): ~2 r 1e-7
    constexpr double kOnSweep = 2e-6;
    size_t on_envelope = 0;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3d p(mesh.positions[i]);
      double nearest = HUGE_VAL;
      for (const SweepSegment& segment : s.sweep->segments) {
        const double v = sweep_segment_value(segment, p);
        if (std::abs(v) < std::abs(nearest)) nearest = v;
      }
      ASSERT_LT(nearest, kOnSweep) << "vertex " << i << ", spline " << int(spline);
      on_envelope += std::abs(nearest) < kOnSweep;
    }
    // measured: every vertex of the linear sweep, 96.9 % of the Catmull-Rom one
    EXPECT_GT(double(on_envelope), 0.95 * double(mesh.positions.size())) << int(spline);
  }
}
}  // namespace
}  // namespace fb
