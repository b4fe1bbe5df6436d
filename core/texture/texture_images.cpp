#include "core/texture/texture_images.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cmath>

#include "core/util/error.h"

namespace fb {

namespace {

// Larger images are refused: a scene file is untrusted, and 2^28 pixels (16384^2) is already more
// than a film-resolution texture needs. The TextureSystem's cache bounds what is held in memory.
constexpr double kMaxPixels = double(1u << 28);

constexpr float kCacheMegabytes = 256.f;  // OpenImageIO's default, explicit (see below)

// The longest footprint OpenImageIO filters along before it reads a coarser level instead (over-
// blurring rather than aliasing, TextureOpt::conservative_filter). 16 probes: a ground seen at 4
// degrees, the grazing part of a shot receding to the horizon, is still sharp across; its default
// of 32 doubles the cost of those lookups for what a pixel filter cannot tell apart.
constexpr int kMaxAnisotropy = 16;

OIIO::TextureOpt::Wrap oiio_wrap(TextureWrap w) {
  switch (w) {
    case TextureWrap::kClamp:
      return OIIO::TextureOpt::WrapClamp;
    case TextureWrap::kMirror:
      return OIIO::TextureOpt::WrapMirror;
    case TextureWrap::kBlack:
      return OIIO::TextureOpt::WrapBlack;
    default:
      return OIIO::TextureOpt::WrapPeriodic;
  }
}

OIIO::TextureOpt::InterpMode oiio_interpolation(TextureInterpolation i) {
  switch (i) {
    case TextureInterpolation::kClosest:
      return OIIO::TextureOpt::InterpClosest;
    case TextureInterpolation::kCubic:
      return OIIO::TextureOpt::InterpBicubic;
    default:
      return OIIO::TextureOpt::InterpBilinear;
  }
}

// The extension OpenImageIO picks a reader by, from the embedded image's magic bytes.
std::string embedded_extension(const std::vector<unsigned char>& b) {
  if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return "png";
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "jpg";
  return {};
}

void check_size(const Scene& scene, const TextureImage& image, const OIIO::ImageSpec& spec) {
  if (double(spec.width) * spec.height > kMaxPixels)
    throw InputError(scene.file.string() + ": " + image.name + ": " + std::to_string(spec.width) +
                     "x" + std::to_string(spec.height) + " pixels, more than the 2^28 allowed");
}

}  // namespace

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

struct TextureImages::Impl {
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
  ~Impl() {
    if (system) OIIO::TextureSystem::destroy(system);
    if (cache) OIIO::ImageCache::destroy(cache);
  }
};

TextureImages::TextureImages(const Scene& scene, const std::vector<bool>& used)
    : impl_(std::make_unique<Impl>()) {
  if (std::find(used.begin(), used.end(), true) == used.end()) return;
  Impl& tx = *impl_;
  tx.cache = OIIO::ImageCache::create(/*shared=*/false);
  tx.system = OIIO::TextureSystem::create(/*shared=*/false, tx.cache);
  // Untiled images (PNG, JPEG) are tiled and mip-mapped in the cache as they are read: automip
  // builds a coarser level only when a lookup's footprint asks for it, so a magnified texture
  // costs no more than before. The tile cache keeps OpenImageIO's default of 256 MB, said here
  // because it bounds the memory every image of a scene takes together (the textures of a
  // film-resolution shot fit; more is re-read from the file, not held).
  tx.system->attribute("autotile", 64);
  tx.system->attribute("automip", 1);
  tx.system->attribute("max_memory_MB", kCacheMegabytes);
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
      check_size(scene, image, in->spec());
      in->close();
      tx.readers.back()->seek(0);
      tx.system->imagecache()->add_file(OIIO::ustring(name), nullptr, &config);
    } else {
      auto in = OIIO::ImageInput::open(name);
      if (!in)
        throw InputError(scene.file.string() + ": " + image.name + ": cannot read " + name + ": " +
                         OIIO::geterror());
      check_size(scene, image, in->spec());
    }
    Impl::Image& out = tx.images[i];
    out.handle = tx.system->get_texture_handle(OIIO::ustring(name));
    if (!out.handle ||
        !tx.system->get_texture_info(out.handle, nullptr, 0, OIIO::ustring("channels"),
                                     OIIO::TypeInt, &out.channels))
      throw InputError(scene.file.string() + ": " + image.name +
                       ": cannot open it as a texture: " + tx.system->geterror());
  }
}

TextureImages::~TextureImages() = default;

std::array<float, 4> TextureImages::rgba(const TextureLookup& l) const {
  const Impl::Image& image = impl_->images[l.image];
  OIIO::TextureOpt opt;
  opt.swrap = oiio_wrap(l.wrap_s);
  opt.twrap = oiio_wrap(l.wrap_t);
  opt.interpmode = oiio_interpolation(l.interpolation);
  opt.fill = 1.f;  // a missing alpha channel is opaque
  opt.anisotropic = kMaxAnisotropy;
  // The footprint (core/texture/ray_footprint.h) picks the MIP level and the anisotropic filter;
  // zero derivatives read the finest level.
  std::array<float, 4> rgba{1.f, 1.f, 1.f, 1.f};
  OIIO::TextureSystem* ts = impl_->system;
  ts->texture(image.handle, ts->get_perthread_info(), opt, l.s, l.t, l.ds_dx, l.dt_dx, l.ds_dy,
              l.dt_dy, std::min(image.channels, 4), rgba.data());
  if (image.channels <= 2) {  // grey, grey + alpha
    const float alpha = image.channels == 2 ? rgba[1] : 1.f;
    rgba = {rgba[0], rgba[0], rgba[0], alpha};
  }
  if (l.srgb)
    for (int c = 0; c < 3; ++c)
      rgba[c] = srgb_to_linear(rgba[c]);
  return rgba;
}

}  // namespace fb
