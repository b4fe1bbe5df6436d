#include "core/texture/texture_images.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/util/error.h"

namespace fb {

namespace {

// Larger images are refused: a scene file is untrusted, and 2^28 pixels (16384^2) is already more
// than a film-resolution texture needs. The TextureSystem's cache bounds what is held in memory.
constexpr double kMaxPixels = double(1u << 28);

constexpr float kCacheMegabytes = 256.f;  // OpenImageIO's default, explicit (see below)

// The longest footprint OpenImageIO filters along before it reads a coarser level instead (over-
// blurring rather than aliasing, TextureOpt::conservative_filter). Chosen by measurement on the
// receding ground of tests/bench/texture_filtering_bench.cpp at 4 spp (docs/benchmarks.md,
// "Texture filtering"): 4 probes had the error of 8 and 16 (0.0387 against 0.0386) in half their
// time; 2 probes and isotropic trilinear filtering were cheaper but blurred more (0.049, 0.050).
constexpr int kMaxAnisotropy = 4;

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
  // Per scene image: its MIP-mapped textures, read as stored [0] or from sRGB [1] (levels
  // averaged in linear light); for one read from sRGB, also the file as stored, whose finest level
  // magnified lookups read as Cycles does; and its size in texels.
  struct Entry {
    std::array<Image, 2> mip;
    Image stored;
    float width = 0.f, height = 0.f;
  };
  std::vector<Entry> images;
  // The MIP-mapped textures (tiled OpenEXR in memory) and their readers, which outlive the cache.
  std::vector<std::unique_ptr<std::vector<unsigned char>>> textures;
  std::vector<std::unique_ptr<OIIO::Filesystem::IOMemReader>> readers;
  // Each thread's lookup state (its micro-cache of tiles), made by this system and destroyed with
  // it. OpenImageIO's own per-thread records (get_perthread_info) outlive a private cache in the
  // render loop's long-lived TBB workers, and released tiles into a destroyed cache: a crash in
  // OpenImageIO 2.4 (decr_tiles) when jobs with textures ran one after another.
  mutable tbb::enumerable_thread_specific<OIIO::TextureSystem::Perthread*> thread_info{nullptr};
  OIIO::TextureSystem::Perthread* this_thread() const {
    OIIO::TextureSystem::Perthread*& info = thread_info.local();
    if (!info) info = system->create_thread_info();
    return info;
  }
  ~Impl() {
    for (OIIO::TextureSystem::Perthread* info : thread_info)
      if (info) system->destroy_thread_info(info);
    if (system) OIIO::TextureSystem::destroy(system);
    if (cache) OIIO::ImageCache::destroy(cache);
  }
};

namespace {

// Opens a scene image for reading, from its file or its embedded bytes; refuses one too large.
std::unique_ptr<OIIO::ImageInput> open_image(
    const Scene& scene, const TextureImage& image,
    std::unique_ptr<OIIO::Filesystem::IOMemReader>& reader) {
  OIIO::ImageSpec config;
  // glTF colours with alpha are straight (unassociated), as PNG stores them: read them so, not
  // multiplied by alpha as OpenImageIO's readers otherwise return them.
  config.attribute("oiio:UnassociatedAlpha", 1);
  std::string name = image.file.string();
  if (image.file.empty()) {
    const std::string ext = embedded_extension(image.bytes);
    if (ext.empty())
      throw InputError(scene.file.string() + ": " + image.name +
                       ": embedded image is neither PNG nor JPEG (the formats glTF allows)");
    reader =
        std::make_unique<OIIO::Filesystem::IOMemReader>(image.bytes.data(), image.bytes.size());
    name = "filmback-embedded." + ext;
    void* proxy = reader.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  }
  auto in = OIIO::ImageInput::open(name, &config);
  if (!in)
    throw InputError(scene.file.string() + ": " + image.name + ": cannot " +
                     (image.file.empty() ? "decode the embedded image" : "read " + name) + ": " +
                     OIIO::geterror());
  check_size(scene, image, in->spec());
  return in;
}

// The image's first four channels as half floats, the colour channels (all but a last alpha)
// decoded from sRGB when `srgb`: MIP levels must average light, not its encoding, or a minified
// black-and-white checker turns the grey of sRGB 0.5 (0.21) instead of 0.5. Read in bands of rows,
// so that only the half-float copy is held whole.
OIIO::ImageBuf linear_image(const Scene& scene, const TextureImage& image, OIIO::ImageInput& in,
                            bool srgb) {
  const OIIO::ImageSpec& spec = in.spec();
  const int channels = std::min(spec.nchannels, 4);
  const int colour = channels == 2 || channels == 4 ? channels - 1 : channels;
  OIIO::ImageBuf out(OIIO::ImageSpec(spec.width, spec.height, channels, OIIO::TypeHalf));
  constexpr int kBand = 64;
  std::vector<float> rows(size_t(spec.width) * kBand * channels);
  for (int y0 = 0; y0 < spec.height; y0 += kBand) {
    const int y1 = std::min(y0 + kBand, spec.height);
    if (!in.read_scanlines(0, 0, spec.y + y0, spec.y + y1, 0, 0, channels, OIIO::TypeFloat,
                           rows.data()))
      throw InputError(scene.file.string() + ": " + image.name +
                       ": cannot decode its pixels: " + in.geterror());
    if (srgb)
      for (size_t i = 0; i < size_t(spec.width) * (y1 - y0); ++i)
        for (int c = 0; c < colour; ++c)
          rows[i * channels + c] = srgb_to_linear(rows[i * channels + c]);
    out.set_pixels(OIIO::ROI(0, spec.width, y0, y1, 0, 1, 0, channels), OIIO::TypeFloat,
                   rows.data());
  }
  return out;
}

// A tiled, MIP-mapped OpenEXR of `level0` in memory, each level box-filtered from the one above
// (as OpenImageIO's maketx does), down to one pixel (OpenEXR's MIPMAP_LEVELS, ROUND_DOWN).
std::vector<unsigned char> mip_mapped_exr(OIIO::ImageBuf level) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  OIIO::ImageSpec spec = level.spec();
  spec.tile_width = spec.tile_height = 64;
  spec.attribute("textureformat", "Plain Texture");  // what makes OpenEXR's output keep levels
  spec.attribute("compression", "none");             // read back often: no decoding cost
  void* p = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &p);
  auto out = OIIO::ImageOutput::create("filmback-texture.exr");
  bool ok = out && out->open("filmback-texture.exr", spec) && level.write(out.get());
  for (int w = spec.width, h = spec.height; ok && (w > 1 || h > 1);) {
    w = std::max(1, w / 2), h = std::max(1, h / 2);
    OIIO::ImageBuf next(OIIO::ImageSpec(w, h, spec.nchannels, OIIO::TypeHalf));
    OIIO::ImageSpec level_spec = spec;
    level_spec.width = level_spec.full_width = w;
    level_spec.height = level_spec.full_height = h;
    ok = OIIO::ImageBufAlgo::resize(next, level, "box") &&
         out->open("filmback-texture.exr", level_spec, OIIO::ImageOutput::AppendMIPLevel) &&
         next.write(out.get());
    level.swap(next);
  }
  ok = ok && out->close();
  if (!ok) throw std::runtime_error("cannot build a texture's MIP levels: " + OIIO::geterror());
  return bytes;
}

}  // namespace

