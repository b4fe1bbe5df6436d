#include "importers/pov/sdl/evaluate.h"
#include "importers/pov/sdl/sdl_test_fixture.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/error.h"

namespace fb::pov {
namespace {

namespace fs = std::filesystem;

TEST_F(Sdl, ArithmeticPrecedenceAndFunctions) {
  EXPECT_DOUBLE_EQ(number("1 + 2 * 3 - 4 / 8"), 6.5);
  EXPECT_DOUBLE_EQ(number("-2 * -3"), 6);
  EXPECT_DOUBLE_EQ(number("(1 < 2) + (2 <= 2) + (3 = 3) + (3 != 3) + (1 > 2)"), 3);
  EXPECT_DOUBLE_EQ(number("(1 & 0) + (1 | 0) + !0"), 2);
  EXPECT_DOUBLE_EQ(number("0 ? 5 : 7"), 7);
  // povray 3.7.0.10 prints 1038 and 1 for these (#debug str(...)): 4 + 1024 + 3 + 9 - 2, and
  // fmod 1 + truncated 3 + truncated -2 + floor -3 + ceil 2
  EXPECT_DOUBLE_EQ(number("sqrt(16) + pow(2, 10) + abs(-3) + max(1, 9, 4) + min(3, -2)"), 1038);
  EXPECT_DOUBLE_EQ(number("mod(7, 3) + div(7, 2) + int(-2.7) + floor(-2.5) + ceil(1.2)"), 1);
  EXPECT_NEAR(number("degrees(pi) + radians(180) + atan2(1, 1)"), 180 + M_PI + M_PI / 4, 1e-12);
  EXPECT_NEAR(number("select(-1, 10, 20, 30) + select(0, 10, 20, 30) + select(1, 10, 20, 30)"), 60,
              0);
  EXPECT_DOUBLE_EQ(number("image_width / image_height"), 320.0 / 240.0);
}

TEST_F(Sdl, VectorPromotionAndComponents) {
  Vec3d c = centre("#declare V = <1, 2, 3> * 2 + 1; sphere { V, 1 }");
  EXPECT_EQ(c.x, 3);
  EXPECT_EQ(c.y, 5);
  EXPECT_EQ(c.z, 7);
  c = centre("sphere { 2, 1 }");  // a float where a vector goes fills every component
  EXPECT_EQ(c.x, 2);
  EXPECT_EQ(c.z, 2);
  c = centre("sphere { <1, 2>, 1 }");  // a 2-vector gains z = 0
  EXPECT_EQ(c.y, 2);
  EXPECT_EQ(c.z, 0);
  c = centre("#declare V = <4, 5, 6>; sphere { <V.z, V.y, V.x> + x, 1 }");
  EXPECT_EQ(c.x, 7);
  EXPECT_EQ(c.z, 4);
  // vrotate about y by 90 maps +x to -z (POV-Ray's rotate, ../shared/notes/povray-camera.md 1.1)
  c = centre("sphere { vrotate(x, <0, 90, 0>), 1 }");
  EXPECT_NEAR(c.x, 0, 1e-12);
  EXPECT_NEAR(c.z, -1, 1e-12);
  c = centre("sphere { vaxis_rotate(x, y, 90) + vcross(x, y) + vnormalize(<0, 3, 0>), 1 }");
  EXPECT_NEAR(c.y, 1, 1e-12);
  EXPECT_NEAR(c.z, 0, 1e-12);
  EXPECT_DOUBLE_EQ(number("vlength(<3, 4, 0>) + vdot(x + y, y)"), 6);
  // no comma is needed between two vectors, as in POV-Ray
  Scene scene = run("box { <-1, -2, -3> <1, 2, 3> }");
  EXPECT_EQ(scene.objects.at(0).b.z, 3);
}

TEST_F(Sdl, ColourPromotionAndKeywords) {
  sdl_true("(rgb 1).filter = 0 & (rgb 1).transmit = 0 & (rgb 1).green = 1");
  // a float where a colour goes fills all five components (POV-Ray manual 3.3.1.5)
  sdl_true("(color 0.5).transmit = 0.5");
  sdl_true("(rgbf <1, 2, 3, 4>).filter = 4 & (rgbt <1, 2, 3, 4>).transmit = 4");
  sdl_true("(rgbft <1, 2, 3, 4, 5>).transmit = 5");
  sdl_true("(color red 1 green 0.5 filter 0.25).green = 0.5");
  sdl_true("(color rgb <1, 0, 0> transmit 0.5).transmit = 0.5");
  sdl_true("abs((srgb 0.5).red - 0.21404114) < 1e-6");
  Scene scene = run("#declare C = rgb <1, 0.5, 0> * 0.5; background { C }");
  ASSERT_TRUE(scene.background);
  EXPECT_DOUBLE_EQ(scene.background->g, 0.25);
}

// No comma is needed between a list's colours either: a second `rgb` starts the next colour
// (POV-Ray renders `checker rgb <1,0,0> rgb <0,1,0>` red and green), where `filter` and
// `transmit` after a colour still modify it.
TEST_F(Sdl, ColourListsNeedNoComma) {
  const Scene scene =
      run("plane { y, 0 pigment { checker rgb <1, 0, 0> rgbt <0, 1, 0, 0.5> transmit 0.25 } }");
  const Pigment& checker = scene.objects.at(0).texture.pigment;
  ASSERT_EQ(checker.list.size(), 2u);
  EXPECT_EQ(checker.list[0].colour.r, 1);
  EXPECT_EQ(checker.list[0].colour.g, 0);
  EXPECT_EQ(checker.list[1].colour.g, 1);
  EXPECT_EQ(checker.list[1].colour.transmit, 0.25);
}

TEST_F(Sdl, Strings) {
  sdl_true("strcmp(str(2, -5, 1), \"002.0\") = 0");  // measured with povray 3.7.0.10
  sdl_true("strcmp(str(3.14159, 0, 2), \"3.14\") = 0");
  sdl_true("strcmp(str(2.5, 6, -1), \"2.500000\") = 0");
  sdl_true("strcmp(concat(\"a\", \"bc\", chr(100)), \"abcd\") = 0");
  sdl_true("strlen(\"hello\") = 5 & asc(\"A\") = 65 & val(\"2.5\") = 2.5");
  sdl_true("strcmp(substr(\"abcdef\", 2, 3), \"bcd\") = 0");
  sdl_true("strcmp(strupr(\"aB\"), \"AB\") = 0 & strcmp(strlwr(\"aB\"), \"ab\") = 0");
  sdl_true("strcmp(\"tab\\there\", concat(\"tab\", chr(9), \"here\")) = 0");
}

TEST_F(Sdl, RandMatchesPovRay) {
  // povray 3.7.0.10: seed(42) gives 0.723582911241, 0.329979259598, 0.755761670357
  Scene scene =
      run("#declare S = seed(42);"
          "sphere { <rand(S), rand(S), rand(S)>, 1 }");
  EXPECT_NEAR(scene.objects.at(0).a.x, 0.723582911241, 1e-12);
  EXPECT_NEAR(scene.objects.at(0).a.y, 0.329979259598, 1e-12);
  EXPECT_NEAR(scene.objects.at(0).a.z, 0.755761670357, 1e-12);
}

TEST_F(Sdl, CommentsNestAndDirectivesRun) {
  Scene scene = run(
      "/* outer /* inner */ still a comment */ // line\n"
      "#declare N = 0;\n"
      "#while (N < 5) #declare N = N + 1; #end\n"
      "#for (I, 1, 3) #declare N = N + I; #end\n"  // 5 + 6
      "#if (N = 11) #declare R = 1; #elseif (N = 12) #declare R = 2; #else #declare R = 3; #end\n"
      "#switch (N)\n"
      "  #case (3) #declare S = 30; #break\n"
      "  #range (10, 12) #declare S = 40; #break\n"
      "  #else #declare S = 50;\n"
      "#end\n"
      "#ifdef (R) #declare T = 1; #else #declare T = 2; #end\n"
      "#ifndef (Nothing) #declare T = T + 10; #end\n"
      "#undef R\n"
      "#ifdef (R) #declare T = 100; #end\n"
      "sphere { <N, S, T>, 1 }");
  EXPECT_EQ(scene.objects.at(0).a.x, 11);
  EXPECT_EQ(scene.objects.at(0).a.y, 40);
  EXPECT_EQ(scene.objects.at(0).a.z, 11);
}

TEST_F(Sdl, MacrosScopesAndReferences) {
  Scene scene =
      run("#macro Fact(N) #if (N <= 1) 1 #else N * Fact(N - 1) #end #end\n"
          "#macro SetTo(Target, V) #declare Target = V; #end\n"  // by-reference parameter
          "#macro Local() #local Hidden = 5; Hidden * 2 #end\n"
          "#declare A = 1;\n"
          "SetTo(A, 7)\n"
          "#declare B = Local();\n"
          "#ifdef (Hidden) #error \"a macro's #local leaked\" #end\n"
          "sphere { <Fact(5), A, B>, 1 }\n");
  EXPECT_EQ(scene.objects.at(0).a.x, 120);
  EXPECT_EQ(scene.objects.at(0).a.y, 7);
  EXPECT_EQ(scene.objects.at(0).a.z, 10);
  // a macro that writes object statements
  scene = run("#macro Ball(P) sphere { P, 0.5 } #end Ball(x) Ball(y) union { Ball(z) Ball(-z) }");
  EXPECT_EQ(scene.objects.size(), 3u);
}

TEST_F(Sdl, ArraysMultiDimensional) {
  Scene scene =
      run("#declare A = array[2][3] { {1, 2, 3}, {4, 5, 6} };\n"
          "#declare B = array[4];\n"
          "#declare B[2] = A[1][2] * 10;\n"
          "#declare D = dimensions(A) + dimension_size(A, 2);\n"
          "sphere { <B[2], D, defined(B[0]) + 2 * defined(B[2])>, 1 }");
  EXPECT_EQ(scene.objects.at(0).a.x, 60);
  EXPECT_EQ(scene.objects.at(0).a.y, 5);
  EXPECT_EQ(scene.objects.at(0).a.z, 2);
  EXPECT_NE(error_of("#declare A = array[2]; #declare B = A[2];").find("out of range"),
            std::string::npos);
  EXPECT_NE(error_of("#declare A = array[2]; #declare B = A[1];").find("not initialised"),
            std::string::npos);
}

TEST_F(Sdl, IncludesScopeAndLibraryPath) {
  write("lib/lib.inc", "#declare FromLib = 3; #local Private = 1;");
  write("scene/sub/near.inc", "#declare FromSub = 4;");
  Scene scene =
      run("#include \"lib.inc\"\n#include \"sub/near.inc\"\n"
          "#ifdef (Private) #error \"an include's #local leaked\" #end\n"
          "sphere { <FromLib, FromSub, 0>, 1 }");
  EXPECT_EQ(scene.objects.at(0).a.x, 3);
  EXPECT_EQ(scene.objects.at(0).a.y, 4);
}

TEST_F(Sdl, IncludesNeverEscapeTheAllowedFolders) {
  write("outside.inc", "#declare Secret = 1;");
  std::string error = error_of("#include \"../outside.inc\"");
  EXPECT_NE(error.find("cannot include \"../outside.inc\""), std::string::npos) << error;
  error = error_of("#include \"" + (root_ / "outside.inc").string() + "\"");
  EXPECT_NE(error.find("an absolute path is refused"), std::string::npos) << error;
  error = error_of("#include \"/etc/passwd\"");
  EXPECT_NE(
      error.find("scene.pov:1:10: cannot include \"/etc/passwd\": an absolute path is refused"),
      std::string::npos)
      << error;
  error = error_of("#include \"sub/../../outside.inc\"");
  EXPECT_NE(error.find("cannot include"), std::string::npos) << error;
  error = error_of("#fopen F \"../outside.inc\" read");
  EXPECT_NE(error.find("cannot #fopen"), std::string::npos) << error;
  sdl_true("!file_exists(\"../outside.inc\")");
  // a symbolic link in the scene's folder to a file outside every allowed folder
  fs::create_symlink(root_ / "outside.inc", root_ / "scene" / "link.inc");
  error = error_of("#include \"link.inc\"");
  EXPECT_NE(error.find("cannot include \"link.inc\": not found"), std::string::npos) << error;
  error = error_of("#include \"link\"");  // POV-Ray's implied .inc
  EXPECT_NE(error.find("cannot include \"link\": not found"), std::string::npos) << error;
  error = error_of("#fopen F \"link.inc\" read");
  EXPECT_NE(error.find("cannot #fopen \"link.inc\""), std::string::npos) << error;
  // a link that stays inside is followed
  write("scene/real.inc", "#declare Inside = 2;");
  fs::create_symlink(root_ / "scene" / "real.inc", root_ / "scene" / "alias.inc");
  EXPECT_EQ(run("#include \"alias.inc\"\nsphere { 0, Inside }").objects.at(0).r0, 2);
}

TEST_F(Sdl, ErrorsCarryLocationAndIncludeChain) {
  std::string error = error_of("#declare A = 1;\n\nsphere { 0, }");
  EXPECT_EQ(error.rfind("scene.pov:3:13: ", 0), 0u) << error;
  write("scene/bad.inc", "\n  #declare X = undefined_thing;");
  error = error_of("// first line\n#include \"bad.inc\"");
  EXPECT_EQ(error.rfind("bad.inc:2:16: ", 0), 0u) << error;
  EXPECT_NE(error.find("(included from scene.pov:2:10)"), std::string::npos) << error;
  error = error_of("#error \"stop here\"");
  EXPECT_NE(error.find("scene.pov:1:"), std::string::npos);
  EXPECT_NE(error.find("stop here"), std::string::npos);
  error = error_of("#macro M() #declare Q = nope; #end\nM()");
  EXPECT_NE(error.find("in macro M called from scene.pov:2:1"), std::string::npos) << error;
  EXPECT_NE(error_of("\"unterminated").find("unterminated string"), std::string::npos);
  EXPECT_NE(error_of("/* open").find("unterminated /* comment"), std::string::npos);
}

// Each runaway fails with its limit named, within a second of processor time (docs/pov.md "The
// language").
TEST_F(Sdl, RunawayScenesFailCleanlyAndQuickly) {
  const EvaluateLimits limits;
  auto fails_quickly_with = [&](const std::string& text, const std::string& message) {
    // processor time, so that other work on the machine does not count
    const std::clock_t start = std::clock();
    std::string error = error_of(text);
    const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
    EXPECT_NE(error.find(message), std::string::npos) << error;
    EXPECT_LT(seconds, 1.0) << message;
    return error;
  };
  fails_quickly_with("#while (1) #end", "scene.pov:1:12: more than " +
                                            std::to_string(limits.loop_iterations) +
                                            " loop iterations (limit)");
  // a macro calling itself twice: few loops, many tokens
  fails_quickly_with("#macro R(N) #if (N > 0) R(N - 1) R(N - 1) #end #end R(60)",
                     "more than " + std::to_string(limits.tokens) + " tokens read (limit)");
  // the chain names the three innermost calls, how many more, and the call in the scene
  std::string error =
      fails_quickly_with("#macro R() R() #end\nR()", "macro calls nested deeper than 256 (limit)");
  EXPECT_NE(error.find("(in macro R called from scene.pov:1:12, in macro R called from "
                       "scene.pov:1:12, in macro R called from scene.pov:1:12, ... 252 more, "
                       "in macro R called from scene.pov:2:1)"),
            std::string::npos)
      << error;
  write("scene/self.inc", "#include \"self.inc\"");
  error = fails_quickly_with("#include \"self.inc\"", "includes nested deeper than 32 (limit)");
  EXPECT_NE(error.find("... 28 more, included from scene.pov:1:10)"), std::string::npos) << error;
  const std::string elements = std::to_string(limits.array_elements);
  fails_quickly_with("#declare A = array[100000000];",
                     "scene.pov:1:29: array of 100000000 elements: more than " + elements +
                         " array elements in all (limit)");
  fails_quickly_with(
      "#declare A = array[1000][1000][1000];",
      "array of 1000000000 elements: more than " + elements + " array elements in all (limit)");
  fails_quickly_with("#declare S = \"ab\"; #while (1) #declare S = concat(S, S); #end",
                     "string longer than 1048576 bytes (limit)");
  // deep nesting where an expression is expected, in each form that recurses
  fails_quickly_with("sphere { 0, " + std::string(100000, '(') + "1 }",
                     "nesting deeper than 400 levels");
  fails_quickly_with("sphere { 0, " + std::string(100000, '-') + "1 }",
                     "nesting deeper than 400 levels");
  fails_quickly_with("sphere { " + std::string(100000, '<') + "1 }",
                     "nesting deeper than 400 levels");
  fails_quickly_with(std::string(100000, '(') + "1", "unexpected '(' at the top level");
  EvaluateOptions tight;
  tight.limits.tokens = 1000;
  error = error_of("#declare I = 0; #while (I < 1000) #declare I = I + 1; #end", tight);
  EXPECT_NE(error.find("more than 1000 tokens read (limit)"), std::string::npos) << error;
}

// Found by tests/fuzz/fuzz_pov.cpp: a directive met while another one reads its arguments runs
// inside it, so directives nested that way recursed until the stack overflowed.
TEST_F(Sdl, DirectivesInsideDirectiveArgumentsCountAsNesting) {
  std::string scene;
  for (int i = 0; i < 20000; ++i)
    scene += "#switch (0) #case (1 ";
  const std::string error = error_of(scene);
  EXPECT_NE(error.find("scene.pov:1:"), std::string::npos) << error;
  // 400 levels, or fewer in a sanitized build, whose larger frames reach the stack bound first
  EXPECT_NE(error.find("nesting deeper than "), std::string::npos) << error;
  // the stack bound holds for every path that recurses through a directive
  scene.clear();
  for (int i = 0; i < 20000; ++i)
    scene += "#declare R = #switch (0) #case (1 ";
  EXPECT_NE(error_of(scene).find("nesting deeper than "), std::string::npos);
}

TEST_F(Sdl, TransformsInPovRayOrder) {
  Scene scene = run("sphere { 0, 1 scale 2 rotate y * 90 translate x }");
  const Object& o = scene.objects.at(0);
  // (1,0,0) -> scale (2,0,0) -> rotate y 90 (+x to -z) -> (0,0,-2) -> translate (1,0,-2)
  Vec3d p = o.world_from_object.point({1, 0, 0});
  EXPECT_NEAR(p.x, 1, 1e-12);
  EXPECT_NEAR(p.y, 0, 1e-12);
  EXPECT_NEAR(p.z, -2, 1e-12);
  // matrix <...> is POV-Ray's row-vector layout: the last triple translates
  scene = run(
      "#declare T = transform { matrix <1,0,0, 0,1,0, 0,0,1, 5,6,7> } sphere { 0, 1 transform T }");
  p = scene.objects.at(0).world_from_object.point({0, 0, 0});
  EXPECT_EQ(p.x, 5);
  EXPECT_EQ(p.z, 7);
  // a CSG's transforms reach its leaves; `inverse` in transform{} undoes
  scene =
      run("union { sphere { 0, 1 translate x } box { 0, 1 } translate y }"
          "sphere { 0, 1 transform { translate z inverse } }");
  EXPECT_EQ(scene.objects.at(0).children.at(0).world_from_object.point({0, 0, 0}).x, 1);
  EXPECT_EQ(scene.objects.at(0).children.at(1).world_from_object.point({0, 0, 0}).y, 1);
  EXPECT_EQ(scene.objects.at(1).world_from_object.point({0, 0, 0}).z, -1);
}

TEST_F(Sdl, TexturesInheritAndMoveWithTheObject) {
  Scene scene =
      run("#default { finish { ambient 0.3 } }\n"
          "#declare F = finish { phong 1 }\n"
          "union {\n"
          "  sphere { 0, 1 }\n"
          "  sphere { x, 1 pigment { rgb <0, 0, 1> } }\n"
          "  pigment { checker rgb 1, rgb 0 scale 2 } finish { F }\n"
          "  translate <3, 0, 0>\n"
          "}\n"
          "box { 0, 1 }");
  const Object& u = scene.objects.at(0);
  ASSERT_EQ(u.children.size(), 2u);
  EXPECT_EQ(u.children[0].texture.pigment.pattern, Pattern::kChecker);
  EXPECT_EQ(u.children[0].texture.finish.phong, 1);
  EXPECT_EQ(u.children[1].texture.pigment.pattern, Pattern::kSolid);
  EXPECT_EQ(u.children[1].texture.pigment.colour.b, 1);
  EXPECT_EQ(u.children[1].texture.finish.ambient.r, 0.3);  // #default finish under its pigment
  // pattern space = inverse(scale 2) then inverse(translate 3x): world (3,0,0) -> pattern origin
  Vec3d p = u.children[0].texture.pigment.pattern_from_world.point({3, 0, 0});
  EXPECT_NEAR(p.x, 0, 1e-12);
  p = u.children[0].texture.pigment.pattern_from_world.point({5, 2, 0});
  EXPECT_NEAR(p.x, 1, 1e-12);
  EXPECT_NEAR(p.y, 1, 1e-12);
  EXPECT_EQ(scene.objects.at(1).texture.finish.ambient.r, 0.3);  // the #default texture
}

TEST_F(Sdl, PigmentsAndMaps) {
  Scene scene =
      run("#declare M = color_map { [0 rgb 0] [1 rgb 1] }\n"
          "sphere { 0, 1 pigment { gradient y color_map { M } turbulence 0.5 octaves 3"
          "  omega 0.4 lambda 3 frequency 2 phase 0.1 sine_wave } }\n"
          "sphere { 0, 1 pigment { bozo color_map { [0.0, 0.5 color rgb 1 color rgb 1]"
          "  [0.5, 1.0 color rgb 0 color rgb 0] } } }\n");
  const Pigment& g = scene.objects.at(0).texture.pigment;
  EXPECT_EQ(g.pattern, Pattern::kGradient);
  EXPECT_EQ(g.gradient.y, 1);
  EXPECT_EQ(g.colour_map.size(), 2u);
  EXPECT_NEAR(g.colour.r, 0.5, 1e-12);  // the map's mean
  EXPECT_EQ(g.turbulence.x, 0.5);
  EXPECT_EQ(g.octaves, 3);
  EXPECT_EQ(g.wave, Wave::kSine);
  EXPECT_EQ(g.frequency, 2);
  const Pigment& b = scene.objects.at(1).texture.pigment;
  EXPECT_EQ(b.colour_map.size(), 4u);  // the old two-colour form
  EXPECT_NEAR(b.colour.r, 0.5, 1e-12);
}

TEST_F(Sdl, CameraLastExecutedWins) {
  EvaluateOptions options;
  options.image_width = 640;
  options.image_height = 480;
  Scene scene =
      run("#declare Cam = camera { location <0, 1, -5> look_at 0 angle 40 "
          "  right x * image_width / image_height }\n"
          "#if (0) camera { location 100 } #end\n"
          "camera { Cam rotate y * 30 }\n",
          options);
  ASSERT_TRUE(scene.camera);
  const CameraStatement& c = *scene.camera;
  EXPECT_EQ(c.location.y, 1);
  ASSERT_TRUE(c.look_at);
  EXPECT_EQ(*c.angle_deg, 40);
  EXPECT_TRUE(c.right_given);
  EXPECT_DOUBLE_EQ(c.right.x, 640.0 / 480.0);
  EXPECT_NEAR(c.transform.vector({1, 0, 0}).z, -0.5, 1e-12);  // rotate y*30 kept
  EXPECT_NE(error_of("#declare C = camera {} camera { C location 1 }").find("only transforms"),
            std::string::npos);
}

TEST_F(Sdl, LightsAndGlobals) {
  Scene scene =
      run("global_settings { assumed_gamma 1.0 ambient_light rgb 0.5 }\n"
          "light_source { <0, 10, 0>, rgb 1 spotlight point_at 0 radius 10 falloff 20 tightness 5"
          "  fade_distance 2 fade_power 2 translate x }\n"
          "light_source { 0, 1 area_light x, z, 3, 4 circular shadowless }\n"
          "union { light_source { 0, 1 } sphere { 0, 1 } translate y }\n");
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[0].kind, LightKind::kSpot);
  EXPECT_EQ(scene.lights[0].location.x, 1);
  EXPECT_EQ(scene.lights[0].point_at.x, 1);  // transforms move point_at too
  EXPECT_EQ(scene.lights[0].fade_power, 2);
  EXPECT_TRUE(scene.lights[1].area);
  EXPECT_EQ(scene.lights[1].size2, 4);
  EXPECT_TRUE(scene.lights[1].shadowless);
  EXPECT_EQ(scene.lights[2].location.y, 1);  // a light inside a union moves with it
  EXPECT_EQ(*scene.assumed_gamma, 1.0);
  EXPECT_EQ(scene.ambient_light.g, 0.5);
}

// The trace depth and the reflection falloff, which the `povray` integrator reads (docs/pov.md,
// "The povray integrator"); a depth or bailout past POV-Ray's bounds is refused where it stands.
TEST_F(Sdl, TraceDepthAndReflectionFalloffAreRead) {
  Scene scene =
      run("global_settings { max_trace_level 12 adc_bailout 0.01 }\n"
          "sphere { 0, 1 finish { reflection { 0.1, 0.8 falloff 3 exponent 0.5 } } }\n");
  EXPECT_EQ(*scene.max_trace_level, 12);
  EXPECT_EQ(*scene.adc_bailout, 0.01);
  ASSERT_EQ(scene.objects.size(), 1u);
  const Finish& f = scene.objects[0].texture.finish;
  EXPECT_EQ(f.reflection_falloff, 3);
  EXPECT_EQ(f.reflection_exponent, 0.5);
  EXPECT_EQ(f.reflection_max.r, 0.8);
  const std::string deep = error_of("global_settings { max_trace_level 300 }");
  EXPECT_NE(deep.find("scene.pov:1:"), std::string::npos) << deep;
  EXPECT_NE(deep.find("max_trace_level 300 is outside [1, 256]"), std::string::npos) << deep;
  EXPECT_NE(error_of("global_settings { adc_bailout -1 }").find("outside [0, 1]"),
            std::string::npos);
}

TEST_F(Sdl, UnsupportedFeaturesAreReportedAndSkipped) {
  Scene scene =
      run("rainbow { angle 42 width 5 }\n"
          "julia_fractal { <-0.083, 0, -0.83, -0.025> hypercomplex exp translate x }\n"
          "#declare F = function(a) { a * 2 }\n"
          "sphere { 0, 1 normal { quilted 0.5 } }\n"
          "global_settings { radiosity { count 100 } }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  ASSERT_GE(scene.unsupported.size(), 4u);
  EXPECT_EQ(scene.unsupported[0].feature, "rainbow");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:1:1");
  EXPECT_EQ(scene.unsupported[1].feature, "julia_fractal hypercomplex exp");
  EXPECT_EQ(scene.unsupported[1].where.line, 2u);
  ASSERT_TRUE(scene.objects[0].texture.normal);
  EXPECT_FALSE(scene.objects[0].texture.normal->rendered);
  EXPECT_EQ(scene.unsupported[2].feature, "normal pattern quilted");
}

// fog (POV-Ray 3.7 reference, "Fog"): its type, distance, colour with filter and transmit, ground
// fog's offset and altitude, and its up vector turned by its transforms; turbulence is read and
// reported; a type POV-Ray does not have, or a ground fog without altitude, is refused.
TEST_F(Sdl, FogIsReadWithItsTypeColourAndUp) {
  Scene scene =
      run("fog { fog_type 2 distance 50 colour rgbft <0.5, 0.6, 0.7, 0.1, 0.2> fog_offset 3\n"
          "      fog_alt 1.5 up x rotate z * 90 turbulence 0.2 octaves 3 }\n"
          "fog { distance 10 rgb 1 }\n");
  ASSERT_EQ(scene.fogs.size(), 2u);
  const Fog& ground = scene.fogs[0];
  EXPECT_TRUE(ground.ground);
  EXPECT_EQ(ground.distance, 50);
  EXPECT_EQ(ground.colour.g, 0.6);
  EXPECT_EQ(ground.colour.filter, 0.1);
  EXPECT_EQ(ground.colour.transmit, 0.2);
  EXPECT_EQ(ground.offset, 3);
  EXPECT_EQ(ground.altitude, 1.5);
  EXPECT_NEAR(ground.up.x, 0, 1e-12);
  EXPECT_NEAR(ground.up.y, 1, 1e-12);
  EXPECT_FALSE(scene.fogs[1].ground);
  EXPECT_EQ(scene.fogs[1].colour.b, 1);
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "fog turbulence");
  EXPECT_EQ(scene.unsupported[0].where.line, 2u);
  const std::string type = error_of("fog { fog_type 3 distance 1 }");
  EXPECT_NE(type.find("scene.pov:1:"), std::string::npos) << type;
  EXPECT_NE(type.find("fog_type must be 1 (constant) or 2"), std::string::npos) << type;
  const std::string alt = error_of("fog { fog_type 2 distance 1 }");
  EXPECT_NE(alt.find("needs a fog_alt above 0"), std::string::npos) << alt;
  const std::string huge = error_of("fog { distance 1e300 * 1e300 }");
  EXPECT_NE(huge.find("must be finite"), std::string::npos) << huge;
}

TEST_F(Sdl, MediaAreReadIntoTheInteriorWithTheirDensity) {
  Scene scene =
      run("#declare M = media { emission rgb <0.1, 0.2, 0.3> }\n"
          "sphere { 0, 1 hollow pigment { rgbt 1 } interior {\n"
          "  media { absorption 0.5 scattering { 1, rgb <0.2, 0.4, 0.6> extinction 0.5 }\n"
          "          density { rgb 0.5 } density { rgb <1, 1, 0.5> }\n"
          "          method 3 intervals 2 samples 3, 5 jitter 0.1 translate x }\n"
          "  media { M } } }\n"
          "box { 0, 1 interior { media { absorption 1 scattering { 2, 0.1 eccentricity 0.3 }\n"
          "  density { spherical color_map { [0 rgb 0] [1 rgb 1] } } } } }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  ASSERT_TRUE(scene.objects[0].interior);
  const std::vector<Media>& media = scene.objects[0].interior->media;
  ASSERT_EQ(media.size(), 2u);
  // each coefficient times the product of the constant densities: 0.5 <1, 1, 0.5>
  EXPECT_DOUBLE_EQ(media[0].absorption.r, 0.25);
  EXPECT_DOUBLE_EQ(media[0].absorption.b, 0.125);
  EXPECT_DOUBLE_EQ(media[0].scattering.g, 0.2);
  EXPECT_DOUBLE_EQ(media[0].scattering.b, 0.15);
  EXPECT_DOUBLE_EQ(media[0].extinction, 0.5);
  EXPECT_DOUBLE_EQ(media[0].emission.r, 0);
  EXPECT_EQ(media[0].samples, 3);  // the least of `samples 3, 5`
  EXPECT_EQ(media[0].intervals, 2);
  EXPECT_DOUBLE_EQ(media[1].emission.b, 0.3);  // the declared media
  EXPECT_EQ(media[1].samples, 10);             // POV-Ray 3.7's default
  // a density with a pattern counts as 1; scattering type 2 as isotropic: each reported
  const Media& patterned = scene.objects[1].interior->media.at(0);
  EXPECT_DOUBLE_EQ(patterned.absorption.g, 1);
  EXPECT_DOUBLE_EQ(patterned.scattering.r, 0.1);
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_NE(scene.unsupported[0].feature.find("scattering type"), std::string::npos);
  EXPECT_EQ(scene.unsupported[0].where.line, 7u);
  EXPECT_NE(scene.unsupported[1].feature.find("density pattern"), std::string::npos);
  EXPECT_EQ(scene.unsupported[1].where.line, 8u);

  const std::string negative = error_of("sphere { 0, 1 interior { media {\n absorption -0.5 } } }");
  EXPECT_NE(negative.find("scene.pov:2:13"), std::string::npos) << negative;
  EXPECT_NE(negative.find("absorption must be finite and at least 0"), std::string::npos)
      << negative;
  const std::string type = error_of("sphere { 0, 1 interior { media { scattering { 7, 1 } } } }");
  EXPECT_NE(type.find("scattering type must be 1 to 5"), std::string::npos) << type;
  const std::string samples = error_of("sphere { 0, 1 interior { media { samples 0 } } }");
  EXPECT_NE(samples.find("media samples must be 1 to 1000"), std::string::npos) << samples;
  const std::string unknown = error_of("sphere { 0, 1 interior { media { colour 1 } } }");
  EXPECT_NE(unknown.find("unexpected 'colour' in media"), std::string::npos) << unknown;
}

TEST_F(Sdl, NormalsAreReadWithTheirPatternAmountAndTransforms) {
  Scene scene =
      run("#declare N = normal { ripples 0.8 frequency 3 }\n"
          "plane { y, 0 normal { bumps 0.3 scale 0.1 accuracy 0.05 } }\n"
          "sphere { 0, 1 texture { normal { N translate x } } }\n"
          "box { 0, 1 normal { gradient x, 0.6 slope_map { [0, <0, 1>] [1 <1, 1>] } } }\n"
          "sphere { 0, 1 normal { wrinkles bump_size 2 turbulence 0.5 no_bump_scale } }\n"
          "sphere { 0, 1 normal { checker normal { bumps } normal { dents } } }\n");
  ASSERT_EQ(scene.objects.size(), 5u);
  const Normal& bumps = *scene.objects[0].texture.normal;
  EXPECT_EQ(bumps.pattern, Pattern::kBumps);
  EXPECT_TRUE(bumps.rendered);
  EXPECT_EQ(bumps.amount, 0.3);
  EXPECT_EQ(bumps.accuracy, 0.05);
  EXPECT_NEAR(bumps.pattern_from_world.point({1, 0, 0}).x, 10, 1e-12);  // scale 0.1, inverted
  const Normal& ripples = *scene.objects[1].texture.normal;
  EXPECT_EQ(ripples.pattern, Pattern::kRipples);
  EXPECT_EQ(ripples.amount, 0.8);
  EXPECT_EQ(ripples.frequency, 3);
  EXPECT_NEAR(ripples.pattern_from_world.point({0, 0, 0}).x, -1, 1e-12);
  const Normal& gradient = *scene.objects[2].texture.normal;
  EXPECT_EQ(gradient.amount, 0.6);
  EXPECT_EQ(gradient.gradient.x, 1);
  ASSERT_EQ(gradient.slope_map.size(), 2u);
  EXPECT_EQ(gradient.slope_map[1].height, 1);
  const Normal& wrinkles = *scene.objects[3].texture.normal;
  EXPECT_EQ(wrinkles.amount, 2);
  EXPECT_EQ(wrinkles.turbulence.y, 0.5);
  EXPECT_FALSE(wrinkles.scale_bumps);
  EXPECT_FALSE(scene.objects[4].texture.normal->rendered);  // a normal list: reported
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "normal list checker");
}

TEST_F(Sdl, NormalMapEntriesKeepTheirOwnSpaceInsideTheMaps) {
  Scene scene =
      run("plane { y, 0 normal { gradient x normal_map { [0.3 marble turbulence 0.5] "
          "[0.7 bumps 0.2 scale 0.25] } scale 2 } }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Normal& n = *scene.objects[0].texture.normal;
  EXPECT_TRUE(n.rendered);
  ASSERT_EQ(n.normal_map.size(), 2u);
  EXPECT_EQ(n.normal_map[0].value, 0.3);
  EXPECT_EQ(n.normal_map[0].normal.pattern, Pattern::kMarble);
  EXPECT_EQ(n.normal_map[0].normal.turbulence.x, 0.5);
  EXPECT_EQ(n.normal_map[1].normal.amount, 0.2);
  // the map's scale moves the map; the entry's own scale only the entry, in the map's space
  EXPECT_NEAR(n.pattern_from_world.point({1, 0, 0}).x, 0.5, 1e-12);
  EXPECT_NEAR(n.normal_map[1].normal.pattern_from_world.point({1, 0, 0}).x, 4, 1e-12);
  EXPECT_TRUE(scene.unsupported.empty());
  // POV-Ray's normavg.pov: an average map's entries have no values; read, and reported
  Scene averaged =
      run("plane { z, 0 normal { average normal_map { [gradient x, -5.0 scallop_wave scale 0.5] "
          "[gradient y, -5.0] } } }\n");
  EXPECT_FALSE(averaged.objects.at(0).texture.normal->rendered);
  ASSERT_EQ(averaged.unsupported.size(), 1u);
  EXPECT_EQ(averaged.unsupported[0].feature, "normal pattern average");
  // nested maps cost 2^depth bends per hit: deeper than 6 is an error naming the line
  const std::string error = error_of(
      "#declare N = normal { bumps }\n"
      "#for (i, 1, 8) #declare N = normal { gradient x normal_map { [0 N] [1 N] } } #end\n"
      "plane { y, 0 normal { N } }\n");
  EXPECT_NE(error.find("scene.pov:2:"), std::string::npos) << error;
  EXPECT_NE(error.find("at most 6 deep"), std::string::npos) << error;
}

// #default { normal {..} } is where every later normal starts (POV-Ray's normmap.pov sets
// bump_size 1.5 so), and a default with a pattern bends every later texture.
TEST_F(Sdl, DefaultNormalIsWhereNormalsStart) {
  Scene scene =
      run("#default { normal { bump_size 1.5 } }\n"
          "sphere { 0, 1 normal { marble } }\n"
          "sphere { 0, 1 pigment { rgb 1 } }\n"
          "#default { normal { dents 0.3 } }\n"
          "sphere { 0, 1 pigment { rgb 1 } }\n");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].texture.normal->amount, 1.5);
  EXPECT_TRUE(scene.objects[0].texture.normal->rendered);
  EXPECT_FALSE(scene.objects[1].texture.normal && scene.objects[1].texture.normal->rendered);
  ASSERT_TRUE(scene.objects[2].texture.normal);
  EXPECT_EQ(scene.objects[2].texture.normal->pattern, Pattern::kDents);
  EXPECT_EQ(scene.objects[2].texture.normal->amount, 0.3);
}

