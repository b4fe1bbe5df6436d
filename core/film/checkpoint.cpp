#include "core/film/checkpoint.h"

#include <OpenImageIO/imageio.h>

#include <vector>

#include "core/film/film_state_exr.h"
#include "core/util/error.h"
#include "core/util/temporary_file.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

constexpr int kCheckpointVersion = 1;

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw InputError(located(file.string(), "", "cannot resume from this checkpoint: " + why));
}

}  // namespace

void write_checkpoint(const Film& film, const std::string& key, const fs::path& file,
                      const std::optional<PixelRect>& region) {
  const PixelRect saved = region.value_or(whole_frame(film.width(), film.height()));
  const std::vector<uint32_t> pixels = encode_film_state(film, saved);
  OIIO::ImageSpec spec = film_state_spec(film, saved);
  spec.attribute("filmback/checkpoint_version", kCheckpointVersion);
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
                     uint32_t tile_size, Film& film, const std::optional<PixelRect>& region) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) fail(file, OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.get_int_attribute("filmback/checkpoint_version") != kCheckpointVersion)
    fail(file,
         "it is not a filmback checkpoint (version " + std::to_string(kCheckpointVersion) + ")");
  if (spec.get_string_attribute("filmback/checkpoint_key") != key)
    fail(file,
         "it was written for another render (the scene file or the render's settings "
         "differ: the same scene, options, seed and part are needed)");
  const PixelRect saved = region.value_or(whole_frame(film.width(), film.height()));
  if (const std::string why = decode_film_state(*in, saved, film); !why.empty()) fail(file, why);
  for (uint32_t y = saved.y0; y < saved.y1; ++y)
    for (uint32_t x = saved.x0; x < saved.x1; ++x) {
      const uint32_t count = film.sample_count(x, y);
      const uint32_t tile_count = film.sample_count(x - x % tile_size, y - y % tile_size);
      if (count > samples_per_pixel || count != tile_count)
        fail(file, "pixel " + std::to_string(x) + "," + std::to_string(y) + " has " +
                       std::to_string(count) + " samples, which a render of " +
                       std::to_string(samples_per_pixel) + " per pixel cannot have left");
    }
}

}  // namespace fb
