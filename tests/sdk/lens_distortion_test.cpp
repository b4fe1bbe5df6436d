// Blender's tracking distortion models (filmback/lens_distortion.h): the inverse is an inverse
// (round trips to 1e-9 px), the forward maps are libmv's equations at analytic points, a model that
// folds over gives no position (the camera's weight 0), and hostile parameters are refused.
#include <gtest/gtest.h>

#include <cmath>

#include <filmback/lens_distortion.h>

namespace fb {
namespace {

// A 1920 x 1080 clip, f = 1500 px, the optical centre off the middle.
LensDistortionParams clip() {
  LensDistortionParams p;
  p.clip_width_px = 1920;
  p.clip_height_px = 1080;
  p.focal_length_px = 1500;
  p.principal_px = {970.5, 531.25};
  return p;
}

struct Case {
  const char* name;
  LensDistortionParams params;
};

std::vector<Case> models() {
  std::vector<Case> cases;
  LensDistortionParams p = clip();
  p.polynomial_k = {-0.12, 0.05, -0.01};
  cases.push_back({"polynomial", p});
  p = clip();
  p.division_k = {-0.08, 0.01};
  cases.push_back({"division", p});
  p = clip();
  p.nuke_k = {0.07, -0.01};
  cases.push_back({"nuke", p});
  p = clip();
  p.brown_k = {-0.1, 0.03, -0.004, 0.0005};
  p.brown_p = {0.002, -0.0015};
  cases.push_back({"brown", p});
  p = clip();
  p.pixel_aspect = 1.25;
  p.brown_k = {0.09, 0, 0, 0};
  cases.push_back({"brown, pixel aspect 1.25", p});
  return cases;
}

TEST(LensDistortion, UndistortThenDistortReturnsTheDistortedPointTo1e9Px) {
  for (const Case& c : models()) {
    const LensDistortion lens(c.params);
    ASSERT_FALSE(lens.identity()) << c.name;
    for (double x = 0; x <= 1920; x += 160)
      for (double y = 0; y <= 1080 / c.params.pixel_aspect; y += 90) {
        const std::optional<Vec2d> u = lens.undistort({x, y});
        ASSERT_TRUE(u) << c.name << " at " << x << ", " << y;
        const std::optional<Vec2d> d = lens.distort(*u);
        ASSERT_TRUE(d) << c.name;
        EXPECT_NEAR(d->x, x, 1e-9) << c.name;
        EXPECT_NEAR(d->y, y, 1e-9) << c.name;
      }
  }
}

TEST(LensDistortion, DistortThenUndistortReturnsTheUndistortedPoint) {
  for (const Case& c : models()) {
    const LensDistortion lens(c.params);
    for (double x = 100; x <= 1820; x += 172)
      for (double y = 60; y <= 800; y += 74) {
        const std::optional<Vec2d> d = lens.distort({x, y});
        ASSERT_TRUE(d) << c.name;
        const std::optional<Vec2d> u = lens.undistort(*d);
        ASSERT_TRUE(u) << c.name;
        EXPECT_NEAR(u->x, x, 1e-9) << c.name;
        EXPECT_NEAR(u->y, y, 1e-9) << c.name;
      }
  }
}

// libmv's equations at one point, by hand: normalized (0.3, -0.2), r^2 = 0.13.
TEST(LensDistortion, ForwardMapsAreLibmvsEquations) {
  const double x = 0.3, y = -0.2, r2 = 0.13, f = 1500, px = 970.5, py = 531.25;
  const Vec2d undistorted{px + x * f, py + y * f};
  LensDistortionParams p = clip();
  p.polynomial_k = {-0.12, 0.05, -0.01};
  const double poly = 1 - 0.12 * r2 + 0.05 * r2 * r2 - 0.01 * r2 * r2 * r2;
  Vec2d d = *LensDistortion(p).distort(undistorted);
  EXPECT_NEAR(d.x, px + f * x * poly, 1e-9);
  EXPECT_NEAR(d.y, py + f * y * poly, 1e-9);

  p = clip();
  p.division_k = {-0.08, 0.01};
  const double division = 1 - 0.08 * r2 + 0.01 * r2 * r2;
  d = *LensDistortion(p).distort(undistorted);
  EXPECT_NEAR(d.x, px + f * x / division, 1e-9);
  EXPECT_NEAR(d.y, py + f * y / division, 1e-9);

  p = clip();
  p.brown_k = {-0.1, 0.03, -0.004, 0.0005};
  p.brown_p = {0.002, -0.0015};
  const double radial =
      1 - 0.1 * r2 + 0.03 * r2 * r2 - 0.004 * std::pow(r2, 3) + 0.0005 * std::pow(r2, 4);
  d = *LensDistortion(p).distort(undistorted);
  EXPECT_NEAR(d.x, px + f * (x * radial + 0.002 * (r2 + 2 * x * x) + 2 * -0.0015 * x * y), 1e-9);
  EXPECT_NEAR(d.y, py + f * (y * radial + -0.0015 * (r2 + 2 * y * y) + 2 * 0.002 * x * y), 1e-9);

  // Nuke's closed form goes the other way: distorted -> undistorted, in units of half the larger
  // side (960 px).
  p = clip();
  p.nuke_k = {0.07, -0.01};
  const double qx = 0.3, qy = -0.2, q2 = 0.13;
  const Vec2d u = *LensDistortion(p).undistort({px + qx * 960, py + qy * 960});
  const double nuke = 1 + 0.07 * q2 - 0.01 * q2 * q2;
  EXPECT_NEAR(u.x, px + 960 * qx / nuke, 1e-9);
  EXPECT_NEAR(u.y, py + 960 * qy / nuke, 1e-9);
}

// r (1 - 0.5 r^2) rises to its fold at r = sqrt(2/3) (where it reaches 0.5443): a distorted
// point beyond that radius has no undistorted point, and one inside it the inner one only.
TEST(LensDistortion, AFoldingPolynomialGivesNoPositionBeyondItsFold) {
  LensDistortionParams p = clip();
  p.polynomial_k = {-0.5, 0, 0};
  const LensDistortion lens(p);
  const double f = 1500, fold_value = std::sqrt(2.0 / 3) * (1 - 0.5 * 2.0 / 3);
  EXPECT_FALSE(lens.undistort({970.5 + f * (fold_value + 0.01), 531.25}));
  EXPECT_FALSE(lens.undistort({970.5 + f * 0.6, 531.25 + f * 0.3}));
  const std::optional<Vec2d> inside = lens.undistort({970.5 + f * 0.5, 531.25});
  ASSERT_TRUE(inside);
  EXPECT_LT((inside->x - 970.5) / f, std::sqrt(2.0 / 3));
  // The outer branch of the same distorted radius is refused by the forward map too.
  EXPECT_FALSE(lens.distort({970.5 + f * 1.0, 531.25}));
  // No NaN reaches the film: the render-frame mapping says "none" as well.
  EXPECT_FALSE(lens.undistorted_film({1919.5, 540}, 1920, 1080));
}

TEST(LensDistortion, NoCoefficientsIsTheIdentity) {
  const LensDistortion lens(LensDistortionParams{});
  EXPECT_TRUE(lens.identity());
  const Vec2d film = *lens.undistorted_film({12.25, 7.5}, 96, 64);
  EXPECT_EQ(film.x, 12.25);
  EXPECT_EQ(film.y, 7.5);
}

// The render's raster maps to the clip's frame as the compositor does: pixel centres at integers,
// y up, the pixel indices scaled by the size ratio (1/20 here). The principal point stays put: the
// clip's (959.5, 539.5) is the render's pixel-index (47.975, 26.975), raster (48.475, 26.525).
TEST(LensDistortion, TheRenderFrameIsTheClipsScaled) {
  LensDistortionParams p = clip();
  p.polynomial_k = {-0.2, 0, 0};
  p.principal_px = {959.5, 539.5};
  const LensDistortion lens(p);
  const Vec2d centre = *lens.undistorted_film({48.475, 26.525}, 96, 54);
  EXPECT_NEAR(centre.x, 48.475, 1e-12);
  EXPECT_NEAR(centre.y, 26.525, 1e-12);
  // Barrel distortion (k1 < 0) shows the undistorted image's far points nearer the centre: a
  // film point maps outwards.
  const Vec2d corner = *lens.undistorted_film({90, 5}, 96, 54);
  EXPECT_GT(corner.x, 90);
  EXPECT_LT(corner.y, 5);
}

TEST(LensDistortion, RefusesTwoModelsAndAMissingClip) {
  LensDistortionParams p = clip();
  p.polynomial_k = {0.1, 0, 0};
  p.nuke_k = {0.1, 0};
  EXPECT_THROW(LensDistortion{p}, std::invalid_argument);
  p = LensDistortionParams{};
  p.division_k = {0.1, 0};
  EXPECT_THROW(LensDistortion{p}, std::invalid_argument);  // no focal length, no clip size
}

}  // namespace
}  // namespace fb
