#include "core/render/render_loop.h"

#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/film/splat_tiles.h"
#include "core/render/sampler.h"
#include "core/render/trace_context.h"

namespace fb {
namespace {

// Rotation part in float: render space only differs from camera space by orientation.
struct Rotation {
  float m[3][3];
  explicit Rotation(const Transform& t) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        m[r][c] = float(t(r, c));
  }
  void apply(const float v[3], float out[3]) const {
    for (int r = 0; r < 3; ++r)
      out[r] = m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2];
  }
};

// Per-thread buffers, allocated once and reused for every tile the thread renders: a tile of 256
// samples is too short to pay for a dozen heap allocations of its own.
struct TileWork {
  std::vector<uint32_t> px, py;
  std::vector<DimensionSeed> filter_seed, lens_seed, time_seed;  // per pixel (Sampler::seed)
  std::vector<float> filter_u;
  std::vector<fb_filter_sample> filter_samples;
  std::vector<fb_camera_sample> camera_samples;
  std::vector<fb_camera_ray> camera_rays;
  // With texture footprints: each sample's neighbours one pixel right (2 i) and down (2 i + 1).
  std::vector<fb_camera_sample> neighbour_samples;
  std::vector<fb_camera_ray> neighbour_rays;
  std::vector<fb_ray> rays;
  std::vector<float> values;
  std::vector<uint32_t> cryptomatte_names;  // one sample's, per Cryptomatte layer
  fb_trace_context context;

  // What plugins write starts zeroed in every tile, as in a fresh buffer, so that a plugin that
  // leaves a value unwritten cannot pass one tile's data to the next one on its thread.
  void reset(size_t samples, size_t channels, bool footprint) {
    px.resize(samples), py.resize(samples);
    filter_seed.resize(samples), lens_seed.resize(samples), time_seed.resize(samples);
    filter_u.resize(2 * samples);
    filter_samples.assign(samples, {});
    camera_samples.resize(samples);
    camera_rays.assign(samples, {});
    rays.resize(samples);
    values.assign(samples * channels, 0.f);
    context.paths.resize(samples);
    neighbour_samples.resize(footprint ? 2 * samples : 0);
    neighbour_rays.assign(footprint ? 2 * samples : 0, {});
    context.differentials.resize(footprint ? samples : 0);
    context.camera_rays = rays.data();
  }
};

// The camera's narrowest pixel (pbrt-v4 CameraBase::FindMinimumDifferentials, on a coarser
// grid): the least distance between neighbouring rays' origins and between their unit
// directions, over a 16 x 16 grid of raster positions through the lens centre, at the frame's
// time. For the footprint of rays that carry no differentials.
PixelSpread narrowest_pixel(const CameraInstance& camera, float width_px, float height_px) {
  constexpr int kGrid = 16;
  std::vector<fb_camera_sample> samples;
  samples.reserve(3 * kGrid * kGrid);
  for (int gy = 0; gy < kGrid; ++gy)
    for (int gx = 0; gx < kGrid; ++gx) {
      const float x = (gx + 0.5f) / kGrid * width_px, y = (gy + 0.5f) / kGrid * height_px;
      for (const Vec2f d : {Vec2f{0.f, 0.f}, Vec2f{1.f, 0.f}, Vec2f{0.f, 1.f}})
        samples.push_back({x + d.x, y + d.y, 0.5f, 0.5f, 0.f});
    }
  std::vector<fb_camera_ray> rays(samples.size());
  camera.generate_rays(samples, rays.data());
  PixelSpread spread{HUGE_VALF, HUGE_VALF};
  for (size_t i = 0; i < rays.size(); i += 3) {
    if (!(rays[i].weight > 0.f)) continue;
    for (size_t n = i + 1; n < i + 3; ++n) {
      if (!(rays[n].weight > 0.f)) continue;
      spread.origin_m =
          std::min(spread.origin_m, length(Vec3f(rays[n].origin) - Vec3f(rays[i].origin)));
      spread.direction_rad = std::min(
          spread.direction_rad,
          length(normalize(Vec3f(rays[n].direction)) - normalize(Vec3f(rays[i].direction))));
    }
  }
  return std::isfinite(spread.origin_m) && std::isfinite(spread.direction_rad) ? spread
                                                                               : PixelSpread{};
}

