#include "importers/gltf/gltf_shot.h"

#include <cmath>
#include <optional>
#include <string>

#include "core/scene/sensor_fit.h"
#include "core/util/error.h"

namespace fb::gltf {
namespace {

// Frames of a focus track and samples of a shutter curve, at most: bounds on what a file allocates.
constexpr size_t kMaxTrackFrames = 100000;
constexpr size_t kMaxCurveSamples = 4096;

template <typename T>
void set(std::optional<double> value, T& field) {
  if (value) field = T(*value);
}

bool same_word(const std::string& a, const char* b) {
  if (a.size() != std::char_traits<char>::length(b)) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  return true;
}

// Cycles' pixel filters as filter plugins (docs/filters.md, "Against Blender"): Blackman-Harris of
// width w spans +-w; the Gaussian of width w is exp(-8x^2/w^2) (sigma = w/4) cut at +-1.5w; the box
// of width w spans +-w/2.
std::string cycles_filter(const Fields& f) {
  const std::string type = f.word("filter_type").value_or("BLACKMAN_HARRIS");
  const double w = f.number("filter_width_px", 0.01, 10).value_or(1.5);
  if (same_word(type, "blackman_harris")) return "blackman_harris:width=" + number_text(w);
  if (same_word(type, "gaussian"))
    return "gaussian:radius=" + number_text(1.5 * w) + ",sigma=" + number_text(w / 4);
  if (same_word(type, "box")) return "box:radius=" + number_text(w / 2);
  f.fail("filter_type", "'" + type + "', expected BLACKMAN_HARRIS, GAUSSIAN or BOX");
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

}  // namespace

bool apply_camera_fields(const Fields& f, PhysicalCamera& camera) {
  bool found = false;
  const auto note = [&](auto value) {
    found |= value.has_value();
    return value;
  };
  set(note(f.number("focal_length_mm", 1e-3, 1e5)), camera.focal_length_mm);
  set(note(f.number("sensor_width_mm", 1e-3, 1e4)), camera.sensor_width_mm);
  set(note(f.number("sensor_height_mm", 1e-3, 1e4)), camera.sensor_height_mm);
  if (const auto fit = note(f.word("sensor_fit"))) {
    const std::optional<uint32_t> named = sensor_fit_named(*fit);
    if (!named) f.fail("sensor_fit", "'" + *fit + "', expected " + sensor_fit_choices());
    camera.sensor_fit = *named;
  }
  set(note(f.number("shift_x", -100, 100)), camera.shift_x);
  set(note(f.number("shift_y", -100, 100)), camera.shift_y);
  set(note(f.number("ortho_scale_m", 1e-9, 1e9)), camera.ortho_scale_m);
  set(note(f.number("clip_near_m", 0, 1e18)), camera.clip_near_m);
  set(note(f.number("clip_far_m", 0, 1e18)), camera.clip_far_m);
  if (!(camera.clip_far_m > camera.clip_near_m))
    f.fail("clip_far_m", "expected clip_far_m > clip_near_m");
  // 0: Blender's depth of field is off, a pinhole.
  if (const auto n = note(f.number("fstop", 0, 1e6))) camera.fstop = *n > 0 ? *n : HUGE_VAL;
  set(note(f.number("focus_distance_m", 1e-6, 1e18)), camera.focus_distance_m);
  set(note(f.whole("aperture_blades", 0, 64)), camera.aperture_blades);
  if (camera.aperture_blades == 1 || camera.aperture_blades == 2)
    f.fail("aperture_blades", "expected 0 (round) or 3 to 64 blades");
  set(note(f.number("aperture_rotation_rad", -1e3, 1e3)), camera.aperture_rotation_rad);
  set(note(f.number("aperture_ratio", 1e-2, 1e2)), camera.aperture_ratio);
  return found;
}

bool apply_ext_camera_physical(const Fields& f, PhysicalCamera& camera) {
  const auto focal = f.number("focalLength", 1e-6, 1e2);
  const auto sensor = f.numbers("sensorSize", 2, 1e-6, 10);
  if (sensor && sensor->size() != 2) f.fail("sensorSize", "expected [width, height] in metres");
  if (focal) camera.focal_length_mm = *focal * 1000;
  if (sensor)
    camera.sensor_width_mm = (*sensor)[0] * 1000, camera.sensor_height_mm = (*sensor)[1] * 1000;
  return focal || sensor;
}

std::optional<FocusTrack> read_focus_track(const Fields& camera) {
  const Fields f = camera.object("focus_distance_per_frame_m");
  if (!camera.has("focus_distance_per_frame_m")) return std::nullopt;
  const auto first = f.whole("first_frame", -1e9, 1e9);
  auto values = f.numbers("values", kMaxTrackFrames, 1e-6, 1e18);
  if (!first || !values || values->empty())
    throw_input(f.file(), f.path(),
                "expected first_frame and a non-empty array 'values' of distances in metres");
  return FocusTrack{*first, std::move(*values)};
}

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
  }
  if (f.has("filter_type") || f.has("filter_width_px")) s.filter = cycles_filter(f);
  s.film_exposure = f.number("film_exposure", 0, 1e6).value_or(1.0);
  read_view_settings(f, s);
  return s;
}

}  // namespace fb::gltf
