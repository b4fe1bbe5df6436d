// What a glTF material's textures read: images, how each texture maps onto a surface, and the
// per-vertex data (texture coordinates, tangents) that mapping needs. Evaluated by the host at
// every hit (core/texture/surface_shader.h); plugins see only the result (fb_hit).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <filmback/vec.h>

namespace fb {

// An image as the file gives it: a file inside the scene's folder, or bytes embedded in the file
// (a data: URI or a bufferView), decoded when the render opens it.
struct TextureImage {
  std::string name;  // for messages: "images[2] (wood.png)"
  std::filesystem::path file;
  std::vector<unsigned char> bytes;  // when `file` is empty
};

constexpr uint32_t kNoImage = 0xffffffffu;

// kBlack: transparent black outside [0, 1] (Blender's CLIP extension).
enum class TextureWrap { kRepeat, kClamp, kMirror, kBlack };
enum class TextureInterpolation : uint8_t { kLinear, kClosest, kCubic };

struct TextureRef {
  uint32_t image = kNoImage;  // index into Scene::images
  uint32_t texcoord = 0;      // TEXCOORD_n
  // KHR_texture_transform as a 2x3 matrix, row-major: uv' = [a b c; d e f] (u, v, 1).
  std::array<float, 6> uv_transform{1, 0, 0, 0, 1, 0};
  TextureWrap wrap_s = TextureWrap::kRepeat, wrap_t = TextureWrap::kRepeat;
  bool present() const { return image != kNoImage; }
};

struct MaterialTextures {
  TextureRef base_color;          // sRGB-encoded RGB, linear alpha
  TextureRef metallic_roughness;  // linear: G roughness, B metallic
  TextureRef normal;              // linear, tangent space, scaled by normal_scale in x and y
  float normal_scale = 1.f;
  TextureRef emissive;  // sRGB-encoded
  bool any() const {
    return base_color.present() || metallic_roughness.present() || normal.present() ||
           emissive.present();
  }
};

enum class AlphaMode { kOpaque, kMask, kBlend };

// Per vertex, parallel to TriangleMesh::positions; empty when no material of the mesh needs it.
struct VertexTextureData {
  static constexpr uint32_t kSets = 2;  // TEXCOORD_0 and TEXCOORD_1
  std::array<std::vector<Vec2f>, kSets> texcoords;
  std::vector<std::array<float, 4>> tangents;  // xyz unit, w = +-1: bitangent = w (n x t)
  // Cycles' default tangent for anisotropic closures (svm_node_tangent, radial about the object's
  // Blender Z axis): the direction (-(g.y - 1/2), g.x - 1/2, 0) of the Generated coordinates g,
  // in object space, to be transformed as a normal; affine in the position, so interpolating it
  // per vertex is exact. Empty unless an anisotropic Blender material needs it.
  std::vector<Vec3f> radial_tangents;
};

}  // namespace fb
