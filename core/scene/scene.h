// What an importer produces: geometry, materials, lights and cameras in world space (right-handed,
// +Y up, metres). It knows nothing of plugins or of how the render will use it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/image/view_settings.h"
#include "core/math/bounds.h"
#include "core/math/transform.h"
#include "core/scene/animation.h"
#include "core/scene/camera.h"
#include "core/scene/global_medium.h"
#include "core/scene/interior_medium.h"
#include "core/scene/material_textures.h"
#include "core/scene/mesh_deformation.h"
#include "core/scene/pov_finish.h"
#include "core/scene/shader_graph.h"
#include "core/scene/solid.h"
#include "core/scene/solid_texture.h"
#include "core/scene/subdivision_surface.h"
#include "core/scene/value_origin.h"

namespace fb {

struct TriangleMesh {
  std::string name;               // for messages and `filmback info`
  std::vector<Vec3f> positions;   // object space
  std::vector<Vec3f> normals;     // empty, or one per position
  VertexTextureData texturing;    // texture coordinates and tangents, when a material needs them
  std::vector<uint32_t> indices;  // three per triangle, counter-clockwise front faces
  uint32_t material = 0;
  size_t triangle_count() const { return indices.size() / 3; }
};

struct MeshInstance {
  uint32_t mesh = 0;
  Transform world_from_object;  // rest pose
  std::string node;
  uint32_t node_index = kNoNode;  // in Scene::hierarchy, whose animation may move it
  // Index into Scene::assets: the topmost node above it (Blender's CryptoAsset names an object by
  // its topmost parent); kNoAsset names it by `node`.
  uint32_t asset = kNoAsset;
};

// glTF metallic-roughness (core/shading/gltf_bsdf.h has the BSDF); factors multiply textures. Or
// a Blender shader graph.
struct Material {
  std::string name;
  Rgb base_color{1.f, 1.f, 1.f};  // linear (glTF's default base colour)
  Rgb emission{0.f, 0.f, 0.f};    // radiance, W sr^-1 m^-2
  bool double_sided = false;
  float metallic = 0.f;       // the importer sets glTF's default of 1 for materials it reads
  float roughness = 1.f;      // perceptual: GGX alpha = roughness^2
  float transmission = 0.f;   // KHR_materials_transmission
  float ior = 1.5f;           // KHR_materials_ior
  float specular = 1.f;       // KHR_materials_specular specularFactor: 0 makes it Lambertian
  MaterialTextures textures;  // none by default
  // A POV-Ray pigment (importers/pov): the base colour and the emission are base_color and
  // emission times this solid texture's colour at the hit's world position, its transmit scales
  // the coverage (alpha) and its filter the transmission (docs/pov.md, "Appearance").
  std::optional<SolidPattern> base_color_pattern;
  // A POV-Ray normal pattern: the shading normal bent at every hit (core/texture/solid_normal.h).
  std::optional<SolidNormal> normal_pattern;
  // POV-Ray's layered textures: materials over this one, each over the one before, each with a
  // base_color_pattern whose filter and transmit at the hit let the layers below show through
  // (SurfaceShader::shade; docs/pov.md "Layered textures"). Their emission composites as their
  // colours do (SurfaceShader::emission); only the base material's alpha and ior count.
  std::vector<Material> layers;
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha = 1.f;          // baseColorFactor's fourth component
  float alpha_cutoff = 0.5f;  // kMask
  // A Blender material (filmback's add-on, docs/blender.md "Materials"): rendered as Cycles 3.4
  // renders its shader nodes; the glTF factors above then serve only other uses. Its importer sets
  // `emission` to a bound of what it emits (for light selection), double_sided (Cycles' emission
  // leaves both faces) and alpha_mode kBlend when a node can be transparent.
  std::optional<ShaderGraph> shader_graph;
  // A POV-Ray texture's finish and interior as written (importers/pov), for the `povray`
  // integrator; the fields above are its physical mapping. The base layer's only.
  std::optional<PovFinish> pov_finish;
  // The medium inside a closed surface of this material (POV-Ray's interior media).
  std::optional<InteriorMedium> medium;
};

enum class LightType { kPoint, kSpot, kDirectional, kArea };

// The outline of an area light (Blender's SQUARE and RECTANGLE are rectangles, DISK and ELLIPSE
// ellipses).
enum class AreaShape { kRectangle, kEllipse };

// How a spot fades between its cones: glTF's KHR_lights_punctual ramp, or Cycles' (Blender's
// spot_size and spot_blend: cos(angle) times a smoothstep, docs/blender.md "Lights and world").
// kPov: POV-Ray's spotlight, cos(angle)^tightness times a cubic from 0 at the outer cone
// (falloff) to 1 at the inner one (radius) (POV-Ray's Attenuate_Light).
enum class SpotFalloff { kGltf, kCycles, kPov };

// How a point or spot light dims with distance d: physically (1/d^2, glTF and Blender), or as
// POV-Ray does, not at all unless fade_power > 0, then by 2 / (1 + (d / fade_distance)^fade_power)
// (d^-fade_power for a zero fade_distance) (POV-Ray's Attenuate_Light, docs/pov.md "Appearance").
enum class LightDecay { kInverseSquare, kPovRay };

// Point, spot, sun and area lights. Like Cycles' lights they are not surfaces: camera and shadow
// rays pass through them, and those with a size (a radius, an angle, an area) are found by light
// sampling and by BSDF-sampled rays alike (core/render/light_sampler.h).
struct Light {
  std::string name;
  LightType type = LightType::kPoint;
  // Per channel: radiant intensity in W/sr (point, spot), irradiance in W/m^2 (directional), or
  // radiance in W sr^-1 m^-2 (area: Cycles' P / (4 A) before the spread's redistribution).
  Rgb intensity{1.f, 1.f, 1.f};
  Transform world_from_light;  // rest pose; lights shine down their -Z axis
  uint32_t node_index = kNoNode;
  SpotFalloff spot_falloff = SpotFalloff::kGltf;
  double spot_inner_angle_rad = 0.0;                 // kGltf: full intensity inside this half-angle
  double spot_outer_angle_rad = 0.7853981633974483;  // half-angle of the cone
  double spot_blend = 0.0;  // kCycles: fraction of the cone's (1 - cos) that fades
  // Point and spot with LightDecay::kInverseSquare: Cycles 3.4's soft light, a disk of this radius
  // facing the shading point with radiance I / (pi r^2); 0 is a true point.
  double radius_m = 0.0;
  // Directional: the sun's angular diameter, its directions spread over a disk of radius
  // tan(angle/2) one unit away (Cycles' distant light); 0 is a single direction.
  double angle_rad = 0.0;
  // Area: a one-sided rectangle or ellipse centred on the light in its XY plane, shining down its
  // -Z, of these full extents along X and Y in world metres (the node's scale applied).
  AreaShape area_shape = AreaShape::kRectangle;
  double size_x_m = 1.0, size_y_m = 1.0;
  // Area: Blender's Spread, the full angle about the normal that the light fills (Cycles 3.4's
  // soft-box grid, area_light_spread_attenuation); pi leaves it unrestricted.
  double spread_rad = 3.141592653589793;
  LightDecay decay = LightDecay::kInverseSquare;
  double fade_distance_m = 0.0, fade_power = 0.0;  // LightDecay::kPovRay
  double spot_tightness = 0.0;                     // SpotFalloff::kPov
  bool casts_shadows = true;  // false: POV-Ray's `shadowless`, no shadow ray is traced
  // POV-Ray's area_light: area_size1 x area_size2 points spread evenly over area_axis1 and
  // area_axis2 (light space, centred on the light), each with 1 / (size1 size2) of the intensity;
  // each light sample takes one of them. `area_circular` folds the grid onto the ellipse the axes
  // span; `area_orient` turns the axes to face the lit point.
  Vec3d area_axis1{0, 0, 0}, area_axis2{0, 0, 0};
  uint32_t area_size1 = 1, area_size2 = 1;
  bool area_circular = false, area_orient = false;
};

// An equirectangular world image (Blender's Environment Texture, Cycles' mapping): column
// u = 0.5 - atan2(y, x) / (2 pi), row v = acos(z) / pi from the top, in Blender's Z-up world
// axes; texels are radiance (image times the world's strength), top row first. A world (glTF,
// Y-up) direction (x, y, z) is Blender's (x, -z, y): the image's centre column (u = 0.5) looks down
// world +X, its top row up world +Y, and u = 0.25 looks down world -Z
// (core/render/environment.cpp).
struct EnvironmentMap {
  std::string name;  // the image file, for messages
  uint32_t width = 0, height = 0;
  std::vector<Rgb> texels;
};

// What a file says about how its shot is rendered (glTF: scenes[i].extras, docs/scenes.md).
// Cycles' Film > Pixel Filter as a scene names it: typed, so that its exact values reach the filter
// plugin the render chooses for it (core/render/scene_filter.h).
struct PixelFilterSetting {
  enum class Type { kBlackmanHarris, kGaussian, kBox };
  Type type = Type::kBlackmanHarris;
  double width_px = 1.5;  // Cycles' filter_width
  ValueOrigin origin;     // the scene file and the JSON path of the object that names it
};

// Cycles' Sampling > Adaptive Sampling as a shot names it (docs/blender.md).
struct ShotAdaptiveSampling {
  bool use = false;      // use_adaptive_sampling
  double threshold = 0;  // adaptive_threshold; 0 with `use`: Cycles' automatic max(0.001, 1/spp)
  uint32_t min_samples = 0;  // adaptive_min_samples; 0: automatic
};

struct ShotSettings {
  std::optional<uint32_t> width_px, height_px;
  std::optional<double> fps;
  std::optional<double> frame;
  std::optional<double> shutter_open_s, shutter_close_s;  // relative to the frame's time
  std::vector<double> shutter_curve;   // weights evenly spaced over the open shutter; empty: box
  ValueOrigin shutter_curve_origin;    // where shutter_curve came from
  std::optional<double> pixel_aspect;  // pixel width / height
  std::optional<PixelFilterSetting> filter;  // the shot's pixel filter
  double film_exposure = 1.0;                // linear gain on the image (Cycles' Film > Exposure)
  std::optional<ShotAdaptiveSampling> adaptive;  // none: the file does not say
  // Cycles' rolling shutter (rolling_shutter_type TOP): its duration, a share of the shutter in
  // [0, 1] (docs/camera-model.md, "Rolling shutter"); none: a global shutter.
  std::optional<double> rolling_shutter_duration;
  // Blender's Color Management and Dither, for 8-bit outputs only (docs/blender.md); a file that
  // names no view transform gets the plain sRGB curve.
  ViewSettings view;
  std::string view_json_path;  // the object that names them, for warnings about unknown names
};

struct Scene;

// The camera named `name`; throws UsageError ("--camera ...") listing the scene's cameras.
const SceneCamera& find_camera(const Scene& scene, const std::string& name);

struct Scene {
  std::filesystem::path file;
  std::vector<TriangleMesh> meshes;
  std::vector<MeshInstance> instances;
  // Refined into meshes and instances by the render (core/subdiv/refine_scene.h), not before.
  std::vector<SubdivisionSurface> subdivision_surfaces;
  // Analytic shapes and their CSG, intersected exactly by the render (POV-Ray's primitives).
  std::vector<Solid> solids;
  std::vector<Material> materials;
  std::vector<TextureImage> images;  // what materials' textures read
  std::vector<Light> lights;
  std::vector<SceneCamera> cameras;           // in the order the scene's nodes were met
  Rgb background{0.f, 0.f, 0.f};              // uniform radiance seen by rays that escape
  std::optional<EnvironmentMap> environment;  // replaces `background` when present
  // Media filling the scene (POV-Ray's fog, fb_scene_api::medium_segment); none: the render is
  // as without them, bit for bit.
  std::vector<GlobalMedium> media;
  ShotSettings settings;
  NodeHierarchy hierarchy;  // nodes and animation curves; empty for a scene without nodes
  // The names of the roots of the scene's node trees (a node without a name: its JSON path), which
  // MeshInstance::asset indexes; kept for every file, one string per root.
  std::vector<std::string> assets;
  // Meshes posed by the render at the shot's still time (pose_deformed_meshes), not before.
  std::vector<MeshDeformation> deformations;
  // A POV-Ray scene's trace depth (global_settings); none for other scenes.
  std::optional<PovTracing> pov_tracing;

  size_t triangle_count() const;
  Bounds3d world_bounds(double time_s) const;  // of all instanced geometry and bounded solids

  // Placements at time t on the scene's timeline (s): the rest pose unless the node is animated.
  Transform world_from_object(const MeshInstance& instance, double time_s) const;
  Transform world_from_camera(const SceneCamera& camera, double time_s) const;  // scale removed
  Transform world_from_light(const Light& light, double time_s) const;          // scale removed
  // Whether the node's placement can change within [t0, t1] (never for kNoNode).
  bool moves(uint32_t node_index, double t0, double t1) const;
};

}  // namespace fb
