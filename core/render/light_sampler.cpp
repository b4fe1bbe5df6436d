#include "core/render/light_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include <filmback/geometry.h>
#include <filmback/sampling.h>

#include "core/math/constants.h"
#include "core/util/error.h"

namespace fb {
namespace {

// KHR_lights_punctual's recommended spot falloff: a smooth ramp in cos(angle) between the cones.
float gltf_spot_falloff(float cos_angle, float cos_inner, float cos_outer) {
  const float scale = 1.f / std::max(0.001f, cos_inner - cos_outer);
  const float t = std::clamp((cos_angle - cos_outer) * scale, 0.f, 1.f);
  return t * t;
}

// Cycles' spot_light_attenuation (intern/cycles/kernel/light/spot.h): the intensity falls with
// cos(angle) inside the cone, times smoothstep over the last `smooth` of cos(angle) before its
// edge.
float cycles_spot_falloff(float cos_angle, float cos_outer, float smooth) {
  if (cos_angle <= cos_outer) return 0.f;
  const float t = cos_angle - cos_outer;
  if (t >= smooth || smooth == 0.f) return cos_angle;
  const float s = t / smooth;
  return cos_angle * s * s * (3.f - 2.f * s);
}

// POV-Ray's cubic_spline(): 0 below low, 1 from high on, smooth in between.
float cubic_spline(float low, float high, float pos) {
  if (pos < low) return 0.f;
  if (pos >= high || !(high > low)) return 1.f;
  const float t = (pos - low) / (high - low);
  return (3.f - 2.f * t) * t * t;
}

// POV-Ray's spotlight (Attenuate_Light, SPOT_SOURCE): cos^tightness, faded by the cubic from the
// falloff cone to the radius cone; nothing behind the light.
float pov_spot_falloff(float cos_angle, float cos_radius, float cos_falloff, float tightness) {
  if (!(cos_angle > 0.f)) return 0.f;
  float a = tightness != 0.f ? std::pow(cos_angle, tightness) : 1.f;
  if (cos_radius > 0.f && cos_angle < cos_radius)
    a *= cubic_spline(cos_falloff, cos_radius, cos_angle);
  return a;
}

// POV-Ray's distance attenuation (Attenuate_Light): none unless fade_power > 0.
float pov_fade(float distance, float fade_distance, float fade_power) {
  if (!(fade_power > 0.f)) return 1.f;
  if (std::abs(fade_distance) >= 1e-10f)
    return 2.f / (1.f + std::pow(distance / fade_distance, fade_power));
  return std::pow(distance, -fade_power);
}

// A box of half-extents `half` about `centre`, for the light tree.
LightBounds box_around(Vec3f centre, Vec3f half, float intensity) {
  LightBounds b;
  b.lo = centre - half;
  b.hi = centre + half;
  b.intensity = intensity;
  return b;
}

// Where a lamp is and where it shines (pbrt 4e §12.6.3: a point light's cone is the whole sphere,
// theta_o = pi; a spot's is its cone; an area light's its normal, theta_o = 0; light leaves up to
// theta_e = pi/2 past them). A spot's cone only needs to hold its light within pi/2 of its edge
// for the tree to stay unbiased, so a POV-Ray spotlight without a radius cone (which lights the
// whole hemisphere) is given the hemisphere.
LightBounds lamp_bounds(const Light& light, Vec3f position, Vec3f axis, float cos_inner,
                        float cos_outer, const Transform& render_from_light) {
  const float intensity = luminance(light.intensity);
  float reach = light.radius_m > 0 ? float(light.radius_m) : 0.f;
  if (light.area_size1 * light.area_size2 > 1)  // POV-Ray's grid, maybe turned to face the point
    reach = 0.5f * float(length(render_from_light.vector(light.area_axis1)) +
                         length(render_from_light.vector(light.area_axis2)));
  LightBounds b = box_around(position, {reach, reach, reach}, intensity);
  b.axis = axis;
  switch (light.type) {
    case LightType::kPoint:
      b.cos_theta_o = -1.f;
      break;
    case LightType::kSpot:
      b.cos_theta_o = light.spot_falloff == SpotFalloff::kPov && !(cos_inner > 0.f)
                          ? 0.f
                          : std::clamp(cos_outer, -1.f, 1.f);
      break;
    case LightType::kArea: {
      const Vec3f half_u = Vec3f(normalize(render_from_light.vector({1, 0, 0}))) *
                           float(0.5 * light.size_x_m),
                  half_v = Vec3f(normalize(render_from_light.vector({0, 1, 0}))) *
                           float(0.5 * light.size_y_m);
      b = box_around(position, abs(half_u) + abs(half_v),
                     float(light.size_x_m * light.size_y_m) * intensity);
      b.axis = axis;
      b.cos_theta_o = 1.f;
      break;
    }
    case LightType::kDirectional:
      return {};  // no place: beside the tree
  }
  return b;
}

// An emissive triangle's bounds: its vertices' box, its normal, and its intensity along the
// normal, L A.
LightBounds triangle_bounds(const EmissiveTriangle& e, const Material& m) {
  LightBounds b;
  b.lo = min(e.p0, min(e.p1, e.p2));
  b.hi = max(e.p0, max(e.p1, e.p2));
  b.intensity = e.moving ? 0.f : luminance(m.emission) * e.area;
  b.axis = e.normal;
  b.cos_theta_o = 1.f;
  b.two_sided = m.double_sided;
  return b;
}

}  // namespace

LightSampler::LightSampler(const Scene& scene, const Transform& render_from_world,
                           const RenderGeometry& geometry, double frame_s,
                           std::optional<Rgb> background_override, LightSelection selection)
    : emitters_(geometry.emitters()),
      geometry_(geometry),
      background_(background_override.value_or(scene.background)),
      materials_(scene.materials) {
  std::vector<double> power;
  std::vector<LightBounds> bounds;  // per light; empty for the sun and the world
  const double scene_radius = std::max(geometry.bounds_radius(), 1e-3f);
  for (const Light& light : scene.lights) {
    const Transform render_from_light = render_from_world * scene.world_from_light(light, frame_s);
    const float cos_outer = float(std::cos(light.spot_outer_angle_rad));
    Lamp lamp{light.type,
              Vec3f(render_from_light.point({0, 0, 0})),
              Vec3f(normalize(render_from_light.vector({0, 0, -1}))),
              light.intensity,
              light.spot_falloff,
              float(std::cos(light.spot_inner_angle_rad)),
              cos_outer,
              float((1 - cos_outer) * light.spot_blend),  // Cycles' spot_smooth
              light.decay,
              float(light.fade_distance_m),
              float(light.fade_power),
              float(light.spot_tightness),
              light.casts_shadows,
              Vec3f(render_from_light.vector(light.area_axis1)),
              Vec3f(render_from_light.vector(light.area_axis2)),
              std::max(light.area_size1, 1u),
              std::max(light.area_size2, 1u),
              light.area_circular,
              light.area_orient,
              {}};
    const double lum = luminance(light.intensity);
    const bool soft = light.decay == LightDecay::kInverseSquare &&
                      lamp.area_size1 * lamp.area_size2 == 1 && light.radius_m > 0;
    switch (light.type) {
      case LightType::kPoint:
        power.push_back(4 * kPiF * lum);
        if (soft) lamp.size = FacingDisk(lamp.position, float(light.radius_m));
        break;
      case LightType::kSpot:
        power.push_back(2 * kPiF * (1 - 0.5 * (lamp.cos_inner + lamp.cos_outer)) * lum);
        if (soft) lamp.size = FacingDisk(lamp.position, float(light.radius_m));
        break;
      case LightType::kDirectional:
        lamp.axis = -lamp.axis;  // towards the light
        power.push_back(kPiF * scene_radius * scene_radius * lum);
        if (light.angle_rad > 0) lamp.size = SunDisk(lamp.axis, float(light.angle_rad));
        break;
      case LightType::kArea: {
        const AreaLight area(lamp.position, Vec3f(normalize(render_from_light.vector({1, 0, 0}))),
                             Vec3f(normalize(render_from_light.vector({0, 1, 0}))), lamp.axis,
                             float(light.size_x_m), float(light.size_y_m),
                             light.area_shape == AreaShape::kEllipse, light.spread_rad);
        // The spread redistributes the light's power, pi A L, without changing it.
        power.push_back(kPiF * area.area() * lum);
        lamp.size = area;
        break;
      }
    }
    bounds.push_back(lamp_bounds(light, lamp.position, lamp.axis, lamp.cos_inner, lamp.cos_outer,
                                 render_from_light));
    if (!std::holds_alternative<std::monostate>(lamp.size))
      sized_.push_back(uint32_t(lamps_.size()));
    lamps_.push_back(lamp);
  }
  // Power ignores distance and aim: a spot lighting the frame beside a stronger point light would
  // be chosen rarely and each choice weigh much. Half of the lamps' share is therefore spread
  // evenly over those that emit (defensive mixture, Hesterberg 1995); their total share against
  // emissive triangles is unchanged.
  double lamp_power = 0;
  size_t emitting = 0;
  for (double w : power)
    if (w > 0) lamp_power += w, ++emitting;
  for (double& w : power)
    if (w > 0) w = 0.5 * w + 0.5 * lamp_power / double(emitting);
  for (const EmissiveTriangle& e : emitters_) {
    const Material& m = materials_[e.material];
    // Zero power: never chosen, so its light_pdf is 0 and BSDF sampling alone (MIS weight 1)
    // finds it where the ray's time put it.
    power.push_back(e.moving ? 0.0
                             : kPiF * e.area * luminance(m.emission) * (m.double_sided ? 2 : 1));
    bounds.push_back(triangle_bounds(e, m));
  }
  if (scene.environment && !background_override) {
    environment_.emplace(*scene.environment);
    // As a sun's: the irradiance pi L of a uniform world as bright, over the scene's disk.
    power.push_back(kPiF * scene_radius * scene_radius * kPiF * environment_->mean_luminance());
    bounds.emplace_back();
  }
  choice_ = LightChoice(power, bounds, selection);
}

bool LightSampler::sample_lamp(uint32_t index, Vec3f position, const float u[2],
                               fb_light_sample& out) const {
  if (index >= lamps_.size()) return false;
  const Lamp& lamp = lamps_[index];
  if (std::holds_alternative<std::monostate>(lamp.size))
    return sample_delta(lamp, position, u, out);
  constexpr float kCentre[2] = {0.5f, 0.5f};
  SizedLightPoint point;
  if (!sample_sized(lamp, position, u ? u : kCentre, point)) return false;
  const Rgb L = radiance(lamp, point);
  point.direction.store(out.direction);
  L.store(out.radiance);
  out.distance = lamp.casts_shadows ? point.distance : 0.f;
  out.pdf = point.pdf;
  out.is_delta = 0;
  return max_component(L) > 0.f;
}

bool LightSampler::sample(Vec3f position, const float u[3], fb_light_sample& out) const {
  uint32_t index;
  float pmf;
  if (!choice_.choose(position, u[0], index, pmf)) return false;
  bool ok;
  if (index < lamps_.size()) {
    ok = sample_lamp(index, position, u + 1, out);
  } else if (index < lamps_.size() + emitters_.size()) {
    ok = sample_triangle(uint32_t(index - lamps_.size()), position, u + 1, out);
  } else {
    Vec3f w;
    ok = environment_->sample({u[1], u[2]}, w, out.pdf);
    if (ok) {
      w.store(out.direction);
      environment_->radiance(w).store(out.radiance);
      out.distance = HUGE_VALF;
      out.is_delta = 0;
    }
  }
  out.pdf *= pmf;
  return ok;
}

bool LightSampler::sample_sized(const Lamp& lamp, Vec3f position, const float u[2],
                                SizedLightPoint& point) {
  const Vec2f uv{u[0], u[1]};
  if (const auto* disk = std::get_if<FacingDisk>(&lamp.size))
    return disk->sample(position, uv, point);
  if (const auto* sun = std::get_if<SunDisk>(&lamp.size)) return sun->sample(uv, point);
  return std::get<AreaLight>(lamp.size).sample(position, uv, point);
}

bool LightSampler::cross_sized(const Lamp& lamp, const fb_ray& ray, float t_end,
                               SizedLightPoint& point) {
  const Vec3f origin(ray.origin), direction(ray.direction);
  const float t_min = std::max(ray.t_min, 0.f);
  if (const auto* disk = std::get_if<FacingDisk>(&lamp.size))
    return disk->crossed(origin, direction, t_min, t_end, point);
  if (const auto* sun = std::get_if<SunDisk>(&lamp.size))
    return std::isinf(t_end) && sun->crossed(direction, point);
  return std::get<AreaLight>(lamp.size).crossed(origin, direction, t_min, t_end, point);
}

// The lamp's radiance towards the shading point: its intensity times the shape's scale, and a
// spot's falloff in the direction from the light's centre the point is lit along (Cycles 3.4
// evaluates spot_light_attenuation with the sampled point's direction, -D).
Rgb LightSampler::radiance(const Lamp& lamp, const SizedLightPoint& point) {
  float scale = point.scale;
  if (lamp.type == LightType::kSpot) {
    const float cos_angle = dot(lamp.axis, -point.direction);
    switch (lamp.falloff) {
      case SpotFalloff::kGltf:
        scale *= gltf_spot_falloff(cos_angle, lamp.cos_inner, lamp.cos_outer);
        break;
      case SpotFalloff::kCycles:
        scale *= cycles_spot_falloff(cos_angle, lamp.cos_outer, lamp.spot_smooth);
        break;
      case SpotFalloff::kPov:
        scale *= pov_spot_falloff(cos_angle, lamp.cos_inner, lamp.cos_outer, lamp.spot_tightness);
        break;
    }
  }
  return lamp.intensity * scale;
}

bool LightSampler::sample_delta(const Lamp& lamp, Vec3f position, const float u[2],
                                fb_light_sample& out) const {
  out.is_delta = 1;
  out.pdf = 1.f;
  if (lamp.type == LightType::kDirectional) {
    lamp.axis.store(out.direction);
    lamp.intensity.store(out.radiance);  // irradiance E, W/m^2
    out.distance = lamp.casts_shadows ? HUGE_VALF : 0.f;
    return max_component(lamp.intensity) > 0.f;
  }
  const Vec3f q =
      u && lamp.area_size1 * lamp.area_size2 > 1 ? area_point(lamp, position, u) : lamp.position;
  const Vec3f d = q - position;
  const float distance2 = dot(d, d);
  if (!(distance2 > 0.f)) return false;
  SizedLightPoint point{d / std::sqrt(distance2), std::sqrt(distance2), 1.f,
                        lamp.decay == LightDecay::kPovRay
                            ? pov_fade(std::sqrt(distance2), lamp.fade_distance, lamp.fade_power)
                            : 1.f / distance2};  // I / d^2
  const Rgb arriving = radiance(lamp, point);
  point.direction.store(out.direction);
  arriving.store(out.radiance);
  // distance 0: no shadow ray (fb_light_sample)
  out.distance = lamp.casts_shadows ? point.distance : 0.f;
  return max_component(arriving) > 0.f;
}

Vec3f LightSampler::area_point(const Lamp& light, Vec3f position, const float u[2]) {
  // Grid point (i, j) at (i / (n1 - 1) - 1/2) axis1 + (j / (n2 - 1) - 1/2) axis2, as POV-Ray lays
  // out its area_light (without jitter or adaptive subdivision).
  const auto coordinate = [](float v, uint32_t n) {
    if (n < 2) return 0.f;
    const uint32_t i = std::min(uint32_t(v * float(n)), n - 1);
    return float(i) / float(n - 1) - 0.5f;
  };
  float s = coordinate(u[0], light.area_size1), t = coordinate(u[1], light.area_size2);
  if (light.area_circular) {
    // The square grid folded onto the disk (Shirley and Chiu's concentric map of [-1, 1]^2).
    const Vec2f d = sample_concentric_disk({s + 0.5f, t + 0.5f});
    s = 0.5f * d.x, t = 0.5f * d.y;
  }
  Vec3f a1 = light.area_axis1, a2 = light.area_axis2;
  const Vec3f to_point = position - light.position;
  if (light.area_orient && dot(to_point, to_point) > 0.f) {
    // The grid turned to face the lit point, each axis keeping its length.
    const Frame frame(normalize(to_point));
    a1 = frame.to_world({1.f, 0.f, 0.f}) * length(a1);
    a2 = frame.to_world({0.f, 1.f, 0.f}) * length(a2);
  }
  return light.position + a1 * s + a2 * t;
}

bool LightSampler::sample_triangle(uint32_t index, Vec3f position, const float u[2],
                                   fb_light_sample& out) const {
  const EmissiveTriangle& e = emitters_[index];
  const Material& m = materials_[e.material];
  const Vec2f b = sample_uniform_triangle({u[0], u[1]});
  const Vec3f q = e.p0 * b.x + e.p1 * b.y + e.p2 * (1.f - b.x - b.y);
  const Vec3f d = q - position;
  const float distance2 = dot(d, d);
  if (!(distance2 > 0.f) || !(e.area > 0.f)) return false;
  out.distance = std::sqrt(distance2);
  const Vec3f wi = d / out.distance;
  float cos_light = -dot(e.normal, wi);
  if (m.double_sided) cos_light = std::abs(cos_light);
  if (!(cos_light > 0.f)) return false;
  wi.store(out.direction);
  // q = p0 b0 + p1 b1 + p2 (1 - b0 - b1): Embree's barycentrics are (b1, 1 - b0 - b1).
  geometry_.emission_at(e, b.y, 1.f - b.x - b.y).store(out.radiance);
  // area measure to solid angle: pdf_w = pdf_A d^2 / cos(theta_light)
  out.pdf = distance2 / (cos_light * e.area);
  out.is_delta = 0;
  return true;
}

float LightSampler::pdf(Vec3f position, const fb_hit& hit) const {
  if (hit.emitter == FB_NONE || choice_.empty()) return 0.f;
  const EmissiveTriangle& e = emitters_[hit.emitter];
  const Vec3f d = Vec3f(hit.position) - position;
  const float distance2 = dot(d, d);
  float cos_light = -dot(e.normal, d) / std::sqrt(distance2);
  if (materials_[e.material].double_sided) cos_light = std::abs(cos_light);
  if (!(cos_light > 0.f) || !(e.area > 0.f)) return 0.f;
  return choice_.pmf(position, uint32_t(lamps_.size() + hit.emitter)) * distance2 /
         (cos_light * e.area);
}

Rgb LightSampler::background(Vec3f w, float& pdf) const {
  if (!environment_) {
    pdf = 0.f;
    return background_;
  }
  // The world has no place: its choice does not depend on the shading point.
  pdf = choice_.pmf({}, uint32_t(lamps_.size() + emitters_.size())) * environment_->pdf(w);
  return environment_->radiance(w);
}

uint32_t LightSampler::crossed(const fb_ray& ray, float t_end, fb_light_crossing* crossings,
                               uint32_t capacity) const {
  uint32_t count = 0;
  for (uint32_t index : sized_) {
    const Lamp& lamp = lamps_[index];
    SizedLightPoint point;
    if (!cross_sized(lamp, ray, t_end, point)) continue;
    const Rgb L = radiance(lamp, point);
    if (!(max_component(L) > 0.f)) continue;
    // Insertion by distance, keeping the `capacity` nearest.
    uint32_t at = count;
    while (at > 0 && crossings[at - 1].t > point.distance)
      --at;
    if (at >= capacity) continue;
    for (uint32_t k = std::min(count, capacity - 1); k > at; --k)
      crossings[k] = crossings[k - 1];
    fb_light_crossing& c = crossings[at];
    L.store(c.radiance);
    // The ray leaves from the shading point lifted off its surface by a few ulps
    // (offset_ray_origin), which the tree's estimate does not notice.
    c.pdf = point.pdf * choice_.pmf(Vec3f(ray.origin), index);
    c.t = point.distance;
    count = std::min(count + 1, capacity);
  }
  return count;
}

}  // namespace fb