TEST_F(Sdl, LayeredTexturesKeepEveryLayerInOrder) {
  Scene scene =
      run("#declare T = texture { pigment { rgb 1 } } texture { pigment { rgbt <1, 0, 0, 0.5> } }\n"
          "plane { y, 0 texture { T translate x } texture { pigment { rgbf <0, 0, 1, 0.9> } } }\n"
          "sphere { 0, 1 texture { T } }\n"
          "box { 0, 1 material { texture { T } texture { pigment { rgbt 1 } } } }\n");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[2].texture.layers.size(), 2u);
  const Texture& plane = scene.objects[0].texture;
  ASSERT_EQ(plane.layers.size(), 2u);
  EXPECT_EQ(plane.pigment.colour.g, 1);
  EXPECT_EQ(plane.layers[0].pigment.colour.transmit, 0.5);
  EXPECT_EQ(plane.layers[1].pigment.colour.filter, 0.9);
  EXPECT_TRUE(plane.layers[0].layers.empty());
  EXPECT_EQ(scene.objects[1].texture.layers.size(), 1u);
  EXPECT_TRUE(scene.unsupported.empty());
  // layers built in a loop are bounded: an error naming the line, not a slow render
  const std::string error = error_of(
      "#declare T = texture { pigment { rgb 1 } }\n"
      "#declare L = T\n"
      "#for (i, 1, 100) #declare L = texture { L } texture { T } #end\n"
      "plane { y, 0 texture { L } }\n");
  EXPECT_NE(error.find("scene.pov:3:"), std::string::npos) << error;
  EXPECT_NE(error.find("at most 64 layers"), std::string::npos) << error;
}

