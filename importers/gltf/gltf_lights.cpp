#include "importers/gltf/gltf_lights.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/image/image_io.h"
#include "core/math/constants.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_file.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/gltf/gltf_json.h"
#include "importers/gltf/gltf_povray_light.h"

namespace fb::gltf {
namespace {

// Blender stores angles in single precision: its 180 degrees is pi rounded up to a float, a little
// above pi. Angles up to it are read, then limited to pi.
constexpr double kBlenderPi = double(std::numbers::pi_v<float>);
double angle(const Fields& f, const char* key, double lowest, double fallback) {
  return std::min(f.number(key, lowest, kBlenderPi).value_or(fallback), kPi);
}

std::string light_name(const std::string& own, const tinygltf::Node& node,
                       const std::string& path) {
  return !own.empty() ? own : !node.name.empty() ? node.name : path;
}

// Blender's area light: a one-sided rectangle or ellipse facing the node's -Z. Cycles 3.4 gives it
// radiance P / (4 A) (eval_fac = 0.25 * invarea in kernel/light/light.h; measured: a 1 m square of
// 100 W, 2 m above a white diffuse plane, renders 1.8316 where P / (4 A) predicts 1.8369 over the
// patch's cos^3 spread), with A the world-space area: the node's scale stretches the light, as
// Cycles takes its axes from the object's matrix.
void read_area_light(const Fields& f, const Transform& world, Rgb color, double power_w,
                     Light& light) {
  const std::string shape = f.word("shape").value_or("SQUARE");
  const bool round = shape == "DISK" || shape == "ELLIPSE";
  if (!round && shape != "SQUARE" && shape != "RECTANGLE")
    f.fail("shape", "'" + shape +
                        "' is not an area light shape (expected SQUARE, RECTANGLE, DISK " +
                        "or ELLIPSE)");
  const double size = f.number("size_m", 1e-6, 1e6).value_or(0.25);  // Blender's default
  // size_y counts for RECTANGLE and ELLIPSE only, as in Blender.
  const double size_y = shape == "RECTANGLE" || shape == "ELLIPSE"
                            ? f.number("size_y_m", 1e-6, 1e6).value_or(size)
                            : size;
  light.type = LightType::kArea;
  light.area_shape = round ? AreaShape::kEllipse : AreaShape::kRectangle;
  light.size_x_m = length(world.vector({size, 0, 0}));
  light.size_y_m = length(world.vector({0, size_y, 0}));
  light.spread_rad = angle(f, "spread_rad", 0, kPi);  // Blender's default, 180 degrees
  const double area = light.size_x_m * light.size_y_m * (round ? kPi / 4 : 1.0);
  if (!(area > 0) || !std::isfinite(area))
    throw_input(f.file(), f.path(), "the node's transform collapses the area light to zero area");
  light.intensity = color * float(power_w / (4 * area));
  if (!is_finite(light.intensity))
    throw_input(
        f.file(), f.path(),
        "colour times power over area (" + number_text(area) + " m^2) overflows single precision");
}

void read_blender_light(const tinygltf::Value& value, const tinygltf::Node& node,
                        const std::string& path, const Transform& world, uint32_t scene_node,
                        const std::string& file, Scene& scene, Diagnostics& diagnostics) {
  const std::string lpath = path + ".extensions.FILMBACK_blender.light";
  if (!value.IsObject()) throw_input(file, lpath, "expected an object");
  const Fields f(value, lpath, file);
  const std::optional<std::string> type = f.word("type");
  if (!type) throw_input(file, lpath, "expected a type (POINT, SPOT, SUN or AREA)");
  const Rgb color = f.color("color").value_or(Rgb(1.f, 1.f, 1.f));
  const std::optional<double> energy = f.number("energy_w", 0, 1e30);
  if (!energy) f.fail("energy_w", "expected the light's power in W (a sun's strength in W/m^2)");
  if (f.flag("use_nodes").value_or(false))
    diagnostics.warn(
        located(file, lpath + ".use_nodes",
                "the light's node tree is not carried; rendering its colour and power"));
  Light light;
  light.name = light_name("", node, path);
  light.world_from_light = world.without_scale();
  light.node_index = scene_node;
  if (*type == "POINT" || *type == "SPOT") {
    light.type = *type == "POINT" ? LightType::kPoint : LightType::kSpot;
    light.intensity = color * float(*energy / (4 * kPi));  // I = P / (4 pi), measured in Cycles
    light.radius_m = f.number("radius_m", 0, 1e6).value_or(0.0);
    if (light.type == LightType::kSpot) {
      light.spot_falloff = SpotFalloff::kCycles;
      light.spot_outer_angle_rad = angle(f, "spot_size_rad", 1e-6, kPi / 4) / 2;
      light.spot_blend = f.number("spot_blend", 0, 1).value_or(0.15);
      // What KHR_lights_punctual would say: for light selection's power estimate.
      light.spot_inner_angle_rad = light.spot_outer_angle_rad * (1 - light.spot_blend);
    }
  } else if (*type == "SUN") {
    light.type = LightType::kDirectional;
    light.intensity = color * float(*energy);  // irradiance S W/m^2
    light.angle_rad = angle(f, "angle_rad", 0, 0.0);
  } else if (*type == "AREA") {
    read_area_light(f, world, color, *energy, light);
  } else {
    f.fail("type", "'" + *type + "' is not a light type (expected POINT, SPOT, SUN or AREA)");
  }
  if (!is_finite(light.intensity))
    throw_input(file, lpath, "colour times power overflows single precision");
  scene.lights.push_back(light);
}

void read_khr_light(const tinygltf::Model& model, const tinygltf::Value& ext,
                    const tinygltf::Node& node, const std::string& path, const Transform& world,
                    uint32_t scene_node, const std::string& file, Scene& scene,
                    Diagnostics& diagnostics) {
  const std::string ext_path = path + ".extensions.KHR_lights_punctual";
  const double index = ext.IsObject() && ext.Has("light") && ext.Get("light").IsNumber()
                           ? ext.Get("light").GetNumberAsDouble()
                           : -1;
  if (!(index >= 0 && index < double(model.lights.size()) && index == std::floor(index)))
    throw_input(file, ext_path + ".light",
                "light index " + number_text(index) + ", expected a whole number below " +
                    std::to_string(model.lights.size()) + " (the number of lights)");
  const tinygltf::Light& g = model.lights[size_t(index)];
  const std::string lpath = "extensions.KHR_lights_punctual." + index_path("lights", size_t(index));
  Light light;
  light.name = light_name(g.name, node, lpath);
  light.world_from_light = world.without_scale();
  light.node_index = scene_node;
  Rgb color{1, 1, 1};
  if (g.color.size() == 3) color = Rgb(float(g.color[0]), float(g.color[1]), float(g.color[2]));
  if (!is_finite(color) || color.x < 0 || color.y < 0 || color.z < 0 ||
      !std::isfinite(g.intensity) || g.intensity < 0)
    throw_input(file, lpath, "colour and intensity must be finite and non-negative");
  light.intensity = color * float(g.intensity / kLumensPerWatt);
  if (g.type == "point") {
    light.type = LightType::kPoint;
  } else if (g.type == "spot") {
    light.type = LightType::kSpot;
    light.spot_inner_angle_rad = g.spot.innerConeAngle;
    light.spot_outer_angle_rad = g.spot.outerConeAngle;
    if (!(g.spot.innerConeAngle >= 0 && g.spot.innerConeAngle < g.spot.outerConeAngle &&
          g.spot.outerConeAngle <= kPi / 2))
      throw_input(file, lpath + ".spot", "expected 0 <= innerConeAngle < outerConeAngle <= pi/2");
  } else if (g.type == "directional") {
    light.type = LightType::kDirectional;
  } else {
    throw_input(file, lpath + ".type",
                "'" + g.type + "' is not a light type (expected point, spot or directional)");
  }
  if (g.range > 0)
    diagnostics.warn(located(file, lpath + ".range",
                             "range is ignored: lights fall off with the inverse square law"));
  scene.lights.push_back(light);
}

// Largest environment image read: 8192 x 4096 RGB float is 400 MB.
constexpr size_t kMaxEnvironmentPixels = size_t(8192) * 4096;

// Blender's Environment Texture: the image (any format OpenImageIO reads, scene-linear) times the
// world's strength, its first three channels (one channel: grey).
EnvironmentMap read_environment(const std::string& file, const std::string& where,
                                const std::string& uri, float strength) {
  const std::filesystem::path path = confined_external_file(file, uri, where);
  const Image image = read_image(path, kMaxEnvironmentPixels);
  const size_t channels = image.channels.size();
  EnvironmentMap map{uri, image.width, image.height, {}};
  map.texels.reserve(size_t(image.width) * image.height);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const Rgb texel = channels >= 3
                            ? Rgb(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2))
                            : Rgb(image.at(x, y, 0), image.at(x, y, 0), image.at(x, y, 0));
      if (!is_finite(texel) || texel.x < 0 || texel.y < 0 || texel.z < 0)
        throw_input(file, where,
                    "'" + uri + "' pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                        ") is negative or not finite; expected radiance");
      map.texels.push_back(texel * strength);
    }
  return map;
}

}  // namespace

