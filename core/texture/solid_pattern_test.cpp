#include "core/texture/solid_pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "core/function/user_function.h"

namespace fb {
namespace {

SolidPattern plain(Rgb c) {
  SolidPattern s;
  s.colour.rgb = c;
  return s;
}

SolidPattern grey_ramp(SolidPatternKind kind) {
  SolidPattern s;
  s.kind = kind;
  s.colour_map = {{0.f, {{0, 0, 0}, 0, 0}}, {1.f, {{1, 1, 1}, 0, 0}}};
  return s;
}

TEST(SolidPattern, CheckerAlternatesByTheParityOfTheUnitCube) {
  SolidPattern s;
  s.kind = SolidPatternKind::kChecker;
  s.list = {plain({1, 0, 0}), plain({0, 0, 1})};
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) {
        const Vec3d p{x + 0.5, y + 0.25, z + 0.75};
        const bool odd = ((x + y + z) % 2 + 2) % 2 == 1;
        EXPECT_EQ(evaluate_solid(s, p).rgb.x, odd ? 0.f : 1.f) << x << " " << y << " " << z;
      }
  // No list given: POV-Ray's default blue and green.
  s.list.clear();
  EXPECT_EQ(evaluate_solid(s, {0.5, 0.5, 0.5}).rgb.z, 1.f);
  EXPECT_EQ(evaluate_solid(s, {1.5, 0.5, 0.5}).rgb.y, 1.f);
}

// A surface lying on a cell border (`plane { z, 0 }` moved under the checker) is hit at float
// precision: points a few 1e-6 either side of the border take one side, not a speckle of both;
// a point clearly past the border takes the other.
TEST(SolidPattern, LatticeBordersHoldAtFloatPrecision) {
  for (const SolidPatternKind kind : {SolidPatternKind::kChecker, SolidPatternKind::kCells}) {
    SolidPattern s = grey_ramp(kind);
    s.list = {plain({1, 0, 0}), plain({0, 0, 1})};
    for (const Vec3d on_border : {Vec3d{0.5, 0.5, 0}, Vec3d{-3.5, 20, 0.25}, Vec3d{7, 0.5, 2.5}}) {
      const float centre = evaluate_solid(s, on_border).rgb.x;
      for (const double error : {-4e-6, -1e-6, 1e-6, 4e-6})
        for (int axis = 0; axis < 3; ++axis) {
          Vec3d p = on_border;
          (axis == 0 ? p.x : axis == 1 ? p.y : p.z) += error;
          EXPECT_EQ(evaluate_solid(s, p).rgb.x, centre) << int(kind) << " axis " << axis;
        }
    }
  }
  SolidPattern checker = grey_ramp(SolidPatternKind::kChecker);
  checker.list = {plain({1, 0, 0}), plain({0, 0, 1})};
  EXPECT_NE(evaluate_solid(checker, {0.5, 0.5, -1e-3}).rgb.x,
            evaluate_solid(checker, {0.5, 0.5, 0}).rgb.x);
}

TEST(SolidPattern, ListEntriesKeepTheirOwnPatternSpace) {
  SolidPattern inner;
  inner.kind = SolidPatternKind::kChecker;
  inner.list = {plain({1, 1, 1}), plain({0.5f, 0.5f, 0.5f})};
  inner.pattern_from_world = Transform::scale({10, 10, 10});  // cells 0.1 wide
  SolidPattern outer;
  outer.kind = SolidPatternKind::kChecker;
  outer.list = {inner, plain({0, 0, 0})};
  EXPECT_EQ(evaluate_solid(outer, {0.05, 0.05, 0.05}).rgb.x, 1.f);
  EXPECT_EQ(evaluate_solid(outer, {0.15, 0.05, 0.05}).rgb.x, 0.5f);
  EXPECT_EQ(evaluate_solid(outer, {1.05, 0.05, 0.05}).rgb.x, 0.f);
}

TEST(SolidPattern, GradientRampsAndWrapsLikePovRay) {
  SolidPattern s = grey_ramp(SolidPatternKind::kGradient);
  for (double y : {0.1, 0.25, 0.8, 1.25, 2.6, -0.25, -1.7}) {
    const double expected = y - std::floor(y);
    EXPECT_NEAR(evaluate_solid(s, {3, y, -2}).rgb.x, expected, 1e-4) << y;
  }
  // A scaled pattern space stretches the ramp.
  s.pattern_from_world = Transform::scale({1, 0.5, 1});
  EXPECT_NEAR(evaluate_solid(s, {0, 0.5, 0}).rgb.x, 0.25, 1e-4);
}

TEST(SolidPattern, ColourMapInterpolatesBetweenStopsAndClampsOutside) {
  const std::vector<SolidColourStop> map = {{0.2f, {{1, 0, 0}, 0, 0}},
                                            {0.6f, {{0, 1, 0}, 0, 1}},
                                            {0.6f, {{0, 0, 1}, 0.5f, 0}},
                                            {0.8f, {{0, 0, 0}, 0, 0}}};
  EXPECT_EQ(solid::colour_at(map, 0.0).rgb.x, 1.f);
  const SolidColour mid = solid::colour_at(map, 0.4);
  EXPECT_NEAR(mid.rgb.x, 0.5, 1e-6);
  EXPECT_NEAR(mid.rgb.y, 0.5, 1e-6);
  EXPECT_NEAR(mid.transmit, 0.5, 1e-6);
  EXPECT_NEAR(solid::colour_at(map, 0.6).rgb.y, 1.f, 1e-6);  // a step: the first stop up to 0.6
  EXPECT_NEAR(solid::colour_at(map, 0.7).rgb.z, 0.5, 1e-6);
  EXPECT_NEAR(solid::colour_at(map, 0.7).filter, 0.25, 1e-6);
  EXPECT_EQ(solid::colour_at(map, 0.95).rgb.z, 0.f);
}

TEST(SolidPattern, WavesShapeTheValueAsPovRayDefinesThem) {
  SolidPattern s;
  s.wave = SolidWave::kTriangle;
  EXPECT_NEAR(solid::shape_value(s, 0.25), 0.5, 1e-9);
  EXPECT_NEAR(solid::shape_value(s, 0.75), 0.5, 1e-9);
  s.wave = SolidWave::kSine;
  EXPECT_NEAR(solid::shape_value(s, 0.25), 1.0, 1e-9);
  s.wave = SolidWave::kCubic;
  EXPECT_NEAR(solid::shape_value(s, 0.5), 0.5, 1e-9);
  s.wave = SolidWave::kPoly;
  s.wave_exponent = 2;
  EXPECT_NEAR(solid::shape_value(s, 0.5), 0.25, 1e-9);
  s.wave = SolidWave::kRamp;
  s.frequency = 2, s.phase = 0.1;
  EXPECT_NEAR(solid::shape_value(s, 0.3), 0.7, 1e-4);
  EXPECT_NEAR(solid::shape_value(s, -0.3), 0.5, 1e-4);  // -0.5 wraps into [0, 1)
}

// POV-Ray 3.7's bozo over a 40 x 40 plane: mean 0.5007, standard deviation 0.132, range
// [0.075, 0.956] (16-bit linear render of `bozo color_map { [0 rgb 0] [1 rgb 1] }`).
TEST(SolidPattern, NoiseHasPovRaysMeanAndSpreadAndStaysInTheUnitInterval) {
  double sum = 0, sum2 = 0, lo = 1, hi = 0;
  int n = 0;
  for (int i = 0; i < 400; ++i)
    for (int j = 0; j < 400; ++j) {
      const double v = solid::noise({-20 + i * 0.1 + 0.013, -20 + j * 0.1 + 0.029, 0.0});
      sum += v, sum2 += v * v, ++n;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.5, 0.01);
  EXPECT_NEAR(sd, 0.132, 0.004);
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
}

TEST(SolidPattern, TurbulenceIsBoundedByItsOctavesAndDeterministic) {
  // Each octave adds at most omega^k: the sum of a geometric series.
  const double bound = (1 - std::pow(0.5, 6)) / (1 - 0.5);
  for (int i = 0; i < 2000; ++i) {
    const Vec3d p{i * 0.37 - 300, i * 0.11 + 5, -i * 0.23};
    const double t = solid::turbulence(p, 6, 0.5, 2.0);
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, bound);
    const Vec3d v = solid::vector_turbulence(p, 6, 0.5, 2.0);
    EXPECT_LE(std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}), bound);
    EXPECT_EQ(t, solid::turbulence(p, 6, 0.5, 2.0));
  }
  // Octaves are bounded whatever the scene asks for.
  EXPECT_TRUE(std::isfinite(solid::turbulence({1, 2, 3}, 1 << 30, 0.9, 2.0)));
}

