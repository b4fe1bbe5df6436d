#include "importers/gltf/gltf_writer.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>

#include "core/scene/sensor_fit.h"
#include "core/util/error.h"
#include "core/util/temporary_file.h"
#include "importers/gltf/gltf_khr_stand_in.h"
#include "importers/gltf/gltf_povray_light.h"
#include "importers/gltf/gltf_povray_pattern.h"

namespace fb {
namespace {

namespace fs = std::filesystem;
using tinygltf::Value;

// Blender's exporter's PBR_WATTS_TO_LUMENS, which importers/gltf/gltf_lights.cpp divides by.
constexpr double kLumensPerWatt = 683;

// The roughness written for Lambertian materials (material() below).
constexpr double kLambertianViewerRoughness = 0.5;

Value number(double v) {
  return Value(v);
}

// Appends `bytes` to the one buffer, aligned to 4 bytes; returns its buffer view.
int add_view(tinygltf::Model& model, const void* bytes, size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) & ~size_t(3));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  data.insert(data.end(), static_cast<const unsigned char*>(bytes),
              static_cast<const unsigned char*>(bytes) + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

int add_vec3_accessor(tinygltf::Model& model, const std::vector<Vec3f>& values, bool bounds) {
  tinygltf::Accessor a;
  a.bufferView =
      add_view(model, values.data(), values.size() * sizeof(Vec3f), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = values.size();
  if (bounds) {  // glTF requires min and max on positions
    Vec3f lo = values[0], hi = values[0];
    for (const Vec3f& v : values)
      lo = min(lo, v), hi = max(hi, v);
    a.minValues = {lo.x, lo.y, lo.z};
    a.maxValues = {hi.x, hi.y, hi.z};
  }
  model.accessors.push_back(a);
  return int(model.accessors.size() - 1);
}

int add_mesh(tinygltf::Model& model, const TriangleMesh& mesh) {
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = int(mesh.material);
  primitive.attributes["POSITION"] = add_vec3_accessor(model, mesh.positions, true);
  if (!mesh.normals.empty())
    primitive.attributes["NORMAL"] = add_vec3_accessor(model, mesh.normals, false);
  tinygltf::Accessor indices;
  indices.bufferView = add_view(model, mesh.indices.data(), mesh.indices.size() * 4,
                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.type = TINYGLTF_TYPE_SCALAR;
  indices.count = mesh.indices.size();
  model.accessors.push_back(indices);
  primitive.indices = int(model.accessors.size() - 1);
  tinygltf::Mesh out;
  out.name = mesh.name;
  out.primitives.push_back(primitive);
  model.meshes.push_back(out);
  return int(model.meshes.size() - 1);
}

// KHR_materials_specular as a viewer that knows only standard glTF reads it (docs/pov.md "Other
// viewers"). filmback's specular s scales the whole dielectric Fresnel term, which is
// specularFactor (F0 and F90); Blender 3.4's importer ignores specularFactor and sets Principled
// Specular from specularColorFactor and the ior alone (lum(colour) F0(ior) / 0.08), so every
// material there kept F0 = 0.04. Hence: s = 0 is both factors 0, no specular layer in any
// reading; 0 < s < 1 on an opaque material is specularColorFactor s, F0 = s F0(ior) for every
// viewer (F90 stays 1 where filmback's is s: grazing angles only), with s itself in
// FILMBACK_povray. A transmissive material keeps specularFactor: Blender's reading subtracts the
// transmission from the colour, and its ior also sets refraction.
struct KhrSpecular {
  Value::Object khr;           // empty: the extension's defaults are right
  bool exact_in_ours = false;  // s goes into FILMBACK_povray's specular_factor
};

KhrSpecular khr_specular_for_viewers(const Material& m) {
  KhrSpecular out;
  if (m.specular >= 1.f) return out;
  if (m.specular > 0.f && m.transmission == 0.f) {
    out.khr["specularColorFactor"] = gltf::number_array(Rgb(m.specular, m.specular, m.specular));
    out.exact_in_ours = true;
    return out;
  }
  out.khr["specularFactor"] = number(m.specular);
  if (m.specular == 0.f) out.khr["specularColorFactor"] = gltf::number_array(Rgb(0.f, 0.f, 0.f));
  return out;
}

tinygltf::Material material(const Material& m, Diagnostics& diagnostics) {
  tinygltf::Material out;
  out.name = m.name;
  out.pbrMetallicRoughness.baseColorFactor = {m.base_color.x, m.base_color.y, m.base_color.z,
                                              m.alpha};
  out.pbrMetallicRoughness.metallicFactor = m.metallic;
  out.pbrMetallicRoughness.roughnessFactor = m.roughness;
  // A Lambertian material (specular 0: filmback ignores its roughness) is matte in glTF's own
  // BSDF at any roughness, but Blender's Principled diffuse (Disney's) brightens with roughness
  // (retro-reflection): at roughness 0.5 it reflects, averaged over directions, what Lambert's
  // does (1.008; 1.065 at roughness 1).
  // Not under a POV-Ray pattern with filter, which makes points of it refract.
  if (m.specular == 0 && m.metallic == 0 && m.transmission == 0 &&
      !(m.base_color_pattern && gltf::mean_colour(*m.base_color_pattern).filter > 0))
    out.pbrMetallicRoughness.roughnessFactor = kLambertianViewerRoughness;
  out.doubleSided = m.double_sided;
  out.alphaMode = m.alpha_mode == AlphaMode::kMask    ? "MASK"
                  : m.alpha_mode == AlphaMode::kBlend ? "BLEND"
                                                      : "OPAQUE";
  if (m.alpha_mode == AlphaMode::kMask) out.alphaCutoff = m.alpha_cutoff;
  // glTF's emissiveFactor stops at 1: the rest goes to KHR_materials_emissive_strength. Under a
  // POV-Ray pigment, other viewers get the emission times the pigment's mean colour.
  const Rgb emission =
      m.base_color_pattern ? m.emission * gltf::mean_colour(*m.base_color_pattern).rgb : m.emission;
  const float strength = std::max(max_component(emission), 1.f);
  out.emissiveFactor = {emission.x / strength, emission.y / strength, emission.z / strength};
  if (strength > 1)
    out.extensions["KHR_materials_emissive_strength"] =
        Value(Value::Object{{"emissiveStrength", number(strength)}});
  if (m.transmission > 0)
    out.extensions["KHR_materials_transmission"] =
        Value(Value::Object{{"transmissionFactor", number(m.transmission)}});
  if (m.ior != 1.5f)
    out.extensions["KHR_materials_ior"] = Value(Value::Object{{"ior", number(m.ior)}});
  // FILMBACK_povray: a POV-Ray pigment, a base colour beyond glTF's [0, 1] and a specular factor
  // other viewers get as a colour (khr_specular_for_viewers); they get the base colour factor
  // times the pigment's mean colour, clamped.
  Value::Object ours;
  const KhrSpecular specular = khr_specular_for_viewers(m);
  if (!specular.khr.empty()) out.extensions["KHR_materials_specular"] = Value(specular.khr);
  if (specular.exact_in_ours) ours["specular_factor"] = number(m.specular);
  Rgb viewed = m.base_color;
  if (m.base_color_pattern) viewed = viewed * gltf::mean_colour(*m.base_color_pattern).rgb;
  if (m.base_color_pattern || max_component(m.base_color) > 1) {
    ours["base_color_factor"] = gltf::number_array(m.base_color);
    if (m.base_color_pattern) {
      ours["pigment"] = gltf::pattern_json(*m.base_color_pattern);
      if (max_component(m.emission) > 0) ours["emission_factor"] = gltf::number_array(m.emission);
    }
    out.pbrMetallicRoughness.baseColorFactor = {std::min(viewed.x, 1.f), std::min(viewed.y, 1.f),
                                                std::min(viewed.z, 1.f), m.alpha};
  }
  if (!ours.empty()) out.extensions["FILMBACK_povray"] = Value(std::move(ours));
  if (m.textures.any())
    diagnostics.warn("material '" + m.name + "': its textures are not written by convert");
  if (m.normal_pattern || !m.layers.empty())
    diagnostics.warn("material '" + m.name +
                     "': its POV-Ray normal pattern and texture layers are not written by convert");
  return out;
}

// Column-major 4x4, as glTF's node "matrix".
std::vector<double> column_major(const Transform& t) {
  std::vector<double> m(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      m[size_t(c * 4 + r)] = t(r, c);
  return m;
}

// KHR_lights_punctual for any viewer, and the exact light in our extension (gltf_lights.cpp).
// `khr_scale` multiplies the KHR intensity only (gltf_khr_stand_in.h).
void add_light(tinygltf::Model& model, tinygltf::Node& node, const Light& light, double khr_scale) {
  constexpr double kPi = std::numbers::pi;
  tinygltf::Light out;
  out.name = light.name;
  const double peak = double(std::max(max_component(light.intensity), 0.f));
  const Rgb colour = peak > 0 ? light.intensity * float(1 / peak) : Rgb(1.f, 1.f, 1.f);
  out.color = {colour.x, colour.y, colour.z};
  out.intensity = peak * kLumensPerWatt * khr_scale;
  Value::Object ours{{"color", gltf::number_array(colour)}};
  switch (light.type) {
    case LightType::kPoint:
    case LightType::kSpot:
      out.type = light.type == LightType::kPoint ? "point" : "spot";
      ours["type"] = Value(std::string(light.type == LightType::kPoint ? "POINT" : "SPOT"));
      ours["energy_w"] = number(peak * 4 * kPi);
      ours["radius_m"] = number(light.radius_m);
      // KHR_lights_punctual: 0 <= inner < outer <= pi / 2 (POV-Ray's falloff may exceed it).
      out.spot.innerConeAngle = gltf::khr_spot_cone(light).inner_rad;
      out.spot.outerConeAngle = gltf::khr_spot_cone(light).outer_rad;
      if (light.type == LightType::kSpot) {
        ours["spot_size_rad"] = number(2 * light.spot_outer_angle_rad);
        ours["spot_blend"] = number(light.spot_blend);
      }
      break;
    case LightType::kDirectional:
      out.type = "directional";
      ours["type"] = Value(std::string("SUN"));
      ours["energy_w"] = number(peak);
      ours["angle_rad"] = number(light.angle_rad);
      break;
    case LightType::kArea: {
      // KHR_lights_punctual has no area lights: our extension alone, its size in world metres
      // (the node's matrix has no scale), power back from Cycles' radiance P / (4 A).
      const bool round = light.area_shape == AreaShape::kEllipse;
      ours["type"] = Value(std::string("AREA"));
      ours["shape"] = Value(std::string(round ? "ELLIPSE" : "RECTANGLE"));
      ours["size_m"] = number(light.size_x_m);
      ours["size_y_m"] = number(light.size_y_m);
      ours["spread_rad"] = number(light.spread_rad);
      ours["energy_w"] = number(peak * 4 * light.size_x_m * light.size_y_m * (round ? kPi / 4 : 1));
      node.extensions["FILMBACK_blender"] = Value(Value::Object{{"light", Value(std::move(ours))}});
      return;
    }
  }
  model.lights.push_back(out);
  node.extensions["KHR_lights_punctual"] =
      Value(Value::Object{{"light", Value(int(model.lights.size() - 1))}});
  // POV-Ray's light model in its own extension; a spot with glTF's own falloff is exact in
  // KHR_lights_punctual alone.
  if (gltf::is_povray_light(light))
    node.extensions["FILMBACK_povray"] =
        Value(Value::Object{{"light", gltf::povray_light_json(light)}});
  else if (light.type != LightType::kSpot || light.spot_falloff == SpotFalloff::kCycles)
    node.extensions["FILMBACK_blender"] = Value(Value::Object{{"light", Value(std::move(ours))}});
}

void add_camera(tinygltf::Model& model, tinygltf::Node& node, const SceneCamera& camera,
                uint32_t width_px, uint32_t height_px) {
  const PhysicalCamera& p = camera.physical;
  tinygltf::Camera out;
  out.name = camera.name;
  const CameraQuantities q = describe_camera(p, width_px, height_px);
  const double aspect = double(width_px) / height_px;
  if (p.projection == FB_PROJECTION_ORTHOGRAPHIC) {
    out.type = "orthographic";
    const double half_width = p.ortho_scale_m / 2;
    out.orthographic.xmag = q.horizontal_fit ? half_width : half_width * aspect;
    out.orthographic.ymag = out.orthographic.xmag / aspect;
    out.orthographic.znear = std::max(p.clip_near_m, 0.0);
    out.orthographic.zfar = std::isfinite(p.clip_far_m) ? p.clip_far_m : 1e9;
  } else {
    out.type = "perspective";
    out.perspective.yfov = q.vertical_fov_deg * std::numbers::pi / 180;
    out.perspective.aspectRatio = aspect;
    // glTF needs 0 < znear < zfar, and tinygltf always writes zfar: a camera that clips nothing
    // (POV-Ray's) gets 1 mm and 1e9 m here; FILMBACK_blender keeps the exact clip_near_m.
    out.perspective.znear = p.clip_near_m > 0 ? p.clip_near_m : 1e-3;
    out.perspective.zfar = std::isfinite(p.clip_far_m) ? p.clip_far_m : 1e9;
  }
  Value::Object ours{{"focal_length_mm", number(p.focal_length_mm)},
                     {"sensor_width_mm", number(p.sensor_width_mm)},
                     {"sensor_height_mm", number(p.sensor_height_mm)},
                     {"sensor_fit", Value(std::string(sensor_fit_name(p.sensor_fit)))},
                     {"shift_x", number(p.shift_x)},
                     {"shift_y", number(p.shift_y)},
                     {"clip_near_m", number(p.clip_near_m)},
                     {"ortho_scale_m", number(p.ortho_scale_m)},
                     {"aperture_blades", Value(int(p.aperture_blades))},
                     {"aperture_rotation_rad", number(p.aperture_rotation_rad)},
                     {"aperture_ratio", number(p.aperture_ratio)}};
  if (std::isfinite(p.clip_far_m)) ours["clip_far_m"] = number(p.clip_far_m);
  if (p.has_aperture()) ours["fstop"] = number(p.fstop);
  if (std::isfinite(p.focus_distance_m)) ours["focus_distance_m"] = number(p.focus_distance_m);
  out.extensions["FILMBACK_blender"] = Value(std::move(ours));
  model.cameras.push_back(out);
  node.camera = int(model.cameras.size() - 1);
}

// The mean radiance of an equirectangular world image over the sphere (each row weighted by the
// solid angle it covers, sin of its polar angle): the uniform world that sends the same light.
Rgb mean_radiance(const EnvironmentMap& map) {
  Rgb sum{0.f, 0.f, 0.f};
  double weights = 0;
  for (uint32_t y = 0; y < map.height; ++y) {
    const double w = std::sin(std::numbers::pi * (y + 0.5) / map.height);
    for (uint32_t x = 0; x < map.width; ++x)
      sum += map.texels[size_t(y) * map.width + x] * float(w);
    weights += w * map.width;
  }
  return weights > 0 ? sum * float(1 / weights) : sum;
}

Value::Object scene_settings(const Scene& scene, uint32_t width_px, uint32_t height_px) {
  const ShotSettings& s = scene.settings;
  Value::Object out{
      {"resolution_x_px", Value(int(width_px))},
      {"resolution_y_px", Value(int(height_px))},
      {"resolution_percentage", Value(100)},
      {"pixel_aspect_x", number(s.pixel_aspect.value_or(1.0))},
      {"pixel_aspect_y", number(1)},
      {"film_exposure", number(s.film_exposure)},
      // A world image (a POV-Ray sky_sphere) is not written: its mean is.
      {"world_color", gltf::number_array(scene.environment ? mean_radiance(*scene.environment)
                                                           : scene.background)},
      {"world_strength", number(1)}};
  if (s.fps) out["fps"] = number(*s.fps);
  if (s.frame) out["frame"] = number(*s.frame);
  return out;
}

}  // namespace

void write_gltf(const Scene& scene, const fs::path& file, Diagnostics& diagnostics) {
  if (scene.environment)
    diagnostics.warn("'" + file.string() + "': the world image '" + scene.environment->name +
                     "' is not written; its mean radiance is, as the world colour");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "filmback convert";
  model.buffers.emplace_back();
  for (const Material& m : scene.materials)
    model.materials.push_back(material(m, diagnostics));
  std::vector<int> mesh_of;
  for (const TriangleMesh& mesh : scene.meshes)
    mesh_of.push_back(add_mesh(model, mesh));

  tinygltf::Scene root;
  for (const MeshInstance& instance : scene.instances) {
    tinygltf::Node node;
    node.name = instance.node;
    node.mesh = mesh_of[instance.mesh];
    node.matrix = column_major(instance.world_from_object);
    root.nodes.push_back(int(model.nodes.size()));
    model.nodes.push_back(node);
  }
  // Cameras first, written after the lights: the first one, as a viewer sees through it, sets
  // how bright the lights' KHR stand-ins are.
  const uint32_t width = scene.settings.width_px.value_or(800);
  const uint32_t height = scene.settings.height_px.value_or(600);
  std::vector<tinygltf::Node> camera_nodes;
  for (const SceneCamera& camera : scene.cameras) {
    if (camera.world_from_camera.determinant3x3() < 0)
      diagnostics.warn("camera '" + camera.name +
                       "': a mirrored camera cannot be written to glTF; its image will be flipped");
    tinygltf::Node node;
    node.name = camera.name;
    node.matrix = column_major(camera.world_from_camera);
    add_camera(model, node, camera, width, height);
    camera_nodes.push_back(node);
  }
  const std::vector<double> khr_scales =
      scene.cameras.empty()
          ? std::vector<double>(scene.lights.size(), 1.0)
          : gltf::khr_intensity_scales(scene, model.cameras[0], scene.cameras[0].world_from_camera);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    tinygltf::Node node;
    node.name = light.name;
    node.matrix = column_major(light.world_from_light);
    add_light(model, node, light, khr_scales[i]);
    root.nodes.push_back(int(model.nodes.size()));
    model.nodes.push_back(node);
  }
  for (tinygltf::Node& node : camera_nodes) {
    root.nodes.push_back(int(model.nodes.size()));
    model.nodes.push_back(std::move(node));
  }
  root.extensions["FILMBACK_blender"] = Value(scene_settings(scene, width, height));
  model.scenes.push_back(root);
  model.defaultScene = 0;
  if (!model.lights.empty()) model.extensionsUsed.push_back("KHR_lights_punctual");
  model.extensionsUsed.push_back("FILMBACK_blender");
  const auto povray = [](const tinygltf::ExtensionMap& e) {
    return e.count("FILMBACK_povray") > 0;
  };
  if (std::any_of(model.nodes.begin(), model.nodes.end(),
                  [&](const tinygltf::Node& n) { return povray(n.extensions); }) ||
      std::any_of(model.materials.begin(), model.materials.end(),
                  [&](const tinygltf::Material& m) { return povray(m.extensions); }))
    model.extensionsUsed.push_back("FILMBACK_povray");
  for (const char* ext : {"KHR_materials_emissive_strength", "KHR_materials_transmission",
                          "KHR_materials_ior", "KHR_materials_specular"})
    for (const tinygltf::Material& m : model.materials)
      if (m.extensions.count(ext)) {
        model.extensionsUsed.push_back(ext);
        break;
      }

  // A scene without meshes has no binary data: glTF allows no empty buffer.
  if (model.buffers[0].data.empty()) model.buffers.clear();
  std::ostringstream text;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, text, true, false))
    throw InputError("'" + file.string() + "': the glTF writer failed");
  write_atomically(file, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text.str();
    out.close();
    return out ? std::string() : std::string(std::strerror(errno));
  });
}

}  // namespace fb
