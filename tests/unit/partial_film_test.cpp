// Parts of a render (docs/cli.md, "Parts of a render"): a frame rendered as parts, each written as
// a partial film and read back, merges into the very image of the whole render, bit for bit, for
// every sampler, a narrow and a wide filter, both reconstructions, two seeds and 1, 3 or 8 uneven
// parts; a part's checkpoint resumes it bit-identically.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>

#include "core/film/checkpoint.h"
#include "core/film/part_coverage.h"
#include "core/film/partial_film.h"
#include "core/render/render_job.h"
#include "core/scene/camera.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kFrameWidth = 70, kFrameHeight = 45;  // tiles cut at the right and bottom edges

const Scene& default_scene() {
  static const Scene scene = [] {
    Diagnostics diagnostics;
    return import_gltf(fs::path(FILMBACK_SOURCE_DIR) / "scenes/default/default.gltf", diagnostics);
  }();
  return scene;
}

// Uneven parts that tile the 70x45 frame, none on the 16-pixel tile grid but the frame's edges.
std::vector<PixelRect> parts_of(int count) {
  if (count == 1) return {{0, 0, kFrameWidth, kFrameHeight}};
  if (count == 3)
    return {{0, 0, 23, 17}, {23, 0, kFrameWidth, 17}, {0, 17, kFrameWidth, kFrameHeight}};
  return {{0, 0, 9, 20},   {9, 0, 40, 7},
          {9, 7, 40, 20},  {40, 0, kFrameWidth, 20},
          {0, 20, 31, 21}, {31, 20, kFrameWidth, 33},
          {0, 21, 31, 45}, {31, 33, kFrameWidth, kFrameHeight}};
}

PartialFilmHeader header(const RenderJob& job, const RenderResult& result, const PixelRect& crop,
                         size_t splat_tiles) {
  PartialFilmHeader h;
  h.width = job.width(), h.height = job.height(), h.crop = crop;
  h.render_key = "test key";
  h.reconstruction = job.reconstruction();
  h.channels = job.make_film().channels();
  h.samples_per_pixel = job.samples_per_pixel();
  h.splat_tile_count = splat_tiles;
  h.metadata = job.metadata(result);
  return h;
}

// Renders `crops` as parts into partial films under `folder`.
std::vector<fs::path> write_parts(const RenderJob& job, const std::vector<PixelRect>& crops,
                                  const fs::path& folder) {
  std::vector<fs::path> files;
  for (size_t i = 0; i < crops.size(); ++i) {
    Film film = job.make_film();
    SamplingState state;
    const RenderResult result = job.run(film, state, {}, crops[i]);
    files.push_back(folder / ("part" + std::to_string(i) + ".exr"));
    write_partial_film(files.back(), header(job, result, crops[i], state.splat_tiles.size()), film,
                       state.splat_tiles);
  }
  return files;
}

std::vector<PartialFilmHeader> headers_of(const std::vector<fs::path>& files) {
  std::vector<PartialFilmHeader> headers;
  for (const fs::path& file : files)
    headers.push_back(read_partial_film_header(file));
  return headers;
}

Image merged(const RenderJob& job, const std::vector<PixelRect>& crops, const fs::path& folder) {
  const std::vector<fs::path> files = write_parts(job, crops, folder);
  return merge_partial_films(files, headers_of(files)).resolve();
}

bool same_bits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(PartialFilm, MergedPartsAreTheWholeRenderBitForBit) {
  const fs::path folder = test::scratch_dir() / "partial_film_merge";
  fs::create_directories(folder);
  int config = 0;
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kStratified,
                                    SamplerKind::kSobol, SamplerKind::kZSobol})
    for (const char* filter : {"box", "gaussian:radius=2.5"})
      for (const Reconstruction reconstruction :
           {Reconstruction::kImportance, Reconstruction::kSplat})
        for (const uint64_t seed : {0u, 7u}) {
          RenderOptions o;
          o.width = kFrameWidth, o.height = kFrameHeight, o.samples_per_pixel = 4, o.seed = seed;
          o.sampler = sampler, o.filter = filter, o.reconstruction = reconstruction;
          o.show_progress = false;
          if (config % 5 == 0) {  // depth of field: lens samples too
            o.camera_overrides.fstop = fstop_from(1.4);
            o.camera_overrides.focus_distance_m = 2.0;
          }
          const int count = std::array{1, 3, 8}[config++ % 3];
          const RenderJob job(default_scene(), o, test::loader());
          const Image whole = job.run().image;
          SCOPED_TRACE(std::string(sampler_name(sampler)) + ", " + filter + ", " +
                       reconstruction_name(reconstruction) + ", seed " + std::to_string(seed) +
                       ", " + std::to_string(count) + " parts");
          EXPECT_TRUE(same_bits(merged(job, parts_of(count), folder), whole));
        }
}

