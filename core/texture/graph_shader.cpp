#include "core/texture/graph_shader.h"

#include <algorithm>
#include <cmath>

#include "core/shading/fresnel.h"
#include "core/texture/surface_point.h"

namespace fb {

namespace {

// Cycles' weights below this make no closure (CLOSURE_WEIGHT_CUTOFF, kernel/closure/alloc.h).
constexpr float kWeightCutoff = 1e-5f;

// Blender's config's luma coefficients (config.ocio `luma`), which Cycles' implicit colour to
// float conversion uses (svm_node_convert, linear_rgb_to_gray).
float luma(Vec3f c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// What a Principled BSDF leaves besides its closures: PrincipledBsdfNode::expand
// (scene/shader_nodes.cpp) makes it Mix(alpha, Transparent, Add(Emission(emission, strength),
// BSDF)), the factor clamped as every mix's.
float principled_alpha(float alpha) {
  return std::clamp(alpha, 0.f, 1.f);
}

bool any_weight(Rgb w) {
  return std::max({std::abs(w.x), std::abs(w.y), std::abs(w.z)}) > kWeightCutoff;
}

// Cycles' default Tangent input (svm_node_tangent, radial): the radial direction made
// perpendicular to the normal, T = N x normalize(radial x N); zero (Surface then picks one) without
// the mesh's radial data.
Vec3f default_tangent(Vec3f radial, Vec3f n) {
  const Vec3f side = cross(radial, n);
  const float len = length(side);
  return len > 0.f ? cross(n, side / len) : Vec3f{};
}

// Nesting bound for the walk: the importer refuses cycles, and a graph has at most 1024 nodes.
constexpr int kMaxDepth = 1024;

}  // namespace

std::array<float, 4> GraphShader::texel(uint32_t index, const SurfacePoint& point) const {
  const ImageTextureNode& t = graph_.textures[index];
  TextureLookup lookup(t.image, texture_position(point, t.uv_slot, t.uv_transform));
  lookup.wrap_s = lookup.wrap_t = t.wrap;
  lookup.interpolation = t.interpolation;
  lookup.srgb = t.srgb;
  std::array<float, 4> rgba = images_.rgba(lookup);
  if (t.ignore_alpha) rgba[3] = 1.f;
  return rgba;
}

Vec3f GraphShader::colour(const ShaderInput& in, const SurfacePoint& point) const {
  if (in.kind != ShaderInput::Kind::kTexture) return in.value;
  const auto c = texel(in.texture, point);
  switch (in.output) {
    case TextureOutput::kColor:
      return {c[0], c[1], c[2]};
    case TextureOutput::kAlpha:
      return {c[3], c[3], c[3]};
    default: {
      const float v = c[size_t(in.output) - size_t(TextureOutput::kRed)];
      return {v, v, v};
    }
  }
}

float GraphShader::number(const ShaderInput& in, const SurfacePoint& point) const {
  if (in.kind != ShaderInput::Kind::kTexture) return in.value.x;
  if (in.output == TextureOutput::kColor) return luma(colour(in, point));
  return colour(in, point).x;
}

Vec3f GraphShader::normal(const ShaderInput& in, const SurfacePoint& point, Vec3f smooth) const {
  if (in.kind != ShaderInput::Kind::kNormalMap || !(dot(point.tangent, point.tangent) > 0.f))
    return smooth;
  // Cycles' svm_node_normal_map, tangent space: the colour (the image as its colour space says)
  // to [-1, 1], N = normalize(c.x T + c.y B + c.z N) with B = sign (N x T), then bent back towards
  // the interpolated normal by the strength.
  const auto c = texel(in.texture, point);
  const Vec3f tangent = normalize(point.tangent - smooth * dot(smooth, point.tangent));
  const Vec3f bitangent = cross(smooth, tangent) * point.bitangent_sign;
  Vec3f n =
      tangent * (2.f * c[0] - 1.f) + bitangent * (2.f * c[1] - 1.f) + smooth * (2.f * c[2] - 1.f);
  const float len = length(n);
  if (!(len > 0.f) || !std::isfinite(len)) return smooth;
  n = n / len;
  if (in.strength != 1.f) {
    const Vec3f bent = smooth + (n - smooth) * std::max(in.strength, 0.f);
    const float bent_len = length(bent);
    n = bent_len > 0.f ? bent / bent_len : smooth;
  }
  return n;
}

template <typename Visit>
void GraphShader::walk(const SurfacePoint& point, Visit&& visit) const {
  if (graph_.surface != ShaderNode::kNone)
    walk(graph_.surface, Rgb{1.f, 1.f, 1.f}, point, visit, 0);
}

template <typename Visit>
void GraphShader::walk(uint32_t index, Rgb weight, const SurfacePoint& point, Visit& visit,
                       int depth) const {
  if (!any_weight(weight) || depth > kMaxDepth) return;
  const ShaderNode& node = graph_.nodes[index];
  const auto child = [&](int i, Rgb w) {
    if (node.shaders[i] != ShaderNode::kNone) walk(node.shaders[i], w, point, visit, depth + 1);
  };
  switch (node.type) {
    case ShaderNodeType::kMix: {
      // svm_node_mix_closure: the factor clamped to [0, 1].
      const float fac = std::clamp(number(node.in(Socket::kFac), point), 0.f, 1.f);
      child(0, weight * (1.f - fac));
      child(1, weight * fac);
      break;
    }
    case ShaderNodeType::kAdd:
      child(0, weight);
      child(1, weight);
      break;
    default:
      visit(node, weight);
  }
}

float GraphShader::coverage(const SurfacePoint& point) const {
  float transparent = 0.f;
  walk(point, [&](const ShaderNode& node, Rgb w) {
    if (node.type == ShaderNodeType::kTransparent)
      transparent += average(w * colour(node.in(Socket::kColor), point));
    else if (node.type == ShaderNodeType::kPrincipled)
      transparent += average(w) * (1.f - principled_alpha(number(node.in(Socket::kAlpha), point)));
  });
  return std::clamp(1.f - transparent, 0.f, 1.f);
}

Rgb GraphShader::emission(const SurfacePoint& point) const {
  Rgb e{};
  walk(point, [&](const ShaderNode& node, Rgb w) {
    if (node.type == ShaderNodeType::kEmission)
      e += w * colour(node.in(Socket::kColor), point) * number(node.in(Socket::kStrength), point);
    else if (node.type == ShaderNodeType::kPrincipled)
      e += w * colour(node.in(Socket::kEmission), point) *
           (number(node.in(Socket::kEmissionStrength), point) *
            principled_alpha(number(node.in(Socket::kAlpha), point)));
  });
  const float kept = coverage(point);
  return kept > 0.f ? max(e, Rgb{}) * (1.f / kept) : Rgb{};
}

void GraphShader::shade(const SurfacePoint& point, fb_hit& hit) const {
  const Vec3f smooth(hit.shading_normal);
  std::copy(hit.shading_normal, hit.shading_normal + 3, hit.smooth_normal);
  bool first = true;
  Rgb base{};
  walk(point, [&](const ShaderNode& node, Rgb) {
    if (!first || node.type == ShaderNodeType::kEmission ||
        node.type == ShaderNodeType::kTransparent)
      return;
    first = false;
    const bool principled = node.type == ShaderNodeType::kPrincipled;
    base = colour(node.in(principled ? Socket::kBaseColor : Socket::kColor), point);
    hit.metallic = principled ? std::clamp(number(node.in(Socket::kMetallic), point), 0.f, 1.f)
                              : float(node.type == ShaderNodeType::kGlossy);
    hit.roughness = std::clamp(number(node.in(Socket::kRoughness), point), 0.f, 1.f);
    hit.transmission = principled
                           ? std::clamp(number(node.in(Socket::kTransmission), point), 0.f, 1.f)
                           : float(node.type == ShaderNodeType::kGlass);
    hit.ior = node.type == ShaderNodeType::kDiffuse ? 1.5f : number(node.in(Socket::kIor), point);
    hit.specular =
        principled ? std::clamp(number(node.in(Socket::kSpecular), point) * 2.f, 0.f, 1.f) : 1.f;
    normal(node.in(Socket::kNormal), point, smooth).store(hit.shading_normal);
  });
  min(max(base, Rgb{}), Rgb{1.f, 1.f, 1.f}).store(hit.base_color);
  emission(point).store(hit.emission);
}

void GraphShader::build(const SurfacePoint& point, const ShadingFrame& frame,
                        Surface& surface) const {
  const float kept = coverage(point);
  if (!(kept > 0.f)) return;
  const float scale = 1.f / kept;
  // Normals on the front side (fb_hit's orientation): the surface turns them to the ray's.
  const Vec3f smooth = frame.backfacing ? -frame.N : frame.N;
  walk(point, [&](const ShaderNode& node, Rgb w) {
    const Rgb weight = w * scale;
    const auto in_colour = [&](Socket s) { return colour(node.in(s), point); };
    const auto in_number = [&](Socket s) { return number(node.in(s), point); };
    const auto in_normal = [&](Socket s) { return normal(node.in(s), point, smooth); };
    switch (node.type) {
      case ShaderNodeType::kPrincipled: {
        PrincipledInputs p;
        p.base_color = in_colour(Socket::kBaseColor);
        p.subsurface = in_number(Socket::kSubsurface);
        p.subsurface_radius = in_colour(Socket::kSubsurfaceRadius);
        p.subsurface_color = in_colour(Socket::kSubsurfaceColor);
        p.subsurface_ior = in_number(Socket::kSubsurfaceIor);
        p.subsurface_anisotropy = in_number(Socket::kSubsurfaceAnisotropy);
        p.metallic = in_number(Socket::kMetallic);
        p.specular = in_number(Socket::kSpecular);
        p.specular_tint = in_number(Socket::kSpecularTint);
        p.roughness = in_number(Socket::kRoughness);
        p.anisotropic = in_number(Socket::kAnisotropic);
        p.anisotropic_rotation = in_number(Socket::kAnisotropicRotation);
        p.sheen = in_number(Socket::kSheen);
        p.sheen_tint = in_number(Socket::kSheenTint);
        p.clearcoat = in_number(Socket::kClearcoat);
        p.clearcoat_roughness = in_number(Socket::kClearcoatRoughness);
        p.ior = in_number(Socket::kIor);
        p.transmission = in_number(Socket::kTransmission);
        p.transmission_roughness = in_number(Socket::kTransmissionRoughness);
        p.normal = in_normal(Socket::kNormal);
        p.clearcoat_normal = in_normal(Socket::kClearcoatNormal);
        p.tangent = default_tangent(point.radial_tangent, smooth);
        p.distribution = node.distribution;
        p.subsurface_method = node.subsurface_method;
        const float alpha = principled_alpha(in_number(Socket::kAlpha));
        surface.add_principled(p, weight * alpha);
        break;
      }
      case ShaderNodeType::kDiffuse:
        surface.add_diffuse(in_colour(Socket::kColor), in_number(Socket::kRoughness),
                            in_normal(Socket::kNormal), weight);
        break;
      case ShaderNodeType::kGlossy:
        surface.add_glossy(node.distribution, in_colour(Socket::kColor),
                           in_number(Socket::kRoughness), in_normal(Socket::kNormal), weight);
        break;
      case ShaderNodeType::kGlass:
        surface.add_glass(node.distribution, in_colour(Socket::kColor),
                          in_number(Socket::kRoughness), in_number(Socket::kIor),
                          in_normal(Socket::kNormal), weight);
        break;
      default:  // emission and transparency are not closures here (emission(), coverage())
        break;
    }
  });
}

bool GraphShader::can_be_transparent(const ShaderGraph& graph) {
  for (const ShaderNode& node : graph.nodes) {
    if (node.type == ShaderNodeType::kTransparent) return true;
    const ShaderInput& alpha = node.in(Socket::kAlpha);
    if (node.type == ShaderNodeType::kPrincipled &&
        (alpha.kind == ShaderInput::Kind::kTexture || alpha.value.x < 1.f))
      return true;
  }
  return false;
}

Rgb GraphShader::emission_bound(const ShaderGraph& graph) {
  // Every node counted with weight 1 (a mix's weights are at most 1 each), textures as 1.
  const auto value = [](const ShaderInput& in) {
    return in.kind == ShaderInput::Kind::kTexture ? Vec3f{1.f, 1.f, 1.f} : max(in.value, Vec3f{});
  };
  Rgb bound{};
  for (const ShaderNode& node : graph.nodes) {
    if (node.type == ShaderNodeType::kEmission)
      bound += value(node.in(Socket::kColor)) * value(node.in(Socket::kStrength)).x;
    else if (node.type == ShaderNodeType::kPrincipled)
      bound += value(node.in(Socket::kEmission)) * value(node.in(Socket::kEmissionStrength)).x;
  }
  return bound;
}

}  // namespace fb
