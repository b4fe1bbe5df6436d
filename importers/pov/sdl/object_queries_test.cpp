// trace(), inside(), min_extent() and max_extent() against shapes whose answers are known in
// closed form: where a ray meets a sphere, a transformed box, a difference and a mesh, the normal
// it reports there, and POV-Ray's answers for a miss and for an unbounded object.
#include <gtest/gtest.h>

#include <string>

#include "importers/pov/sdl/sdl_test_fixture.h"

namespace fb::pov {
namespace {

constexpr double kTraceTolerance = 1e-9;          // double-precision solids
constexpr double kTriangleTraceTolerance = 1e-5;  // triangles are intersected in float

class ObjectQueries : public Sdl {
 protected:
  // The value of the vector `expression` after `declarations`: read through the centre of the
  // scene's only placed object.
  Vec3d vector_of(const std::string& declarations, const std::string& expression) {
    return centre(declarations + "\nsphere { " + expression + ", 1 }");
  }
  // The normal the trace() `call` leaves in N.
  Vec3d normal_of(const std::string& declarations, const std::string& call) {
    return vector_of(declarations + "#declare P = " + call + ";", "N");
  }
};

void expect_near(Vec3d actual, Vec3d expected, double tolerance, const char* what) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

const char* const kSphere = "#declare S = sphere { <1, 2, 3>, 2 }\n#declare N = <9, 9, 9>;\n";

TEST_F(ObjectQueries, TraceMeetsASphereWhereItsEquationSaysWithItsOutwardNormal) {
  // The direction's length does not matter: POV-Ray normalises it.
  expect_near(vector_of(kSphere, "trace(S, <1, 10, 3>, -5*y, N)"), {1, 4, 3}, kTraceTolerance,
              "from above");
  expect_near(normal_of(kSphere, "trace(S, <1, 10, 3>, -y, N)"), {0, 1, 0}, kTraceTolerance,
              "normal from above");
  expect_near(vector_of(kSphere, "trace(S, <-10, 2, 3>, x)"), {-1, 2, 3}, kTraceTolerance,
              "from the side, no normal asked");
  // From inside, the ray leaves through the far side.
  expect_near(vector_of(kSphere, "trace(S, <1, 2, 3>, z, N)"), {1, 2, 5}, kTraceTolerance,
              "from inside");
}

TEST_F(ObjectQueries, TraceThatMissesGivesZeroAndAZeroNormal) {
  expect_near(vector_of(kSphere, "trace(S, <10, 10, 10>, y, N)"), {0, 0, 0}, 0, "miss");
  expect_near(normal_of(kSphere, "trace(S, <10, 10, 10>, y, N)"), {0, 0, 0}, 0, "normal of a miss");
  // Behind the origin is no hit either.
  expect_near(vector_of(kSphere, "trace(S, <1, 10, 3>, y, N)"), {0, 0, 0}, 0, "behind");
}

// POV-Ray's rotate 90*y takes +x to -z: the box <-2, -1, -1> ... <2, 1, 1> becomes
// <-1, -1, -2> ... <1, 1, 2>, then moves to z = 3 ... 7.
const char* const kBox =
    "#declare B = box { -1, 1 scale <2, 1, 1> rotate 90*y translate <0, 0, 5> }\n"
    "#declare N = <9, 9, 9>;\n";

TEST_F(ObjectQueries, TraceAndExtentsFollowATransformedBox) {
  expect_near(vector_of(kBox, "trace(B, <0.5, 0.5, -10>, z, N)"), {0.5, 0.5, 3}, kTraceTolerance,
              "front face");
  expect_near(normal_of(kBox, "trace(B, <0.5, 0.5, -10>, z, N)"), {0, 0, -1}, kTraceTolerance,
              "front face normal");
  expect_near(vector_of(kBox, "min_extent(B)"), {-1, -1, 3}, kTraceTolerance, "min_extent");
  expect_near(vector_of(kBox, "max_extent(B)"), {1, 1, 7}, kTraceTolerance, "max_extent");
  sdl_true(std::string(kBox) + "inside(B, <0.9, 0.9, 6.9>) = 1");
  sdl_true(std::string(kBox) + "inside(B, <1.1, 0, 5>) = 0");
  sdl_true(std::string(kBox) + "inside(B, <0, 0, 2.9>) = 0");
}

// A box with a sphere cut out of its top, scaled and moved: the sphere's centre is at <5, 2, 0>
// with radius 1, so a ray down the middle first meets the set at y = 1, where the cut's surface
// faces up, out of the set (POV-Ray inverts the normal of the inverted sphere).
const char* const kDifference =
    "#declare D = difference { box { -1, 1 } sphere { y, 0.5 } scale 2 translate 5*x }\n"
    "#declare N = <9, 9, 9>;\n";

TEST_F(ObjectQueries, TraceInsideAndExtentsFollowATransformedDifference) {
  expect_near(vector_of(kDifference, "trace(D, <5, 10, 0>, -y, N)"), {5, 1, 0}, kTraceTolerance,
              "cut");
  expect_near(normal_of(kDifference, "trace(D, <5, 10, 0>, -y, N)"), {0, 1, 0}, kTraceTolerance,
              "cut normal");
  // Beside the cut, the box's top.
  expect_near(vector_of(kDifference, "trace(D, <3.5, 10, 0>, -y)"), {3.5, 2, 0}, kTraceTolerance,
              "top");
  // POV-Ray bounds a difference by its base.
  expect_near(vector_of(kDifference, "min_extent(D)"), {3, -2, -2}, kTraceTolerance, "min");
  expect_near(vector_of(kDifference, "max_extent(D)"), {7, 2, 2}, kTraceTolerance, "max");
  sdl_true(std::string(kDifference) + "inside(D, <5, 0, 0>) = 1");
  sdl_true(std::string(kDifference) + "inside(D, <5, 1.5, 0>) = 0");  // in the cut
  sdl_true(std::string(kDifference) + "inside(D, <0, 0, 0>) = 0");
}

// Two triangles making the square |x|, |z| <= 1 at y = 1.
const char* const kMesh =
    "#declare M = mesh { triangle { <-1, 0, -1>, <1, 0, -1>, <-1, 0, 1> }\n"
    "  triangle { <1, 0, -1>, <1, 0, 1>, <-1, 0, 1> } translate y }\n"
    "#declare N = <9, 9, 9>;\n";

TEST_F(ObjectQueries, TraceMeetsAMeshWithItsNormalTowardsTheRay) {
  expect_near(vector_of(kMesh, "trace(M, <0.2, 5, 0.3>, -y, N)"), {0.2, 1, 0.3},
              kTriangleTraceTolerance, "from above");
  expect_near(normal_of(kMesh, "trace(M, <0.2, 5, 0.3>, -y, N)"), {0, 1, 0},
              kTriangleTraceTolerance, "normal from above");
  expect_near(normal_of(kMesh, "trace(M, <0.2, -5, 0.3>, y, N)"), {0, -1, 0},
              kTriangleTraceTolerance, "normal from below");
  expect_near(vector_of(kMesh, "trace(M, <3, 5, 0>, -y, N)"), {0, 0, 0}, 0, "beside");
  expect_near(vector_of(kMesh, "min_extent(M)"), {-1, 1, -1}, kTriangleTraceTolerance, "min");
  expect_near(vector_of(kMesh, "max_extent(M)"), {1, 1, 1}, kTriangleTraceTolerance, "max");
  // Triangles have no inside here: 0, reported as a function answered with zero.
  const Scene scene = run(std::string(kMesh) + "sphere { 0, 1 + inside(M, <0, 0.5, 0>) }");
  EXPECT_EQ(scene.objects.at(0).r0, 1);
  ASSERT_EQ(scene.unsupported.size(), 1u);
  EXPECT_EQ(scene.unsupported[0].feature, "inside");
}

// A height field of a constant function is flat at that height over x, z in [0, 1], before its
// transforms.
TEST_F(ObjectQueries, TraceMeetsAHeightField) {
  const std::string field =
      "#declare H = height_field { function 8, 8 { 0.5 } scale <4, 2, 4> translate <-2, 0, -2> }\n"
      "#declare N = <9, 9, 9>;\n";
  expect_near(vector_of(field, "trace(H, <0.7, 10, -0.4>, -y, N)"), {0.7, 1, -0.4},
              kTriangleTraceTolerance, "surface");
  expect_near(normal_of(field, "trace(H, <0.7, 10, -0.4>, -y, N)"), {0, 1, 0},
              kTriangleTraceTolerance, "normal");
}

// A side with no end is POV-Ray's BOUND_HUGE / 2.
TEST_F(ObjectQueries, ExtentsOfAnUnboundedObjectArePovRaysLargeNumbers) {
  const std::string plane = "#declare P = plane { y, 1 }\n";
  expect_near(vector_of(plane, "min_extent(P) / 1e10"), {-1, -1, -1}, 0, "min");
  expect_near(vector_of(plane, "max_extent(P) / 1e10"), {1, 1, 1}, 0, "max");
  sdl_true(plane + "inside(P, <0, 0.5, 0>) = 1");
  sdl_true(plane + "inside(P, <0, 1.5, 0>) = 0");
  expect_near(vector_of(plane, "trace(P, <3, 5, 1>, <0, -1, 1>)"), {3, 1, 5}, kTraceTolerance,
              "slanted ray");
}

TEST_F(ObjectQueries, BadArgumentsAreLocatedErrors) {
  EXPECT_EQ(error_of("#declare V = trace(1, 0, y);"),
            "scene.pov:1:20: trace() expects an object identifier");
  EXPECT_EQ(error_of(std::string(kSphere) + "#declare V = trace(S, 0, y, Undeclared);"),
            "scene.pov:3:29: trace(): its fourth argument must be a declared identifier, found "
            "'Undeclared'");
}

TEST_F(ObjectQueries, AnUnsupportedObjectIsReportedAndAnsweredWithZeros) {
  const Scene scene =
      run("#declare J = julia_fractal { <0.4, 0.4, 0.1, 0.1> hypercomplex exp }\n"
          "sphere { trace(J, <0, 5, 0>, -y) + min_extent(J), 1 + inside(J, 0) }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  expect_near(scene.objects[0].a, {0, 0, 0}, 0, "zeros");
  EXPECT_EQ(scene.objects[0].r0, 1);
  ASSERT_EQ(scene.unsupported.size(), 3u);
  EXPECT_EQ(scene.unsupported[0].feature, "trace");
  EXPECT_EQ(scene.unsupported[0].where.text(), "scene.pov:2:10");
}

}  // namespace
}  // namespace fb::pov
