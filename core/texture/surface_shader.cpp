#include "core/texture/surface_shader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cmath>

#include "core/texture/solid_pattern.h"
#include "core/util/error.h"

namespace fb {

namespace {

// Larger images are refused: a scene file is untrusted, and 2^28 pixels (16384^2) is already more
// than a film-resolution texture needs. The TextureSystem's cache bounds what is held in memory.
constexpr double kMaxPixels = double(1u << 28);

OIIO::TextureOpt::Wrap oiio_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::kClamp:
      return OIIO::TextureOpt::WrapClamp;
    case TextureWrap::kMirror:
      return OIIO::TextureOpt::WrapMirror;
    default:
      return OIIO::TextureOpt::WrapPeriodic;
  }
}

// The extension OpenImageIO picks a reader by, from the embedded image's magic bytes.
std::string embedded_extension(const std::vector<unsigned char>& b) {
  if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "png";
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "jpg";
  return {};
}

}  // namespace

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

struct SurfaceShader::Textures {
  // The cache is made and destroyed here, not left to the TextureSystem: a private cache that
  // OpenImageIO 2.4 made itself leaked when an image was refused before any file was added to it
  // (LeakSanitizer in the sanitized build, SurfaceShader.UnreadableEmbeddedImageIsAnErrorNamingIt).
  OIIO::ImageCache* cache = nullptr;
  OIIO::TextureSystem* system = nullptr;
  struct Image {
    OIIO::TextureSystem::TextureHandle* handle = nullptr;
    int channels = 0;
  };
  std::vector<Image> images;
  std::vector<std::unique_ptr<OIIO::Filesystem::IOMemReader>> readers;  // outlive the cache
  ~Textures() {
    if (system) OIIO::TextureSystem::destroy(system);
    if (cache) OIIO::ImageCache::destroy(cache);
  }
};

SurfaceShader::SurfaceShader(const Scene& scene, const Transform& world_from_render)
    : materials_(scene.materials),
      world_from_render_(world_from_render),
      textures_(std::make_unique<Textures>()) {
  std::vector<bool> used(scene.images.size(), false);
  for (const Material& m : scene.materials)
    for (const TextureRef* t : {&m.textures.base_color, &m.textures.metallic_roughness,
                                &m.textures.normal, &m.textures.emissive})
      if (t->present()) used.at(t->image) = true;
  if (std::find(used.begin(), used.end(), true) == used.end()) return;

  Textures& tx = *textures_;
  tx.cache = OIIO::ImageCache::create(/*shared=*/false);
  tx.system = OIIO::TextureSystem::create(/*shared=*/false, tx.cache);
  // Untiled images (PNG, JPEG) are tiled and mip-mapped in the cache as they are read.
  tx.system->attribute("autotile", 64);
  tx.system->attribute("automip", 1);
  // glTF colours with alpha are straight (unassociated), as PNG stores them: keep them so.
  tx.system->attribute("unassociatedalpha", 1);
  tx.images.resize(scene.images.size());
  for (size_t i = 0; i < scene.images.size(); ++i) {
    if (!used[i]) continue;
    const TextureImage& image = scene.images[i];
    OIIO::ImageSpec config;
    std::string name = image.file.string();
    if (image.file.empty()) {
      const std::string ext = embedded_extension(image.bytes);
      if (ext.empty())
        throw InputError(scene.file.string() + ": " + image.name +
                         ": embedded image is neither PNG nor JPEG (the formats glTF allows)");
      tx.readers.push_back(
          std::make_unique<OIIO::Filesystem::IOMemReader>(image.bytes.data(), image.bytes.size()));
      name = "filmback-embedded-" + std::to_string(i) + "." + ext;
      void* proxy = tx.readers.back().get();
      config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
      auto in = OIIO::ImageInput::open(name, &config);
      if (!in)
        throw InputError(scene.file.string() + ": " + image.name +
                         ": cannot decode the embedded image: " + OIIO::geterror());
      const OIIO::ImageSpec& spec = in->spec();
      if (double(spec.width) * spec.height > kMaxPixels)
        throw InputError(scene.file.string() + ": " + image.name + ": " +
                         std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                         " pixels, more than the 2^28 allowed");
      in->close();
      tx.readers.back()->seek(0);
      tx.system->imagecache()->add_file(OIIO::ustring(name), nullptr, &config);
    } else {
      auto in = OIIO::ImageInput::open(name);
      if (!in)
        throw InputError(scene.file.string() + ": " + image.name + ": cannot read " + name + ": " +
                         OIIO::geterror());
      const OIIO::ImageSpec& spec = in->spec();
      if (double(spec.width) * spec.height > kMaxPixels)
        throw InputError(scene.file.string() + ": " + image.name + ": " +
                         std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                         " pixels, more than the 2^28 allowed");
    }
    Textures::Image& out = tx.images[i];
    out.handle = tx.system->get_texture_handle(OIIO::ustring(name));
    if (!out.handle ||
        !tx.system->get_texture_info(out.handle, nullptr, 0, OIIO::ustring("channels"),
                                     OIIO::TypeInt, &out.channels))
      throw InputError(scene.file.string() + ": " + image.name +
                       ": cannot open it as a texture: " + tx.system->geterror());
  }
}