// A finish, pigment or normal after a layered texture changes its top layer, the last written, as
// POV-Ray changes the head of its layer list (measured: `texture { T finish { ambient 1 diffuse
// 0 } }` over a blue base under a half-transparent red layer renders (0.5, 0, 0.05)); a finish
// changes the finish it finds rather than starting from the default one.
TEST_F(Sdl, ChangesAfterALayeredTextureGoToItsTopLayer) {
  Scene scene =
      run("#declare T = texture { pigment { rgb <0, 0, 1> } finish { phong 0.5 } }\n"
          "  texture { pigment { rgbt <1, 0, 0, 0.5> } finish { phong 0.7 } }\n"
          "box { 0, 1 texture { T finish { ambient 1 diffuse 0 } } }\n"
          "box { 0, 1 texture { T } finish { ambient 0.5 } normal { bumps 0.3 } }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  for (const Object& o : scene.objects) {
    ASSERT_EQ(o.texture.layers.size(), 1u);
    EXPECT_EQ(o.texture.finish.ambient.r, 0.1);  // the base keeps POV-Ray's default
    EXPECT_EQ(o.texture.finish.phong, 0.5);
    EXPECT_EQ(o.texture.layers[0].finish.phong, 0.7);  // kept: the finish was changed, not reset
  }
  EXPECT_EQ(scene.objects[0].texture.layers[0].finish.ambient.r, 1);
  EXPECT_EQ(scene.objects[0].texture.layers[0].finish.diffuse, 0);
  EXPECT_EQ(scene.objects[1].texture.layers[0].finish.ambient.r, 0.5);
  EXPECT_FALSE(scene.objects[1].texture.normal);
  ASSERT_TRUE(scene.objects[1].texture.layers[0].normal);
}

