// Cycles' panoramic projections (filmback/panorama.h) and their camera plugins: film -> direction
// -> film round trips, directions at points where Cycles' definitions give them in closed form,
// black (weight 0, finite direction) outside a fisheye's circle and past a polynomial's fold, and
// create() failing with the parameter's name for fields of view beyond 360 degrees.
#include <filmback/panorama.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/plugin/instances.h"
#include "core/scene/camera.h"
#include "core/util/error.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::generate_ray;
using test::make_camera;

namespace pano = fb::panorama;
using pano::Film;
constexpr double kPi = pano::kPi;

void expect_direction(Vec3d d, Vec3d expected, const char* what) {
  EXPECT_NEAR(length(d), 1.0, 1e-12) << what;
  EXPECT_NEAR(d.x, expected.x, 1e-9) << what;
  EXPECT_NEAR(d.y, expected.y, 1e-9) << what;
  EXPECT_NEAR(d.z, expected.z, 1e-9) << what;
}

// Every film point of a grid over [0,1]^2 whose direction is defined returns to itself.
void expect_round_trips(const std::function<Vec3d(Film)>& to_direction,
                        const std::function<Film(Vec3d)>& to_film, const char* what) {
  int defined = 0;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const Film f{0.01 + 0.98 * i / 40, 0.01 + 0.98 * j / 40};
      const Vec3d d = to_direction(f);
      if (length(d) == 0) continue;
      ++defined;
      EXPECT_NEAR(length(d), 1.0, 1e-12) << what;
      const Film back = to_film(d);
      EXPECT_NEAR(back.u, f.u, 1e-9) << what << " at (" << f.u << ", " << f.v << ")";
      EXPECT_NEAR(back.v, f.v, 1e-9) << what << " at (" << f.u << ", " << f.v << ")";
    }
  EXPECT_GT(defined, 400) << what;
}

TEST(PanoramaMapping, RoundTripsFilmToDirectionToFilm) {
  const pano::AngleRange lon{-2.5, 3.0}, lat{-1.2, 1.4}, height{-1.5, 0.7};
  expect_round_trips([&](Film f) { return pano::equirectangular_direction(f, lon, lat); },
                     [&](Vec3d d) { return pano::equirectangular_film(d, lon, lat); },
                     "equirectangular");
  expect_round_trips([](Film f) { return pano::equidistant_direction(f, 3.0); },
                     [](Vec3d d) { return pano::equidistant_film(d, 3.0); }, "equidistant");
  const Vec2d sensor{36, 24};
  expect_round_trips([&](Film f) { return pano::equisolid_direction(f, 9.0, 2 * kPi, sensor); },
                     [&](Vec3d d) { return pano::equisolid_film(d, 9.0, sensor); }, "equisolid");
  expect_round_trips(pano::mirrorball_direction, pano::mirrorball_film, "mirror ball");
  expect_round_trips([&](Film f) { return pano::central_cylindrical_direction(f, lon, height); },
                     [&](Vec3d d) { return pano::central_cylindrical_film(d, lon, height); },
                     "central cylindrical");
  expect_round_trips(pano::cubemap_face_direction, pano::cubemap_face_film, "cubemap face");
  // Blender's default lens polynomial, and one with theta decreasing (the image turned over).
  for (const pano::Polynomial p :
       {pano::Polynomial{{-1.17e-5, -0.0199887, -3.35e-6, 3.0993e-6, -2.6065e-8}},
        pano::Polynomial{{0, 0.06, 0, -1e-5, 0}}}) {
    const double fold = p.fold_radius_mm(std::hypot(18.0, 12.0));
    expect_round_trips(
        [&](Film f) { return pano::polynomial_direction(f, p, 2 * kPi, fold, sensor); },
        [&](Vec3d d) { return pano::polynomial_film(d, p, fold, sensor); }, "polynomial");
  }
}

