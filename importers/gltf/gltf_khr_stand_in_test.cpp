// The KHR_lights_punctual stand-ins of POV-Ray's lights (docs/pov.md "Conversion"): the intensity
// scale against the inverse-square law, the points a viewer's camera sees, and what
// `filmback convert` writes for other viewers while FILMBACK_povray keeps the exact light.
#include "importers/gltf/gltf_khr_stand_in.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <string>

#include "core/math/constants.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/gltf/gltf_writer.h"
#include "support/gltf_builder.h"
#include "support/povray_light.h"
#include "support/written_gltf.h"

namespace fb {
namespace {

using gltf::khr_intensity_scale;
using gltf::ViewedPoint;

Light povray_stand_in_light(LightType type, Vec3d position) {
  return test::povray_light(type, Transform::translate(position));
}

// A point facing straight up at (x, y, 0).
ViewedPoint floor_point(double x, double y) {
  return {{x, y, 0}, {0, 0, 1}};
}

TEST(GltfKhrStandIn, ScaleIsTheSquaredDistanceToWhatIsSeen) {
  const Light light = povray_stand_in_light(LightType::kPoint, {0, 0, 4});
  const ViewedPoint one[] = {floor_point(0, 0)};
  EXPECT_NEAR(khr_intensity_scale(light, one, std::nullopt), 16, 1e-12);
  // Two points seen square on at 1 m and 3 m: the irradiances' sum is kept, I (1 + 1) = I' (1 +
  // 1/9), the harmonic mean of d^2.
  const ViewedPoint two[] = {{{0, 0, 3}, {0, 0, 1}}, {{0, 0, 1}, {0, 0, -1}}};
  EXPECT_NEAR(khr_intensity_scale(light, two, std::nullopt), 2 / (1 + 1.0 / 9), 1e-12);
  // Lambert's cosine weighs each point as both renderers light it. A wall point at 4 m seen
  // square on (light along its normal) counts as the floor's centre does...
  const ViewedPoint wall[] = {floor_point(0, 0), {{4, 0, 4}, {1, 0, 0}}};
  EXPECT_NEAR(khr_intensity_scale(light, wall, std::nullopt), 16, 1e-12);
  // ...a slanted one at (3, 0, 0), d = 5, with |cos| = |(0.6, 0, 0.8) . (-0.6, 0, 0.8)| = 0.28,
  // less.
  const ViewedPoint grazing[] = {floor_point(0, 0), {{3, 0, 0}, {0.6, 0, 0.8}}};
  const double expected = (1 + 0.28) / (1.0 / 16 + 0.28 / 25);
  EXPECT_NEAR(khr_intensity_scale(light, grazing, std::nullopt), expected, 1e-12);
}

TEST(GltfKhrStandIn, FadingLightsKeepPovRaysFadeAtTheSeenDistance) {
  Light light = povray_stand_in_light(LightType::kPoint, {0, 0, 4});
  light.fade_distance_m = 2, light.fade_power = 2;
  const ViewedPoint one[] = {floor_point(0, 0)};
  // POV-Ray: I 2 / (1 + (4/2)^2) = 0.4 I at 4 m; the stand-in I' / 16 there.
  EXPECT_NEAR(khr_intensity_scale(light, one, std::nullopt), 0.4 * 16, 1e-12);
  // Far beyond fade_distance, fade_power 2 is an inverse-square law of intensity 2 fd^2 I: the
  // scale no longer depends on the distance.
  light.world_from_light = Transform::translate({0, 0, 1000});
  EXPECT_NEAR(khr_intensity_scale(light, one, std::nullopt), 2 * 4, 1e-4);
}

TEST(GltfKhrStandIn, SpotsWeighPovRaysProfileAgainstKhrsCone) {
  Light spot = povray_stand_in_light(LightType::kSpot, {0, 0, 4});
  spot.spot_falloff = SpotFalloff::kPov;
  spot.spot_inner_angle_rad = 0.2, spot.spot_outer_angle_rad = 0.3;
  // (0, 0, 0) is on the axis; (4, 0, 0) 45 degrees off it, outside the falloff cone.
  const ViewedPoint seen[] = {floor_point(0, 0), floor_point(4, 0)};
  EXPECT_NEAR(khr_intensity_scale(spot, seen, std::nullopt), 16, 1e-12);
  // Inside the radius cone POV-Ray's spot is cos^tightness, KHR's flat: at 0.1 rad off the axis,
  // d^2 = 16 / cos^2.
  spot.spot_tightness = 10;
  const double c = std::cos(0.1);
  const ViewedPoint inside[] = {floor_point(4 * std::tan(0.1), 0)};
  EXPECT_NEAR(khr_intensity_scale(spot, inside, std::nullopt), std::pow(c, 10) * 16 / (c * c),
              1e-9);
  // Between the cones POV-Ray's cubic (3 - 2t) t^2 against KHR's ramp ((c - cos_outer) /
  // (cos_inner - cos_outer))^2 on the stand-in's cone.
  spot.spot_tightness = 0;
  const double c25 = std::cos(0.25);
  const double t = (c25 - std::cos(0.3)) / (std::cos(0.2) - std::cos(0.3));
  const gltf::KhrSpotCone cone = gltf::khr_spot_cone(spot);
  const double ramp =
      (c25 - std::cos(cone.outer_rad)) / (std::cos(cone.inner_rad) - std::cos(cone.outer_rad));
  ASSERT_GT(ramp, 0);
  ASSERT_LT(ramp, 1);
  const ViewedPoint between[] = {floor_point(4 * std::tan(0.25), 0)};
  EXPECT_NEAR(khr_intensity_scale(spot, between, std::nullopt),
              (3 - 2 * t) * t * t / (ramp * ramp) * 16 / (c25 * c25), 1e-9);
  // Nothing seen in the cone: the distance to the viewer.
  const ViewedPoint outside[] = {floor_point(4, 0)};
  EXPECT_NEAR(khr_intensity_scale(spot, outside, Vec3d{0, 3, 0}), 25, 1e-12);
  EXPECT_EQ(khr_intensity_scale(spot, outside, std::nullopt), 1);
}

// KHR's flux of a cone, over 2 pi: full to the inner cone, the ramp t^2 (1/3 on average) beyond.
double khr_cone_flux(const gltf::KhrSpotCone& cone) {
  const double ci = std::cos(cone.inner_rad), co = std::cos(cone.outer_rad);
  return (1 - ci) + (ci - co) / 3;
}

TEST(GltfKhrStandIn, SpotConesCarryPovRaysFlux) {
  Light spot = povray_stand_in_light(LightType::kSpot, {0, 0, 4});
  spot.spot_falloff = SpotFalloff::kPov;
  // Tightness 0: full to the radius, the cubic (1/2 on average) to the falloff.
  spot.spot_inner_angle_rad = 0.2, spot.spot_outer_angle_rad = 0.3;
  const double flat = (1 - std::cos(0.2)) + (std::cos(0.2) - std::cos(0.3)) / 2;
  gltf::KhrSpotCone cone = gltf::khr_spot_cone(spot);
  EXPECT_NEAR(khr_cone_flux(cone), flat, 1e-5 * flat);
  EXPECT_NEAR(cone.inner_rad, 0.95 * std::acos(1 - flat), 1e-4);
  EXPECT_GT(cone.outer_rad, cone.inner_rad);
  EXPECT_LT(cone.outer_rad, 0.3);  // narrower than POV-Ray's falloff: the ramp is short
  // cos^10 out to a 60 degree cone with radius = falloff: integral of c^10 from 0.5 to 1.
  spot.spot_tightness = 10;
  spot.spot_inner_angle_rad = spot.spot_outer_angle_rad = kPi / 3;
  const double tight = (1 - std::pow(0.5, 11)) / 11;
  cone = gltf::khr_spot_cone(spot);
  EXPECT_NEAR(khr_cone_flux(cone), tight, 1e-5 * tight);
  // POV-Ray takes cosines, so scenes write falloff 250: KHR's cone stops at 90 degrees.
  spot.spot_tightness = 0;
  spot.spot_inner_angle_rad = 1.5, spot.spot_outer_angle_rad = 250 * kPi / 180;
  cone = gltf::khr_spot_cone(spot);
  EXPECT_DOUBLE_EQ(cone.outer_rad, kPi / 2);
  EXPECT_LT(cone.inner_rad, cone.outer_rad);
  // A glTF spot keeps its cone.
  Light gltf_spot = spot;
  gltf_spot.spot_falloff = SpotFalloff::kGltf;
  gltf_spot.spot_inner_angle_rad = 0.2, gltf_spot.spot_outer_angle_rad = 0.6;
  EXPECT_EQ(gltf::khr_spot_cone(gltf_spot).inner_rad, 0.2);
  EXPECT_EQ(gltf::khr_spot_cone(gltf_spot).outer_rad, 0.6);
}

TEST(GltfKhrStandIn, DirectionalAndPhysicalLightsAreUnchanged) {
  const ViewedPoint one[] = {floor_point(0, 0)};
  EXPECT_EQ(khr_intensity_scale(povray_stand_in_light(LightType::kDirectional, {0, 0, 4}), one, {}),
            1);
  Light physical = povray_stand_in_light(LightType::kPoint, {0, 0, 4});
  physical.decay = LightDecay::kInverseSquare;
  EXPECT_EQ(khr_intensity_scale(physical, one, Vec3d{0, 0, 9}), 1);
}

// A square of side `size_m` in the z = 0 plane, centred on the origin.
Scene floor_scene(float size_m) {
  Scene scene;
  scene.materials.emplace_back();
  TriangleMesh mesh;
  const float h = size_m / 2;
  mesh.positions = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes.push_back(mesh);
  scene.instances.push_back({0, Transform(), "floor"});
  return scene;
}

TEST(GltfKhrStandIn, ViewedPointsAreWhereTheViewersRaysMeetTheGeometry) {
  const Scene scene = floor_scene(100);
  const Transform world_from_camera = Transform::translate({0, 0, 10});  // looks down -Z
  tinygltf::Camera perspective;
  perspective.type = "perspective";
  perspective.perspective.yfov = 0.5;
  perspective.perspective.aspectRatio = 4.0 / 3;
  const std::vector<ViewedPoint> seen = gltf::viewed_points(scene, perspective, world_from_camera);
  ASSERT_EQ(seen.size(), 32u * 24u);
  double most_x = 0, most_y = 0;
  for (const ViewedPoint& p : seen) {
    EXPECT_NEAR(p.position.z, 0, 1e-5);
    EXPECT_NEAR(std::abs(p.normal.z), 1, 1e-6);
    most_x = std::max(most_x, p.position.x), most_y = std::max(most_y, p.position.y);
  }
  // The outermost cell centres, 31/32 and 23/24 of the half extents.
  const double half_y = 10 * std::tan(0.25);
  EXPECT_NEAR(most_x, half_y * 4 / 3 * 31 / 32, 1e-4);
  EXPECT_NEAR(most_y, half_y * 23 / 24, 1e-4);

  tinygltf::Camera ortho;
  ortho.type = "orthographic";
  ortho.orthographic.xmag = 2, ortho.orthographic.ymag = 1.5;
  const std::vector<ViewedPoint> flat = gltf::viewed_points(scene, ortho, world_from_camera);
  ASSERT_EQ(flat.size(), 32u * 24u);
  most_x = most_y = 0;
  for (const ViewedPoint& p : flat)
    most_x = std::max(most_x, p.position.x), most_y = std::max(most_y, p.position.y);
  EXPECT_NEAR(most_x, 2.0 * 31 / 32, 1e-5);
  EXPECT_NEAR(most_y, 1.5 * 23 / 24, 1e-5);

  // Rays that miss are left out: a 1 m square seen from 10 m fills a small part of the frame.
  const std::vector<ViewedPoint> few =
      gltf::viewed_points(floor_scene(1), perspective, world_from_camera);
  EXPECT_GT(few.size(), 0u);
  EXPECT_LT(few.size(), seen.size() / 10);
}

// A 1 m square at z = 2 shadows |x|, |y| < 1 of the floor from a light at (0, 0, 4): those floor
// points are left out; a shadowless light counts them.
TEST(GltfKhrStandIn, ShadowedPointsAreLeftOut) {
  Scene scene = floor_scene(6);
  TriangleMesh blocker = scene.meshes[0];
  for (Vec3f& p : blocker.positions)
    p = Vec3f{p.x / 6, p.y / 6, 2.f};
  scene.meshes.push_back(blocker);
  scene.instances.push_back({1, Transform(), "blocker"});
  Light light = povray_stand_in_light(LightType::kPoint, {0, 0, 4});
  scene.lights = {light};
  light.casts_shadows = false;
  scene.lights.push_back(light);
  tinygltf::Camera camera;
  camera.type = "perspective";
  camera.perspective.yfov = 0.7;
  camera.perspective.aspectRatio = 4.0 / 3;
  const Transform world_from_camera = Transform::translate({0.3, 0.2, 10});
  const std::vector<ViewedPoint> seen = gltf::viewed_points(scene, camera, world_from_camera);
  std::vector<ViewedPoint> lit;
  for (const ViewedPoint& p : seen)
    if (p.position.z > 1 || std::abs(p.position.x) > 1 || std::abs(p.position.y) > 1)
      lit.push_back(p);
  ASSERT_LT(lit.size(), seen.size());
  ASSERT_GT(lit.size(), seen.size() / 2);
  const std::vector<double> scales = gltf::khr_intensity_scales(scene, camera, world_from_camera);
  ASSERT_EQ(scales.size(), 2u);
  EXPECT_NEAR(scales[0], khr_intensity_scale(scene.lights[0], lit, std::nullopt), 1e-9);
  EXPECT_NEAR(scales[1], khr_intensity_scale(scene.lights[1], seen, std::nullopt), 1e-9);
  EXPECT_NE(scales[0], scales[1]);
}

// What convert writes: KHR intensities scaled for viewers with the inverse-square law, spot cones
// carrying POV-Ray's flux, the sun's irradiance as lux; FILMBACK_povray as before.
TEST(GltfKhrStandIn, ConvertWritesScaledStandInsAndKeepsPovRaysLights) {
  Scene scene = floor_scene(4);
  SceneCamera camera;
  camera.name = "camera";
  camera.world_from_camera = Transform::translate({0, 0, 10});
  scene.cameras.push_back(camera);
  scene.settings.width_px = 320, scene.settings.height_px = 240;
  const Light point = povray_stand_in_light(LightType::kPoint, {0, 0, 4});
  Light spot = povray_stand_in_light(LightType::kSpot, {0, 0, 6});
  spot.spot_falloff = SpotFalloff::kPov;
  spot.spot_inner_angle_rad = 0.2, spot.spot_outer_angle_rad = 0.6, spot.spot_tightness = 3;
  const Light parallel = povray_stand_in_light(LightType::kDirectional, {0, 0, 4});
  scene.lights = {point, spot, parallel};
  // POV-Ray's default finish: Lambertian (roughness unused), and a glossy one.
  scene.materials[0].specular = 0;
  Material glossy;
  glossy.roughness = 0.3f;
  scene.materials.push_back(glossy);
  const std::filesystem::path file = test::scratch_dir() / "stand_ins.gltf";
  const tinygltf::Model model = test::written_gltf(scene, file);
  ASSERT_EQ(model.lights.size(), 3u);
  ASSERT_EQ(model.cameras.size(), 1u);
  const std::vector<ViewedPoint> seen =
      gltf::viewed_points(scene, model.cameras[0], camera.world_from_camera);
  ASSERT_GT(seen.size(), 100u);
  const double peak = 0.8 * kPi;
  const double lumens_per_watt = 683;
  // The 4 m floor seen from 10 m, lit from 4 m and 6 m above its centre: between d^2 at the
  // centre and at the corners.
  const double point_scale = khr_intensity_scale(point, seen, std::nullopt);
  EXPECT_GT(point_scale, 16);
  EXPECT_LT(point_scale, 16 + 8);
  const double point_khr = float(peak) * lumens_per_watt * point_scale;
  EXPECT_NEAR(model.lights[0].intensity, point_khr, 1e-6 * point_khr);
  const double spot_khr =
      float(peak) * lumens_per_watt * khr_intensity_scale(spot, seen, std::nullopt);
  EXPECT_NEAR(model.lights[1].intensity, spot_khr, 1e-6 * spot_khr);
  EXPECT_EQ(model.lights[1].type, "spot");
  EXPECT_DOUBLE_EQ(model.lights[1].spot.innerConeAngle, gltf::khr_spot_cone(spot).inner_rad);
  EXPECT_DOUBLE_EQ(model.lights[1].spot.outerConeAngle, gltf::khr_spot_cone(spot).outer_rad);
  EXPECT_EQ(model.lights[2].type, "directional");
  EXPECT_NEAR(model.lights[2].intensity, float(peak) * lumens_per_watt, 1e-6 * peak * 683);

  // Lambertian: roughness 0.5, where Blender's Disney diffuse matches Lambert's on average.
  ASSERT_EQ(model.materials.size(), 2u);
  EXPECT_EQ(model.materials[0].pbrMetallicRoughness.roughnessFactor, 0.5);
  EXPECT_FLOAT_EQ(float(model.materials[1].pbrMetallicRoughness.roughnessFactor), 0.3f);

  // filmback reads FILMBACK_povray: the lights exactly as they were.
  Diagnostics diagnostics;
  const Scene back = import_gltf(file, diagnostics);
  ASSERT_EQ(back.lights.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(back.lights[i].decay, LightDecay::kPovRay);
    EXPECT_EQ(back.lights[i].intensity.x, scene.lights[i].intensity.x);
  }
}

// glTF has no world image: convert writes the image's mean radiance over the sphere (rows
// weighted by sin of their polar angle) as FILMBACK_blender's world colour, which viewers' own
// background settings and filmback's import read.
TEST(GltfKhrStandIn, WorldImageIsWrittenAsItsMeanRadiance) {
  Scene scene = floor_scene(1);
  EnvironmentMap sky{"sky", 2, 4, std::vector<Rgb>(8, Rgb(0.f, 0.f, 0.f))};
  sky.texels[6] = sky.texels[7] = Rgb(8.f, 4.f, 2.f);  // the bottom row
  scene.environment = sky;
  const std::filesystem::path file = test::scratch_dir() / "world_mean.gltf";
  Diagnostics diagnostics;
  write_gltf(scene, file, diagnostics);
  EXPECT_EQ(diagnostics.count(), 1u);  // the image itself is not written
  const double a = std::sin(kPi / 8), b = std::sin(3 * kPi / 8);
  const Scene back = import_gltf(file, diagnostics);
  EXPECT_FALSE(back.environment);
  EXPECT_NEAR(back.background.x, 8 * a / (2 * a + 2 * b), 1e-6);
  EXPECT_NEAR(back.background.y, 4 * a / (2 * a + 2 * b), 1e-6);
}

}  // namespace
}  // namespace fb