class TileRenderer {
 public:
  TileRenderer(const RenderInputs& in, Film& film, SplatTiles* splats, ConvergenceMap* convergence,
               Vec2<uint32_t> domain)
      : in_(in),
        film_(film),
        splats_(splats),
        convergence_(convergence),
        margin_x_(splats ? float(splats->margin(0)) : 0.f),
        margin_y_(splats ? float(splats->margin(1)) : 0.f),
        sampler_(in.sampler, in.seed, in.samples_per_pixel, domain.x, domain.y),
        rotation_(in.render_from_camera),
        channels_(in.integrator.channels().size()),
        needs_(in.camera.needs()) {
    if (!in.texture_footprint) return;
    footprint_.spread = narrowest_pixel(in.camera, float(domain.x) - 2.f * margin_x_,
                                        float(domain.y) - 2.f * margin_y_);
    footprint_.scale = footprint_scale(in.samples_per_pixel);
  }

  // Samples [first, last) of every pixel of the tile that has not converged, in sample order;
  // after each sample index, stops when `stop()` says so (so a started tile always moves on).
  // Returns the index reached.
  template <typename Stop>
  uint32_t render_tile(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, uint32_t first,
                       uint32_t last, const Stop& stop, TileWork& w, RenderStats& stats) const {
    // The pixels first (room for the whole tile), then the per-sample buffers for those kept.
    const size_t tile_pixels = size_t(x1 - x0) * (y1 - y0);
    w.px.resize(tile_pixels), w.py.resize(tile_pixels);
    // 4x4 blocks, so that consecutive camera rays (Embree's packets of up to 16) cover a square.
    size_t n = 0;
    for (uint32_t by = y0; by < y1; by += 4)
      for (uint32_t bx = x0; bx < x1; bx += 4)
        for (uint32_t y = by; y < std::min(by + 4, y1); ++y)
          for (uint32_t x = bx; x < std::min(bx + 4, x1); ++x)
            if (!convergence_ || !convergence_->converged(x, y)) w.px[n] = x, w.py[n++] = y;
    if (n == 0) return last;  // every pixel converged: nothing left to sample
    w.reset(n, channels_, in_.texture_footprint);
    for (size_t i = 0; i < n; ++i) {
      w.filter_seed[i] = sampler_.seed(w.px[i], w.py[i], kFilterDimension);
      if (needs_ & FB_CAMERA_NEEDS_LENS)
        w.lens_seed[i] = sampler_.seed(w.px[i], w.py[i], kLensDimension);
      if (in_.time.curve) w.time_seed[i] = sampler_.seed(w.px[i], w.py[i], kTimeDimension);
    }
    fb_trace_context& context = w.context;
    context.geometry = &in_.geometry;
    context.lights = &in_.lights;
    context.media = in_.media;
    context.sampler = &sampler_;
    context.hit_size = in_.integrator.hit_size();
    context.rays_traced = 0;
    context.footprint = footprint_;
    SplatTiles::Tile* splat_tile = splats_ ? &splats_->tile(x0, y0) : nullptr;

    uint32_t s = first;
    while (s < last) {
      for (size_t i = 0; i < n; ++i) {
        const Vec2f u = sampler_.get_2d(w.filter_seed[i], s);
        w.filter_u[2 * i] = u.x;
        w.filter_u[2 * i + 1] = u.y;
        context.paths[i] = {w.px[i], w.py[i], s, kIntegratorDimension};
      }
      // Reconstruction (docs/filters.md): importance sampling draws the offset from the filter
      // and weights the sample h / pdf; splatting draws it uniformly over the pixel and applies h
      // when it spreads the sample to its neighbours (core/film/splat_tiles.h).
      if (splat_tile) {
        for (size_t i = 0; i < n; ++i)
          w.filter_samples[i] = {w.filter_u[2 * i] - 0.5f, w.filter_u[2 * i + 1] - 0.5f, 1.f};
      } else {
        in_.filter.sample(w.filter_u, w.filter_samples.data());
      }
      for (size_t i = 0; i < n; ++i) {
        fb_camera_sample& c = w.camera_samples[i];
        c = {};
        const Vec2f film = film_position(w, i);
        c.film_x = film.x;
        c.film_y = film.y;
        if (needs_ & FB_CAMERA_NEEDS_LENS) {
          const Vec2f u = sampler_.get_2d(w.lens_seed[i], s);
          c.lens_u = u.x;
          c.lens_v = u.y;
        }
        // Ray differentials: the same lens sample and time one raster pixel right and down.
        fb_camera_sample* neighbours =
            in_.texture_footprint ? &w.neighbour_samples[2 * i] : nullptr;
        if (neighbours) {
          neighbours[0] = neighbours[1] = c;
          neighbours[0].film_x += 1.f;
          neighbours[1].film_y += 1.f;
        }
        if (in_.time.curve) {  // the shutter integral: only when something moves while it is open
          // A rolling shutter's row is the pixel's, as Cycles' (not the filtered position's).
          const double fraction =
              in_.time.fraction(sampler_.get_1d(w.time_seed[i], s), float(w.py[i]) - margin_y_);
          c.time_s = in_.time.time_s(fraction);
          if (in_.zoom) in_.zoom->apply(fraction, c.film_x, c.film_y);
          if (neighbours)
            for (int k = 0; k < 2; ++k) {
              neighbours[k].time_s = c.time_s;
              if (in_.zoom) in_.zoom->apply(fraction, neighbours[k].film_x, neighbours[k].film_y);
            }
        }
      }
      in_.camera.generate_rays(w.camera_samples, w.camera_rays.data());
      if (in_.texture_footprint)
        in_.camera.generate_rays(w.neighbour_samples, w.neighbour_rays.data());
      for (size_t i = 0; i < n; ++i) {
        place(w.camera_rays[i], w.camera_samples[i].time_s, w.rays[i]);
        if (in_.texture_footprint) w.context.differentials[i] = differential(w, i);
      }
      context.surfaces.reset();  // the previous call's hits are done with
      in_.integrator.radiance(in_.scene, &context, w.rays, w.values.data());
      if (in_.cryptomatte || in_.motion_vector_film) add_identified_samples(w, n);
      for (size_t i = 0; i < n; ++i) {
        float* v = &w.values[i * channels_];
        const float camera_weight = w.camera_rays[i].weight;
        if (camera_weight > 0.f) {
          for (size_t c = 0; c < channels_; ++c)
            v[c] *= camera_weight;
        } else {
          std::fill_n(v, channels_, 0.f);
        }
        // Splatted where the sample lies on the film, not where a zoom sent the camera's look.
        const Vec2f at = film_position(w, i);
        const bool kept = splat_tile ? splats_->splat(*splat_tile, at.x, at.y, v)
                                     : film_.add(w.px[i], w.py[i], v, w.filter_samples[i].weight);
        if (!kept) ++stats.dropped_samples;
        if (kept && convergence_)
          convergence_->add(w.px[i], w.py[i], s, v, w.filter_samples[i].weight);
      }
      stats.samples += n;
      if (++s < last && stop()) break;
    }
    if (splat_tile) splat_tile->samples = s;
    stats.rays += context.rays_traced;
    return s;
  }