// Adaptive sampling: a pixel's convergence depends on its neighbours', so each part samples an
// apron around its crop (one pixel per check, render_loop.h part_region) and merges into the very
// image of the whole render. The threshold lets pixels converge at every check, so that an apron
// one pixel short would change pixels at the parts' borders (docs/distributed.md measures it).
TEST(PartialFilm, AdaptivePartsMergeIntoTheWholeRenderBitForBit) {
  const fs::path folder = test::scratch_dir() / "partial_film_adaptive";
  fs::create_directories(folder);
  RenderOptions o;
  o.width = kFrameWidth, o.height = kFrameHeight, o.samples_per_pixel = 64, o.seed = 4;
  o.adaptive_threshold = 0.05, o.adaptive_min_samples = 16;  // checks at 16, 32 and 48
  o.show_progress = false;
  const RenderJob job(default_scene(), o, test::loader());
  EXPECT_EQ(job.part_tiles({20, 20, 21, 21}), (PixelRect{16, 16, 32, 32}));
  EXPECT_EQ(job.part_tiles({9, 13, 40, 20}), (PixelRect{0, 0, 48, 32}));  // 3 pixels of apron
  Film whole_film = job.make_film();
  const Image whole = job.run(whole_film).image;
  const std::set<uint32_t> counts(whole_film.sample_counts(),
                                  whole_film.sample_counts() + whole_film.pixel_count());
  EXPECT_GE(counts.size(), 4u) << "pixels should converge at every check and some never";
  for (const int count : {3, 8}) {
    SCOPED_TRACE(std::to_string(count) + " parts");
    EXPECT_TRUE(same_bits(merged(job, parts_of(count), folder), whole));
  }
  // Edges where whole tiles add nothing to an apron one pixel short (2 pixels from x = 30 to the
  // tile edge at 32, from y = 18 to 16): there that apron would be all the part had.
  const std::vector<PixelRect> tight = {
      {0, 0, 30, 18}, {30, 0, kFrameWidth, 18}, {0, 18, kFrameWidth, kFrameHeight}};
  EXPECT_TRUE(same_bits(merged(job, tight, folder), whole)) << "parts with tight aprons";
}