TEST(PanoramaMapping, DirectionsAtPointsOfKnownAngle) {
  const pano::AngleRange lon{-kPi, kPi}, lat{-kPi / 2, kPi / 2};
  // Longitude runs rightwards from the view axis (-Z), latitude upwards.
  expect_direction(pano::equirectangular_direction({0.5, 0.5}, lon, lat), {0, 0, -1}, "ahead");
  expect_direction(pano::equirectangular_direction({0.75, 0.5}, lon, lat), {1, 0, 0}, "right");
  expect_direction(pano::equirectangular_direction({0.0, 0.5}, lon, lat), {0, 0, 1}, "behind");
  expect_direction(pano::equirectangular_direction({0.3, 1.0}, lon, lat), {0, 1, 0}, "zenith");
  // Equidistant: 180 degrees across the inscribed circle, so its rim is 90 degrees off the axis.
  expect_direction(pano::equidistant_direction({1.0, 0.5}, kPi), {1, 0, 0}, "rim, right");
  expect_direction(pano::equidistant_direction({0.5, 0.75}, kPi),
                   {0, std::sin(kPi / 4), -std::cos(kPi / 4)}, "half way up");
  // Equisolid: r = 2 f sin(theta / 2); 90 degrees at r = 2 f sin(45 deg) mm.
  const Vec2d sensor{36, 24};
  const double r90 = 2 * 10 * std::sin(kPi / 4);
  expect_direction(pano::equisolid_direction({0.5 - r90 / 36, 0.5}, 10, kPi, sensor), {-1, 0, 0},
                   "equisolid, 90 deg left");
  // Mirror ball: the normal at 45 degrees reflects the view ray sideways; the rim looks back.
  expect_direction(pano::mirrorball_direction({0.5 + std::sqrt(0.5) / 2, 0.5}), {1, 0, 0},
                   "mirror ball, 45 deg normal");
  expect_direction(pano::mirrorball_direction({0.5, 1.0}), {0, 0, 1}, "mirror ball rim");
  // Polynomial theta = 0.05 r: 90 degrees at r = 10 pi mm.
  const pano::Polynomial linear{{0, -0.05, 0, 0, 0}};
  expect_direction(
      pano::polynomial_direction({0.5, 0.5 + 10 * kPi / 24}, linear, kPi, 1e9, {36, 24}), {0, 1, 0},
      "polynomial, 90 deg up");
  // Cubemap face: 45 degrees at the face's edge; central cylindrical: height 1 on radius 1.
  expect_direction(pano::cubemap_face_direction({1.0, 0.5}), normalize(Vec3d{1, 0, -1}),
                   "face edge");
  expect_direction(pano::cubemap_face_direction({0.5, 0.25}),
                   normalize(Vec3d{0, -std::tan(kPi / 8), -1}), "a quarter down");
  expect_direction(pano::central_cylindrical_direction({0.75, 1.0}, lon, {-1, 1}),
                   normalize(Vec3d{1, 1, 0}), "cylinder, right and up");
}

TEST(PanoramaMapping, OutsideTheImageCircleThereIsNoDirection) {
  EXPECT_EQ(length(pano::equidistant_direction({0.97, 0.97}, kPi)), 0);
  EXPECT_EQ(length(pano::mirrorball_direction({0.02, 0.5 + 0.3})), 0);
  // 10 mm, 180 deg: the circle's radius is 2 f sin(45 deg) = 14.1 mm, beyond the 12 mm half height.
  EXPECT_GT(length(pano::equisolid_direction({0.5, 0.0}, 10, kPi, {36, 24})), 0);
  EXPECT_EQ(length(pano::equisolid_direction({0.02, 0.5}, 10, kPi, {36, 24})), 0);
  const pano::Polynomial linear{{0, -0.05, 0, 0, 0}};  // a 90 deg field of view ends at 15.7 mm
  EXPECT_GT(
      length(pano::polynomial_direction({0.5 + 15.6 / 36, 0.5}, linear, kPi / 2, 1e9, {36, 24})),
      0);
  EXPECT_EQ(
      length(pano::polynomial_direction({0.5 + 15.8 / 36, 0.5}, linear, kPi / 2, 1e9, {36, 24})),
      0);
}

TEST(PanoramaMapping, APolynomialThatFoldsOverIsCutAtItsFold) {
  // theta = (r - r^3 / 300) / 10 turns back at r = 10 mm (dtheta/dr = (1 - r^2 / 100) / 10).
  const pano::Polynomial folding{{0, -0.1, 0, 0.1 / 300, 0}};
  EXPECT_NEAR(folding.fold_radius_mm(30), 10, 1e-9);
  EXPECT_EQ(folding.fold_radius_mm(8), 8);  // no fold within 8 mm
  const double fold = folding.fold_radius_mm(30);
  EXPECT_GT(
      length(pano::polynomial_direction({0.5 + 9.9 / 36, 0.5}, folding, 2 * kPi, fold, {36, 24})),
      0);
  EXPECT_EQ(
      length(pano::polynomial_direction({0.5 + 10.1 / 36, 0.5}, folding, 2 * kPi, fold, {36, 24})),
      0);
}

// ------------------------------------------------------------------ the plugins, through the ABI

fb_camera_setup panoramic_setup(uint32_t width, uint32_t height) {
  PhysicalCamera physical;
  physical.projection = FB_PROJECTION_PANORAMIC;
  physical.clip_near_m = 0.5;
  physical.clip_far_m = 90;
  return make_camera_setup(physical, width, height);
}

const char* const kPlugins[] = {
    "equirectangular",    "fisheye_equidistant", "fisheye_equisolid",       "mirrorball",
    "fisheye_polynomial", "central_cylindrical", "equiangular_cubemap_face"};

