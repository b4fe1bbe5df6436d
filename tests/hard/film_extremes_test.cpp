// The film at its extremes (scenes/hard/README.md): a 1 x 1 image, a 16384-pixel-wide one, pixel
// filters of 0.01 px and 8 px, and a shutter of zero length. Each scene is an emitter of known
// radiance, so every pixel has an exact value.
#include <gtest/gtest.h>

#include <cmath>

#include "core/util/error.h"
#include "hard_case.h"
#include "support/plugins.h"

namespace fb {
namespace {

using test::report_case;

// The largest relative difference of channels 0-2 of pixel (x, y) from `radiance`.
double off_by(const Image& image, uint32_t x, uint32_t y, Rgb radiance) {
  double worst = 0;
  for (size_t c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(double(image.at(x, y, c)) / radiance[c] - 1));
  return worst;
}

TEST(FilmExtremes, OnePixelImageIsTheRadianceItSees) {
  const Scene scene = test::load_hard_scene("one_pixel.gltf");  // 1 x 1 in the file
  const Rgb glow = scene.materials.at(0).emission;
  for (Reconstruction reconstruction : {Reconstruction::kImportance, Reconstruction::kSplat}) {
    RenderOptions options;
    options.samples_per_pixel = 16;
    options.reconstruction = reconstruction;
    const test::TimedRender r = test::render_timed(scene, options);
    ASSERT_EQ(r.result.image.width * r.result.image.height, 1u);
    report_case(std::string("1x1, ") + reconstruction_name(reconstruction),
                r.result.stats.dropped_samples, off_by(r.result.image, 0, 0, glow), 1e-6,
                "|pixel / emitted radiance - 1|", r.seconds);
  }
}

// The wall covers the image left of column 8192 exactly: with a 1 px box filter every pixel is
// the emitter's radiance or 0, whatever its index. (Raster positions are floats: at x = 8192 they
// step by 1/1024 px, so a sample within that of the edge may fall on it; the two columns beside
// it are checked by their sum.)
TEST(FilmExtremes, ImageOf16384PixelsAcrossKeepsEveryColumnInPlace) {
  const Scene scene = test::load_hard_scene("wide_image.gltf");  // 16384 x 64 in the file
  const Rgb glow = scene.materials.at(0).emission;
  RenderOptions options;
  options.samples_per_pixel = 1;
  options.filter = "box";
  const test::TimedRender r = test::render_timed(scene, options);
  const Image& image = r.result.image;
  ASSERT_EQ(image.width, 16384u);
  double worst = 0, edge = 0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      edge += image.at(x, y, 1) / glow.y / image.height;
      if (x == 8191 || x == 8192) continue;
      worst = std::max(worst, x < 8192 ? off_by(image, x, y, glow) : double(image.at(x, y, 0)));
    }
  const uint64_t non_finite = r.result.stats.dropped_samples;
  report_case("16384 wide", non_finite, worst, 1e-6,
              "worst |pixel - exact| / radiance, lit left of column 8192", r.seconds);
  report_case("16384 wide, edge", non_finite, std::abs(edge - 8192), 1.0 / 64,
              "|mean row sum / radiance - 8192|, px", r.seconds);
}

// A vertical edge at raster x = 40.3 between the emitter and black: far from it the image is
// constant (exactly the radiance, or 0), and each row's sum over the radiance is where the edge
// is, the area under the step (for the 8 px filters; a filter far narrower than a pixel samples
// each pixel at its centre, which puts the edge at the nearest pixel boundary, 40).
TEST(FilmExtremes, TinyAndWideFiltersKeepConstantsConstantAndEdgesInPlace) {
  const Scene scene = test::load_hard_scene("filter_edge.gltf");
  const Rgb glow = scene.materials.at(0).emission;
  const double edge_px = 40.3;
  struct Case {
    const char* filter;
    double reach_px, expected_edge_px, limit_px;
  };
  for (const Case& c : {Case{"box:radius=0.01", 0.01, 40, 1e-6},
                        Case{"gaussian:radius=0.01,sigma=0.005", 0.01, 40, 1e-6},
                        Case{"box:radius=8", 8, edge_px, 0.02},
                        Case{"gaussian:radius=8,sigma=2.5", 8, edge_px, 0.02}})
    for (Reconstruction reconstruction : {Reconstruction::kImportance, Reconstruction::kSplat}) {
      RenderOptions options;
      // Splatting an 8 px filter spreads each sample over 17 x 17 pixels: fewer samples do.
      options.samples_per_pixel = reconstruction == Reconstruction::kSplat ? 32 : 256;
      options.filter = c.filter;
      options.reconstruction = reconstruction;
      options.show_progress = false;
      // A splatted sample lies anywhere in its pixel: a filter reaching less than half a pixel
      // would leave most pixels without any (measured before this was refused: 90 % of them
      // black at 256 samples, the edge 36 px off).
      if (reconstruction == Reconstruction::kSplat && c.reach_px < 0.5) {
        EXPECT_THROW(RenderJob(scene, options, test::loader()), UsageError) << c.filter;
        continue;
      }
      const test::TimedRender r = test::render_timed(scene, options);
      const Image& image = r.result.image;
      double constant = 0, edge = 0;
      for (uint32_t y = 0; y < image.height; ++y) {
        double sum = 0;
        for (uint32_t x = 0; x < image.width; ++x) {
          sum += image.at(x, y, 1) / glow.y;
          const double centre = x + 0.5;
          if (centre + 0.5 + c.reach_px < edge_px)
            constant = std::max(constant, off_by(image, x, y, glow));
          else if (centre - 0.5 - c.reach_px > edge_px)
            constant = std::max(constant, double(image.at(x, y, 1)) / glow.y);
        }
        edge += sum / image.height;
      }
      const std::string name = std::string(c.filter) + ", " + reconstruction_name(reconstruction);
      report_case(name + ": constant", r.result.stats.dropped_samples, constant, 1e-6,
                  "worst |pixel - exact| / radiance beyond the filter's reach of the edge",
                  r.seconds);
      report_case(name + ": edge", r.result.stats.dropped_samples,
                  std::abs(edge - c.expected_edge_px), c.limit_px,
                  "|mean row sum / radiance - edge position|, px", r.seconds);
    }
}

// A zero-length shutter is an instant: at OPEN = CLOSE = 0 the image is the closed shutter's, bit
// for bit and without time samples; at 0.25 s it is the closed shutter's at the frame 0.25 s
// later (the emitter moves 1 m/s, 3.4 px at this lens and distance, so a wrong instant shows).
TEST(FilmExtremes, ZeroLengthShutterIsTheInstantItNames) {
  const Scene scene = test::load_hard_scene("moving_emitter.gltf");
  RenderOptions closed;
  closed.samples_per_pixel = 16;
  const test::TimedRender reference = test::render_timed(scene, closed);
  RenderOptions instant = closed;
  instant.shutter_s = Vec2d{0, 0};
  closed.show_progress = instant.show_progress = false;
  EXPECT_NE(RenderJob(scene, instant, test::loader()).plan().find("no time samples"),
            std::string::npos);
  const test::TimedRender zero = test::render_timed(scene, instant);
  EXPECT_EQ(zero.result.image.pixels, reference.result.image.pixels);

  instant.shutter_s = Vec2d{0.25, 0.25};
  RenderOptions later = closed;
  later.frame = 0.25 * 24;  // the scene's 24 fps
  const test::TimedRender at = test::render_timed(scene, instant),
                          expected = test::render_timed(scene, later);
  double worst = 0;
  for (size_t i = 0; i < at.result.image.pixels.size(); ++i)
    worst = std::max(worst,
                     double(std::abs(at.result.image.pixels[i] - expected.result.image.pixels[i])));
  report_case("zero-length shutter at 0.25 s", at.result.stats.dropped_samples, worst, 0,
              "max |pixel - the closed shutter's 0.25 s later|", at.seconds + zero.seconds);
}

}  // namespace
}  // namespace fb