// An unsupported object is reported where the scene places it, not where it is declared: an
// include that declares shapes the scene never uses leaves its geometry complete.
TEST_F(Sdl, UnsupportedObjectsAreReportedWherePlaced) {
  // (a julia_fractal of a function filmback does not render: an object reported as such)
  write("lib/shapes.inc",
        "#declare Q = julia_fractal { <-0.083, 0, -0.83, -0.025> hypercomplex exp }\n");
  Scene scene = run("#include \"shapes.inc\"\nsphere { 0, 1 }");
  EXPECT_TRUE(scene.unsupported.empty());
  ASSERT_EQ(scene.objects.size(), 1u);

  scene = run("#include \"shapes.inc\"\nobject { Q translate x }");
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "julia_fractal hypercomplex exp");
  const std::string written = scene.unsupported[0].where.text();
  EXPECT_EQ(written.substr(written.size() - 19), "lib/shapes.inc:1:14") << written;
  ASSERT_TRUE(scene.unsupported[0].placed);
  EXPECT_EQ(scene.unsupported[0].placed->text(), "scene.pov:2:1");

  // inside CSG, twice: once per placement; the placement is the top-level statement
  scene =
      run("#include \"shapes.inc\"\n#declare U = union { sphere { 0, 1 } object { Q } }\n"
          "union { object { U } box { 0, 1 } }\nobject { U }");
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_EQ(scene.unsupported[0].placed->text(), "scene.pov:3:1");
  EXPECT_EQ(scene.unsupported[1].placed->text(), "scene.pov:4:1");
  EXPECT_EQ(scene.objects.size(), 2u);  // the union keeps its supported members

  // written where it is placed: no separate placement; in clipped_by too
  scene =
      run("#include \"shapes.inc\"\njulia_fractal { <0, 0, 0, 0> hypercomplex exp }\n"
          "sphere { 0, 1 clipped_by { object { Q } } }");
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_EQ(scene.unsupported[0].feature, "julia_fractal hypercomplex exp");
  EXPECT_FALSE(scene.unsupported[0].placed);
  EXPECT_EQ(scene.unsupported[1].placed->text(), "scene.pov:3:1");
}