TextureImages::TextureImages(const Scene& scene, const std::vector<uint8_t>& uses)
    : impl_(std::make_unique<Impl>()) {
  if (std::all_of(uses.begin(), uses.end(), [](uint8_t u) { return u == 0; })) return;
  Impl& tx = *impl_;
  tx.cache = OIIO::ImageCache::create(/*shared=*/false);
  tx.system = OIIO::TextureSystem::create(/*shared=*/false, tx.cache);
  // Every image is decoded here into a tiled, MIP-mapped texture of linear half floats held in
  // memory (mip_mapped_exr), rather than left to OpenImageIO's automip, which averages the sRGB
  // encoding and, with autotile, read past its tiles in OpenImageIO 2.4 when footprints reached
  // the coarse levels. The tile cache keeps OpenImageIO's default of 256 MB, said here because it
  // bounds what is decoded from those textures at once.
  tx.system->attribute("max_memory_MB", kCacheMegabytes);
  // Stored images (PNG, JPEG), read at their finest level only, are tiled in the cache as they are
  // read; glTF colours with alpha are straight (unassociated), as PNG stores them: keep them so.
  tx.system->attribute("autotile", 64);
  tx.system->attribute("unassociatedalpha", 1);
  const auto open_texture = [&](const TextureImage& image, const std::string& name,
                                OIIO::Filesystem::IOMemReader* reader, Impl::Image& out) {
    if (reader) {
      OIIO::ImageSpec config;
      void* proxy = reader;
      config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
      tx.system->imagecache()->add_file(OIIO::ustring(name), nullptr, &config);
    }
    out.handle = tx.system->get_texture_handle(OIIO::ustring(name));
    if (!out.handle ||
        !tx.system->get_texture_info(out.handle, nullptr, 0, OIIO::ustring("channels"),
                                     OIIO::TypeInt, &out.channels))
      throw InputError(scene.file.string() + ": " + image.name +
                       ": cannot open it as a texture: " + tx.system->geterror());
  };
  tx.images.resize(scene.images.size());
  for (size_t i = 0; i < scene.images.size(); ++i) {
    const TextureImage& image = scene.images[i];
    Impl::Entry& entry = tx.images[i];
    for (const bool srgb : {false, true}) {
      if (!(uses[i] & (srgb ? kReadFromSrgb : kReadLinear))) continue;
      std::unique_ptr<OIIO::Filesystem::IOMemReader> source;
      const auto in = open_image(scene, image, source);
      entry.width = float(in->spec().width), entry.height = float(in->spec().height);
      tx.textures.push_back(std::make_unique<std::vector<unsigned char>>(
          mip_mapped_exr(linear_image(scene, image, *in, srgb))));
      tx.readers.push_back(std::make_unique<OIIO::Filesystem::IOMemReader>(
          tx.textures.back()->data(), tx.textures.back()->size()));
      open_texture(image,
                   "filmback-texture-" + std::to_string(i) + (srgb ? "-srgb" : "-linear") + ".exr",
                   tx.readers.back().get(), entry.mip[srgb]);
      if (!srgb) continue;
      in->close();
      if (source) {
        source->seek(0);
        tx.readers.push_back(std::move(source));
        open_texture(
            image, "filmback-embedded-" + std::to_string(i) + "." + embedded_extension(image.bytes),
            tx.readers.back().get(), entry.stored);
      } else {
        open_texture(image, image.file.string(), nullptr, entry.stored);
      }
    }
  }
}

