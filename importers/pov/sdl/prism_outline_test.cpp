// POV-Ray's prism splines as outlines: each spline's curves through the points POV-Ray's
// reference says they pass, sub-polygons closing where points repeat, and what lacks points or
// does not close refused or left out as POV-Ray does.
#include "importers/pov/sdl/prism_outline.h"

#include <gtest/gtest.h>

namespace fb::pov::sdl {
namespace {

bool contains(const Outline& o, double x, double y) {
  return outline_contains(o, {x, y});
}

TEST(PrismOutline, LinearSubPolygonsCloseWhereTheirFirstPointRepeats) {
  std::vector<std::string> warnings;
  // A square with a square hole: two sub-polygons.
  const std::optional<Outline> o = prism_outline(
      PrismSpline::kLinear,
      {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}, {-2, -2}, {-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}},
      warnings);
  ASSERT_TRUE(o);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(o->segments.size(), 8u);
  EXPECT_TRUE(contains(*o, 1.5, 0));
  EXPECT_FALSE(contains(*o, 0, 0));
  EXPECT_FALSE(contains(*o, 2.5, 0));
}

TEST(PrismOutline, UnclosedLinearIsClosedOtherSplinesAreLeftOut) {
  std::vector<std::string> warnings;
  const auto o = prism_outline(PrismSpline::kLinear, {{0, 0}, {1, 0}, {1, 1}}, warnings);
  ASSERT_TRUE(o);
  EXPECT_EQ(o->segments.size(), 3u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not closed"), std::string::npos);
  warnings.clear();
  EXPECT_FALSE(
      prism_outline(PrismSpline::kQuadratic, {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0.5}}, warnings));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("left out"), std::string::npos);
}

TEST(PrismOutline, SplinesWithTooFewPointsAreRefused) {
  std::vector<std::string> warnings;
  EXPECT_THROW(prism_outline(PrismSpline::kCubic, {{0, 0}, {1, 0}, {1, 1}}, warnings),
               std::invalid_argument);
  EXPECT_THROW(prism_outline(PrismSpline::kBezier, {{0, 0}, {1, 0}, {1, 1}}, warnings),
               std::invalid_argument);
  // Points left after a closed sub-polygon that make no segment.
  EXPECT_THROW(prism_outline(PrismSpline::kQuadratic,
                             {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {1, 0}, {1, 0}, {5, 5}}, warnings),
               std::invalid_argument);
  EXPECT_THROW(prism_outline(PrismSpline::kLinear, {{0, 0}}, warnings), std::invalid_argument);
  const std::vector<Vec2d> million(1'000'000, Vec2d{0, 0});
  EXPECT_THROW(prism_outline(PrismSpline::kLinear, million, warnings), std::invalid_argument);
}

// Quadratic: the curve from P[i+1] to P[i+2] leaves P[i+1] along (P[i+2] - P[i]) / 2; cubic
// (Catmull-Rom) the same at its start and (P[i+3] - P[i+1]) / 2 at its end.
TEST(PrismOutline, QuadraticAndCubicSplinesPassThroughTheirPointsWithPovRaysTangents) {
  std::vector<std::string> warnings;
  const std::vector<Vec2d> ring = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  std::vector<Vec2d> quadratic = {ring[3]};  // control, then the ring closing on its first
  for (int i = 0; i <= 4; ++i)
    quadratic.push_back(ring[i % 4]);
  const auto q = prism_outline(PrismSpline::kQuadratic, quadratic, warnings);
  ASSERT_TRUE(q);
  ASSERT_EQ(q->segments.size(), 4u);
  const OutlineSegment& s = q->segments[1];  // from ring[1] to ring[2], after ring[0]
  EXPECT_EQ(segment_point(s, 0).x, 1);
  EXPECT_NEAR(segment_point(s, 1).y, 1, 1e-15);
  EXPECT_NEAR(segment_tangent(s, 0).x, (ring[2].x - ring[0].x) / 2, 1e-15);
  EXPECT_NEAR(segment_tangent(s, 0).y, (ring[2].y - ring[0].y) / 2, 1e-15);
  std::vector<Vec2d> cubic = {ring[3]};
  for (int i = 0; i <= 5; ++i)
    cubic.push_back(ring[i % 4]);
  const auto c = prism_outline(PrismSpline::kCubic, cubic, warnings);
  ASSERT_TRUE(c);
  ASSERT_EQ(c->segments.size(), 4u);
  const OutlineSegment& t = c->segments[1];
  EXPECT_NEAR(segment_tangent(t, 1).x, (ring[3].x - ring[1].x) / 2, 1e-15);
  EXPECT_NEAR(segment_tangent(t, 1).y, (ring[3].y - ring[1].y) / 2, 1e-15);
  EXPECT_TRUE(contains(*c, 0, 0));
  EXPECT_FALSE(contains(*c, 1.2, 0.1));
  EXPECT_TRUE(warnings.empty());
}

TEST(PrismOutline, BezierSegmentsChainIntoClosedLoops) {
  std::vector<std::string> warnings;
  // Two segments: the upper and lower halves of a lens.
  const auto o = prism_outline(
      PrismSpline::kBezier,
      {{-1, 0}, {-0.5, 1}, {0.5, 1}, {1, 0}, {1, 0}, {0.5, -1}, {-0.5, -1}, {-1, 0}}, warnings);
  ASSERT_TRUE(o);
  EXPECT_EQ(o->segments.size(), 2u);
  EXPECT_TRUE(contains(*o, 0, 0.7));
  EXPECT_FALSE(contains(*o, 0, 0.8));
  EXPECT_NEAR(o->hi.y, 0.75, 1e-15);  // the cubic's own extreme, not its control points'
  // A gap between segments is no closed loop.
  EXPECT_FALSE(prism_outline(
      PrismSpline::kBezier,
      {{-1, 0}, {-0.5, 1}, {0.5, 1}, {1, 0}, {0.9, 0}, {0.5, -1}, {-0.5, -1}, {-1, 0}}, warnings));
}

}  // namespace
}  // namespace fb::pov::sdl