TEST_F(Sdl, PolynomialObjects) {
  std::string coefficients35;
  for (int i = 1; i <= 35; ++i)
    coefficients35 += (i > 1 ? ", " : "") + std::to_string(i);
  Scene scene =
      run("quadric { <1, 2, 3>, <4, 5, 6>, <7, 8, 9>, 10 }\n"
          "cubic { <1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20> sturm }\n"
          "quartic { <" +
          coefficients35 +
          "> translate x }\n"
          "poly { 2 <1 0 0 0 1 0 0 1 0, -1> }\n"  // few commas, as objects/primitiv.pov
          "poly { 5, <" +
          coefficients35 +
          ", 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, "
          "1, 1, 1> }\n");
  ASSERT_EQ(scene.objects.size(), 5u);
  EXPECT_EQ(scene.objects[3].order, 2);
  EXPECT_EQ(scene.objects[3].coefficients.at(9), -1);
  // quadric: A x2 + B y2 + C z2 + D xy + E xz + F yz + G x + H y + I z + J in poly order
  const std::vector<double> quadric{1, 4, 5, 7, 2, 6, 8, 3, 9, 10};
  EXPECT_EQ(scene.objects[0].order, 2);
  EXPECT_EQ(scene.objects[0].coefficients, quadric);
  EXPECT_EQ(scene.objects[1].order, 3);
  EXPECT_EQ(scene.objects[1].coefficients.size(), 20u);
  EXPECT_EQ(scene.objects[2].coefficients.at(34), 35);
  EXPECT_EQ(scene.objects[2].world_from_object.point({0, 0, 0}).x, 1);
  EXPECT_EQ(scene.objects[4].order, 5);  // up to 15, as POV-Ray
  EXPECT_EQ(scene.objects[4].coefficients.size(), 56u);
  EXPECT_TRUE(scene.unsupported.empty());
  EXPECT_NE(error_of("poly { 16, <1> }").find("order must be 2 to 15"), std::string::npos);
}

// polynomial { N, xyz(i, j, k): c, ... } (POV-Ray 3.7): each named term at its place in poly
// order, the rest 0; a power past the order refused at the term.
TEST_F(Sdl, PolynomialTermsByTheirPowers) {
  Scene scene = run("polynomial { 4, xyz(4, 0, 0): 2, xyz(0,0,0): -1 xyz(1, 1, 2): 3.5 sturm }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& o = scene.objects[0];
  EXPECT_EQ(o.shape, Shape::kPolynomial);
  EXPECT_EQ(o.order, 4);
  ASSERT_EQ(o.coefficients.size(), 35u);
  EXPECT_EQ(o.coefficients[0], 2);    // x^4 first
  EXPECT_EQ(o.coefficients[34], -1);  // the constant last
  // poly order: the x^1 terms start after x^4 (1 term), x^3 (3) and x^2 (6); among them y^3,
  // y^2 z, y^2, then y z^2
  EXPECT_EQ(o.coefficients[10 + 3], 3.5);
  double sum = 0;
  for (double c : o.coefficients)
    sum += std::abs(c);
  EXPECT_EQ(sum, 6.5);  // no other term
  const std::string error = error_of("polynomial { 3,\n  xyz(2, 1, 1): 1 }");
  EXPECT_EQ(error.rfind("scene.pov:2:7: ", 0), 0u) << error;
  EXPECT_NE(error.find("above the order 3"), std::string::npos) << error;
  EXPECT_NE(error_of("polynomial { 3, xyz(1.5, 0, 0): 1 }").find("whole number"),
            std::string::npos);
}

// superellipsoid { <e, n> }: its exponents and flags read; hostile exponents refused with their
// place, extreme ones bounded with a warning.
TEST_F(Sdl, SuperellipsoidExponents) {
  Scene scene = run("superellipsoid { <0.25, 2.5> sturm scale 2 }");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].shape, Shape::kSuperellipsoid);
  EXPECT_EQ(scene.objects[0].r0, 0.25);
  EXPECT_EQ(scene.objects[0].r1, 2.5);
  EXPECT_TRUE(scene.unsupported.empty());
  std::string error = error_of("\nsuperellipsoid { <0, 1> }");
  EXPECT_EQ(error.rfind("scene.pov:2:18: ", 0), 0u) << error;
  EXPECT_NE(error.find("positive"), std::string::npos) << error;
  error = error_of("#declare E = -1;\nsuperellipsoid {\n  <1, E> }");
  EXPECT_EQ(error.rfind("scene.pov:3:3: ", 0), 0u) << error;
  scene = run("superellipsoid { <1e-9, 1e9> }");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].r0, 1e-3);
  EXPECT_EQ(scene.objects[0].r1, 1e3);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("scene.pov:1:"), std::string::npos) << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("bounded to <0.001, 1000>"), std::string::npos)
      << scene.warnings[0];
}

// A colour-mapped PNG whose palette is no grey ramp: red falling as the index rises.
void write_palette_png(const fs::path& file, uint32_t width, uint32_t height,
                       const std::vector<uint8_t>& indices) {
  FILE* out = std::fopen(file.c_str(), "wb");
  ASSERT_TRUE(out);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, out);
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette(256);
  for (int i = 0; i < 256; ++i)
    palette[size_t(i)] = {png_byte(255 - i), 0, png_byte(i / 2)};
  png_set_PLTE(png, info, palette.data(), 256);
  png_write_info(png, info);
  for (uint32_t y = 0; y < height; ++y)
    png_write_row(png, indices.data() + size_t(y) * width);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(out);
}

// height_field from images: its grid, heights and water level, the palette index of a
// colour-mapped image, and bad or hostile images refused with the file name's place.
TEST_F(Sdl, HeightFieldFromImages) {
  // 3 x 2 grey pixels, top row first: 0 128 255 / 10 20 30
  std::ofstream(root_ / "scene" / "h.pgm", std::ios::binary)
      << "P5\n3 2\n255\n"
      << std::string("\x00\x80\xff\x0a\x14\x1e", 6);
  Scene scene = run("height_field { pgm \"h.pgm\" smooth water_level 0.09 translate x }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& hf = scene.objects[0];
  EXPECT_EQ(hf.shape, Shape::kMesh);
  EXPECT_EQ(hf.keyword, "height_field");
  // the 3 x 2 grid, then four points where triangle edges meet the water line
  ASSERT_EQ(hf.vertices.size(), 10u);
  ASSERT_EQ(hf.normals.size(), 10u);
  for (size_t i = 6; i < 10; ++i)
    EXPECT_NEAR(hf.vertices[i].y, 0.09, 1e-12);
  const double scale = 65535.0 / 65536;  // POV-Ray's heights stay below 1
  // the top row at the far edge (z = 1), columns from x = 0 to 1
  EXPECT_EQ(hf.vertices[2].x, 1);
  EXPECT_EQ(hf.vertices[2].z, 1);
  EXPECT_NEAR(hf.vertices[2].y, 1 * scale, 1e-7);
  EXPECT_EQ(hf.vertices[3].z, 0);
  EXPECT_NEAR(hf.vertices[3].y, 10 / 255.0 * scale, 1e-7);
  // Clipped at the water line 0.09 (as POV-Ray clips): of the four triangles, the one whose
  // corners (10, 0, 20) all lie below it goes, one with one dry corner leaves a triangle, one
  // with two a quadrilateral (two triangles), the dry one stays: four.
  EXPECT_EQ(hf.indices.size(), 12u);
  EXPECT_EQ(hf.world_from_object.point({0, 0, 0}).x, 1);
  // Normals lean away from the rise: the heights grow with x on the top row.
  EXPECT_LT(hf.normals[1].x, 0);
  EXPECT_GT(hf.normals[1].y, 0);

  write_palette_png(root_ / "lib" / "p.png", 2, 2, {0, 64, 128, 255});
  scene = run("height_field { png \"p.png\" }");
  ASSERT_EQ(scene.objects.size(), 1u);
  ASSERT_EQ(scene.objects[0].vertices.size(), 4u);
  EXPECT_EQ(scene.objects[0].vertices[1].y, 64 / 256.0);  // the index, not the colour
  EXPECT_EQ(scene.objects[0].vertices[3].y, 255 / 256.0);
  EXPECT_EQ(scene.objects[0].indices.size(), 6u);
  EXPECT_TRUE(scene.objects[0].normals.empty());

  scene = run("height_field { pot \"mtmand.pot\" smooth }");
  EXPECT_TRUE(scene.objects.empty());
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "height_field");

  std::string error = error_of("height_field { pgm \"none.pgm\" }");
  EXPECT_EQ(error.rfind("scene.pov:1:20: ", 0), 0u) << error;
  write("outside.pgm", "P5\n2 2\n255\n\x01\x02\x03\x04");
  error = error_of("\nheight_field { pgm \"../outside.pgm\" }");
  EXPECT_EQ(error.rfind("scene.pov:2:20: ", 0), 0u) << error;
  write("scene/line.pgm", "P5\n3 1\n255\nabc");
  error = error_of("height_field { \"line.pgm\" }");
  EXPECT_EQ(error.rfind("scene.pov:1:16: ", 0), 0u) << error;
  EXPECT_NE(error.find("at least 2x2"), std::string::npos) << error;
  write("scene/broken.png", "\x89PNG\r\n\x1a\n garbage");
  error = error_of("height_field { png \"broken.png\" }");
  EXPECT_EQ(error.rfind("scene.pov:1:20: ", 0), 0u) << error;
  EvaluateOptions few;
  few.limits.objects = 5;  // the 3 x 2 image has more pixels than that: refused unread
  error = error_of("height_field { pgm \"h.pgm\" }", few);
  EXPECT_EQ(error.rfind("scene.pov:1:20: ", 0), 0u) << error;
  EXPECT_NE(error.find("at most 5"), std::string::npos) << error;
}