 private:
  // Sample i's position on the film, raster pixels: its pixel plus the filter's offset.
  Vec2f film_position(const TileWork& w, size_t i) const {
    return {float(w.px[i]) - margin_x_ + 0.5f + w.filter_samples[i].x,
            float(w.py[i]) - margin_y_ + 0.5f + w.filter_samples[i].y};
  }

  // Each sample's object, material and point, found by intersecting its camera ray again, into
  // the Cryptomatte and Vector films with the sample's filter weight, as the film takes the sample.
  void add_identified_samples(TileWork& w, size_t n) const {
    const std::vector<CryptomatteLayer>* layers =
        in_.cryptomatte ? &in_.cryptomatte->layers() : nullptr;
    if (layers) w.cryptomatte_names.resize(layers->size());
    for (size_t i = 0; i < n; ++i) {
      const auto met = in_.geometry.identify(w.rays[i]);
      const float weight = w.filter_samples[i].weight;
      if (met && in_.motion_vector_film)
        in_.motion_vector_film->add(w.px[i], w.py[i], in_.motion_vectors->at(w.rays[i], *met),
                                    weight);
      if (!layers) continue;
      for (size_t k = 0; k < layers->size(); ++k)
        // CryptoAsset's names are per object too (cryptomatte_layers.h).
        w.cryptomatte_names[k] = !met ? kCryptomatteNothing
                                 : (*layers)[k].key == CryptomatteKey::kMaterial ? met->material
                                                                                 : met->object;
      in_.cryptomatte->add(w.px[i], w.py[i], w.cryptomatte_names.data(), weight);
    }
  }