TextureImages::~TextureImages() = default;

std::array<float, 4> TextureImages::rgba(const TextureLookup& l) const {
  const Impl::Entry& entry = impl_->images[l.image];
  // A footprint within one texel (or none) reads the finest level: an image read from sRGB then
  // from its stored values, interpolated before they are decoded as Cycles interpolates them
  // (svm_node_tex_image), so that a magnified texture renders as before and as Cycles renders
  // it. A wider footprint filters the levels made in linear light.
  const float texels = std::max(std::hypot(l.ds_dx * entry.width, l.dt_dx * entry.height),
                                std::hypot(l.ds_dy * entry.width, l.dt_dy * entry.height));
  const bool stored = l.srgb && !(texels > 1.f);
  const Impl::Image& image = stored ? entry.stored : entry.mip[l.srgb];
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
  if (stored)
    ts->texture(image.handle, impl_->this_thread(), opt, l.s, l.t, 0.f, 0.f, 0.f, 0.f,
                std::min(image.channels, 4), rgba.data());
  else
    ts->texture(image.handle, impl_->this_thread(), opt, l.s, l.t, l.ds_dx, l.dt_dx, l.ds_dy,
                l.dt_dy, std::min(image.channels, 4), rgba.data());
  if (image.channels <= 2) {  // grey, grey + alpha
    const float alpha = image.channels == 2 ? rgba[1] : 1.f;
    rgba = {rgba[0], rgba[0], rgba[0], alpha};
  }
  if (stored)
    for (int c = 0; c < 3; ++c)
      rgba[c] = srgb_to_linear(rgba[c]);
  return rgba;
}

}  // namespace fb