// image_map: the file found as #include finds files (the type's extension added when the name has
// none), one image per file, the map's options, how its values decode (POV-Ray 3.7's rules),
// unread types averaged, and a missing or escaping file refused with its place.
TEST_F(Sdl, ImageMapsAreFoundAndDecodedAsPovRayReadsThem) {
  write("scene/map.png", "not read by the parser");
  write("lib/sky.jpg", "not read by the parser");
  write("scene/light.exr", "not read by the parser");
  Scene scene =
      run("#version 3.7;\n"
          "sphere { 0, 1 pigment { image_map { png \"map.png\" map_type 1 once interpolate 2\n"
          "  filter all 0.2 transmit all 0.3 } scale 2 } }\n"
          "sphere { 0, 1 pigment { image_map { jpeg \"sky\" map_type 5 major_radius 3 } } }\n"
          "sphere { 0, 1 pigment { image_map { \"map.png\" gamma 1.8 map_type 4 } } }\n"
          "sphere { 0, 1 pigment { image_map { exr \"light.exr\" } } }\n"
          "sphere { 0, 1 pigment { image_map { gif \"anim.gif\" once } } }\n"
          "sphere { 0, 1 pigment { image_map { \"sky\" } } }\n");  // no type: sky.jpg
  ASSERT_EQ(scene.objects.size(), 6u);
  EXPECT_EQ(scene.objects[5].texture.pigment.image_map.image, 1u);
  ASSERT_EQ(scene.images.size(), 3u);  // map.png once for two pigments
  EXPECT_EQ(scene.images[0], root_ / "scene" / "map.png");
  EXPECT_EQ(scene.images[1], root_ / "lib" / "sky.jpg");
  const Pigment& first = scene.objects[0].texture.pigment;
  EXPECT_EQ(first.pattern, Pattern::kImageMap);
  EXPECT_FALSE(first.averaged);
  EXPECT_EQ(first.image_map.image, 0u);
  EXPECT_EQ(first.image_map.projection, SolidImageProjection::kSpherical);
  EXPECT_TRUE(first.image_map.once);
  EXPECT_EQ(first.image_map.interpolation, TextureInterpolation::kLinear);
  EXPECT_FLOAT_EQ(first.image_map.filter_all, 0.2f);
  EXPECT_FLOAT_EQ(first.image_map.transmit_all, 0.3f);
  EXPECT_TRUE(first.image_map.srgb);                                 // an 8-bit file in a 3.7 scene
  EXPECT_DOUBLE_EQ(first.pattern_from_world.point({2, 0, 0}).x, 1);  // the pigment's scale
  const SolidImageMap& torus = scene.objects[1].texture.pigment.image_map;
  EXPECT_EQ(torus.image, 1u);
  EXPECT_EQ(torus.projection, SolidImageProjection::kTorus);
  EXPECT_EQ(torus.major_radius, 3);
  EXPECT_EQ(torus.interpolation, TextureInterpolation::kClosest);
  const SolidImageMap& gamma = scene.objects[2].texture.pigment.image_map;
  EXPECT_EQ(gamma.image, 0u);
  EXPECT_EQ(gamma.projection, SolidImageProjection::kPlanar);  // map_type 4: planar, as POV-Ray
  EXPECT_FALSE(gamma.srgb);
  EXPECT_FLOAT_EQ(gamma.decode_gamma, 1.8f);
  const SolidImageMap& linear = scene.objects[3].texture.pigment.image_map;
  EXPECT_FALSE(linear.srgb);
  EXPECT_FLOAT_EQ(linear.decode_gamma, 1.f);
  const Pigment& gif = scene.objects[4].texture.pigment;
  EXPECT_TRUE(gif.averaged);
  EXPECT_EQ(gif.name, "image_map gif");

  // A legacy scene: the stored values, decoded as its colours are; assumed_gamma makes it 3.7's.
  const SolidImageMap legacy =
      run("#version 3.6;\nsphere { 0, 1 pigment { image_map { png \"map.png\" } } }")
          .objects.at(0)
          .texture.pigment.image_map;
  EXPECT_FALSE(legacy.srgb);
  EXPECT_FLOAT_EQ(legacy.decode_gamma, 2.2f);
  EXPECT_TRUE(run("#version 3.6;\nglobal_settings { assumed_gamma 1 }\n"
                  "sphere { 0, 1 pigment { image_map { png \"map.png\" } } }")
                  .objects.at(0)
                  .texture.pigment.image_map.srgb);

  std::string error = error_of("sphere { 0, 1 pigment { image_map { png \"none.png\" } } }");
  EXPECT_EQ(error.rfind("scene.pov:1:41: ", 0), 0u) << error;
  EXPECT_NE(error.find("none.png"), std::string::npos) << error;
  write("outside.png", "not read");
  error = error_of("\nsphere { 0, 1 pigment { image_map { png \"../outside.png\" } } }");
  EXPECT_EQ(error.rfind("scene.pov:2:41: ", 0), 0u) << error;
  error = error_of("sphere { 0, 1 pigment { image_map { \"map.png\" tile 3 } } }");
  EXPECT_NE(error.find("'tile' in image_map"), std::string::npos) << error;
}

// blob: threshold and components in both syntaxes, their transforms; hostile values refused with
// their place; a component's texture reported.
TEST_F(Sdl, BlobComponents) {
  Scene scene =
      run("blob { threshold 0.6 sturm\n"
          "  sphere { <1, 0, 0>, 2, strength 1.5 scale 2 }\n"
          "  cylinder { 0, y, 0.5, -1 translate x pigment { rgb 1 } }\n"
          "  component 1, 0.7, <0, 0, 3>\n"
          "  translate z }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& blob = scene.objects[0];
  EXPECT_EQ(blob.shape, Shape::kBlob);
  EXPECT_EQ(blob.r0, 0.6);
  ASSERT_EQ(blob.blob_components.size(), 3u);
  EXPECT_EQ(blob.blob_components[0].strength, 1.5);
  EXPECT_EQ(blob.blob_components[0].radius, 2);
  EXPECT_EQ(blob.blob_components[0].blob_from_component.point({1, 0, 0}).x, 2);
  EXPECT_TRUE(blob.blob_components[1].cylinder);
  EXPECT_EQ(blob.blob_components[1].strength, -1);
  EXPECT_EQ(blob.blob_components[1].b.y, 1);
  EXPECT_EQ(blob.blob_components[2].a.z, 3);
  EXPECT_EQ(blob.world_from_object.point({0, 0, 0}).z, 1);
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "blob component pigment");
  // components written by a loop, as advanced/biscuit.pov writes them
  scene = run("blob { threshold 0.5 #for (I, 1, 3) sphere { x * I, 1, 1 } #end }");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].blob_components.size(), 3u);

  std::string error = error_of("blob { threshold 0.5\n  sphere { 0, 0, 1 } }");
  EXPECT_EQ(error.rfind("scene.pov:2:3: ", 0), 0u) << error;
  EXPECT_NE(error.find("radius"), std::string::npos) << error;
  error = error_of("blob { threshold -1 sphere { 0, 1, 1 } }");
  EXPECT_EQ(error.rfind("scene.pov:1:18: ", 0), 0u) << error;
  error = error_of("blob { cylinder { x, x, 1, 1 } }");
  EXPECT_EQ(error.rfind("scene.pov:1:8: ", 0), 0u) << error;
  error = error_of("blob { sphere { 0, 1, 1 matrix <1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0> } }");
  EXPECT_EQ(error.rfind("scene.pov:1:8: ", 0), 0u) << error;
  scene = run("blob { threshold 1 }");  // empty: no error (the converter leaves it out)
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(scene.objects[0].blob_components.empty());
}

// sor: its points and open flag; too few points or a height not above the previous one refused
// at its place.
TEST_F(Sdl, SorPoints) {
  Scene scene = run("sor { 4, <1, 0>, <1, 1>, <0.5, 2>, <0.5, 3> open sturm }");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].shape, Shape::kSor);
  ASSERT_EQ(scene.objects[0].profile.size(), 4u);
  EXPECT_EQ(scene.objects[0].profile[2].first, 0.5);
  EXPECT_EQ(scene.objects[0].profile[2].second, 2);
  EXPECT_TRUE(scene.objects[0].open);
  scene = run("sor { 4, <0, 0>, <0.1, 0>, <0.6, 0.5>, <0.2, 0.5> }");  // ends may be level
  EXPECT_EQ(scene.objects.size(), 1u);
  std::string error = error_of("sor { 5, <1, 0>, <1, 1>,\n  <1, 1>, <1, 3>, <1, 4> }");
  EXPECT_EQ(error.rfind("scene.pov:2:3: ", 0), 0u) << error;
  error = error_of("sor { 3, <1, 0>, <1, 1>, <1, 2> }");
  EXPECT_NE(error.find("at least 4 points"), std::string::npos) << error;
}

// lathe: its spline's segments over consecutive points (Compute_Lathe), sharing their ends; too
// few points, a Bézier count not a multiple of 4, an inner point left of the axis refused at
// their place.
TEST_F(Sdl, LatheSplines) {
  Scene scene =
      run("lathe { 4, <1, 0>, <1, 1>, <0.5, 2>, <0.5, 3> sturm }\n"
          "lathe { quadratic_spline 4, <0, 0>, <1, 0>, <1, 1>, <0.5, 2> }\n"
          "lathe { cubic_spline 5, <0, 0>, <1, 0>, <1, 1>, <0.5, 2>, <0, 3> }\n"
          "lathe { bezier_spline 8, <0, 0>, <1, 0>, <1, 1>, <0.5, 1>, <0.5, 1>, <0.2, 1>, <0, 2>, "
          "<0, 3> }");
  ASSERT_EQ(scene.objects.size(), 4u);
  for (const Object& o : scene.objects)
    EXPECT_EQ(o.shape, Shape::kLathe);
  const size_t segments[4] = {3, 2, 2, 2};
  const int degrees[4] = {1, 2, 3, 3};
  for (size_t i = 0; i < 4; ++i) {
    const std::vector<OutlineSegment>& s = scene.objects[i].outline->segments;
    ASSERT_EQ(s.size(), segments[i]) << i;
    EXPECT_EQ(s[0].degree, degrees[i]) << i;
    EXPECT_EQ(s[0].end.x, s[1].start.x) << i;
    EXPECT_EQ(s[0].end.y, s[1].start.y) << i;
  }
  // quadratic: from the second point to the third, the first steering the start's slope
  const OutlineSegment& q = scene.objects[1].outline->segments[0];
  EXPECT_EQ(q.start.x, 1);
  EXPECT_EQ(q.start.y, 0);
  EXPECT_EQ(q.end.y, 1);
  EXPECT_EQ(segment_tangent(q, 0).x, 0.5);  // (p2 - p0) / 2
  std::string error = error_of("lathe { cubic_spline 3, <0, 0>, <1, 0>, <1, 1> }");
  EXPECT_NE(error.find("at least 4 points"), std::string::npos) << error;
  error = error_of("lathe { bezier_spline 6, <0, 0>, <1, 0>, <1, 1>, <0, 1>, <0, 2>, <1, 2> }");
  EXPECT_NE(error.find("four points a segment"), std::string::npos) << error;
  error = error_of("lathe { 3, <0, 0>,\n <-1, 1>, <0, 2> }");
  EXPECT_EQ(error.rfind("scene.pov:2:2: ", 0), 0u) << error;
  // the first and last points only steer a spline's ends: they may lie left of the axis
  EXPECT_EQ(run("lathe { cubic_spline 4, <-1, 0>, <1, 1>, <1, 2>, <-1, 3> }").objects.size(), 1u);
}