// f(x, y, z) = x * scale, as the SDL reader compiles `function { x * scale }`.
std::shared_ptr<const UserFunction> x_times(double scale) {
  auto f = std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
  f->push_parameter(0);
  f->push_constant(scale);
  f->apply(FunctionOp::kMultiply, 2);
  f->finish();
  return f;
}

// POV-Ray's function pattern: the function's value in pattern space, values above 1 wrapped.
TEST(SolidPattern, FunctionPatternIsTheFunctionsValueInPatternSpace) {
  SolidPattern s = grey_ramp(SolidPatternKind::kFunction);
  s.function = x_times(0.25);
  s.pattern_from_world = Transform::scale({0.5, 1, 1});
  EXPECT_NEAR(evaluate_solid(s, {2, 0, 0}).rgb.x, 0.25, 1e-6);   // pattern x = 1
  EXPECT_NEAR(evaluate_solid(s, {10, 0, 0}).rgb.x, 0.25, 1e-5);  // 1.25 wraps to 0.25
  SolidPattern none = grey_ramp(SolidPatternKind::kFunction);
  EXPECT_EQ(evaluate_solid(none, {3, 1, 2}).rgb.x, 0.f);  // no function: 0 everywhere
}

TEST(SolidPattern, EveryValuePatternStaysInTheUnitIntervalAfterItsWave) {
  using K = SolidPatternKind;
  for (const auto& [kind, name] : kSolidPatternNames) {
    if (kind == K::kSolid || kind == K::kChecker || kind == K::kHexagon || kind == K::kBrick ||
        kind == K::kImageMap)
      continue;  // a colour, the list patterns and image maps: no value to wave
    SolidPattern s = grey_ramp(kind);
    s.turbulence = {0.5, 0.5, 0.5};
    if (kind == K::kFunction) s.function = x_times(0.1);
    double lo = 1, hi = 0;
    for (int i = 0; i < 3000; ++i) {
      const Vec3d p{std::sin(i * 1.3) * 7, std::cos(i * 0.7) * 7, i * 0.01 - 15};
      const SolidColour c = evaluate_solid(s, p);
      ASSERT_TRUE(std::isfinite(c.rgb.x)) << int(kind);
      lo = std::min(lo, double(c.rgb.x)), hi = std::max(hi, double(c.rgb.x));
    }
    EXPECT_GE(lo, 0.0) << int(kind);
    EXPECT_LE(hi, 1.0) << int(kind);
    EXPECT_GT(hi - lo, 0.1) << "pattern " << int(kind) << " hardly varies";
  }
}

