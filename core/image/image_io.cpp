#include "core/image/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/util/error.h"
#include "core/util/temporary_file.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

OIIO::ImageSpec spec_for(const Image& image, ImageFormat format, const ImageMetadata& metadata,
                         const DisplayTransform& display) {
  const bool bytes = is_8_bit(format);
  OIIO::ImageSpec spec(int(image.width), int(image.height), bytes ? 3 : int(image.channels.size()),
                       bytes ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
  if (format == ImageFormat::kExr) {
    spec.channelnames = image.channels;
    spec.attribute("compression", "zip");
  } else {
    spec.channelnames = {"R", "G", "B"};
    if (display.srgb_encoded()) spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("filmback/transfer", display.description());
    if (format == ImageFormat::kJpeg)
      spec.attribute("Compression", "jpeg:90");  // Blender's default
  }
  for (const auto& [name, m] : metadata.matrices) {
    // Imath's M44f multiplies row vectors (p' = p M): store the transpose.
    std::array<float, 16> imath;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        imath[c * 4 + r] = m[r * 4 + c];
    spec.attribute(name, OIIO::TypeMatrix44, imath.data());
  }
  for (const auto& [name, v] : metadata.floats)
    spec.attribute(name, v);
  for (const auto& [name, v] : metadata.ints)
    spec.attribute(name, v);
  for (const auto& [name, v] : metadata.strings)
    spec.attribute(name, v);
  return spec;
}

// Writes `file`'s content to `temporary`; returns what went wrong, or an empty string.
std::string write_temporary(const Image& image, const fs::path& file, const fs::path& temporary,
                            const ImageMetadata& metadata, const DisplayTransform& display) {
  const ImageFormat format = image_format_for(file);
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) return OIIO::geterror();
  if (!out->open(temporary.string(), spec_for(image, format, metadata, display)))
    return out->geterror();
  const bool written = is_8_bit(format)
                           ? out->write_image(OIIO::TypeDesc::UINT8, display.encode(image).data())
                           : out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  std::string why = written ? "" : out->geterror();
  if (!out->close() && why.empty()) why = out->geterror();
  return why;
}

}  // namespace

ImageFormat image_format_for(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".exr") return ImageFormat::kExr;
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::kJpeg;
  throw UsageError("output '" + file.string() + "': unknown image type '" + ext +
                   "' (expected .exr, .png, .jpg or .jpeg)");
}

void write_images(const Image& image, const std::vector<fs::path>& files,
                  const ImageMetadata& metadata, const DisplayTransform& display) {
  auto fail = [](const fs::path& file, const std::string& why) {
    return InputError(located(file.string(), "", "cannot write the image: " + why));
  };
  std::vector<std::unique_ptr<TemporaryFile>> temporaries;  // removed unless committed
  for (const fs::path& file : files) {
    std::error_code ec;
    if (fs::is_directory(file, ec)) throw fail(file, "it is a folder");
    temporaries.push_back(std::make_unique<TemporaryFile>(file));
    if (std::string why =
            write_temporary(image, file, temporaries.back()->path(), metadata, display);
        !why.empty())
      throw fail(file, why);
  }
  // Move each old file aside, then the new one in; if any step fails, undo in reverse, so the
  // folder ends as it began: all new images, or all old ones.
  std::vector<fs::path> previous(files.size());  // empty where no file was there before
  std::string why;
  size_t installed = 0;
  for (; installed < files.size(); ++installed) {
    const fs::path& file = files[installed];
    std::error_code ec;
    if (fs::exists(file, ec)) {
      fs::path aside = temporaries[installed]->path();
      aside += ".previous";
      fs::rename(file, aside, ec);
      if (ec) {
        why = ec.message();
        break;
      }
      previous[installed] = aside;
    }
    if (!temporaries[installed]->commit(why)) {
      std::error_code ignored;
      if (!previous[installed].empty()) fs::rename(previous[installed], file, ignored);
      break;
    }
  }
  if (installed < files.size()) {
    for (size_t i = installed; i-- > 0;) {
      std::error_code ignored;
      if (previous[i].empty())
        fs::remove(files[i], ignored);
      else
        fs::rename(previous[i], files[i], ignored);
    }
    throw fail(files[installed], why);
  }
  for (const fs::path& aside : previous) {
    std::error_code ignored;
    if (!aside.empty()) fs::remove(aside, ignored);
  }
}

bool is_finished_image(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) {
    OIIO::geterror();  // read, so that OIIO's error does not show up in a later message
    return false;
  }
  return in->spec().get_int_attribute("filmback/interrupted", 0) == 0;
}

Image read_image(const fs::path& file, size_t max_pixels) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in)
    throw InputError(located(file.string(), "", "cannot read the image: " + OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      double(spec.width) * spec.height > double(max_pixels))
    throw InputError(located(file.string(), "",
                             "the image is " + std::to_string(spec.width) + "x" +
                                 std::to_string(spec.height) + " pixels; expected at most " +
                                 std::to_string(max_pixels)));
  Image image{uint32_t(spec.width), uint32_t(spec.height), spec.channelnames, {}};
  image.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw InputError(located(file.string(), "", "cannot read the image: " + in->geterror()));
  return image;
}

}  // namespace fb