  // Camera ray `c` in render space, leaving at `time_s`.
  void place(const fb_camera_ray& c, float time_s, fb_ray& r) const {
    if (in_.camera_path) {
      in_.camera_path->place(c, time_s, r);
    } else {
      rotation_.apply(c.origin, r.origin);  // the camera sits at the render-space origin
      rotation_.apply(c.direction, r.direction);
    }
    r.t_min = c.t_min;
    r.t_max = c.weight > 0.f ? c.t_max : -1.f;  // an empty interval: the integrator sees a miss
    r.time_s = time_s;
  }

  // Sample i's ray differential from its neighbours' rays. A neighbour the camera cannot make (past
  // a fisheye's circle) leaves it NaN, which position_differentials refuses: that ray's footprint
  // falls back to the camera's spread.
  RayDifferential differential(const TileWork& w, size_t i) const {
    const fb_ray& r = w.rays[i];
    fb_ray neighbour[2];
    for (int k = 0; k < 2; ++k) {
      const fb_camera_ray& c = w.neighbour_rays[2 * i + k];
      if (!(c.weight > 0.f)) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        return {{nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan}};
      }
      place(c, r.time_s, neighbour[k]);
    }
    const auto offset = [](const float a[3], const float b[3]) { return Vec3f(a) - Vec3f(b); };
    return {offset(neighbour[0].origin, r.origin), offset(neighbour[0].direction, r.direction),
            offset(neighbour[1].origin, r.origin), offset(neighbour[1].direction, r.direction)};
  }

  const RenderInputs& in_;
  Film& film_;
  SplatTiles* splats_;           // null: importance sampling, every sample in its own pixel
  ConvergenceMap* convergence_;  // null: no adaptive sampling
  float margin_x_, margin_y_;    // of the sample domain around the film (splatting only)
  Sampler sampler_;
  Rotation rotation_;
  size_t channels_;
  uint32_t needs_;
  FootprintSource footprint_;  // the camera's spread and the supersampling scale, when on
};

// Pixel (x, y) of the sample domain is film pixel (x - margin, y - margin): splatting draws
// samples a filter's reach beyond the film (core/film/splat_tiles.h); importance sampling does not.
Vec2<uint32_t> sample_domain(const RenderInputs& inputs, uint32_t width, uint32_t height) {
  if (inputs.reconstruction != Reconstruction::kSplat) return {width, height};
  float radius[2];
  inputs.filter.radius(radius);
  return {width + 2 * SplatTiles::reach(radius[0]), height + 2 * SplatTiles::reach(radius[1])};
}

// The tiles of the sample domain, row by row, and which of them a part takes (RenderInputs::crop).
class TileGrid {
 public:
  TileGrid(const RenderInputs& inputs, uint32_t width, uint32_t height)
      : width_(width),
        height_(height),
        domain_(sample_domain(inputs, width, height)),
        margin_x_((domain_.x - width) / 2),
        margin_y_((domain_.y - height) / 2),
        tiles_x_((domain_.x + kTileSize - 1) / kTileSize),
        tiles_(uint64_t(tiles_x_) * ((domain_.y + kTileSize - 1) / kTileSize)),
        splat_(inputs.reconstruction == Reconstruction::kSplat) {
    if (inputs.crop)
      crop_ = splat_ ? *inputs.crop
                     : part_region(*inputs.crop, inputs.adaptive, inputs.samples_per_pixel, width,
                                   height);
  }

