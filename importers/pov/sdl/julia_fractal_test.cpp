// julia_fractal as the SDL reader reads it: its keywords and POV-Ray's defaults, the slice made
// unit, hostile parameters refused at their place, a step finer than the march's cap raised with
// a warning, and the functions it does not render reported.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "importers/pov/sdl/sdl_test_fixture.h"

namespace fb::pov {
namespace {

TEST_F(Sdl, JuliaFractalReadsItsKeywordsAndPovRaysDefaults) {
  Scene scene =
      run("julia_fractal { <-0.083, 0, -0.83, -0.025> quaternion cube max_iteration 8\n"
          "  precision 200 slice <0, 0, 3, 4>, 10 }\n"
          "julia_fractal { <0.5, 0, 0, 0> hypercomplex }\n"
          "julia_fractal { 1 }\n");
  ASSERT_EQ(scene.objects.size(), 3u);
  ASSERT_EQ(scene.objects[0].shape, Shape::kJuliaFractal);
  const JuliaFractal& a = *scene.objects[0].julia;
  EXPECT_EQ(a.c[2], -0.83);
  EXPECT_EQ(a.algebra, JuliaAlgebra::kQuaternion);
  EXPECT_EQ(a.power, 3);
  EXPECT_EQ(a.max_iteration, 8);
  EXPECT_DOUBLE_EQ(a.least_step, 1.0 / 200);
  EXPECT_DOUBLE_EQ(a.slice[2], 0.6);  // <0, 0, 3, 4> / 5, and its distance with it
  EXPECT_DOUBLE_EQ(a.slice[3], 0.8);
  EXPECT_DOUBLE_EQ(a.slice_distance, 2);
  // POV-Ray's bound: R = min(1 + |c|, 2)
  EXPECT_NEAR(a.radius, 1 + std::sqrt(0.083 * 0.083 + 0.83 * 0.83 + 0.025 * 0.025), 1e-6);
  const JuliaFractal& b = *scene.objects[1].julia;
  EXPECT_EQ(b.algebra, JuliaAlgebra::kHypercomplex);
  EXPECT_EQ(b.power, 2);
  EXPECT_EQ(b.radius, 4);
  EXPECT_EQ(b.exit_value, 16);
  // defaults: sqr, 20 iterations, precision 20, slice <0, 0, 0, 1>, 0; a float is all four parts
  const JuliaFractal& c = *scene.objects[2].julia;
  EXPECT_EQ(c.power, 2);
  EXPECT_EQ(c.max_iteration, 20);
  EXPECT_DOUBLE_EQ(c.least_step, 1.0 / 20);
  EXPECT_EQ(c.slice[3], 1);
  EXPECT_EQ(c.c[3], 1);
  EXPECT_EQ(c.radius, 2);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
  EXPECT_TRUE(scene.unsupported.empty());
}

TEST_F(Sdl, JuliaFractalRefusesParametersThatCannotBeMarched) {
  const struct {
    const char* text;
    const char* place;
    const char* says;
  } cases[] = {
      {"julia_fractal { <1, 0, 0, 1e400> }", "scene.pov:1:17: ", "not finite"},
      {"julia_fractal { <1, 0, 0, 0>\n  max_iteration 0 }", "scene.pov:2:17: ", "max_iteration 0"},
      {"julia_fractal { <1, 0, 0, 0> max_iteration 1e9 }", "scene.pov:1:44: ", "1 to 100"},
      {"julia_fractal { <1, 0, 0, 0> precision 0 }", "scene.pov:1:40: ", "precision 0"},
      {"julia_fractal { <1, 0, 0, 0> slice <1, 0, 0, 0>, 0 }", "scene.pov:1:36: ", "non-zero 4th"},
      {"julia_fractal { <1, 0, 0, 0> slice <0, 0, 0, 0>, 0 }", "scene.pov:1:36: ", "non-zero 4th"},
      {"julia_fractal { <1, 0, 0, 0> quaternion exp }", "scene.pov:1:41: ", "only sqr and cube"},
  };
  for (const auto& c : cases) {
    const std::string error = error_of(c.text);
    EXPECT_EQ(error.rfind(c.place, 0), 0u) << c.text << "\n" << error;
    EXPECT_NE(error.find(c.says), std::string::npos) << c.text << "\n" << error;
  }
}

TEST_F(Sdl, JuliaFractalBoundsItsStepAndReportsWhatItDoesNotRender) {
  Scene scene =
      run("julia_fractal { <1, 0, 0, 0> precision 1e9 }\n"
          "julia_fractal { <1, 0, 0, 0> hypercomplex pwr(2, 1) }\n"
          "julia_fractal { <1, 0, 0, 0> hypercomplex cube }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  const JuliaFractal& j = *scene.objects[0].julia;
  EXPECT_DOUBLE_EQ(j.least_step, 2 * j.radius / kJuliaMaxSamples);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("scene.pov:1:1"), std::string::npos) << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("precision"), std::string::npos) << scene.warnings[0];
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_EQ(scene.unsupported[0].feature, "julia_fractal hypercomplex pwr");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:2:1");
  EXPECT_EQ(scene.unsupported[1].feature, "julia_fractal hypercomplex cube");
}

}  // namespace
}  // namespace fb::pov