void read_node_light(const tinygltf::Model& model, const tinygltf::Node& node,
                     const std::string& path, const Transform& world, uint32_t scene_node,
                     const std::string& file, Scene& scene, Diagnostics& diagnostics) {
  // POV-Ray's light model (docs/pov.md "Conversion") over the others, which approximate it.
  if (auto pov = node.extensions.find("FILMBACK_povray"); pov != node.extensions.end()) {
    const Fields ours(pov->second, path + ".extensions.FILMBACK_povray", file);
    if (ours.has("light")) {
      Light light = read_povray_light(ours.object("light"));
      light.name = light_name("", node, path);
      light.world_from_light = world.without_scale();
      light.node_index = scene_node;
      scene.lights.push_back(light);
      return;
    }
  }
  if (auto ours = node.extensions.find("FILMBACK_blender"); ours != node.extensions.end())
    if (ours->second.IsObject() && ours->second.Has("light")) {
      read_blender_light(ours->second.Get("light"), node, path, world, scene_node, file, scene,
                         diagnostics);
      return;  // the node's KHR_lights_punctual light is the same light in photometric units
    }
  if (auto khr = node.extensions.find("KHR_lights_punctual"); khr != node.extensions.end())
    read_khr_light(model, khr->second, node, path, world, scene_node, file, scene, diagnostics);
}

void read_world(const tinygltf::Model& model, size_t index, const std::string& file, Scene& scene) {
  const tinygltf::Scene& s = model.scenes[index];
  const std::string spath = index_path("scenes", index);
  const auto ours = s.extensions.find("FILMBACK_blender");
  const bool extension = ours != s.extensions.end();
  const Fields f(extension ? ours->second : s.extras,
                 spath + (extension ? ".extensions.FILMBACK_blender" : ".extras"), file);
  const std::optional<Rgb> color = f.color("world_color");
  const std::optional<double> strength = f.number("world_strength", 0, 1e30);
  if (color || strength) {
    const Rgb radiance = color.value_or(Rgb(0.f, 0.f, 0.f)) * float(strength.value_or(1.0));
    if (!is_finite(radiance))
      throw_input(file, f.path(), "world_color times world_strength overflows single precision");
    scene.background = radiance;
  }
  if (const std::optional<std::string> uri = f.word("world_hdr_uri"))
    scene.environment =
        read_environment(file, f.path() + ".world_hdr_uri", *uri, float(strength.value_or(1.0)));
}

}  // namespace fb::gltf
