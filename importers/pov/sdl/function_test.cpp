// User functions in the SDL: compiled once, evaluated where the scene calls them. The expected
// numbers are POV-Ray 3.7.0.10's own #debug output of the same calls (tests/pov/function_calls.pov
// prints them: `povray +Itests/pov/function_calls.pov -D +W8 +H8`).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "core/function/user_function.h"
#include "importers/pov/sdl/sdl_test_fixture.h"

namespace fb::pov {
namespace {

namespace fs = std::filesystem;

const fs::path kFunctionsInc = "/usr/share/povray-3.7/include/functions.inc";

class SdlFunction : public Sdl {
 protected:
  // Three values read back through the centre of the scene's only sphere.
  Vec3d three(const std::string& declarations, const std::string& a, const std::string& b,
              const std::string& c) {
    return centre(declarations + "sphere { <" + a + ", " + b + ", " + c + ">, 1 }\n");
  }
  // POV-Ray's functions.inc in the library folder; false if POV-Ray's includes are not here.
  bool with_functions_inc() {
    if (!fs::exists(kFunctionsInc)) return false;
    fs::copy_file(kFunctionsInc, root_ / "lib" / "functions.inc");
    return true;
  }
};

constexpr const char* kDeclarations =
    "#declare A = 2;\n"
    "#declare B = 2;\n"
    "#declare F = function(a, b) { a * b + A - B }\n"
    "#declare G = function { F(x, y) * select(z, -1, 0, 1) + min(x, y, z) + max(x, 1) }\n"
    "#declare H = function(a) { sqrt(abs(a)) + pow(a, 2) + mod(a, 3) + floor(a / 2) + 10 * (a > "
    "1) + (a < 2 & a > -5) + select(a, 7, 8) }\n";

TEST_F(SdlFunction, OperatorsBuiltinsAndCallsMatchPovRay) {
  Vec3d g = three(kDeclarations, "G(1.5, -2, 0.5)", "G(-1, 3, 0)", "G(2, 2, -1)");
  EXPECT_NEAR(g.x, -3.5, 1e-9);
  EXPECT_NEAR(g.y, 0.0, 1e-9);
  EXPECT_NEAR(g.z, -3.0, 1e-9);
  Vec3d h = three(kDeclarations, "H(3.5)", "H(-4.25)", "H(0)");
  EXPECT_NEAR(h.x, 33.620828693, 1e-8);
  EXPECT_NEAR(h.y, 23.874052813, 1e-8);
  EXPECT_NEAR(h.z, 9.0, 1e-9);
}

TEST_F(SdlFunction, FunctionsIncShapesMatchPovRay) {
  if (!with_functions_inc()) GTEST_SKIP() << "POV-Ray's includes are not installed";
  const std::string declarations =
      "#include \"functions.inc\"\n"
      "#declare T = function { f_torus(x, y, z, 2, 0.5) + f_sphere(x, y, z, 1) + 10 * "
      "f_rounded_box(x, y, z, 0.2, 1, 2, 3) }\n"
      "#declare S = function { f_superellipsoid(x, y, z, 0.5, 2) + f_ellipsoid(x, y, z, 1, 2, 3) "
      "+ f_r(x, y, z) + f_th(x, y, z) + f_ph(x, y, z) }\n"
      "#declare W = function { f_sine_wave(x, y, z) + f_scallop_wave(x, y, z) + f_helix1(x, y, z, "
      "2, 3, 0.2, 1, 1, 0.5, 30) }\n";
  Vec3d t = three(declarations, "T(0.3, 1.2, -0.4)", "T(2.5, 0.1, 1.7)", "0");
  EXPECT_NEAR(t.x, -0.279072729, 1e-8);
  EXPECT_NEAR(t.y, 17.553004795, 1e-8);
  Vec3d s = three(declarations, "S(0.3, 0.2, -0.4)", "S(0.5, -0.1, 0.7)", "0");
  EXPECT_NEAR(s.x, 5.813069076, 1e-8);
  EXPECT_NEAR(s.y, 5.140547881, 1e-8);
  Vec3d w = three(declarations, "W(0.3, 1.2, -0.4)", "W(1.1, 0.4, 0.25)", "0");
  EXPECT_NEAR(w.x, 0.416687030, 1e-8);
  EXPECT_NEAR(w.y, 0.543795324, 1e-8);
}

TEST_F(SdlFunction, WhatIsNotEvaluatedIsReportedWhereItIsCalled) {
  if (!with_functions_inc()) GTEST_SKIP() << "POV-Ray's includes are not installed";
  // declaring every function of functions.inc reports nothing; calling f_boy_surface does
  Scene scene = run("#include \"functions.inc\"\nsphere { 0, 1 }\n");
  EXPECT_TRUE(scene.unsupported.empty());
  scene =
      run("#include \"functions.inc\"\n"
          "#declare P = function { spline { linear_spline 0, <0, 0, 0> 1, <1, 1, 1> } }\n"
          "sphere { 0, 1 + f_boy_surface(1, 2, 3, 1, 1) + P(0.5).x }\n");
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_EQ(scene.unsupported[0].feature, "function internal(8)");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:3:17");
  EXPECT_EQ(scene.unsupported[1].feature, "function spline");
  EXPECT_EQ(scene.objects.at(0).r0, 1);
}

// function { pigment { ... } }: a colour where the scene calls it, a channel inside a function,
// its grey in a height field.
TEST_F(SdlFunction, PigmentFunctionsGiveTheirColour) {
  const std::string declarations =
      "#declare P = function { pigment { checker rgb <1, 0.5, 0>, rgb 0.25 } }\n"
      "#declare G = function { P(x, y, z).green * 2 + P(x, y, z).gray }\n";
  Vec3d v =
      three(declarations, "P(0.5, 0.5, 0.5).red", "P(1.5, 0.5, 0.5).blue", "G(0.5, 0.5, 0.5)");
  EXPECT_DOUBLE_EQ(v.x, 1);
  EXPECT_DOUBLE_EQ(v.y, 0.25);
  EXPECT_NEAR(v.z, 0.5 * 2 + 0.297 + 0.589 * 0.5, 1e-6);
  Scene scene =
      run("height_field { function 2, 2 { pigment { gradient x color_map { [0 rgb 0] [1 rgb 1] } } "
          "} }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  ASSERT_EQ(scene.objects[0].vertices.size(), 4u);
  EXPECT_EQ(scene.objects[0].vertices[0].y, 0);
  EXPECT_NEAR(scene.objects[0].vertices[1].y, 65535.0 / 65536, 1e-4);
  EXPECT_EQ(error_of("#declare P = function { pigment { rgb 1 } }\n"
                     "#declare F = function { P(x, y, z) }"),
            "scene.pov:2:34: pigment function 'P' gives a colour: expected .red, .green, .blue, "
            ".filter, .transmit or .gray");
}

// POV-Ray samples the function at x = column / (W - 1), y = row / (H - 1) into a 16-bit image
// (Make_Pattern_Image), whose first row lies at the far edge, z = 1.
TEST_F(SdlFunction, HeightFieldSamplesTheFunctionAsAnImage) {
  Scene scene =
      run("#declare F = function(a, b) { a * 0.5 + b * 0.25 }\n"
          "height_field { function 3, 2 { F(x, y) + 0.75 * (x > 0.9) } smooth water_level 0.1 }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& o = scene.objects[0];
  ASSERT_GE(o.vertices.size(), 6u);
  EXPECT_FALSE(o.normals.empty());  // smooth was read after the function
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 3; ++column) {
      const double x = column / 2.0, y = row / 1.0;
      const double value = std::min(x * 0.5 + y * 0.25 + (x > 0.9 ? 0.75 : 0.0), 1.0);
      const Vec3d v = o.vertices[size_t(row * 3 + column)];
      EXPECT_DOUBLE_EQ(v.x, x);
      EXPECT_DOUBLE_EQ(v.z, 1 - y);
      EXPECT_DOUBLE_EQ(v.y, std::round(value * 65535) / 65536) << row << " " << column;
    }
  // the corner (0, 0) at height 0 is under the water level: its triangle is cut
  EXPECT_GT(o.vertices.size(), 6u);

  EXPECT_EQ(error_of("height_field { function 1, 5 { x } }"),
            "scene.pov:1:25: height_field function resolution 1, 5: it needs at least 2, 2");
  EXPECT_NE(error_of("height_field { function 1e9, 1e9 { x } }").find("object limit"),
            std::string::npos);
}

TEST_F(SdlFunction, FunctionPatternsInPigmentsAndNormals) {
  Scene scene = run(
      "#declare F = function { x * 0.5 }\n"
      "sphere { 0, 1 pigment { function { F(x, y, z) + y } color_map { [0 rgb 0] [1 rgb 1] } }\n"
      "  normal { function { sin(x) } 0.3 } }\n"
      "#declare S = function { spline { linear_spline 0, <0, 0, 0> 1, <1, 1, 1> } }\n"
      "sphere { 0, 1 pigment { function { S(x).y } } }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  const Pigment& pigment = scene.objects[0].texture.pigment;
  EXPECT_EQ(pigment.pattern, Pattern::kFunction);
  EXPECT_FALSE(pigment.averaged);
  ASSERT_TRUE(pigment.function);
  EXPECT_DOUBLE_EQ(pigment.function->evaluate(0.5, 0.25, 0), 0.5);
  ASSERT_TRUE(scene.objects[0].texture.normal);
  EXPECT_TRUE(scene.objects[0].texture.normal->rendered);
  EXPECT_EQ(scene.objects[0].texture.normal->pattern, Pattern::kFunction);
  // a pattern calling a function filmback does not evaluate: averaged, and reported
  EXPECT_TRUE(scene.objects[1].texture.pigment.averaged);
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "function spline");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:5:34");
}

TEST_F(SdlFunction, BadFunctionsAreLocatedErrors) {
  EXPECT_EQ(error_of("#declare F = function(a) { a * }"),
            "scene.pov:1:32: unexpected '}' in a function");
  EXPECT_EQ(error_of("#declare F = function(a) { a }\nsphere { 0, F(1, 2) }"),
            "scene.pov:2:19: function 'F' takes 1 arguments, not 2");
  EXPECT_EQ(error_of("#declare F = function { q * 2 }"),
            "scene.pov:1:25: unknown identifier 'q' in a function");
  EXPECT_EQ(error_of("#declare F = function { pow(x) }"),
            "scene.pov:1:30: pow() takes 2 arguments, not 1");
  // sqrt of a negative number is NaN in POV-Ray; a scene value stays finite here
  EXPECT_EQ(error_of("#declare F = function { sqrt(x) }\nsphere { 0, F(-1, 0, 0) }"),
            "scene.pov:2:23: function 'F' gives no finite number here");
  // a function nested past the operand stack
  std::string deep = "#declare F = function { ";
  for (int i = 0; i < 70; ++i)
    deep += "x + (";
  deep += "x";
  for (int i = 0; i < 70; ++i)
    deep += ")";
  deep += " }";
  EXPECT_NE(error_of(deep).find("function nested deeper than 64 operands"), std::string::npos);
}

}  // namespace
}  // namespace fb::pov
