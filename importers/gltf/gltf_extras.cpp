#include "importers/gltf/gltf_extras.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "core/util/error.h"

namespace fb::gltf {
namespace {

class Reader {
 public:
  Reader(const tinygltf::Value& extras, const std::string& path, const std::string& file)
      : extras_(extras), path_(path), file_(file) {}

  // The number under `key` if present, checked against [lo, hi]; `whole` requires an integer.
  std::optional<double> number(const char* key, double lo, double hi, bool whole = false) {
    if (!extras_.IsObject() || !extras_.Has(key)) return std::nullopt;
    const tinygltf::Value& v = extras_.Get(key);
    const double x = v.IsNumber() ? v.GetNumberAsDouble() : NAN;
    if (!(x >= lo && x <= hi) || (whole && x != std::floor(x)))
      throw_input(file_, path_ + "." + key,
                  "expected " + std::string(whole ? "a whole number" : "a number") + " in [" +
                      number_text(lo) + ", " + number_text(hi) + "]");
    found_ = true;
    return x;
  }

  std::optional<std::string> word(const char* key) {
    if (!extras_.IsObject() || !extras_.Has(key)) return std::nullopt;
    const tinygltf::Value& v = extras_.Get(key);
    if (!v.IsString()) throw_input(file_, path_ + "." + key, "expected a string");
    std::string s = v.Get<std::string>();
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    found_ = true;
    return s;
  }

  void fail(const char* key, const std::string& what) { throw_input(file_, path_ + "." + key, what); }
  bool found() const { return found_; }

 private:
  const tinygltf::Value& extras_;
  const std::string& path_;
  const std::string& file_;
  bool found_ = false;
};

template <typename T>
void set(std::optional<double> value, T& field) {
  if (value) field = T(*value);
}

}  // namespace

bool apply_camera_extras(const tinygltf::Value& extras, const std::string& path,
                         const std::string& file, PhysicalCamera& camera) {
  Reader r(extras, path, file);
  set(r.number("focal_length_mm", 1e-3, 1e5), camera.focal_length_mm);
  set(r.number("sensor_width_mm", 1e-3, 1e4), camera.sensor_width_mm);
  set(r.number("sensor_height_mm", 1e-3, 1e4), camera.sensor_height_mm);
  if (const auto fit = r.word("sensor_fit")) {
    if (*fit == "auto") camera.sensor_fit = FB_SENSOR_FIT_AUTO;
    else if (*fit == "horizontal") camera.sensor_fit = FB_SENSOR_FIT_HORIZONTAL;
    else if (*fit == "vertical") camera.sensor_fit = FB_SENSOR_FIT_VERTICAL;
    else r.fail("sensor_fit", "'" + *fit + "', expected auto, horizontal or vertical");
  }
  set(r.number("shift_x", -100, 100), camera.shift_x);
  set(r.number("shift_y", -100, 100), camera.shift_y);
  set(r.number("ortho_scale_m", 1e-9, 1e9), camera.ortho_scale_m);
  set(r.number("clip_near_m", 0, 1e18), camera.clip_near_m);
  set(r.number("clip_far_m", 0, 1e18), camera.clip_far_m);
  if (!(camera.clip_far_m > camera.clip_near_m)) r.fail("clip_far_m", "expected clip_far_m > clip_near_m");
  set(r.number("fstop", 1e-3, 1e6), camera.fstop);
  set(r.number("focus_distance_m", 1e-6, 1e18), camera.focus_distance_m);
  set(r.number("aperture_blades", 0, 64, true), camera.aperture_blades);
  if (camera.aperture_blades == 1 || camera.aperture_blades == 2)
    r.fail("aperture_blades", "expected 0 (round) or 3 to 64 blades");
  set(r.number("aperture_rotation_rad", -1e3, 1e3), camera.aperture_rotation_rad);
  set(r.number("aperture_ratio", 1e-2, 1e2), camera.aperture_ratio);
  return r.found();
}

ShotSettings read_shot_extras(const tinygltf::Value& extras, const std::string& path,
                              const std::string& file) {
  Reader r(extras, path, file);
  ShotSettings s;
  if (const auto w = r.number("resolution_x_px", 1, 32768, true)) s.width_px = uint32_t(*w);
  if (const auto h = r.number("resolution_y_px", 1, 32768, true)) s.height_px = uint32_t(*h);
  if (s.width_px.has_value() != s.height_px.has_value())
    r.fail(s.width_px ? "resolution_y_px" : "resolution_x_px", "expected both resolution_x_px and resolution_y_px");
  s.fps = r.number("fps", 1e-3, 1e6);
  s.frame = r.number("frame", -1e9, 1e9);
  s.shutter_open_s = r.number("shutter_open_s", -1e6, 1e6);
  s.shutter_close_s = r.number("shutter_close_s", -1e6, 1e6);
  if (s.shutter_open_s.has_value() != s.shutter_close_s.has_value() ||
      (s.shutter_open_s && !(*s.shutter_close_s >= *s.shutter_open_s)))
    r.fail("shutter_close_s", "expected shutter_open_s and shutter_close_s, with close >= open");
  return s;
}

}  // namespace fb::gltf
