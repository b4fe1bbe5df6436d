#include "core/film/convergence_exr.h"

#include "core/film/film_state_exr.h"

namespace fb {
namespace {

constexpr const char* kCheckedSamples = "filmback/checked_samples";

// The half buffer's channels as the film state's (sum.R.hi ... weight.lo), then the flag.
std::vector<std::string> convergence_channels() {
  std::vector<std::string> names = film_state_channels({"R", "G", "B"}, false);
  names.push_back("converged");
  return names;
}

constexpr size_t kConvergenceStride = 2 * 3 + 2 + 1;

}  // namespace

OIIO::ImageSpec convergence_spec(const ConvergenceMap& map, const PixelRect& region) {
  const std::vector<std::string> names = convergence_channels();
  OIIO::ImageSpec spec(int(region.width()), int(region.height()), int(names.size()),
                       OIIO::TypeDesc::UINT32);
  spec.x = int(region.x0), spec.y = int(region.y0);
  spec.full_width = int(map.width()), spec.full_height = int(map.height());
  spec.channelnames = names;
  spec.attribute("compression", "zip");
  spec.attribute(kCheckedSamples, int(map.checked_samples()));
  return spec;
}

std::vector<uint32_t> encode_convergence(const ConvergenceMap& map, const PixelRect& region) {
  std::vector<uint32_t> pixels(region.area() * kConvergenceStride);
  uint32_t* p = pixels.data();
  for (uint32_t y = region.y0; y < region.y1; ++y)
    for (uint32_t x = region.x0; x < region.x1; ++x, p += kConvergenceStride) {
      const size_t i = size_t(y) * map.width() + x;
      pack_sums(&map.half_sums()[3 * i], map.half_weights()[i], 3, p);
      p[kConvergenceStride - 1] = map.converged_flags()[i];
    }
  return pixels;
}

std::string decode_convergence(OIIO::ImageInput& in, const PixelRect& region, ConvergenceMap& map) {
  const OIIO::ImageSpec& spec = in.spec();
  const PixelRect window = data_window(spec);
  if (spec.full_width != int(map.width()) || spec.full_height != int(map.height()) || spec.x < 0 ||
      spec.y < 0 || !(window == region))
    return "its convergence map holds pixels " + window.text() + ", expected " + region.text();
  std::vector<int> index;
  if (std::string why = channel_positions(spec, convergence_channels(), index); !why.empty())
    return why;
  const int checked = spec.get_int_attribute(kCheckedSamples, -1);
  if (checked < 0) return "its convergence map lacks " + std::string(kCheckedSamples);
  const size_t stride = size_t(spec.nchannels);
  std::vector<uint32_t> pixels;
  if (std::string why = read_state_words(in, region, pixels); !why.empty()) return why;
  const uint32_t* p = pixels.data();
  for (uint32_t y = region.y0; y < region.y1; ++y)
    for (uint32_t x = region.x0; x < region.x1; ++x, p += stride) {
      const size_t i = size_t(y) * map.width() + x;
      const uint32_t flag = p[index[kConvergenceStride - 1]];
      if (!unpack_sums(p, index, 3, &map.half_sums()[3 * i], map.half_weights()[i]) || flag > 1)
        return "pixel " + std::to_string(x) + "," + std::to_string(y) +
               " holds a non-finite half sum or a converged flag other than 0 or 1";
      map.converged_flags()[i] = uint8_t(flag);
    }
  map.set_checked_samples(uint32_t(checked));
  return "";
}

}  // namespace fb
