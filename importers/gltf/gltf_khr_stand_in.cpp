#include "importers/gltf/gltf_khr_stand_in.h"

#include <algorithm>
#include <cmath>

#include "core/accel/render_geometry.h"
#include "core/math/constants.h"
#include "core/scene/povray_light.h"

namespace fb::gltf {
namespace {

// The viewed points sample the frame on this grid: enough that one object's distance does not
// decide a light's brightness, few enough to cost nothing beside the tessellation.
constexpr int kStandInGridX = 32, kStandInGridY = 24;

// A POV-Ray spot's KHR inner cone as a share of the hard cone of its flux. The ramp beyond it
// reaches about 1.09 of that cone; Blender's reading of it (spot_blend 0.13, a smoothstep) sends
// 12 % more than KHR's t^2 ramp, 22 % with 0.9 (measured on a plane under a spot, 1.199).
constexpr double kInnerShare = 0.95;

Vec3d vec3d_from(const float v[3]) {
  return {v[0], v[1], v[2]};
}

// Where the grid of rays through the camera's frame first meets the geometry.
std::vector<ViewedPoint> trace_view(const RenderGeometry& geometry, const tinygltf::Camera& camera,
                                    const Transform& world_from_camera) {
  const bool ortho = camera.type == "orthographic";
  // Half extents of the frame: at unit distance for a perspective camera, in metres for an
  // orthographic one.
  const double half_y = ortho ? camera.orthographic.ymag : std::tan(camera.perspective.yfov / 2);
  const double half_x = ortho ? camera.orthographic.xmag : half_y * camera.perspective.aspectRatio;
  std::vector<ViewedPoint> points;
  for (int j = 0; j < kStandInGridY; ++j)
    for (int i = 0; i < kStandInGridX; ++i) {
      // Cell centres, x right and y up in the camera's frame, which looks down its -Z.
      const double x = half_x * (2 * (i + 0.5) / kStandInGridX - 1);
      const double y = half_y * (1 - 2 * (j + 0.5) / kStandInGridY);
      const Vec3d origin = world_from_camera.point(ortho ? Vec3d{x, y, 0} : Vec3d{0, 0, 0});
      const Vec3d direction =
          normalize(world_from_camera.vector(ortho ? Vec3d{0, 0, -1} : Vec3d{x, y, -1}));
      const fb_ray ray{{float(origin.x), float(origin.y), float(origin.z)},
                       {float(direction.x), float(direction.y), float(direction.z)},
                       0.f,
                       HUGE_VALF,
                       0.f};
      fb_hit hit{};
      if (geometry.intersect(ray, hit))
        points.push_back({vec3d_from(hit.position), vec3d_from(hit.geometric_normal)});
    }
  return points;
}

// Whether nothing lies between the point and `light_position`: the ray leaves from the point
// lifted off its surface towards the light, as a renderer's shadow ray does.
bool unshadowed(const RenderGeometry& geometry, const ViewedPoint& p, Vec3d light_position) {
  const Vec3d to_light = light_position - p.position;
  const double d = length(to_light);
  if (!(d > 0)) return false;
  const double lift = 1e-4 * std::max({1.0, std::abs(p.position.x), std::abs(p.position.y),
                                       std::abs(p.position.z)});
  const Vec3d origin = p.position + p.normal * (dot(p.normal, to_light) > 0 ? lift : -lift);
  const Vec3d direction = to_light / d;
  const fb_ray ray{{float(origin.x), float(origin.y), float(origin.z)},
                   {float(direction.x), float(direction.y), float(direction.z)},
                   0.f,
                   float(d * (1 - 1e-4)),
                   0.f};
  return !geometry.occluded(ray);
}

}  // namespace

std::vector<ViewedPoint> viewed_points(const Scene& scene, const tinygltf::Camera& camera,
                                       const Transform& world_from_camera) {
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  return trace_view(geometry, camera, world_from_camera);
}

std::vector<double> khr_intensity_scales(const Scene& scene, const tinygltf::Camera& camera,
                                         const Transform& world_from_camera) {
  std::vector<double> scales(scene.lights.size(), 1.0);
  if (std::none_of(scene.lights.begin(), scene.lights.end(),
                   [](const Light& l) { return l.decay == LightDecay::kPovRay; }))
    return scales;
  const RenderGeometry geometry(scene, Transform(), ShotTimes{}, MotionTolerance{});
  const std::vector<ViewedPoint> seen = trace_view(geometry, camera, world_from_camera);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    const Vec3d position = light.world_from_light.translation();
    std::vector<ViewedPoint> lit;
    for (const ViewedPoint& p : seen)
      if (!light.casts_shadows || unshadowed(geometry, p, position)) lit.push_back(p);
    scales[i] = khr_intensity_scale(light, lit, world_from_camera.translation());
  }
  return scales;
}

KhrSpotCone khr_spot_cone(const Light& light) {
  double inner = light.spot_inner_angle_rad, outer = light.spot_outer_angle_rad;
  if (light.spot_falloff == SpotFalloff::kPov) {
    // F = integral over cos in [0, 1] of the profile (nothing behind the light), midpoint rule.
    constexpr int kFluxSteps = 4096;
    double flux = 0;
    for (int i = 0; i < kFluxSteps; ++i)
      flux += povray_spot_profile(light, (i + 0.5) / kFluxSteps) / kFluxSteps;
    inner = kInnerShare * std::acos(std::clamp(1 - flux, 0.0, 1.0));
    // KHR's flux: (1 - cos_inner) + (cos_inner - cos_outer) / 3, the ramp t^2 integrating to 1/3.
    const double cos_inner = std::cos(inner);
    outer = std::acos(std::clamp(cos_inner - 3 * (flux - (1 - cos_inner)), 0.0, 1.0));
  }
  outer = std::clamp(outer, 1e-6, kPi / 2);
  return {std::clamp(inner, 0.0, 0.999 * outer), outer};
}

double khr_intensity_scale(const Light& light, std::span<const ViewedPoint> viewed,
                           std::optional<Vec3d> viewer) {
  if (light.decay != LightDecay::kPovRay || light.type == LightType::kDirectional) return 1;
  const bool spot = light.type == LightType::kSpot;
  const Vec3d position = light.world_from_light.translation();
  const Vec3d axis = normalize(light.world_from_light.vector({0, 0, -1}));
  const KhrSpotCone cone = khr_spot_cone(light);
  const double cos_inner = std::cos(cone.inner_rad), cos_outer = std::cos(cone.outer_rad);
  // KHR_lights_punctual's angular attenuation: the square of a ramp from the outer cone to the
  // inner one.
  const auto khr_ramp = [&](double cos_angle) {
    const double t =
        std::clamp((cos_angle - cos_outer) / std::max(cos_inner - cos_outer, 1e-3), 0.0, 1.0);
    return t * t;
  };
  double povray = 0, inverse_square = 0;
  for (const ViewedPoint& p : viewed) {
    const Vec3d to_point = p.position - position;
    const double d = length(to_point);
    if (!(d > 0)) continue;
    const double cos_angle = dot(axis, to_point) / d;
    const double w = std::abs(dot(p.normal, to_point)) / d;
    povray += w * povray_fading(light, d) * (spot ? povray_spot_profile(light, cos_angle) : 1);
    inverse_square += w * (spot ? khr_ramp(cos_angle) : 1) / (d * d);
  }
  if (inverse_square > 0) return povray / inverse_square;
  const double d = viewer ? length(*viewer - position) : 0.0;
  return d > 0 ? povray_fading(light, d) * d * d : 1;
}

}  // namespace fb::gltf
