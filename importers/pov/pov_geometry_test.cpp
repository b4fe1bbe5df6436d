// POV-Ray objects converted to solids and meshes land where POV-Ray puts them, mirrored into
// filmback's world (z -> -z), with POV-Ray's CSG and texture rules.
#include "importers/pov/pov_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/accel/solid_intersect.h"

namespace fb::pov {
namespace {

// Materials are named by their pigment's red channel: texture(0.3) becomes material 3.
Texture texture(double id) {
  Texture t;
  t.pigment.colour.r = id;
  return t;
}
const MaterialFor kMaterialFor = [](const Texture& t, const std::optional<Interior>&) {
  return uint32_t(std::lround(t.pigment.colour.r * 10));
};

Object shape(Shape kind, Vec3d a, Vec3d b, double r0, double r1 = 0, double id = 0.1) {
  Object o;
  o.shape = kind;
  o.keyword = "shape";
  o.where = {"scene.pov", 3, 1};
  o.a = a, o.b = b, o.r0 = r0, o.r1 = r1;
  o.texture = texture(id);
  return o;
}

Object csg(Shape kind, std::vector<Object> children) {
  Object o;
  o.shape = kind;
  o.keyword = "csg";
  o.children = std::move(children);
  return o;
}

struct Converted {
  fb::Scene scene;
  Diagnostics diagnostics;
};

std::unique_ptr<Converted> convert(std::vector<Object> objects) {
  Scene pov;
  pov.objects = std::move(objects);
  auto out = std::make_unique<Converted>();
  convert_objects(pov, kMaterialFor, out->scene, out->diagnostics);
  return out;
}

// The first hit on the only solid of the converted objects, in filmback's world.
std::optional<SolidHit> trace(const Converted& c, Vec3d origin, Vec3d direction) {
  EXPECT_EQ(c.scene.solids.size(), 1u);
  const Bounds3d reach{{-1e6, -1e6, -1e6}, {1e6, 1e6, 1e6}};
  return RenderSolid(c.scene.solids.at(0), Transform(), reach).first_hit(origin, direction, 0);
}

void expect_near(Vec3d actual, Vec3d expected, double tolerance) {
  EXPECT_LT(length(actual - expected), tolerance) << actual.x << " " << actual.y << " " << actual.z;
}

TEST(PovGeometry, SphereIsMirroredAndTransformed) {
  Object sphere = shape(Shape::kSphere, {1, 2, 3}, {}, 0.5);
  sphere.world_from_object = Transform::translate({0, 0, 1});  // POV z 3 + 1 = world z -4
  const auto c = convert({sphere});
  const auto hit = trace(*c, {1, 2, 10}, {0, 0, -1});
  ASSERT_TRUE(hit);
  expect_near(hit->position, {1, 2, -3.5}, 1e-12);
  expect_near(hit->normal, {0, 0, 1}, 1e-12);
  EXPECT_EQ(hit->material, 1u);
}

TEST(PovGeometry, PlaneNormalIsNormalisedButNotItsDistance) {
  const auto c = convert({shape(Shape::kPlane, {0, 2, 0}, {}, 1)});  // Parse_Plane: y = 1
  const auto above = trace(*c, {0.3, 5, 0.2}, {0, -1, 0});
  ASSERT_TRUE(above);
  EXPECT_NEAR(above->position.y, 1, 1e-12);
  expect_near(above->normal, {0, 1, 0}, 1e-12);
  // A plane leaning towards POV-Ray's +z leans towards filmback's -z.
  const auto leaning = convert({shape(Shape::kPlane, {0, 1, 1}, {}, 0)});
  const auto hit = trace(*leaning, {0, 5, 0}, {0, -1, 0});
  expect_near(hit->normal, normalize(Vec3d{0, 1, -1}), 1e-12);
}

TEST(PovGeometry, CylinderConeTorusAndDiscShapes) {
  Object tube = shape(Shape::kCylinder, {0, 0, 0}, {0, 0, 2}, 0.5);  // world z from 0 to -2
  tube.open = true;
  const auto cylinder = convert({tube});
  expect_near(trace(*cylinder, {-5, 0, -1}, {1, 0, 0})->position, {-0.5, 0, -1}, 1e-12);
  EXPECT_FALSE(trace(*cylinder, {0, 0, 5}, {0, 0, -1}));  // open: straight down the bore

  const auto cone = convert({shape(Shape::kCone, {0, 0, 0}, {0, 4, 0}, 2, 0, 0.2)});
  const auto side = trace(*cone, {-5, 1, 0}, {1, 0, 0});  // radius 1.5 at a quarter height
  ASSERT_TRUE(side);
  expect_near(side->position, {-1.5, 1, 0}, 1e-12);
  expect_near(side->normal, normalize(Vec3d{-4, 2, 0}), 1e-12);
  EXPECT_EQ(side->material, 2u);

  const auto torus = convert({shape(Shape::kTorus, {}, {}, 2, 0.5)});  // about POV-Ray's y
  expect_near(trace(*torus, {2, 5, 0}, {0, -1, 0})->position, {2, 0.5, 0}, 1e-12);
  expect_near(trace(*torus, {0, 0, 5}, {0, 0, -1})->position, {0, 0, 2.5}, 1e-12);
  EXPECT_FALSE(trace(*torus, {0, 5, 0}, {0, -1, 0}));  // down the hole

  const auto disc = convert({shape(Shape::kDisc, {0, 1, 0}, {0, 1, 0}, 1, 0.5)});
  expect_near(trace(*disc, {0.75, 5, 0}, {0, -1, 0})->position, {0.75, 1, 0}, 1e-12);
  EXPECT_FALSE(trace(*disc, {0.25, 5, 0}, {0, -1, 0}));
}

TEST(PovGeometry, DifferenceCutWearsTheSubtractedTexture) {
  const auto c =
      convert({csg(Shape::kDifference, {shape(Shape::kSphere, {0, 0, 0}, {}, 1, 0, 0.1),
                                        shape(Shape::kSphere, {0, 0, 1}, {}, 0.5, 0, 0.2)})});
  // The bite is at POV z = 1, world z = -1: a ray up world -z meets its cut first.
  const auto cut = trace(*c, {0, 0, -5}, {0, 0, 1});
  ASSERT_TRUE(cut);
  expect_near(cut->position, {0, 0, -0.5}, 1e-12);
  expect_near(cut->normal, {0, 0, -1}, 1e-12);
  EXPECT_EQ(cut->material, 2u);
  const auto base = trace(*c, {0, 0, 5}, {0, 0, -1});
  ASSERT_TRUE(base);
  EXPECT_EQ(base->material, 1u);
}

TEST(PovGeometry, ClippedByLeavesTheShapeOpenAndInverseFlips) {
  Object bowl = shape(Shape::kSphere, {0, 0, 0}, {}, 1);
  bowl.clipped_by.push_back(shape(Shape::kPlane, {0, 1, 0}, {}, 0, 0, 0.3));
  const auto clipped = convert({bowl});
  const auto inner = trace(*clipped, {0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(inner);
  expect_near(inner->position, {0, -1, 0}, 1e-12);
  EXPECT_EQ(inner->material, 1u);  // the clip is no surface

  Object hollow = shape(Shape::kSphere, {0, 0, 0}, {}, 1);
  hollow.inverse = true;
  const auto inverted = convert({hollow});
  const auto hit = trace(*inverted, {0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  expect_near(hit->normal, {0, -1, 0}, 1e-12);  // out of the inverted set: into the ball
}

TEST(PovGeometry, UnionIsTakenApartMergeAndInvertedUnionStayWhole) {
  const Object a = shape(Shape::kSphere, {0, 0, 0}, {}, 1),
               b = shape(Shape::kSphere, {3, 0, 0}, {}, 1);
  EXPECT_EQ(convert({csg(Shape::kUnion, {a, b})})->scene.solids.size(), 2u);
  EXPECT_EQ(convert({csg(Shape::kMerge, {a, b})})->scene.solids.size(), 1u);
  Object inverted = csg(Shape::kUnion, {a, b});
  inverted.inverse = true;
  EXPECT_EQ(convert({inverted})->scene.solids.size(), 1u);
}

TEST(PovGeometry, MeshGetsOneMeshPerTextureAndAMirroringInstance) {
  Object m = shape(Shape::kMesh, {}, {}, 0, 0, 0.4);
  m.vertices = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  m.indices = {0, 1, 2, 1, 3, 2};
  m.textures = {texture(0.5)};
  m.triangle_textures = {UINT32_MAX, 0};  // the first wears the object's texture
  m.world_from_object = Transform::translate({0, 0, 2});
  const auto c = convert({m});
  ASSERT_EQ(c->scene.meshes.size(), 2u);
  ASSERT_EQ(c->scene.instances.size(), 2u);
  EXPECT_EQ(c->scene.meshes[0].material, 4u);
  EXPECT_EQ(c->scene.meshes[1].material, 5u);
  EXPECT_EQ(c->scene.meshes[0].triangle_count(), 1u);
  EXPECT_EQ(c->scene.meshes[0].positions.size(), 3u);  // only the vertices it uses
  const Transform& world_from_object = c->scene.instances[0].world_from_object;
  EXPECT_LT(world_from_object.determinant3x3(), 0);  // the mirror: RenderGeometry re-winds
  expect_near(world_from_object.point(Vec3d(c->scene.meshes[0].positions[1])), {1, 0, -3}, 1e-12);
}

TEST(PovGeometry, QuadricIsThePolynomialInPovRaysOrder) {
  // quadric { <1, 2, 3>, <0, 0, 0>, <0, 0, 0>, -1 } in poly order (x2 xy xz x y2 yz y z2 z 1): the
  // ellipsoid x^2 + 2 y^2 + 3 z^2 <= 1, mirrored in z
  Object o = shape(Shape::kPolynomial, {}, {}, 0);
  o.order = 2;
  o.coefficients = {1, 0, 0, 0, 2, 0, 0, 3, 0, -1};
  const auto c = convert({o});
  ASSERT_EQ(c->scene.solids.size(), 1u);
  EXPECT_EQ(c->scene.solids[0].kind, SolidKind::kPolynomial);
  EXPECT_EQ(c->scene.solids[0].polynomial.size(), 4u);  // zero terms are left out
  const auto z = trace(*c, {0, 0, 5}, {0, 0, -1});
  ASSERT_TRUE(z);
  EXPECT_NEAR(z->t, 5 - 1 / std::sqrt(3.0), 1e-12);
  const auto y = trace(*c, {0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(y);
  EXPECT_NEAR(y->t, 5 - 1 / std::sqrt(2.0), 1e-12);
}

// POV-Ray 3.7's Ovus::Inside, with the collar's circle as Parse_Ovus places it (centre at
// (-horizontal, vertical), radius twice the larger sphere's, between the heights where it touches
// the spheres): the reference the converted ovus's set is held to.
struct PovOvus {
  double bottom, top, c, v, h, low, high;
  explicit PovOvus(double b, double t) : bottom(b), top(t) {
    if (b > t) {
      c = 2 * b, v = 2 * t - b - t * t / (2 * b), h = std::sqrt(b * b - v * v);
      low = -v, high = (b - v) * t / (c - t) + b;
    } else {
      c = 2 * t, v = -2 * t + b + 1.5 * t * t / b, h = std::sqrt(t * t - (v - b) * (v - b));
      high = 2 * b - v, low = -v * b / (c - b);
    }
  }
  // How far p is inside (negative: outside) each part, the largest.
  double depth(Vec3d p) const {
    const double rho = std::hypot(p.x, p.z);
    double d = std::max(bottom - length(p), top - length(p - Vec3d{0, bottom, 0}));
    if (p.y > low && p.y < high) d = std::max(d, c - std::hypot(rho + h, p.y - v));
    return d;
  }
};

// The ovus (both of Parse_Ovus's cases) is POV-Ray's set: contains() agrees with Ovus::Inside,
// every hit is on its surface (depth 0), and the surface is smooth where the collar meets the
// spheres (POV-Ray's construction makes them touch): normals on either side of a joint agree.
TEST(PovGeometry, OvusIsPovRaysSet) {
  for (const auto& [b, t] : {std::pair{1.0, 0.65}, {0.6, 1.0}}) {
    SCOPED_TRACE(t);
    const PovOvus pov(b, t);
    const auto c = convert({shape(Shape::kOvus, {}, {}, b, t)});
    EXPECT_EQ(c->diagnostics.count(), 0u);
    ASSERT_EQ(c->scene.solids.size(), 1u);
    const RenderSolid solid(c->scene.solids[0], Transform(), {{-1e6, -1e6, -1e6}, {1e6, 1e6, 1e6}});
    uint64_t state = 12345;
    const auto random = [&] {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return double(state >> 11) / double(1ull << 53) * 2 - 1;
    };
    for (int i = 0; i < 3000; ++i) {
      const Vec3d p{random() * 1.5, b / 2 + random() * 2, random() * 1.5};  // POV-Ray's space
      const double depth = pov.depth(p);
      if (std::abs(depth) < 1e-9) continue;
      EXPECT_EQ(solid.contains({p.x, p.y, -p.z}), depth > 0) << p.x << " " << p.y << " " << p.z;
    }
    for (int i = 0; i < 500; ++i) {
      const Vec3d o = normalize(Vec3d{random(), random(), random()}) * 5;
      const Vec3d d = normalize(Vec3d{random() * 0.5, b / 2 + random(), random() * 0.5} - o);
      const auto hit = solid.first_hit(o, d, 0);
      if (!hit) continue;
      const Vec3d q{hit->position.x, hit->position.y, -hit->position.z};
      EXPECT_NEAR(pov.depth(q), 0, 1e-9) << "ray " << i;
    }
    // Across each joint the surface is smooth: rays just above and just below a joint's circle.
    for (const double y : {pov.low, pov.high}) {
      Vec3d normals[2];
      for (int side = 0; side < 2; ++side) {
        const auto hit = solid.first_hit({5, y + (side ? 1e-6 : -1e-6), 0}, {-1, 0, 0}, 0);
        ASSERT_TRUE(hit);
        normals[side] = hit->normal;
      }
      EXPECT_LT(length(normals[0] - normals[1]), 1e-5) << "joint at " << y;
    }
  }
  // A top radius twice the bottom's or more: POV-Ray draws the top sphere, with a warning.
  const auto c = convert({shape(Shape::kOvus, {}, {}, 0.5, 1.2)});
  EXPECT_EQ(c->diagnostics.count(), 1u);
  const auto hit = trace(*c, {0, 5, 0}, {0, -1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->position.y, 0.5 + 1.2, 1e-12);
}

// A lemon between two points, POV-Ray 3.8's: its ends are discs of the given radii on the
// axis's planes, its wall the arc of the circle of the inner radius through both rims.
TEST(PovGeometry, LemonRunsBetweenItsRims) {
  Object o = shape(Shape::kLemon, {0, 1, 0}, {0, -1, 0}, 0.3, 0.5);
  o.r2 = 1.5;
  const auto c = convert({o});
  ASSERT_EQ(c->scene.solids.size(), 1u);
  const RenderSolid solid(c->scene.solids[0], Transform(), {{-1e6, -1e6, -1e6}, {1e6, 1e6, 1e6}});
  // Just inside each end, the wall is at the rim's radius; past the ends, nothing.
  for (const auto& [y, rim] : {std::pair{-1 + 1e-9, 0.5}, {1 - 1e-9, 0.3}}) {
    const auto hit = solid.first_hit({0, y, -5}, {0, 0, 1}, 0);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->position.z, -rim, 1e-8) << y;
  }
  EXPECT_FALSE(solid.first_hit({0, 1.001, -5}, {0, 0, 1}, 0));
  const auto cap = solid.first_hit({0.2, 5, 0}, {0, -1, 0}, 0);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->position.y, 1, 1e-12);
  expect_near(cap->normal, {0, 1, 0}, 1e-12);
  // The wall's points are the inner radius from the circle's centre: three of them fix it.
  Vec3d wall[3];
  for (int i = 0; i < 3; ++i) {
    const auto hit = solid.first_hit({5, -0.5 + 0.5 * i, 0}, {-1, 0, 0}, 0);
    ASSERT_TRUE(hit);
    wall[i] = hit->position;
  }
  // The circle through (x_i, y_i) in the meridian plane: its radius is the inner radius.
  const double ax = wall[0].x, ay = wall[0].y, bx = wall[1].x, by = wall[1].y, cx = wall[2].x,
               cy = wall[2].y;
  const double d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
  const double ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) +
                     (cx * cx + cy * cy) * (ay - by)) /
                    d;
  const double uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) +
                     (cx * cx + cy * cy) * (bx - ax)) /
                    d;
  EXPECT_NEAR(std::hypot(ax - ux, ay - uy), 1.5, 1e-9);
  EXPECT_LT(ux, 0);  // on the far side of the axis: the lemon, not the apple
  EXPECT_NEAR(std::hypot(0.5 - ux, -1 - uy), 1.5, 1e-9);  // through the base's rim
  EXPECT_NEAR(std::hypot(0.3 - ux, 1 - uy), 1.5, 1e-9);   // and the apex's
}

TEST(PovGeometry, WhatCannotBeConvertedIsReported) {
  Object hidden = shape(Shape::kSphere, {0, 0, 0}, {}, 1);
  hidden.no_image = true;
  Object mesh_in_csg = shape(Shape::kMesh, {}, {}, 0);
  mesh_in_csg.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh_in_csg.indices = {0, 1, 2};
  const auto c = convert(
      {hidden, shape(Shape::kSphere, {0, 0, 0}, {}, 0),
       csg(Shape::kIntersection, {shape(Shape::kBox, {0, 0, 0}, {1, 1, 1}, 0), mesh_in_csg})});
  EXPECT_EQ(c->diagnostics.count(), 3u);
  ASSERT_EQ(c->scene.solids.size(), 1u);  // the intersection, without its mesh
  EXPECT_TRUE(c->scene.meshes.empty());
  for (const std::string& message : c->diagnostics.messages())
    EXPECT_EQ(message.rfind("scene.pov:3:1: ", 0), 0u) << message;
  // What leaves the geometry incomplete is an unsupported object, as the sample sweep counts it.
  EXPECT_NE(c->diagnostics.messages()[0].find("unsupported object 'shape with no_image'"),
            std::string::npos);
  EXPECT_NE(c->diagnostics.messages()[2].find("unsupported object 'shape inside CSG'"),
            std::string::npos);
}

// Modifiers that change only how an object is lit are warned about, the object kept (issue 19:
// objectmods/double_illuminate.pov was rendered without a word about its back-lit panel).
TEST(PovGeometry, LightingModifiersNotRenderedAreReported) {
  Object lit_behind = shape(Shape::kSphere, {0, 0, 0}, {}, 1);
  lit_behind.double_illuminate = true;
  Object shadowless = shape(Shape::kSphere, {2, 0, 0}, {}, 1);
  shadowless.no_shadow = true;
  const auto c = convert({lit_behind, shadowless});
  EXPECT_EQ(c->scene.solids.size(), 2u);
  ASSERT_EQ(c->diagnostics.count(), 2u);
  EXPECT_NE(c->diagnostics.messages()[0].find("has double_illuminate, which is not rendered"),
            std::string::npos)
      << c->diagnostics.messages()[0];
  EXPECT_NE(c->diagnostics.messages()[1].find("has no_shadow, which is not rendered"),
            std::string::npos)
      << c->diagnostics.messages()[1];
}

}  // namespace
}  // namespace fb::pov
