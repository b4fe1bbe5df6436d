#include "importers/gltf/gltf_shot.h"

#include <cmath>
#include <optional>
#include <string>

#include "core/util/error.h"

namespace fb::gltf {
namespace {

// Samples of a shutter curve, at most: a bound on what a file allocates.
constexpr size_t kMaxCurveSamples = 4096;
// Blender's largest Adaptive Sampling > Min Samples (rna_cycles: adaptive_min_samples).
constexpr double kMostAdaptiveMinSamples = 4096;

// Cycles' Film > Pixel Filter, typed: the render maps it to a filter plugin (docs/filters.md,
// "Against Blender").
PixelFilterSetting cycles_filter(const Fields& f) {
  PixelFilterSetting filter;
  filter.origin = ValueOrigin::from_file(f.file(), f.path());
  filter.width_px = f.number("filter_width_px", 0.01, 10).value_or(1.5);
  const std::string type = f.word("filter_type").value_or("BLACKMAN_HARRIS");
  if (same_word(type, "blackman_harris"))
    filter.type = PixelFilterSetting::Type::kBlackmanHarris;
  else if (same_word(type, "gaussian"))
    filter.type = PixelFilterSetting::Type::kGaussian;
  else if (same_word(type, "box"))
    filter.type = PixelFilterSetting::Type::kBox;
  else
    f.fail("filter_type", "'" + type + "', expected BLACKMAN_HARRIS, GAUSSIAN or BOX");
  return filter;
}

// Blender's Color Management and Post Processing > Dither (its RNA ranges): display-referred, so
// only 8-bit outputs apply them; the EXR is scene-linear, as Blender's own EXR.
void read_view_settings(const Fields& f, ShotSettings& s) {
  ViewSettings& v = s.view;
  if (const auto view = f.word("view_transform")) {
    v.view_transform = *view;
    v.dither_intensity = 1.0;  // Blender's default, when a file from Blender does not say
  }
  if (const auto look = f.word("look")) v.look = *look;
  if (const auto display = f.word("display_device")) v.display_device = *display;
  v.exposure_stops = f.number("exposure_stops", -32, 32).value_or(0.0);
  v.gamma = f.number("gamma", 0, 5).value_or(1.0);
  if (const auto dither = f.number("dither_intensity", 0, 2)) v.dither_intensity = *dither;
  s.view_json_path = f.path();
}

// Cycles' rolling shutter (scene.cycles.rolling_shutter_type NONE or TOP and its duration, 0.1
// when absent as in Cycles): only with the shutter it reads its rows in.
void read_rolling_shutter(const Fields& f, ShotSettings& s) {
  const auto type = f.word("rolling_shutter_type");
  const auto duration = f.number("rolling_shutter_duration", 0, 1);
  if (!type || same_word(*type, "none")) return;
  if (!same_word(*type, "top"))
    f.fail("rolling_shutter_type", "'" + *type + "', expected NONE or TOP");
  if (!s.shutter_open_s)
    f.fail("rolling_shutter_type",
           "TOP without shutter_open_s and shutter_close_s: expected the shutter the rolling "
           "shutter reads its rows in (Cycles rolls it only with motion blur on)");
  s.rolling_shutter_duration = duration.value_or(0.1);
}

}  // namespace

ShotSettings read_shot_settings(const Fields& f) {
  ShotSettings s;
  if (const auto w = f.whole("resolution_x_px", 1, 32768)) s.width_px = uint32_t(*w);
  if (const auto h = f.whole("resolution_y_px", 1, 32768)) s.height_px = uint32_t(*h);
  if (s.width_px.has_value() != s.height_px.has_value())
    f.fail(s.width_px ? "resolution_y_px" : "resolution_x_px",
           "expected both resolution_x_px and resolution_y_px");
  const auto aspect_x = f.number("pixel_aspect_x", 1e-3, 1e3);
  const auto aspect_y = f.number("pixel_aspect_y", 1e-3, 1e3);
  if (aspect_x || aspect_y) s.pixel_aspect = aspect_x.value_or(1) / aspect_y.value_or(1);
  // The file's timeline is frame / fps: Blender's exporter times animation keys so, leaving
  // fps_base (29.97 = 30 / 1.001) out, and frames must land where their keys are.
  s.fps = f.number("fps", 1e-3, 1e6);
  f.number("fps_base", 1e-6, 1e6);  // checked only
  s.frame = f.number("frame", -1e9, 1e9);
  s.shutter_open_s = f.number("shutter_open_s", -1e6, 1e6);
  s.shutter_close_s = f.number("shutter_close_s", -1e6, 1e6);
  if (s.shutter_open_s.has_value() != s.shutter_close_s.has_value() ||
      (s.shutter_open_s && !(*s.shutter_close_s >= *s.shutter_open_s)))
    f.fail("shutter_close_s", "expected shutter_open_s and shutter_close_s, with close >= open");
  if (auto curve = f.numbers("shutter_curve", kMaxCurveSamples, 0, 1e6)) {
    if (curve->size() < 2) f.fail("shutter_curve", "expected at least two samples");
    s.shutter_curve = std::move(*curve);
    s.shutter_curve_origin = ValueOrigin::from_file(f.file(), f.path() + ".shutter_curve");
  }
  read_rolling_shutter(f, s);
  if (f.has("filter_type") || f.has("filter_width_px")) s.filter = cycles_filter(f);
  s.film_exposure = f.number("film_exposure", 0, 1e6).value_or(1.0);
  if (const auto use = f.flag("use_adaptive_sampling"))
    s.adaptive = ShotAdaptiveSampling{
        *use, f.number("adaptive_threshold", 0, 1).value_or(0.0),
        uint32_t(f.whole("adaptive_min_samples", 0, kMostAdaptiveMinSamples).value_or(0))};
  read_view_settings(f, s);
  return s;
}

}  // namespace fb::gltf
