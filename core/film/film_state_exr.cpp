#include "core/film/film_state_exr.h"

#include <bit>
#include <cmath>

#include "core/util/temporary_file.h"

namespace fb {

std::vector<std::string> film_state_channels(const std::vector<std::string>& channels,
                                             bool with_counts) {
  std::vector<std::string> names;
  for (const std::string& c : channels) {
    names.push_back("sum." + c + ".hi");
    names.push_back("sum." + c + ".lo");
  }
  names.insert(names.end(), {"weight.hi", "weight.lo"});
  if (with_counts) names.push_back("samples");
  return names;
}

namespace {

void split(double v, uint32_t* out) {
  const uint64_t bits = std::bit_cast<uint64_t>(v);
  out[0] = uint32_t(bits >> 32);
  out[1] = uint32_t(bits);
}

double join(uint32_t hi, uint32_t lo) {
  return std::bit_cast<double>(uint64_t(hi) << 32 | lo);
}

}  // namespace

void pack_sums(const double* sums, double weight, size_t channels, uint32_t* out) {
  for (size_t c = 0; c < channels; ++c)
    split(sums[c], out + 2 * c);
  split(weight, out + 2 * channels);
}

bool unpack_sums(const uint32_t* in, const std::vector<int>& index, size_t channels, double* sums,
                 double& weight) {
  bool finite = true;
  for (size_t c = 0; c <= channels; ++c) {
    const double v = join(in[index[2 * c]], in[index[2 * c + 1]]);
    finite = finite && std::isfinite(v);
    (c < channels ? sums[c] : weight) = v;
  }
  return finite;
}

OIIO::ImageSpec film_state_spec(const Film& film, const PixelRect& region) {
  const std::vector<std::string> names = film_state_channels(film.channels(), true);
  OIIO::ImageSpec spec(int(region.width()), int(region.height()), int(names.size()),
                       OIIO::TypeDesc::UINT32);
  spec.x = int(region.x0), spec.y = int(region.y0);
  spec.full_x = 0, spec.full_y = 0;
  spec.full_width = int(film.width()), spec.full_height = int(film.height());
  spec.channelnames = names;
  spec.attribute("compression", "zip");
  return spec;
}

std::vector<uint32_t> encode_film_state(const Film& film, const PixelRect& region) {
  const size_t n = film.channels().size(), stride = 2 * n + 3;
  std::vector<uint32_t> pixels(region.area() * stride);
  uint32_t* p = pixels.data();
  for (uint32_t y = region.y0; y < region.y1; ++y)
    for (uint32_t x = region.x0; x < region.x1; ++x, p += stride) {
      const size_t i = size_t(y) * film.width() + x;
      pack_sums(&film.sums()[i * n], film.weights()[i], n, p);
      p[stride - 1] = film.sample_counts()[i];
    }
  return pixels;
}

std::string channel_positions(const OIIO::ImageSpec& spec, const std::vector<std::string>& names,
                              std::vector<int>& index) {
  index.clear();
  for (const std::string& name : names) {
    index.push_back(spec.channelindex(name));
    if (index.back() < 0) return "channel '" + name + "' is missing";
  }
  return "";
}

void write_state_images(const std::filesystem::path& file, const std::vector<StateImage>& images) {
  write_atomically(file, [&](const std::filesystem::path& temporary) -> std::string {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) return OIIO::geterror();
    std::vector<OIIO::ImageSpec> specs;
    for (const StateImage& image : images)
      specs.push_back(image.spec);
    if (!out->open(temporary.string(), int(specs.size()), specs.data())) return out->geterror();
    std::string why;
    for (size_t i = 0; i < images.size() && why.empty(); ++i)
      if ((i > 0 && !out->open(temporary.string(), specs[i], OIIO::ImageOutput::AppendSubimage)) ||
          !out->write_image(OIIO::TypeDesc::UINT32, images[i].pixels))
        why = out->geterror();
    if (!out->close() && why.empty()) why = out->geterror();
    return why;
  });
}

PixelRect data_window(const OIIO::ImageSpec& spec) {
  const uint32_t x0 = uint32_t(std::max(spec.x, 0)), y0 = uint32_t(std::max(spec.y, 0));
  return {x0, y0, x0 + uint32_t(spec.width), y0 + uint32_t(spec.height)};
}

std::string read_state_words(OIIO::ImageInput& in, const PixelRect& region,
                             std::vector<uint32_t>& words) {
  const OIIO::ImageSpec& spec = in.spec();
  words.resize(region.area() * size_t(spec.nchannels));
  if (!in.read_image(in.current_subimage(), 0, 0, spec.nchannels, OIIO::TypeDesc::UINT32,
                     words.data()))
    return in.geterror();
  return "";
}

std::string decode_film_state(OIIO::ImageInput& in, const PixelRect& region, Film& film) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.full_width != int(film.width()) || spec.full_height != int(film.height()))
    return "its frame is " + std::to_string(spec.full_width) + "x" +
           std::to_string(spec.full_height) + ", the render's " + std::to_string(film.width()) +
           "x" + std::to_string(film.height());
  const PixelRect window = data_window(spec);
  if (spec.x < 0 || spec.y < 0 || !(window == region))
    return "it holds pixels " + window.text() + ", expected " + region.text();
  std::vector<int> index;
  if (std::string why = channel_positions(spec, film_state_channels(film.channels(), true), index);
      !why.empty())
    return why;
  const size_t n = film.channels().size(), stride = size_t(spec.nchannels);
  std::vector<uint32_t> pixels;
  if (std::string why = read_state_words(in, region, pixels); !why.empty()) return why;
  const uint32_t* p = pixels.data();
  for (uint32_t y = region.y0; y < region.y1; ++y)
    for (uint32_t x = region.x0; x < region.x1; ++x, p += stride) {
      const size_t i = size_t(y) * film.width() + x;
      if (!unpack_sums(p, index, n, &film.sums()[i * n], film.weights()[i]))
        return "pixel " + std::to_string(x) + "," + std::to_string(y) + " holds a non-finite sum";
      film.sample_counts()[i] = p[index[2 * n + 2]];
    }
  return "";
}

}  // namespace fb
