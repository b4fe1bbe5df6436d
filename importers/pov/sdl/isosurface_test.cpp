// isosurface and parametric as the SDL reader reads them: keywords and POV-Ray's defaults, bad
// bounds refused at their place, the load-time warnings (a gradient above max_gradient, a
// function with no number in its container), and the parametric mesh's distance from the exact
// surface it samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/function/isosurface_function.h"
#include "importers/pov/sdl/sdl_test_fixture.h"

namespace fb::pov {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(Sdl, IsosurfaceReadsItsKeywordsAndPovRaysDefaults) {
  Scene scene =
      run("isosurface { function { sqrt(x*x + y*y + z*z) - 1 } contained_by { sphere { <0, 1, 0>, "
          "2 } }\n"
          "  threshold 0.5 accuracy 0.01 max_gradient 3 open max_trace 2 all_intersections }\n"
          "isosurface { function { y } }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  const Object& a = scene.objects[0];
  ASSERT_EQ(a.shape, Shape::kIsosurface);
  const Isosurface& iso = *a.isosurface;
  EXPECT_TRUE(a.open);
  EXPECT_TRUE(iso.sphere_container);
  EXPECT_EQ(iso.centre.y, 1);
  EXPECT_EQ(iso.radius, 2);
  EXPECT_EQ(iso.threshold, 0.5);
  EXPECT_EQ(iso.accuracy, 0.01);
  EXPECT_EQ(iso.max_gradient, 3);
  EXPECT_DOUBLE_EQ(isosurface_value(iso, {0, 3, 4}), 4 - 0.5);
  // no contained_by: POV-Ray's box from -1 to 1; threshold 0, accuracy 0.001, max_gradient 1.1
  const Isosurface& b = *scene.objects[1].isosurface;
  EXPECT_FALSE(b.sphere_container);
  EXPECT_EQ(b.box_lo.x, -1);
  EXPECT_EQ(b.box_hi.z, 1);
  EXPECT_EQ(b.threshold, 0);
  EXPECT_EQ(b.accuracy, 0.001);
  EXPECT_EQ(b.max_gradient, 1.1);
  EXPECT_FALSE(scene.objects[1].open);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
}

TEST_F(Sdl, IsosurfaceRefusesBoundsThatCannotBeWalked) {
  const struct {
    const char* text;
    const char* place;
    const char* says;
  } cases[] = {
      {"isosurface { function { y }\n  max_gradient 0 }", "scene.pov:2:16: ", "max_gradient 0"},
      {"isosurface { function { y } accuracy -1 }", "scene.pov:1:38: ", "accuracy -1"},
      {"isosurface { function { y } threshold 1e400 }", "scene.pov:1:39: ", "not finite"},
      {"isosurface { function { y } contained_by { box { 0, <1, 0, 1> } } }",
       "scene.pov:1:44: ", "span a volume"},
      {"isosurface { function { y } contained_by { box { -1e308, 1e308 } } }",
       "scene.pov:1:44: ", "span a volume"},
      {"isosurface { function { y } contained_by { sphere { 0, 0 } } }",
       "scene.pov:1:44: ", "radius must be positive"},
      {"isosurface { function { y } contained_by { cone { 0, 1, 1, 0 } } }",
       "scene.pov:1:44: ", "a box or a sphere"},
      {"isosurface { threshold 1 }", "scene.pov:1:", "function first"},
  };
  for (const auto& c : cases) {
    const std::string error = error_of(c.text);
    EXPECT_EQ(error.rfind(c.place, 0), 0u) << c.text << "\n" << error;
    EXPECT_TRUE(has(error, c.says)) << c.text << "\n" << error;
  }
}

TEST_F(Sdl, IsosurfaceWarnsOfAGradientAboveMaxGradientAndOfNoNumber) {
  Scene scene =
      run("isosurface { function { 5 * x } }\n"
          "isosurface { function { 5 * x } max_gradient 6 }\n"
          "isosurface { function { sqrt(-1 - x * x) } }\n"
          "isosurface { function { 5 * x } evaluate 1, 1.5, 0.7 }\n");
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_TRUE(has(scene.warnings[0], "scene.pov:1:1")) << scene.warnings[0];
  EXPECT_TRUE(has(scene.warnings[0], "maximum gradient found was 5.000, but max_gradient is 1.100"))
      << scene.warnings[0];
  EXPECT_TRUE(has(scene.warnings[1], "scene.pov:3:1")) << scene.warnings[1];
  EXPECT_TRUE(has(scene.warnings[1], "not a number anywhere")) << scene.warnings[1];
  // evaluate: the probe's steepest gradient times P1
  EXPECT_NEAR(scene.objects[3].isosurface->max_gradient, 7.5, 1e-9);
}

// A unit sphere as x = cos u sin v, y = cos v, z = sin u sin v over u in [0, 2 pi], v in [0, pi]:
// every vertex on it, and no triangle's middle (about the farthest point of a flat triangle from
// the sphere) further inside than the chord error of a cell's diagonal, an arc of at most
// sqrt((2 pi / 256)^2 + (pi / 256)^2) = sqrt(5) pi / 256: 1 - cos(sqrt(5) pi / 512) = 9.4e-5.
TEST_F(Sdl, ParametricIsAMeshWithinTheGridsChordErrorOfTheSurface) {
  Scene scene =
      run("parametric { function { cos(u) * sin(v) }, function { cos(v) }, function { sin(u) * "
          "sin(v) }\n"
          "  <0, 0>, <2 * pi, pi> contained_by { box { -2, 2 } } accuracy 0.001 max_gradient 2\n"
          "  precompute 10, x, y, z }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& o = scene.objects[0];
  ASSERT_EQ(o.shape, Shape::kMesh);
  EXPECT_EQ(o.indices.size(), 3u * 2 * 256 * 256);
  ASSERT_EQ(o.normals.size(), o.vertices.size());
  double vertex_error = 0, middle_error = 0;
  for (size_t i = 0; i < o.vertices.size(); ++i) {
    vertex_error = std::max(vertex_error, std::abs(length(o.vertices[i]) - 1));
    EXPECT_GT(dot(o.normals[i], o.vertices[i]) * dot(o.normals[i], o.vertices[i]), 0.99) << i;
  }
  for (size_t t = 0; t < o.indices.size(); t += 3) {
    const Vec3d middle =
        (o.vertices[o.indices[t]] + o.vertices[o.indices[t + 1]] + o.vertices[o.indices[t + 2]]) /
        3.0;
    middle_error = std::max(middle_error, std::abs(length(middle) - 1));
  }
  EXPECT_LT(vertex_error, 1e-12);
  EXPECT_LT(middle_error, 1 - std::cos(std::sqrt(5.0) * M_PI / 512));
  EXPECT_GT(middle_error, 1e-6);  // the mesh is flat between its vertices
}

TEST_F(Sdl, ParametricCutsAtItsContainerAndRefusesAnEmptyRange) {
  // a plane y = 0 over [-2, 2]^2 in the default container: the triangles whose middle is within
  // the box -1 to 1, and no vertex outside it but those they share
  Scene scene =
      run("parametric { function { u }, function { 0 }, function { v } <-2, -2>, <2, 2> }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& o = scene.objects[0];
  EXPECT_NEAR(double(o.indices.size()) / (3 * 2 * 256 * 256), 0.25, 0.01);
  for (const Vec3d& p : o.vertices)
    EXPECT_LE(std::max(std::abs(p.x), std::abs(p.z)), 1 + 4.0 / 256);
  const std::string error =
      error_of("parametric { function { u }, function { 0 }, function { v }\n  <0, 1>, <1, 1> }");
  EXPECT_EQ(error.rfind("scene.pov:2:3: ", 0), 0u) << error;
  EXPECT_TRUE(has(error, "non-zero width")) << error;
}

}  // namespace
}  // namespace fb::pov