// ovus and lemon: their radii; a negative radius, a lemon whose ends coincide refused at their
// place; a lemon's inner radius below the least that reaches both rims raised, with a warning.
TEST_F(Sdl, OvusAndLemon) {
  Scene scene = run("ovus { 1, 0.65 }\nlemon { <0, 1, 0>, 0.3, <0, -1, 0>, 0.5, 2 open }");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].shape, Shape::kOvus);
  EXPECT_EQ(scene.objects[0].r0, 1);
  EXPECT_EQ(scene.objects[0].r1, 0.65);
  const Object& lemon = scene.objects[1];
  EXPECT_EQ(lemon.shape, Shape::kLemon);
  EXPECT_EQ(lemon.a.y, 1);
  EXPECT_EQ(lemon.r0, 0.3);
  EXPECT_EQ(lemon.b.y, -1);
  EXPECT_EQ(lemon.r1, 0.5);
  EXPECT_EQ(lemon.r2, 2);
  EXPECT_TRUE(lemon.open);
  EXPECT_TRUE(scene.warnings.empty());
  // Axis 2 long: in its units a = 0.25, b = 0.15, and the least inner radius is
  // 2 sqrt((a^2 - b^2)^2 + 2 a^2 + 2 b^2 + 1) / 2.
  scene = run("lemon { <0, 1, 0>, 0.3, <0, -1, 0>, 0.5,\n 0.2 }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const double a = 0.25, b = 0.15;
  EXPECT_NEAR(scene.objects[0].r2,
              std::sqrt((a * a - b * b) * (a * a - b * b) + 2 * a * a + 2 * b * b + 1), 1e-15);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0].rfind("scene.pov:2:2: ", 0), 0u) << scene.warnings[0];
  std::string error = error_of("ovus { 1,\n -0.5 }");
  EXPECT_EQ(error.rfind("scene.pov:2:2: ", 0), 0u) << error;
  EXPECT_NE(error.find("not negative"), std::string::npos) << error;
  error = error_of("lemon { <0, 1, 0>, -0.3, <0, -1, 0>, 0.5, 2 }");
  EXPECT_EQ(error.rfind("scene.pov:1:20: ", 0), 0u) << error;
  error = error_of("lemon {\n <0, 1, 0>, 0.3, <0, 1, 0>, 0.5, 2 }");
  EXPECT_EQ(error.rfind("scene.pov:2:2: ", 0), 0u) << error;
  EXPECT_NE(error.find("degenerate lemon"), std::string::npos) << error;
}

// sphere_sweep: its segments per spline; too few spheres, a negative radius and an unknown
// spline refused at their place; `tolerance` read.
TEST_F(Sdl, SphereSweepSplines) {
  Scene scene = run(
      "sphere_sweep { linear_spline 3, <0, 0, 0>, 0.5, <1, 0, 0>, 0.2, <1, 1, 0>, 0.3 "
      "tolerance 1e-4 }\n"
      "sphere_sweep { b_spline 5, <0, 0, 0>, 1, <1, 0, 0>, 1, <2, 0, 0>, 1, <3, 0, 0>, 1, "
      "<4, 0, 0>, 1 }\n"
      "sphere_sweep { cubic_spline 4, <0, 0, 0>, 1, <1, 0, 0>, 1, <2, 0, 0>, 1, <3, 0, 0>, 1 }");
  ASSERT_EQ(scene.objects.size(), 3u);
  for (const Object& o : scene.objects)
    ASSERT_EQ(o.shape, Shape::kSphereSweep);
  ASSERT_EQ(scene.objects[0].sweep->segments.size(), 2u);
  const SweepSegment& linear = scene.objects[0].sweep->segments[1];
  EXPECT_EQ(linear.c[0].x, 1);
  EXPECT_EQ(linear.c[1].y, 1);  // from <1, 0, 0> to <1, 1, 0>
  EXPECT_NEAR(linear.r[1], 0.1, 1e-15);
  ASSERT_EQ(scene.objects[1].sweep->segments.size(), 2u);
  // a uniform B-spline through evenly spaced points starts at (P0 + 4 P1 + P2) / 6 = P1
  EXPECT_NEAR(scene.objects[1].sweep->segments[0].c[0].x, 1, 1e-15);
  ASSERT_EQ(scene.objects[2].sweep->segments.size(), 1u);
  EXPECT_EQ(scene.objects[2].sweep->segments[0].c[0].x, 1);  // Catmull-Rom: from P1 to P2
  std::string error =
      error_of("sphere_sweep { b_spline\n 3, <0, 0, 0>, 1, <1, 0, 0>, 1, <2, 0, 0>, 1 }");
  EXPECT_EQ(error.rfind("scene.pov:2:2: ", 0), 0u) << error;
  EXPECT_NE(error.find("at least 4 spheres"), std::string::npos) << error;
  error = error_of("sphere_sweep { linear_spline 2, <0, 0, 0>, 1,\n <1, 0, 0>, -1 }");
  EXPECT_EQ(error.rfind("scene.pov:2:13: ", 0), 0u) << error;
  error = error_of("sphere_sweep { bezier_spline 2, <0, 0, 0>, 1, <1, 0, 0>, 1 }");
  EXPECT_EQ(error.rfind("scene.pov:1:16: ", 0), 0u) << error;
}

// bicubic_patch: the grid of 2^u_steps x 2^v_steps sub-patches, two triangles each, vertices on
// the Bézier surface (its corners the corner control points) with unit normals; huge step counts
// bounded with a warning; a missing type refused.
TEST_F(Sdl, BicubicPatchTriangles) {
  Scene scene = run(
      "bicubic_patch { type 1 flatness 0.01 u_steps 2 v_steps 3\n"
      "<0, 0, 2>, <1, 0, 0>, <2, 0, 0>, <3, 0, -2>, <0, 1, 0>, <1, 1, 0>, <2, 1, 0>, <3, 1, 0>,\n"
      "<0, 2, 0>, <1, 2, 0>, <2, 2, 0>, <3, 2, 0>, <0, 3, 2>, <1, 3, 0>, <2, 3, 0>, <3, 3, -2> }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& patch = scene.objects[0];
  EXPECT_EQ(patch.shape, Shape::kMesh);
  EXPECT_EQ(patch.keyword, "bicubic_patch");
  ASSERT_EQ(patch.vertices.size(), 5u * 9u);
  ASSERT_EQ(patch.normals.size(), patch.vertices.size());
  EXPECT_EQ(patch.indices.size(), 3u * 2 * 4 * 8);
  // Rows run with u (the first index), columns with v: vertex (i, j) is at (u, v) = (i/4, j/8).
  const auto at = [&](size_t i, size_t j) { return patch.vertices[i * 9 + j]; };
  EXPECT_EQ(at(0, 0).z, 2);
  EXPECT_EQ(at(4, 8).x, 3);
  EXPECT_EQ(at(4, 8).y, 3);
  EXPECT_EQ(at(4, 8).z, -2);
  // Here x = 3 v and y = 3 u exactly (evenly spaced control points), z the Bézier blend.
  const Vec3d mid = at(2, 4);
  EXPECT_NEAR(mid.x, 1.5, 1e-12);
  EXPECT_NEAR(mid.y, 1.5, 1e-12);
  const double b[4] = {0.125, 0.375, 0.375, 0.125};  // Bernstein weights at 1/2
  const double z[4][4] = {{2, 0, 0, -2}, {0, 0, 0, 0}, {0, 0, 0, 0}, {2, 0, 0, -2}};
  double expected_z = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      expected_z += b[i] * b[j] * z[i][j];
  EXPECT_NEAR(mid.z, expected_z, 1e-12);
  for (const Vec3d& n : patch.normals)
    EXPECT_NEAR(length(n), 1, 1e-12);
  scene =
      run("bicubic_patch { type 0 u_steps 1e9 v_steps -3 uv_vectors <0,0> <1,0> <1,1> <0,1>\n"
          "<0,0,0>,<1,0,0>,<2,0,0>,<3,0,0>,"
          "<0,1,0>,<1,1,0>,<2,1,0>,<3,1,0>,<0,2,0>,<1,2,0>,<2,2,0>,<3,2,0>,<0,3,0>,<1,3,0>,"
          "<2,3,0>,<3,3,0> }");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].vertices.size(), 1025u * 2);  // bounded to 2^10 rows, one column
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("bounded to 10"), std::string::npos) << scene.warnings[0];
  ASSERT_EQ(scene.unsupported.size(), 1u);  // uv_vectors: where a texture goes, not the shape
  EXPECT_EQ(scene.unsupported[0].feature, "bicubic_patch uv_vectors");
  const std::string error = error_of("bicubic_patch { u_steps 3 <0,0,0> }");
  EXPECT_NE(error.find("type 0"), std::string::npos) << error;
}

TEST_F(Sdl, PolygonAndMeshes) {
  // an L-shaped (concave) hexagon: 4 triangles covering area 3
  Scene scene = run("polygon { 7, <0,0>, <2,0>, <2,1>, <1,1>, <1,2>, <0,2>, <0,0> }");
  const Object& l = scene.objects.at(0);
  ASSERT_EQ(l.indices.size(), 12u);
  double area = 0;
  for (size_t t = 0; t < l.indices.size(); t += 3) {
    Vec3d a = l.vertices[l.indices[t]], b = l.vertices[l.indices[t + 1]],
          c = l.vertices[l.indices[t + 2]];
    area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  EXPECT_NEAR(area, 3, 1e-12);
  scene =
      run("mesh2 { vertex_vectors { 4, <0,0,0>, <1,0,0>, <1,1,0>, <0,1,0> }"
          "  texture_list { 2, texture { pigment { rgb x } } texture { pigment { rgb y } } }"
          "  face_indices { 2, <0,1,2>, 0, <0,2,3>, 1 } }\n"
          "mesh { triangle { 0, x, y } smooth_triangle { 0, z, x, z, y, z } }");
  const Object& m2 = scene.objects.at(0);
  EXPECT_EQ(m2.indices.size(), 6u);
  ASSERT_EQ(m2.triangle_textures.size(), 2u);
  EXPECT_EQ(m2.triangle_textures[1], 1u);
  EXPECT_EQ(m2.textures.at(1).pigment.colour.g, 1);
  const Object& m = scene.objects.at(1);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.normals.size(), 6u);
  EXPECT_NE(error_of("mesh2 { vertex_vectors { 1, 0 } face_indices { 1, <0,1,2> } }")
                .find("past the vertex_vectors"),
            std::string::npos);
}