TEST(SolidPattern, HexagonsAreThreeColouredWithTheOriginInColourZero) {
  SolidPattern s;
  s.kind = SolidPatternKind::kHexagon;
  for (int i = 0; i < 360; ++i) {
    const double a = i * std::numbers::pi / 180;
    // Inside the central hexagon (inradius sqrt(3)/2 for a unit side) ...
    EXPECT_EQ(solid::raw_value(s, {0.8 * std::cos(a), 0, 0.8 * std::sin(a)}), 0) << i;
    // ... and beyond its circumradius but short of the second ring, a neighbour's colour.
    EXPECT_NE(solid::raw_value(s, {1.3 * std::cos(a), 0, 1.3 * std::sin(a)}), 0) << i;
  }
}

TEST(SolidPattern, BrickHasMortarCoursesAndOffsetJoints) {
  SolidPattern s;
  s.kind = SolidPatternKind::kBrick;  // default size <8, 3, 4.5>, mortar 0.5
  for (double x : {0.3, 2.0, 5.1})
    EXPECT_EQ(solid::raw_value(s, {x, -0.25, 1.0}), 0);  // a horizontal mortar course
  EXPECT_EQ(solid::raw_value(s, {4, 1.5, 1.0}), 1);      // inside a brick
  // The vertical joint of one course is mid-brick in the next: x = -0.25 is a joint at the first
  // course (y in (0, 2.5)) but inside a brick at the second (y in (3, 5.5)).
  EXPECT_EQ(solid::raw_value(s, {-0.25, 1.5, 1.0}), 0);
  EXPECT_EQ(solid::raw_value(s, {-0.25, 4.5, 1.0}), 1);
}

}  // namespace
}  // namespace fb
