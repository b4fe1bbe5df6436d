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

}  // namespace
}  // namespace fb::pov
