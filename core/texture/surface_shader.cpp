#include "core/texture/surface_shader.h"

#include <algorithm>
#include <cmath>

#include "core/texture/solid_image_map.h"
#include "core/texture/solid_normal.h"
#include "core/texture/solid_pattern.h"
#include "core/util/error.h"

namespace fb {

namespace {

// How each image is read (TextureImages::kReadLinear, kReadFromSrgb): colours and emission from
// sRGB (glTF 2.0 §3.9.2), the rest as stored; a shader graph's texture as its node says; a POV-Ray
// image map as its file's gamma says.
std::vector<uint8_t> image_uses(const Scene& scene) {
  std::vector<uint8_t> uses(scene.images.size(), 0);
  const auto mark = [&uses](const TextureRef& t, bool srgb) {
    if (t.present())
      uses.at(t.image) |= srgb ? TextureImages::kReadFromSrgb : TextureImages::kReadLinear;
  };
  const auto mark_patterns = [&uses](const Material& m) {
    if (m.base_color_pattern) mark_image_map_uses(*m.base_color_pattern, uses);
  };
  for (const Material& m : scene.materials) {
    mark_patterns(m);
    for (const Material& layer : m.layers)
      mark_patterns(layer);
    mark(m.textures.base_color, true);
    mark(m.textures.emissive, true);
    mark(m.textures.metallic_roughness, false);
    mark(m.textures.normal, false);
    if (m.shader_graph)
      for (const ImageTextureNode& t : m.shader_graph->textures)
        uses.at(t.image) |= t.srgb ? TextureImages::kReadFromSrgb : TextureImages::kReadLinear;
  }
  return uses;
}

// The normal pattern that bends the shading normal: the topmost layer's that has one (POV-Ray
// lights each layer with its own normal; one shading normal serves them all here).
const SolidNormal* top_normal_pattern(const Material& m) {
  for (auto layer = m.layers.rbegin(); layer != m.layers.rend(); ++layer)
    if (layer->normal_pattern) return &*layer->normal_pattern;
  return m.normal_pattern ? &*m.normal_pattern : nullptr;
}

}  // namespace

SurfaceShader::SurfaceShader(const Scene& scene, const Transform& world_from_render)
    : materials_(scene.materials),
      world_from_render_(world_from_render),
      images_(scene, image_uses(scene)) {
  for (const Material& m : materials_)
    if (m.shader_graph)
      graphs_.emplace_back(std::in_place, *m.shader_graph, images_);
    else
      graphs_.emplace_back();
}

SolidColour SurfaceShader::solid_colour(const SolidPattern& pattern,
                                        const SurfacePoint& point) const {
  return evaluate_solid(pattern, world_from_render_.point(Vec3d(point.position)), &images_);
}

SurfaceShader::LayerCover SurfaceShader::layer_cover(const Material& layer,
                                                     const SurfacePoint& point) const {
  // a layer without a pattern is an opaque one of its base colour
  const SolidColour c = layer.base_color_pattern ? solid_colour(*layer.base_color_pattern, point)
                                                 : SolidColour{{1.f, 1.f, 1.f}, 0.f, 0.f};
  return {c.rgb, std::clamp(1.f - c.filter - c.transmit, 0.f, 1.f),
          c.rgb * c.filter + Rgb{c.transmit, c.transmit, c.transmit}};
}

std::array<float, 4> SurfaceShader::lookup(const TextureRef& ref, const SurfacePoint& point,
                                           bool srgb) const {
  TextureLookup lookup(ref.image, texture_position(point, ref.texcoord, ref.uv_transform));
  lookup.wrap_s = ref.wrap_s;
  lookup.wrap_t = ref.wrap_t;
  lookup.srgb = srgb;
  return images_.rgba(lookup);
}

void SurfaceShader::shade(uint32_t index, const SurfacePoint& point, fb_hit& hit) const {
  if (graphs_[index]) return graphs_[index]->shade(point, hit);
  const Material& m = materials_[index];
  Rgb base = m.base_color;
  float metallic = m.metallic, roughness = m.roughness, transmission = m.transmission;
  float specular = m.specular, ior = m.ior;
  if (m.base_color_pattern) {
    const SolidColour c = solid_colour(*m.base_color_pattern, point);
    base *= c.rgb;
    transmission = std::max(transmission, c.filter);
  }
  const MaterialTextures& t = m.textures;
  if (t.base_color.present()) {
    const auto c = lookup(t.base_color, point, true);
    base *= Rgb(c[0], c[1], c[2]);
  }
  if (t.metallic_roughness.present()) {
    const auto c = lookup(t.metallic_roughness, point, false);
    roughness *= c[1];
    metallic *= c[2];
  }
  // POV-Ray's layered textures, bottom up: each layer covers what is below by 1 - filter -
  // transmit of its pigment at the hit and lets the rest through, tinted by filter times its
  // colour (POV-Ray's layer loop in Compute_Lighted_Texture). Metallic and transmission take the
  // covered share; the strongest highlight (with its ior, which sets its Fresnel F0) wins whatever
  // its layer's coverage, as POV-Ray adds every layer's highlights unweighted (a clear top layer
  // with phong is a clear coat).
  for (const Material& layer : m.layers) {
    const LayerCover c = layer_cover(layer, point);
    base = layer.base_color * c.colour * c.cover + base * c.through;
    metallic += (layer.metallic - metallic) * c.cover;
    transmission += (layer.transmission - transmission) * c.cover;
    if (layer.specular > specular)
      specular = layer.specular, roughness = layer.roughness, ior = layer.ior;
  }
  std::copy(hit.shading_normal, hit.shading_normal + 3, hit.smooth_normal);
  if (t.normal.present() && dot(point.tangent, point.tangent) > 0.f) {
    const auto c = lookup(t.normal, point, false);
    // glTF 2.0 §3.9.3: n = normalize((2 rgb - 1) * (scale, scale, 1)) in the (T, B, N) frame,
    // B = w (N x T); T re-orthogonalised against the interpolated N (Gram-Schmidt).
    const Vec3f n(hit.shading_normal);
    Vec3f tangent = point.tangent - n * dot(n, point.tangent);
    const float len = length(tangent);
    if (len > 0.f) {
      tangent = tangent / len;
      const Vec3f bitangent = cross(n, tangent) * point.bitangent_sign;
      const Vec3f local{(2.f * c[0] - 1.f) * t.normal_scale, (2.f * c[1] - 1.f) * t.normal_scale,
                        2.f * c[2] - 1.f};
      const Vec3f mapped = tangent * local.x + bitangent * local.y + n * local.z;
      const float mapped_len = length(mapped);
      if (mapped_len > 0.f && std::isfinite(mapped_len))
        (mapped / mapped_len).store(hit.shading_normal);
    }
  }
  if (const SolidNormal* bump = top_normal_pattern(m)) {
    // Render space is the world translated (RenderGeometry): normals are the same in both.
    const Vec3d bent = perturbed_normal(*bump, world_from_render_.point(Vec3d(point.position)),
                                        Vec3d(Vec3f(hit.shading_normal)));
    Vec3f(bent).store(hit.shading_normal);
  }
  const auto clamp01 = [](float v) { return std::clamp(v, 0.f, 1.f); };
  min(max(base, Rgb{}), Rgb{1.f, 1.f, 1.f}).store(hit.base_color);
  hit.metallic = clamp01(metallic);
  hit.roughness = clamp01(roughness);
  hit.transmission = clamp01(transmission);
  hit.ior = ior;
  hit.specular = clamp01(specular);
  emission(index, point).store(hit.emission);
}

void SurfaceShader::shade(uint32_t index, const SurfacePoint& point, Vec3f ray_direction,
                          bool camera_ray, fb_hit& hit, Surface& surface) const {
  shade(index, point, hit);
  const Vec3f I = normalize(-ray_direction);
  const Vec3f ng(hit.geometric_normal);
  const bool backfacing = dot(ng, I) < 0.f;
  const float side = backfacing ? -1.f : 1.f;
  const ShadingFrame frame{I, ng * side, Vec3f(hit.smooth_normal) * side, backfacing, camera_ray};
  surface.begin(frame);
  if (graphs_[index]) return graphs_[index]->build(point, frame, surface);
  surface.add_gltf({Rgb(hit.base_color), hit.metallic, hit.roughness, hit.transmission, hit.ior,
                    hit.specular, Vec3f(hit.shading_normal)});
}

Rgb SurfaceShader::emission(uint32_t index, const SurfacePoint& point) const {
  if (graphs_[index]) return graphs_[index]->emission(point);
  const Material& m = materials_[index];
  Rgb emission = m.emission;
  if (m.textures.emissive.present()) {
    const auto c = lookup(m.textures.emissive, point, true);
    emission *= Rgb(c[0], c[1], c[2]);
  }
  // The pattern only where something glows: shade() asks this at every hit.
  if (m.base_color_pattern && max_component(emission) > 0.f)
    emission *= solid_colour(*m.base_color_pattern, point).rgb;
  for (const Material& layer : m.layers) {
    if (max_component(emission) == 0.f && max_component(layer.emission) == 0.f) continue;
    const LayerCover c = layer_cover(layer, point);
    emission = layer.emission * c.colour * c.cover + emission * c.through;
  }
  return max(emission, Rgb{});
}

float SurfaceShader::alpha(uint32_t index, const SurfacePoint& point) const {
  if (graphs_[index]) return graphs_[index]->coverage(point);
  const Material& m = materials_[index];
  float a = m.alpha;
  if (m.textures.base_color.present()) a *= lookup(m.textures.base_color, point, true)[3];
  if (m.base_color_pattern) a *= 1.f - solid_colour(*m.base_color_pattern, point).transmit;
  return a;
}

bool SurfaceShader::covers(uint32_t index, const SurfacePoint& point, uint64_t hit_hash) const {
  const Material& m = materials_[index];
  if (m.alpha_mode == AlphaMode::kOpaque) return true;
  const float a = alpha(index, point);
  if (m.alpha_mode == AlphaMode::kMask) return a >= m.alpha_cutoff;
  return float(hit_hash >> 40) * 0x1p-24f < a;  // the top 24 bits: a uniform float in [0, 1)
}

}  // namespace fb
