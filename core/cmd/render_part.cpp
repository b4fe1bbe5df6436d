#include "core/cmd/render_part.h"

#include <charconv>
#include <vector>

#include "core/cmd/tile_plan_file.h"
#include "core/util/error.h"

namespace fb {
namespace {

// Unsigned integers separated by `separator`, exactly `count` of them; none when it is not so.
std::optional<std::vector<uint32_t>> integers(const std::string& text, char separator,
                                              size_t count) {
  std::vector<uint32_t> values;
  const char* at = text.data();
  const char* end = text.data() + text.size();
  while (values.size() < count) {
    uint32_t v = 0;
    const auto [next, ec] = std::from_chars(at, end, v);
    if (ec != std::errc() || next == at) return std::nullopt;
    values.push_back(v);
    at = next;
    if (values.size() < count) {
      if (at == end || *at != separator) return std::nullopt;
      ++at;
    }
  }
  if (at != end) return std::nullopt;
  return values;
}

const char* const kTileExpected = "expected I/N with N from 1 to 1024 and I from 0 to N - 1";
const char* const kCropExpected = "expected X0,Y0,X1,Y1 in pixels with X0 < X1 and Y0 < Y1";

}  // namespace

void check_part_request(const PartRequest& r) {
  if (!r.tile.empty() && !r.crop.empty())
    throw UsageError("--tile and --crop: give one of them, not both");
  if (!r.tile_plan.empty() && r.tile.empty())
    throw UsageError("--tile-plan: only with --tile I/N (which part of the plan to render)");
  if (!r.tile.empty()) {
    const auto v = integers(r.tile, '/', 2);
    if (!v || (*v)[1] == 0 || (*v)[1] > kMaxParts || (*v)[0] >= (*v)[1])
      throw UsageError("--tile '" + r.tile + "': " + kTileExpected);
  }
  if (!r.crop.empty()) {
    const auto v = integers(r.crop, ',', 4);
    if (!v || (*v)[0] >= (*v)[2] || (*v)[1] >= (*v)[3])
      throw UsageError("--crop '" + r.crop + "': " + kCropExpected);
  }
}

PixelRect equal_area_part(uint32_t index, uint32_t count, uint32_t width, uint32_t height) {
  const uint64_t rows = (height + 15) / 16;
  const auto row = [&](uint64_t i) {
    return uint32_t(std::min<uint64_t>(16 * (i * rows / count), height));
  };
  return {0, row(index), width, row(index + 1)};
}

std::optional<PixelRect> part_crop(const PartRequest& r, uint32_t width, uint32_t height) {
  check_part_request(r);
  const std::string frame = std::to_string(width) + "x" + std::to_string(height);
  if (!r.crop.empty()) {
    const auto v = *integers(r.crop, ',', 4);
    if (v[2] > width || v[3] > height)
      throw UsageError("--crop '" + r.crop + "': outside the " + frame + " frame");
    return PixelRect{v[0], v[1], v[2], v[3]};
  }
  if (r.tile.empty()) return std::nullopt;
  const auto v = *integers(r.tile, '/', 2);
  if (!r.tile_plan.empty()) {
    const TilePlan plan = read_tile_plan(r.tile_plan);
    if (plan.width != width || plan.height != height)
      throw_input(r.tile_plan.string(), "",
                  "a plan for a " + std::to_string(plan.width) + "x" + std::to_string(plan.height) +
                      " frame, the render's is " + frame);
    if (plan.parts.size() != v[1])
      throw_input(r.tile_plan.string(), "parts",
                  "has " + std::to_string(plan.parts.size()) + " parts, --tile '" + r.tile +
                      "' expects " + std::to_string(v[1]));
    return plan.parts[v[0]].crop;
  }
  const uint32_t rows = (height + 15) / 16;
  if (v[1] > rows)
    throw UsageError("--tile '" + r.tile + "': the " + frame + " frame has " +
                     std::to_string(rows) +
                     " rows of 16-pixel tiles, fewer than the parts; give a --tile-plan "
                     "(filmback tile-plan) or fewer parts");
  return equal_area_part(v[0], v[1], width, height);
}

PartialFilmHeader partial_film_header(const RenderJob& job, const RenderResult& result,
                                      const PixelRect& crop, const std::string& render_key,
                                      const ViewSettings& view, double film_exposure) {
  PartialFilmHeader h;
  h.width = job.width(), h.height = job.height();
  h.crop = crop;
  h.render_key = render_key;
  h.reconstruction = job.reconstruction();
  h.samples_per_pixel = job.samples_per_pixel();
  h.film_exposure = film_exposure;
  h.view = view;
  h.metadata = job.metadata(result);
  h.render_seconds = result.stats.seconds;
  h.dropped_samples = result.stats.dropped_samples;
  // The 16x16 film tiles the crop meets, and their seconds.
  const uint32_t tiles_x = (job.width() + 15) / 16;
  h.tiles = {crop.x0 / 16, crop.y0 / 16, (crop.x1 + 15) / 16, (crop.y1 + 15) / 16};
  for (uint32_t ty = h.tiles.y0; ty < h.tiles.y1; ++ty)
    for (uint32_t tx = h.tiles.x0; tx < h.tiles.x1; ++tx)
      h.tile_seconds.push_back(result.stats.tile_seconds.empty()
                                   ? 0.0
                                   : result.stats.tile_seconds[size_t(ty) * tiles_x + tx]);
  return h;
}

}  // namespace fb