// prism's keywords in any order, its points as <x, z>, and what is wrong named by file:line:column
// (importers/pov/sdl/prism_outline_test.cpp tests the splines themselves).
TEST_F(Sdl, PrismObjects) {
  Scene scene =
      run("prism { bezier_spline linear_sweep -1, 2.5, 4, <0,0>, <1,1>, <2,1>, <0,0> open }\n"
          "prism { conic_sweep 0, 1, 4 <0,0> <1,0> <0,1> <0,0> }");
  ASSERT_EQ(scene.objects.size(), 2u);
  const Object& p = scene.objects[0];
  EXPECT_EQ(p.shape, Shape::kPrism);
  EXPECT_EQ(p.r0, -1);
  EXPECT_EQ(p.r1, 2.5);
  EXPECT_TRUE(p.open);
  EXPECT_FALSE(p.conic);
  ASSERT_TRUE(p.outline);
  EXPECT_EQ(p.outline->segments.size(), 1u);
  EXPECT_EQ(p.outline->segments[0].degree, 3);
  EXPECT_TRUE(scene.objects[1].conic);
  EXPECT_EQ(scene.objects[1].outline->segments.size(), 3u);
  EXPECT_NE(error_of("sphere { 0, 1 }\n  prism { cubic_spline 0, 1, 3, <0,0>, <1,0>, <0,1> }")
                .find("scene.pov:2:3: cubic_spline prism: a sub-polygon"),
            std::string::npos);
  EXPECT_NE(
      error_of("prism { 0, 1, 1e6, <0,0> }").find("scene.pov:1:15: prism point count 1e+06 is not"),
      std::string::npos);
  // Unclosed: closed (linear) or left out (the other splines), with a warning naming the line.
  scene =
      run("\nprism { 0, 1, 3, <0,0>, <1,0>, <0,1> }\n"
          "prism { quadratic_spline 0, 1, 5, <0,0>, <1,0>, <1,1>, <0,1>, <0,0.5> }");
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_EQ(scene.warnings[0].rfind("scene.pov:2:1: linear_spline prism not closed", 0), 0u);
  EXPECT_EQ(scene.warnings[1].rfind("scene.pov:3:1: quadratic_spline prism not closed", 0), 0u);
  EXPECT_EQ(scene.objects.at(0).outline->segments.size(), 3u);
  EXPECT_FALSE(scene.objects.at(1).outline);
}

// text: a union of glyph prisms turned to sweep along z, its font found like an #include (the
// library folder here), and what is wrong named by file:line:column.
TEST_F(Sdl, TextObjects) {
  const fs::path font = "/usr/share/povray-3.7/include/timrom.ttf";
  if (!fs::exists(font)) GTEST_SKIP() << "POV-Ray's fonts are not installed (povray-includes)";
  fs::copy_file(font, root_ / "lib" / "timrom.ttf");
  Scene scene = run("text { ttf \"timrom.ttf\" \"Hi\" 0.25, <0.1, 0, 0> translate y }");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& text = scene.objects[0];
  EXPECT_EQ(text.shape, Shape::kUnion);
  ASSERT_EQ(text.children.size(), 2u);
  const Object& h = text.children[0];
  EXPECT_EQ(h.shape, Shape::kPrism);
  EXPECT_EQ(h.r1, 0.25);
  // The prism's sweep (its y) runs along the text's z; the outline's y is the text's y.
  const Vec3d swept = h.world_from_object.vector({0, 1, 0}),
              up = h.world_from_object.vector({0, 0, 1});
  EXPECT_EQ(swept.z, 1);
  EXPECT_EQ(up.y, 1);
  EXPECT_EQ(h.world_from_object.point({0, 0, 0}).y, 1);  // translated with the text
  EXPECT_EQ(run("text { ttf \"timrom\" \"Hi\" 0.25, 0 }").objects.at(0).children.size(), 2u);
  // A font that is not here (or only outside the allowed folders) leaves the text out, reported.
  scene =
      run("sphere { 0, 1 }\ntext { ttf \"missing.ttf\" \"Hi\" 1, 0 }\n"
          "text { ttf \"../timrom.ttf\" \"Hi\" 1, 0 }");
  EXPECT_EQ(scene.objects.size(), 1u);
  ASSERT_EQ(scene.unsupported.size(), 2u);
  EXPECT_EQ(scene.unsupported[0].feature, "text");
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_EQ(scene.warnings[0].rfind("scene.pov:2:12: font \"missing.ttf\" is not in", 0), 0u);
  EXPECT_EQ(scene.warnings[1].rfind("scene.pov:3:12: font \"../timrom.ttf\" is not in", 0), 0u);
  EXPECT_NE(error_of("text { ttf \"timrom.ttf\" 7, 1, 0 }").find("scene.pov:1:25: text expects"),
            std::string::npos);
  // POV-Ray's built-in fonts are not here: such a text is left out and reported where placed.
  scene = run("sphere { 0, 1 }\ntext { internal 1 \"Hi\" 1, 0 }");
  EXPECT_EQ(scene.objects.size(), 1u);
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "text");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:2:1");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0].rfind("scene.pov:2:1: text with an internal font", 0), 0u);
}

// shapes.inc's HFCreate_ writes face_indices as vector expressions `F1+A, F2+A,` with a trailing
// comma: a face is never taken for the texture index of the one before.
TEST_F(Sdl, Mesh2FacesFromVectorIdentifiers) {
  Scene scene =
      run("#declare F1 = <0, 1, 2>; #declare F2 = <0, 2, 3>; #declare T = 1;\n"
          "mesh2 { vertex_vectors { 4, <0,0,0>, <1,0,0>, <1,1,0>, <0,1,0> }\n"
          "  texture_list { 2, texture { pigment { rgb x } } texture { pigment { rgb y } } }\n"
          "  face_indices { 3, F1 + 0, F2, T, <0, 1, 3>, } }");
  const Object& m = scene.objects.at(0);
  ASSERT_EQ(m.indices.size(), 9u);
  EXPECT_EQ(m.indices[3], 0u);
  EXPECT_EQ(m.indices[5], 3u);
  ASSERT_EQ(m.triangle_textures.size(), 3u);
  EXPECT_EQ(m.triangle_textures[0], 0u);
  EXPECT_EQ(m.triangle_textures[1], 1u);  // T, a float identifier, is a texture index
  EXPECT_EQ(m.indices[8], 3u);
}

// The sample that stopped inside shapes.inc's height-field macros now evaluates.
TEST_F(Sdl, ShapesIncHeightFieldMacros) {
  fs::path sample = "/usr/share/doc/povray/examples/incdemo/shapes.pov";
  fs::path includes = "/usr/share/povray-3.7/include";
  if (!fs::exists(sample) || !fs::exists(includes)) GTEST_SKIP() << "povray-examples not installed";
  EvaluateOptions options;
  options.scene_file = sample;
  options.library_paths = {includes};
  Scene scene = evaluate_pov(options);
  EXPECT_EQ(scene.objects.size(), 15u);
}

TEST_F(Sdl, ReadsDataFilesInTheSceneFolder) {
  write("scene/data.txt", "1, <2, 3, 4>, \"five\",\n");
  Scene scene =
      run("#fopen F \"data.txt\" read\n"
          "#read (F, A, V, S)\n"
          "#if (defined(F)) #error \"the handle stays after the end\" #end\n"
          "sphere { <A, V.z, strlen(S)>, 1 }");
  EXPECT_EQ(scene.objects.at(0).a.x, 1);
  EXPECT_EQ(scene.objects.at(0).a.y, 4);
  EXPECT_EQ(scene.objects.at(0).a.z, 4);
  // a file written and read back, as language/fileio/fileio.pov does: in memory, never on disk
  scene =
      run("#fopen Out \"out.txt\" write\n"
          "#write (Out, \"\\\"Testing 123\\\",\", 5, \",\", <1, 2.5, 3>, \"\\n\")\n"
          "#fclose Out\n"
          "#fopen Out \"out.txt\" append #write (Out \",\", -0.25) #fclose Out\n"
          "#fopen In \"out.txt\" read\n"
          "#read (In, S, F, V, G)\n"
          "sphere { <F, V.y, G>, strlen(S) }");
  EXPECT_TRUE(scene.unsupported.empty());
  EXPECT_EQ(scene.objects.at(0).a.x, 5);
  EXPECT_EQ(scene.objects.at(0).a.y, 2.5);
  EXPECT_EQ(scene.objects.at(0).a.z, -0.25);
  EXPECT_EQ(scene.objects.at(0).r0, 11);  // "Testing 123"
  EXPECT_FALSE(fs::exists(root_ / "scene" / "out.txt"));
  EXPECT_NE(error_of("#fopen In \"never.txt\" read").find("cannot #fopen \"never.txt\""),
            std::string::npos);
}

// The samples, when Debian's povray-examples is installed: a cut anywhere in a real scene ends
// in a result or a located error, never a crash or a hang.
TEST_F(Sdl, TruncatedSampleScenesFailCleanly) {
  fs::path sample = "/usr/share/doc/povray/examples/advanced/woodbox.pov";
  fs::path includes = "/usr/share/povray-3.7/include";
  if (!fs::exists(sample) || !fs::exists(includes)) GTEST_SKIP() << "povray-examples not installed";
  std::ifstream in(sample);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int errors = 0;
  for (size_t cut = 0; cut < text.size(); cut += 97) {
    write("scene/scene.pov", text.substr(0, cut));
    EvaluateOptions options;
    options.scene_file = root_ / "scene" / "scene.pov";
    options.library_paths = {includes};
    try {
      evaluate_pov(options);
    } catch (const InputError& e) {
      ++errors;
      EXPECT_EQ(std::string(e.what()).find("internal"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(errors, 0);
}

// language/tracevines.pov is not among them: once trace() answers, its vines grow for 28.7
// million tokens, past the token limit (docs/pov.md "The language").
TEST_F(Sdl, SampleScenesEvaluate) {
  fs::path examples = "/usr/share/doc/povray/examples";
  fs::path includes = "/usr/share/povray-3.7/include";
  if (!fs::exists(examples) || !fs::exists(includes))
    GTEST_SKIP() << "povray-examples not installed";
  for (const char* name :
       {"advanced/woodbox.pov", "advanced/chess2.pov", "advanced/glasschess/glasschess.pov",
        "advanced/benchmark/benchmark.pov", "language/trace-wicker.pov",
        "animations/splinefollow/splinefollow.pov", "objects/mesh2.pov"}) {
    EvaluateOptions options;
    options.scene_file = examples / name;
    options.library_paths = {includes};
    Scene scene;
    EXPECT_NO_THROW(scene = evaluate_pov(options)) << name;
    EXPECT_FALSE(scene.objects.empty()) << name;
    EXPECT_TRUE(scene.camera) << name;
  }
}

}  // namespace
}  // namespace fb::pov
