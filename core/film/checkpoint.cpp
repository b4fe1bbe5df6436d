#include "core/film/checkpoint.h"

#include <OpenImageIO/imageio.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/util/error.h"
#include "core/util/temporary_file.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

constexpr int kVersion = 1;

// The checkpoint's channels, in file order: each sum and the weight as two halves of a double,
// then the sample count.
std::vector<std::string> channel_names(const Film& film) {
  std::vector<std::string> names;
  for (const std::string& c : film.channels()) {
    names.push_back("sum." + c + ".hi");
    names.push_back("sum." + c + ".lo");
  }
  names.insert(names.end(), {"weight.hi", "weight.lo", "samples"});
  return names;
}

void split(double v, uint32_t* out) {
  const uint64_t bits = std::bit_cast<uint64_t>(v);
  out[0] = uint32_t(bits >> 32);
  out[1] = uint32_t(bits);
}
double join(const uint32_t* in) {
  return std::bit_cast<double>(uint64_t(in[0]) << 32 | in[1]);
}

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw InputError(located(file.string(), "", "cannot resume from this checkpoint: " + why));
}

}  // namespace

void write_checkpoint(const Film& film, const std::string& key, const fs::path& file) {
  const size_t n = film.channels().size(), stride = 2 * n + 3;
  std::vector<uint32_t> pixels(film.pixel_count() * stride);
  for (size_t i = 0; i < film.pixel_count(); ++i) {
    uint32_t* p = &pixels[i * stride];
    for (size_t c = 0; c < n; ++c)
      split(film.sums()[i * n + c], p + 2 * c);
    split(film.weights()[i], p + 2 * n);
    p[2 * n + 2] = film.sample_counts()[i];
  }
  OIIO::ImageSpec spec(int(film.width()), int(film.height()), int(stride), OIIO::TypeDesc::UINT32);
  spec.channelnames = channel_names(film);
  spec.attribute("compression", "zip");
  spec.attribute("filmback/checkpoint_version", kVersion);
  spec.attribute("filmback/checkpoint_key", key);
  write_atomically(file, [&](const fs::path& temporary) -> std::string {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) return OIIO::geterror();
    if (!out->open(temporary.string(), spec)) return out->geterror();
    std::string why =
        out->write_image(OIIO::TypeDesc::UINT32, pixels.data()) ? "" : out->geterror();
    if (!out->close() && why.empty()) why = out->geterror();
    return why;
  });
}

void read_checkpoint(const fs::path& file, const std::string& key, uint32_t samples_per_pixel,
                     uint32_t tile_size, Film& film) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) fail(file, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.get_int_attribute("filmback/checkpoint_version") != kVersion)
    fail(file, "it is not a filmback checkpoint (version " + std::to_string(kVersion) + ")");
  if (spec.get_string_attribute("filmback/checkpoint_key") != key)
    fail(file,
         "it was written for another render (the scene file or the render's settings "
         "differ: the same scene, options and seed are needed)");
  if (spec.width != int(film.width()) || spec.height != int(film.height()))
    fail(file, "its size differs from the render's");
  const std::vector<std::string> names = channel_names(film);
  std::vector<int> index;
  for (const std::string& name : names) {
    index.push_back(spec.channelindex(name));  // OpenEXR sorts channels by name: look each up
    if (index.back() < 0) fail(file, "channel '" + name + "' is missing");
  }
  std::vector<uint32_t> pixels(film.pixel_count() * size_t(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT32, pixels.data()))
    fail(file, in->geterror());
  const size_t n = film.channels().size(), stride = size_t(spec.nchannels);
  for (size_t i = 0; i < film.pixel_count(); ++i) {
    const uint32_t* p = &pixels[i * stride];
    const auto pair = [&](size_t first) {
      const uint32_t halves[2] = {p[index[first]], p[index[first + 1]]};
      return join(halves);
    };
    for (size_t c = 0; c < n; ++c)
      film.sums()[i * n + c] = pair(2 * c);
    film.weights()[i] = pair(2 * n);
    film.sample_counts()[i] = p[index[2 * n + 2]];
    bool finite = std::isfinite(film.weights()[i]);
    for (size_t c = 0; c < n; ++c)
      finite = finite && std::isfinite(film.sums()[i * n + c]);
    if (!finite)
      fail(file, "pixel " + std::to_string(i % film.width()) + "," +
                     std::to_string(i / film.width()) + " holds a non-finite sum");
  }
  for (uint32_t y = 0; y < film.height(); ++y)
    for (uint32_t x = 0; x < film.width(); ++x) {
      const uint32_t count = film.sample_count(x, y);
      const uint32_t tile_count = film.sample_count(x - x % tile_size, y - y % tile_size);
      if (count > samples_per_pixel || count != tile_count)
        fail(file, "pixel " + std::to_string(x) + "," + std::to_string(y) + " has " +
                       std::to_string(count) + " samples, which a render of " +
                       std::to_string(samples_per_pixel) + " per pixel cannot have left");
    }
}

}  // namespace fb