// merge_partial_films' message for `files` (with `edit` applied to their headers), or "".
std::string refusal(const std::vector<fs::path>& files,
                    const std::function<void(std::vector<PartialFilmHeader>&)>& edit = {}) {
  try {
    std::vector<PartialFilmHeader> headers = headers_of(files);
    if (edit) edit(headers);
    merge_partial_films(files, headers);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PartialFilm, MergeRefusesWhatIsNotOneRender) {
  const fs::path folder = test::scratch_dir() / "partial_film_refusals";
  fs::create_directories(folder);
  RenderOptions o;
  o.width = kFrameWidth, o.height = kFrameHeight, o.samples_per_pixel = 2, o.filter = "gaussian";
  o.reconstruction = Reconstruction::kSplat, o.show_progress = false;
  const RenderJob job(default_scene(), o, test::loader());
  const std::vector<fs::path> f = write_parts(job, parts_of(3), folder);
  EXPECT_EQ(refusal(f), "");
  const auto says = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  says(refusal(f, [](auto& h) { h[2].render_key = "another seed"; }),
       f[2].string() + ": a part of another render than '" + f[0].string());
  says(refusal(f, [](auto& h) { h[1].view.exposure_stops = 1; }), "the view settings");
  says(refusal({f[0], f[1], f[2], f[1]}),
       f[1].string() + ": its crop 23,0,70,17 overlaps the crop 23,0,70,17");
  says(refusal({f[0], f[2]}), "no part covers pixels 23,0,70,17");
  for (const double kept : {0.4, 0.8}) {  // into the film state, into the splat tiles
    const std::string data = [&] {
      std::ifstream in(f[1], std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    const fs::path cut = folder / "cut.exr";
    std::ofstream(cut, std::ios::binary) << data.substr(0, size_t(double(data.size()) * kept));
    says(refusal({f[0], cut, f[2]}), cut.string() + ": ");
  }
}

// A part written by an earlier filmback (version 1: no samples in its splat tiles' table, no
// adaptive sampling) is refused by version, naming the file, rather than read as truncated.
TEST(PartialFilm, AnOldPartIsRefusedByItsVersion) {
  const fs::path file = test::scratch_dir() / "old_part.exr";
  ImageMetadata version_1;
  version_1.ints = {{"filmback/part/version", 1}};
  write_images(Image{4, 4, {"R", "G", "B"}, std::vector<float>(48, 0.f)}, {file}, version_1);
  try {
    read_partial_film_header(file);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ": a version 1 partial film, this "
                                                         "filmback merges version 2"),
              std::string::npos)
        << e.what();
  }
}

TEST(PartialFilm, ACheckpointedPartResumesBitIdentically) {
  const fs::path folder = test::scratch_dir() / "partial_film_resume";
  fs::create_directories(folder);
  RenderOptions o;
  o.width = kFrameWidth, o.height = kFrameHeight, o.samples_per_pixel = 16, o.seed = 2;
  o.show_progress = false;
  const RenderJob job(default_scene(), o, test::loader());
  const PixelRect crop{9, 7, 40, 20};
  Film uninterrupted = job.make_film();
  SamplingState uninterrupted_state;
  job.run(uninterrupted, uninterrupted_state, {}, crop);

  // Stopped at the third checkpoint offered, saved over the crop's whole tiles, resumed.
  const PixelRect region = job.part_tiles(crop);
  EXPECT_EQ(region, (PixelRect{0, 0, 48, 32}));
  const fs::path checkpoint = folder / "part.checkpoint.exr";
  std::atomic<bool> cancel{false};
  int offered = 0;
  RenderControl control;
  control.cancel = &cancel;
  control.checkpoint = [&](const Film& f, const SamplingState& state) {
    write_checkpoint(f, state, "key", checkpoint, region);
    if (++offered == 3) cancel = true;
  };
  Film stopped = job.make_film();
  SamplingState stopped_state;
  ASSERT_TRUE(job.run(stopped, stopped_state, control, crop).stats.interrupted);
  Film resumed = job.make_film();
  SamplingState resumed_state = job.make_sampling_state();
  read_checkpoint(checkpoint, "key", 16, kTileSize, resumed, resumed_state, region);
  EXPECT_LT(resumed.sample_count(crop.x0, crop.y0), 16u);
  job.run(resumed, resumed_state, {}, crop);
  for (uint32_t y = crop.y0; y < crop.y1; ++y)
    for (uint32_t x = crop.x0; x < crop.x1; ++x) {
      const size_t i = size_t(y) * kFrameWidth + x;
      ASSERT_EQ(resumed.weights()[i], uninterrupted.weights()[i]) << x << "," << y;
      ASSERT_EQ(resumed.sums()[3 * i], uninterrupted.sums()[3 * i]) << x << "," << y;
    }
  // A checkpoint of another part's region is refused.
  Film other = job.make_film();
  SamplingState other_state = job.make_sampling_state();
  EXPECT_THROW(read_checkpoint(checkpoint, "key", 16, kTileSize, other, other_state,
                               PixelRect{0, 0, 48, 16}),
               InputError);
}

TEST(PartCoverage, FindsOverlapsGapsAndCropsOutsideTheFrame) {
  EXPECT_FALSE(check_coverage(parts_of(8), kFrameWidth, kFrameHeight));
  std::vector<PixelRect> gap = parts_of(8);
  gap.erase(gap.begin() + 5);
  const auto missing = check_coverage(gap, kFrameWidth, kFrameHeight);
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->kind, CoverageProblem::Kind::kGap);
  // A rectangle of the missing part (cut at the other parts' edges).
  const PixelRect removed{31, 20, kFrameWidth, 33};
  EXPECT_FALSE(missing->where.empty());
  EXPECT_TRUE(removed.contains(missing->where.x0, missing->where.y0) &&
              removed.contains(missing->where.x1 - 1, missing->where.y1 - 1));
  std::vector<PixelRect> overlap = parts_of(3);
  overlap[1].x0 = 22;
  const auto twice = check_coverage(overlap, kFrameWidth, kFrameHeight);
  ASSERT_TRUE(twice);
  EXPECT_EQ(twice->kind, CoverageProblem::Kind::kOverlap);
  EXPECT_EQ(twice->part, 1u);
  EXPECT_EQ(twice->other, 0u);
  EXPECT_EQ(twice->where, (PixelRect{22, 0, 23, 17}));
  const auto outside =
      check_coverage({{0, 0, kFrameWidth + 1, kFrameHeight}}, kFrameWidth, kFrameHeight);
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->kind, CoverageProblem::Kind::kOutside);
}

}  // namespace
}  // namespace fb