TEST(PanoramaCameras, EveryRayIsFiniteAndBlackOnesWeighNothing) {
  const fb_camera_setup setup = panoramic_setup(96, 64);
  for (const char* name : kPlugins) {
    const auto camera = make_camera(name, setup);
    EXPECT_EQ(camera->needs(), 0u) << name;
    int black = 0;
    for (float y = 0; y <= 64; y += 4)
      for (float x = 0; x <= 96; x += 4) {
        const fb_camera_ray ray = generate_ray(*camera, x, y);
        const Vec3d d{ray.direction[0], ray.direction[1], ray.direction[2]};
        EXPECT_NEAR(length(d), 1.0, 1e-6) << name << " at " << x << ", " << y;
        EXPECT_TRUE(ray.weight == 0.f || ray.weight == 1.f) << name;
        EXPECT_EQ(ray.t_min, 0.5f) << name;  // clipped along the ray, as Cycles clips panoramas
        EXPECT_EQ(ray.t_max, 90.f) << name;
        black += ray.weight == 0.f;
      }
    // Blender's default lens polynomial images at most 25 degrees off the axis on 36 mm, well
    // within its 180 degree cut.
    const std::string n = name;
    const bool has_circle =
        n == "fisheye_equidistant" || n == "fisheye_equisolid" || n == "mirrorball";
    EXPECT_EQ(black > 0, has_circle) << name << ": " << black << " black samples";
  }
  // The image's centre looks down the view axis; the top edge of an equirectangular image, up.
  const auto equirectangular = make_camera("equirectangular", setup);
  EXPECT_NEAR(generate_ray(*equirectangular, 48, 32).direction[2], -1, 1e-6);
  EXPECT_NEAR(generate_ray(*equirectangular, 10, 0).direction[1], 1, 1e-6);
}

TEST(PanoramaCameras, RefuseFieldsOfViewBeyond360Degrees) {
  // Any shot renders through a panorama (its projection is the plugin's own).
  EXPECT_NO_THROW(make_camera("mirrorball", make_camera_setup(PhysicalCamera{}, 10, 10)));
  for (const char* name : {"fisheye_equidistant", "fisheye_equisolid", "fisheye_polynomial"}) {
    try {
      make_camera(name, panoramic_setup(10, 10), {{"fisheye_fov_rad", "6.3"}});
      ADD_FAILURE() << name << " took a field of view beyond 2 pi";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("fisheye_fov_rad"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(make_camera("fisheye_equidistant", panoramic_setup(10, 10),
                              {{"fisheye_fov_rad", "6.2831855"}}));  // 2 pi as a float
  try {
    make_camera("fisheye_polynomial", panoramic_setup(10, 10),
                {{"k0", "0"}, {"k1", "0"}, {"k2", "0"}, {"k3", "0"}, {"k4", "0"}});
    ADD_FAILURE() << "a constant polynomial was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("k1..k4"), std::string::npos) << e.what();
  }
}

// What `filmback info` prints (fb_camera_api::describe), against closed forms.
TEST(PanoramaCameras, DescribeTheirFieldOfView) {
  const fb_camera_setup setup = panoramic_setup(96, 64);  // 36 x 24 mm imaged
  // Equisolid 10 mm, 180 deg: the circle (14.14 mm) fills the width; the height's half (12 mm)
  // sees 2 asin(12 / 20) from the axis.
  const std::string equisolid =
      make_camera("fisheye_equisolid", setup, {{"fisheye_lens_mm", "10"}})->describe();
  const double vertical_deg = 2 * 2 * std::asin(12.0 / 20) * 180 / kPi;
  char expected[96];
  std::snprintf(expected, sizeof expected, "180 deg horizontal x %.6g deg vertical", vertical_deg);
  EXPECT_NE(equisolid.find(expected), std::string::npos) << equisolid;
  std::snprintf(expected, sizeof expected, "35 mm equivalent fisheye lens: %.6g mm",
                10 * 43.27 / std::hypot(36.0, 24.0));  // the 43.27 mm diagonal of 35 mm film
  EXPECT_NE(equisolid.find(expected), std::string::npos) << equisolid;  // 36 x 24 mm is 35 mm film
  const std::string equirectangular =
      make_camera("equirectangular", setup, {{"latitude_min_rad", "0"}})->describe();
  EXPECT_NE(equirectangular.find("360 deg horizontal (longitude -180 to 180 deg) x 90 deg "
                                 "vertical (latitude 0 to 90 deg)"),
            std::string::npos)
      << equirectangular;
  // theta = (r - r^3 / 300) / 10 folds at 10 mm, inside the 21.6 mm corner radius; 1 / |k1| = 10.
  const std::string folding =
      make_camera(
          "fisheye_polynomial", setup,
          {{"k0", "0"}, {"k1", "-0.1"}, {"k2", "0"}, {"k3", "0.00033333333333333332"}, {"k4", "0"}})
          ->describe();
  EXPECT_NE(folding.find("folds over at r = 10 mm"), std::string::npos) << folding;
  EXPECT_NE(folding.find("paraxial focal length: 10 mm"), std::string::npos) << folding;
  // With the shot's aperture: f / 2N across, at the shot's focal length (50 mm).
  const std::string lens =
      make_camera("mirrorball", setup, {{"fstop", "2"}, {"focus_distance_m", "4"}})->describe();
  EXPECT_NE(lens.find("aperture diameter: 25 mm (f/2 of the 50 mm lens), focused 4 m along each "
                      "ray"),
            std::string::npos)
      << lens;
}

}  // namespace
}  // namespace fb
