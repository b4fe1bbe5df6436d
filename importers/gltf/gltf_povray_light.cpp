#include "importers/gltf/gltf_povray_light.h"

#include <cmath>
#include <numbers>
#include <string>

namespace fb::gltf {

namespace {

using tinygltf::Value;

// The importer's bound on area-light grids (importers/pov/pov_appearance.cpp).
constexpr double kMaxGrid = 4096;
constexpr double kLargestLightValue = 1e12;

Vec3d read_axis(const Fields& f, const char* key) {
  const auto v = f.numbers(key, 3, -kLargestLightValue, kLargestLightValue);
  if (!v || v->size() != 3)
    f.fail(key, "expected the axis as three numbers, m in the light's frame");
  return {(*v)[0], (*v)[1], (*v)[2]};
}

}  // namespace

bool is_povray_light(const Light& light) {
  return light.decay == LightDecay::kPovRay;
}

tinygltf::Value povray_light_json(const Light& l) {
  static const char* kTypes[] = {"point", "spot", "parallel"};
  Value::Object o{{"type", Value(std::string(kTypes[int(l.type)]))},
                  {"intensity", number_array(l.intensity)}};
  if (l.fade_power != 0) {
    o["fade_distance_m"] = Value(l.fade_distance_m);
    o["fade_power"] = Value(l.fade_power);
  }
  if (l.type == LightType::kSpot) {
    o["spot_radius_rad"] = Value(l.spot_inner_angle_rad);
    o["spot_falloff_rad"] = Value(l.spot_outer_angle_rad);
    o["spot_tightness"] = Value(l.spot_tightness);
  }
  if (!l.casts_shadows) o["shadowless"] = Value(true);
  if (l.area_size1 * l.area_size2 > 1)
    o["area_light"] = Value(Value::Object{{"axis1", number_array(l.area_axis1)},
                                          {"axis2", number_array(l.area_axis2)},
                                          {"size1", Value(int(l.area_size1))},
                                          {"size2", Value(int(l.area_size2))},
                                          {"circular", Value(l.area_circular)},
                                          {"orient", Value(l.area_orient)}});
  return Value(std::move(o));
}

Light read_povray_light(const Fields& f) {
  constexpr double kPi = std::numbers::pi;
  Light l;
  l.decay = LightDecay::kPovRay;
  const std::optional<std::string> type = f.word("type");
  if (type == "point")
    l.type = LightType::kPoint;
  else if (type == "spot")
    l.type = LightType::kSpot;
  else if (type == "parallel")
    l.type = LightType::kDirectional;
  else
    f.fail("type", "expected point, spot or parallel");
  const std::optional<Rgb> intensity = f.color("intensity");
  if (!intensity) f.fail("intensity", "expected [r, g, b]: W/sr (point, spot) or W/m^2 (parallel)");
  l.intensity = *intensity;
  l.fade_distance_m =
      f.number("fade_distance_m", -kLargestLightValue, kLargestLightValue).value_or(0.0);
  l.fade_power = f.number("fade_power", -kLargestLightValue, kLargestLightValue).value_or(0.0);
  if (l.type == LightType::kSpot) {
    l.spot_falloff = SpotFalloff::kPov;
    // POV-Ray's defaults: radius 30 degrees, falloff 45, tightness 0. It takes their cosines,
    // so any angle is one (scenes write falloff 250).
    l.spot_inner_angle_rad =
        f.number("spot_radius_rad", -kLargestLightValue, kLargestLightValue).value_or(kPi / 6);
    l.spot_outer_angle_rad =
        f.number("spot_falloff_rad", -kLargestLightValue, kLargestLightValue).value_or(kPi / 4);
    l.spot_tightness =
        f.number("spot_tightness", -kLargestLightValue, kLargestLightValue).value_or(0.0);
  }
  l.casts_shadows = !f.flag("shadowless").value_or(false);
  if (f.has("area_light")) {
    const Fields area = f.object("area_light");
    l.area_axis1 = read_axis(area, "axis1");
    l.area_axis2 = read_axis(area, "axis2");
    l.area_size1 = uint32_t(area.whole("size1", 1, kMaxGrid).value_or(1));
    l.area_size2 = uint32_t(area.whole("size2", 1, kMaxGrid).value_or(1));
    l.area_circular = area.flag("circular").value_or(false);
    l.area_orient = area.flag("orient").value_or(false);
  }
  return l;
}

}  // namespace fb::gltf