SurfaceShader::~SurfaceShader() = default;

SolidColour SurfaceShader::solid_colour(const SolidPattern& pattern,
                                        const SurfacePoint& point) const {
  return evaluate_solid(pattern, world_from_render_.point(Vec3d(point.position)));
}

std::array<float, 4> SurfaceShader::lookup(const TextureRef& ref, const SurfacePoint& point,
                                           bool srgb) const {
  const Textures::Image& image = textures_->images[ref.image];
  const Vec2f uv = ref.texcoord < point.uv_sets ? point.uv[ref.texcoord] : Vec2f{0.f, 0.f};
  const auto& m = ref.uv_transform;
  const float s = m[0] * uv.x + m[1] * uv.y + m[2];
  const float t = m[3] * uv.x + m[4] * uv.y + m[5];
  OIIO::TextureOpt opt;
  opt.swrap = oiio_wrap(ref.wrap_s);
  opt.twrap = oiio_wrap(ref.wrap_t);
  opt.interpmode = OIIO::TextureOpt::InterpBilinear;
  opt.fill = 1.f;  // a missing alpha channel is opaque
  // No ray differentials yet: zero derivatives read the finest level, bilinearly. Pixel
  // supersampling does the filtering (docs/blender.md, "Materials").
  std::array<float, 4> rgba{1.f, 1.f, 1.f, 1.f};
  OIIO::TextureSystem* ts = textures_->system;
  ts->texture(image.handle, ts->get_perthread_info(), opt, s, t, 0.f, 0.f, 0.f, 0.f,
              std::min(image.channels, 4), rgba.data());
  if (image.channels <= 2) {  // grey, grey + alpha
    const float alpha = image.channels == 2 ? rgba[1] : 1.f;
    rgba = {rgba[0], rgba[0], rgba[0], alpha};
  }
  if (srgb)
    for (int c = 0; c < 3; ++c)
      rgba[c] = srgb_to_linear(rgba[c]);
  return rgba;
}

void SurfaceShader::shade(uint32_t index, const SurfacePoint& point, fb_hit& hit) const {
  const Material& m = materials_[index];
  Rgb base = m.base_color;
  float metallic = m.metallic, roughness = m.roughness, transmission = m.transmission;
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
  const auto clamp01 = [](float v) { return std::clamp(v, 0.f, 1.f); };
  min(max(base, Rgb{}), Rgb{1.f, 1.f, 1.f}).store(hit.base_color);
  hit.metallic = clamp01(metallic);
  hit.roughness = clamp01(roughness);
  hit.transmission = clamp01(transmission);
  hit.ior = m.ior;
  hit.specular = clamp01(m.specular);
  emission(index, point).store(hit.emission);
}

void SurfaceShader::shade(uint32_t index, const SurfacePoint& point, Vec3f ray_direction,
                          fb_hit& hit, Surface& surface) const {
  shade(index, point, hit);
  const Vec3f I = normalize(-ray_direction);
  const Vec3f ng(hit.geometric_normal);
  const bool backfacing = dot(ng, I) < 0.f;
  const float side = backfacing ? -1.f : 1.f;
  surface.begin({I, ng * side, Vec3f(hit.smooth_normal) * side, backfacing});
  surface.add_gltf({Rgb(hit.base_color), hit.metallic, hit.roughness, hit.transmission, hit.ior,
                    hit.specular, Vec3f(hit.shading_normal)});
}

Rgb SurfaceShader::emission(uint32_t index, const SurfacePoint& point) const {
  const Material& m = materials_[index];
  Rgb emission = m.emission;
  if (m.textures.emissive.present()) {
    const auto c = lookup(m.textures.emissive, point, true);
    emission *= Rgb(c[0], c[1], c[2]);
  }
  return max(emission, Rgb{});
}

float SurfaceShader::alpha(uint32_t index, const SurfacePoint& point) const {
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