  uint64_t size() const { return tiles_; }
  uint32_t margin_x() const { return margin_x_; }
  uint32_t margin_y() const { return margin_y_; }
  Vec2<uint32_t> domain() const { return domain_; }
  // The tile's pixels in the sample domain.
  std::array<uint32_t, 4> box(uint64_t tile) const {
    const uint32_t x0 = uint32_t(tile % tiles_x_) * kTileSize,
                   y0 = uint32_t(tile / tiles_x_) * kTileSize;
    return {x0, y0, std::min(x0 + kTileSize, domain_.x), std::min(y0 + kTileSize, domain_.y)};
  }
  // The film pixel a tile is filed under: its first, clamped to the film.
  Vec2<uint32_t> anchor(uint64_t tile) const {
    const auto [x0, y0, x1, y1] = box(tile);
    return {std::min(std::max(x0, margin_x_) - margin_x_, width_ - 1),
            std::min(std::max(y0, margin_y_) - margin_y_, height_ - 1)};
  }
  bool taken(uint64_t tile) const {
    if (!crop_) return true;
    if (splat_) {
      const Vec2<uint32_t> a = anchor(tile);
      return crop_->contains(a.x, a.y);
    }
    const auto [x0, y0, x1, y1] = box(tile);
    return crop_->intersects({x0, y0, x1, y1});
  }

 private:
  uint32_t width_, height_;
  Vec2<uint32_t> domain_;
  uint32_t margin_x_, margin_y_, tiles_x_;
  uint64_t tiles_;
  bool splat_;
  std::optional<PixelRect> crop_;  // the pixels sampled: importance's with the adaptive apron
};

// The sample counts at which passes end: doubling, so that an interrupted render has every pixel
// sampled about equally often, and each pass over a tile stays short. A render nothing can stop
// takes no doubling passes: each visit of a tile reloads the geometry its rays meet from memory,
// which cost about 0.7 of a sample per extra pass per tile on a 1 M-triangle scene, a third of the
// 8-spp throughput (docs/benchmarks.md, "Issue 17"); the image is the same either way, since every
// pixel's samples are summed in sample order. Adaptive sampling also ends a pass at every count
// where its convergence check is due, stoppable or not.
std::vector<uint32_t> pass_ends(uint32_t samples_per_pixel, const RenderControl& control,
                                const std::optional<AdaptiveSettings>& adaptive) {
  std::vector<uint32_t> ends;
  if (control.cancel || control.checkpoint || control.preview)
    for (uint32_t end = 1; end < samples_per_pixel; end *= 2)
      ends.push_back(end);
  if (adaptive)
    for (uint32_t end = kAdaptiveStep; end < samples_per_pixel; end += kAdaptiveStep)
      if (adaptive_check_due(*adaptive, end)) ends.push_back(end);
  ends.push_back(samples_per_pixel);
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

}  // namespace

uint64_t sample_count(const RenderInputs& inputs, uint32_t width, uint32_t height) {
  const TileGrid grid(inputs, width, height);
  uint64_t pixels = 0;
  for (uint64_t tile = 0; tile < grid.size(); ++tile)
    if (grid.taken(tile)) {
      const auto [x0, y0, x1, y1] = grid.box(tile);
      pixels += uint64_t(x1 - x0) * (y1 - y0);
    }
  return pixels * inputs.samples_per_pixel;
}

PixelRect whole_tiles_around(const PixelRect& crop, uint32_t width, uint32_t height) {
  return {crop.x0 - crop.x0 % kTileSize, crop.y0 - crop.y0 % kTileSize,
          std::min((crop.x1 + kTileSize - 1) / kTileSize * kTileSize, width),
          std::min((crop.y1 + kTileSize - 1) / kTileSize * kTileSize, height)};
}

PixelRect part_region(const PixelRect& crop, const std::optional<AdaptiveSettings>& adaptive,
                      uint32_t samples_per_pixel, uint32_t width, uint32_t height) {
  if (!adaptive) return crop;
  const uint32_t apron = adaptive_check_count(*adaptive, samples_per_pixel);
  return {crop.x0 - std::min(crop.x0, apron), crop.y0 - std::min(crop.y0, apron),
          uint32_t(std::min<uint64_t>(uint64_t(crop.x1) + apron, width)),
          uint32_t(std::min<uint64_t>(uint64_t(crop.y1) + apron, height))};
}

