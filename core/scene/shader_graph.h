// A Blender material's shader nodes as filmback's add-on exports them (docs/blender.md,
// "Materials"): Principled, Diffuse, Glossy, Glass, Emission and Transparent nodes joined by Mix
// and Add shaders, each input a constant or an image texture. The host evaluates it at every hit
// into Cycles 3.4's closures (core/texture/surface_shader.cpp, core/shading/), as Cycles' SVM
// evaluates the same nodes (intern/cycles/kernel/svm/svm_closure.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/scene/material_textures.h"

namespace fb {

enum class ShaderNodeType : uint8_t {
  kPrincipled,
  kDiffuse,
  kGlossy,
  kGlass,
  kEmission,
  kTransparent,
  kMix,  // weight (1 - fac) to shaders[0], fac to shaders[1]
  kAdd,
};

// The Glossy, Glass and Principled nodes' distribution menus (the Principled BSDF has GGX and
// Multiscatter GGX, the Glass node no Ashikhmin-Shirley).
enum class Distribution : uint8_t { kSharp, kBeckmann, kGgx, kAshikhminShirley, kMultiGgx };
// The Principled BSDF's Subsurface Method.
enum class SubsurfaceMethod : uint8_t { kBurley, kRandomWalk, kRandomWalkFixedRadius };

// Every input socket the nodes above have, one namespace for all of them (the Principled BSDF's
// 3.4 sockets first).
enum class Socket : uint8_t {
  kBaseColor,
  kSubsurface,
  kSubsurfaceRadius,
  kSubsurfaceColor,
  kSubsurfaceIor,
  kSubsurfaceAnisotropy,
  kMetallic,
  kSpecular,
  kSpecularTint,
  kRoughness,
  kAnisotropic,
  kAnisotropicRotation,
  kSheen,
  kSheenTint,
  kClearcoat,
  kClearcoatRoughness,
  kIor,
  kTransmission,
  kTransmissionRoughness,
  kEmission,
  kEmissionStrength,
  kAlpha,
  kNormal,
  kClearcoatNormal,
  kTangent,
  kColor,     // Diffuse, Glossy, Glass, Emission, Transparent
  kStrength,  // Emission
  kFac,       // Mix Shader
  kCount
};
constexpr size_t kSocketCount = size_t(Socket::kCount);

// An Image Texture node with the UV Map and Mapping nodes in front of it.
struct ImageTextureNode {
  uint32_t image = kNoImage;  // Scene::images
  uint32_t uv_slot = 0;  // ShaderGraph::uv_maps index; the importer puts that map in TEXCOORD_n
  std::array<float, 6> uv_transform{1, 0, 0, 0, 1, 0};  // as TextureRef::uv_transform
  TextureWrap wrap = TextureWrap::kRepeat;
  TextureInterpolation interpolation = TextureInterpolation::kLinear;
  bool srgb = true;  // the image's colour space is sRGB (else its values are linear as stored)
  bool ignore_alpha = false;  // Blender's alpha mode None: the Alpha output is 1
};

enum class TextureOutput : uint8_t { kColor, kAlpha, kRed, kGreen, kBlue };

struct ShaderInput {
  enum class Kind : uint8_t { kUnset, kConstant, kTexture, kNormalMap };
  Kind kind = Kind::kUnset;  // kUnset: the socket is unlinked and has no value (normal sockets)
  Vec3f value{};             // kConstant: a colour or vector, or a number in x
  uint32_t texture = 0;      // ShaderGraph::textures
  TextureOutput output = TextureOutput::kColor;
  float strength = 1.f;  // kNormalMap: the Normal Map node's strength
};

struct ShaderNode {
  ShaderNodeType type = ShaderNodeType::kDiffuse;
  std::string name;  // Blender's node name, for messages
  Distribution distribution = Distribution::kGgx;
  SubsurfaceMethod subsurface_method = SubsurfaceMethod::kRandomWalk;  // rendered as diffuse
  static constexpr uint32_t kNone = 0xffffffffu;
  std::array<uint32_t, 2> shaders{kNone, kNone};  // kMix, kAdd: node indices
  std::array<ShaderInput, kSocketCount> inputs{};
  const ShaderInput& in(Socket s) const { return inputs[size_t(s)]; }
  ShaderInput& in(Socket s) { return inputs[size_t(s)]; }
};

struct ShaderGraph {
  std::string blender_version;    // of the Blender that exported it, "3.4.1"; empty when unknown
  std::vector<ShaderNode> nodes;  // acyclic (checked on import)
  uint32_t surface = ShaderNode::kNone;  // what the Material Output's Surface receives
  std::vector<ImageTextureNode> textures;
  // The UV maps the textures read, by name ("" is the mesh's active render map); the importer
  // gives each mesh primitive TEXCOORD_n = uv_maps[n].
  std::vector<std::string> uv_maps;
  uint32_t normal_map_uv_slot = 0;  // the UV map whose tangents normal maps use
  bool has_normal_map = false;
  bool needs_radial_tangent = false;  // an anisotropic Principled (Cycles' default tangent)
};

}  // namespace fb