void prepare_sampling_state(const RenderInputs& inputs, uint32_t width, uint32_t height,
                            SamplingState& state) {
  if (inputs.reconstruction == Reconstruction::kSplat && state.splat_tiles.empty())
    state.splat_tiles.resize(SplatTiles::tile_count(width, height, kTileSize, inputs.filter));
  if (inputs.adaptive && !state.convergence)
    state.convergence.emplace(width, height, *inputs.adaptive, inputs.exposure);
}

RenderStats render_image(const RenderInputs& inputs, Film& film, SamplingState& state,
                         const RenderControl& control, Progress* progress) {
  using Clock = std::chrono::steady_clock;
  prepare_sampling_state(inputs, film.width(), film.height(), state);
  std::optional<SplatTiles> splats;
  if (inputs.reconstruction == Reconstruction::kSplat)
    splats.emplace(film.width(), film.height(), kTileSize, inputs.integrator.channels().size(),
                   inputs.filter, state.splat_tiles);
  const TileGrid grid(inputs, film.width(), film.height());
  const Vec2<uint32_t> domain = grid.domain();
  const uint32_t margin_x = grid.margin_x(), margin_y = grid.margin_y();
  const uint64_t tiles = grid.size();
  const auto tile_box = [&](uint64_t tile) { return grid.box(tile); };
  std::vector<double> seconds(tiles, 0.0);  // per tile of the sample domain
  // The film pixels a tile of the sample domain covers (all of them when importance sampling).
  const auto record_count = [&](uint64_t tile, uint32_t count) {
    const auto [x0, y0, x1, y1] = tile_box(tile);
    const uint32_t fx0 = std::max(x0, margin_x) - margin_x, fy0 = std::max(y0, margin_y) - margin_y;
    const uint32_t fx1 = std::min(x1 - margin_x, film.width()),
                   fy1 = std::min(y1 - margin_y, film.height());
    if (x1 > margin_x && y1 > margin_y && fx0 < fx1 && fy0 < fy1)
      film.set_sample_count(fx0, fy0, fx1, fy1, count);
  };
  ConvergenceMap* const convergence = state.convergence ? &*state.convergence : nullptr;
  // A resumed film tells how far each tile got (its most sampled pixel: with adaptive sampling,
  // the converged ones stopped short), a splat tile its own; a fresh one is all zeros.
  std::vector<uint32_t> done(tiles, 0);
  for (uint64_t tile = 0; tile < tiles; ++tile) {
    if (!grid.taken(tile)) continue;
    const auto [x0, y0, x1, y1] = tile_box(tile);
    if (splats) {
      const std::unique_ptr<SplatTiles::Tile>& t = state.splat_tiles[tile];
      done[tile] = t ? std::min(t->samples, inputs.samples_per_pixel) : 0;
      continue;
    }
    for (uint32_t y = y0; y < (convergence ? y1 : y0 + 1); ++y)
      for (uint32_t x = x0; x < (convergence ? x1 : x0 + 1); ++x)
        done[tile] =
            std::max(done[tile], std::min(film.sample_count(x, y), inputs.samples_per_pixel));
  }
  const TileRenderer renderer(inputs, film, splats ? &*splats : nullptr, convergence, domain);
  tbb::enumerable_thread_specific<TileWork> work;
  std::atomic<uint64_t> samples{0}, rays{0}, dropped{0};
  std::atomic<bool> pause{false};  // a checkpoint or preview is due: tiles stop, it is saved, go on
  const auto start = Clock::now();
  auto last_checkpoint = start, last_preview = start;
  const auto cancelled = [&] {
    return control.cancel && control.cancel->load(std::memory_order_relaxed);
  };
  const auto checkpoint_due = [&](Clock::time_point now) {
    return control.checkpoint && now - last_checkpoint >= control.checkpoint_every;
  };
  const auto preview_due = [&](Clock::time_point now) {
    return control.preview && now - last_preview >= control.preview_every;
  };
  // Between two sample indices of a tile: a signal, or a checkpoint or preview that has come due
  // (the clock read only when one is asked for).
  const auto stop = [&] {
    if (pause.load(std::memory_order_relaxed) || cancelled()) return true;
    if (!control.checkpoint && !control.preview) return false;
    if (const auto now = Clock::now(); checkpoint_due(now) || preview_due(now)) {
      pause = true;
      return true;
    }
    return false;
  };
  if (progress)  // what a resumed render has done: a converged pixel's samples are all counted
    for (uint64_t tile = 0; tile < tiles; ++tile) {
      if (!grid.taken(tile)) continue;
      const auto [x0, y0, x1, y1] = tile_box(tile);
      uint64_t taken = uint64_t(done[tile]) * (x1 - x0) * (y1 - y0);
      for (uint32_t y = y0; y < y1 && convergence; ++y)
        for (uint32_t x = x0; x < x1; ++x)
          if (convergence->converged(x, y)) taken += inputs.samples_per_pixel - done[tile];
      progress->advance(taken);
    }
  RenderStats stats;
  for (const uint32_t end : pass_ends(inputs.samples_per_pixel, control, inputs.adaptive)) {
    for (;;) {  // until every tile has reached `end`, saving the film whenever a checkpoint is due
      pause = false;
      tbb::parallel_for(
          tbb::blocked_range<uint64_t>(0, tiles, 1),
          [&](const tbb::blocked_range<uint64_t>& range) {
            // Embree wants denormals flushed in every thread that traces.
            _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
            _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
            for (uint64_t tile = range.begin(); tile != range.end(); ++tile) {
              if (done[tile] >= end || !grid.taken(tile) || pause.load(std::memory_order_relaxed) ||
                  cancelled())
                continue;
              const auto [x0, y0, x1, y1] = tile_box(tile);
              RenderStats local;
              const auto tile_start = Clock::now();
              const uint32_t reached =
                  renderer.render_tile(x0, y0, x1, y1, done[tile], end, stop, work.local(), local);
              seconds[tile] += std::chrono::duration<double>(Clock::now() - tile_start).count();
              if (progress)
                progress->advance(uint64_t(reached - done[tile]) * (x1 - x0) * (y1 - y0));
              done[tile] = reached;
              if (convergence) {  // converged pixels keep the count they stopped at
                for (uint32_t y = y0; y < y1; ++y)
                  for (uint32_t x = x0; x < x1; ++x)
                    if (!convergence->converged(x, y))
                      film.set_sample_count(x, y, x + 1, y + 1, reached);
              } else {
                record_count(tile, reached);
              }
              samples += local.samples;
              rays += local.rays;
              dropped += local.dropped_samples;
            }
          },
          tbb::simple_partitioner());
      if (cancelled()) {
        stats.interrupted = true;
        break;
      }
      if (pause) {
        const auto now = Clock::now();
        if (checkpoint_due(now)) {
          control.checkpoint(film, state);
          last_checkpoint = Clock::now();
        }
        if (preview_due(now)) {
          control.preview(film, state);
          last_preview = Clock::now();
        }
        continue;
      }
      break;
    }
    if (stats.interrupted) break;
    // Once per check: a resumed render's convergence map may have made it already.
    if (convergence && end < inputs.samples_per_pixel &&
        adaptive_check_due(*inputs.adaptive, end) && end > convergence->checked_samples())
      convergence->update(film, end, [&](uint32_t, uint32_t) {
        // The samples it will not take count as done, so that progress ends at 100 %.
        if (progress) progress->advance(inputs.samples_per_pixel - end);
      });
  }
  if (splats) splats->add_to(film);
  const uint32_t film_tiles_x = (film.width() + kTileSize - 1) / kTileSize;
  stats.tile_seconds.assign(size_t(film_tiles_x) * ((film.height() + kTileSize - 1) / kTileSize),
                            0.0);
  for (uint64_t tile = 0; tile < tiles; ++tile) {
    const Vec2<uint32_t> a = grid.anchor(tile);
    stats.tile_seconds[size_t(a.y / kTileSize) * film_tiles_x + a.x / kTileSize] += seconds[tile];
  }
  stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stats.samples = samples;
  stats.rays = rays;
  stats.dropped_samples = dropped;
  return stats;
}

}  // namespace fb
