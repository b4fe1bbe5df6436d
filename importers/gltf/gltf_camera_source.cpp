#include "importers/gltf/gltf_camera_source.h"

#include <algorithm>
#include <iterator>

#include "core/scene/sensor_fit.h"
#include "core/util/error.h"

namespace fb::gltf {
namespace {

// Frames of a lens track, at most: a bound on what a file allocates.
constexpr size_t kMaxTrackFrames = 100000;
constexpr const char* kPerFrame = "per_frame";
constexpr const char* kFocusPerFrame = "focus_distance_per_frame_m";  // before per_frame
constexpr double kMinTrackFstop = 1e-6;

// Each number Blender's camera carries, with the range a file may give it (Blender's RNA ranges,
// widened to what still traces: docs/blender.md, "What is carried").
struct NumberField {
  CameraValue value;
  double lo, hi;
};
constexpr NumberField kNumbers[] = {
    {CameraValue::kFocalLength, 1e-3, 1e5},    {CameraValue::kSensorWidth, 1e-3, 1e4},
    {CameraValue::kSensorHeight, 1e-3, 1e4},   {CameraValue::kShiftX, -100, 100},
    {CameraValue::kShiftY, -100, 100},         {CameraValue::kOrthoScale, 1e-9, 1e9},
    {CameraValue::kClipNear, 0, 1e18},         {CameraValue::kClipFar, 0, 1e18},
    {CameraValue::kFocusDistance, 1e-6, 1e18}, {CameraValue::kApertureRotation, -1e3, 1e3},
    {CameraValue::kApertureRatio, 1e-2, 1e2},
};

uint32_t sensor_fit(const Fields& f, const std::string& word) {
  const std::optional<uint32_t> named = sensor_fit_named(word);
  if (!named) f.fail("sensor_fit", "'" + word + "', expected " + sensor_fit_choices());
  return *named;
}

// The focus track of files the add-on wrote before per_frame (issues 14-15):
// focus_distance_per_frame_m: {"first_frame": F, "values": [m, ...]}, read so that they keep it.
std::optional<LensTrack> read_focus_only_track(const Fields& camera) {
  if (!camera.has(kFocusPerFrame)) return std::nullopt;
  const Fields f = camera.object(kFocusPerFrame);
  const auto first = f.whole("first_frame", -1e9, 1e9);
  auto values = f.numbers("values", kMaxTrackFrames, 1e-6, 1e18);
  if (!first || !values || values->empty())
    throw_input(f.file(), f.path(),
                "expected first_frame and a non-empty array 'values' of distances in metres");
  LensTrack track;
  track.first_frame = *first;
  track.values[size_t(CameraValue::kFocusDistance)] = std::move(*values);
  return track;
}

// per_frame: {"first_frame": F, "focal_length_mm": [...], "focus_distance_m": [...], "fstop":
// [...], "shift_x": [...], "shift_y": [...]}, each list optional, each value in its scalar's
// range (an f-number here, never 0: a pinhole cannot be interpolated).
std::optional<LensTrack> read_lens_track(const Fields& camera) {
  if (!camera.has(kPerFrame)) return read_focus_only_track(camera);
  if (camera.type(kPerFrame) != Fields::Type::kObject)
    camera.fail(kPerFrame,
                "expected an object {\"first_frame\": F, \"focal_length_mm\": [...], ...}");
  const Fields f = camera.object(kPerFrame);
  LensTrack track;
  const auto first = f.whole("first_frame", -1e9, 1e9);
  if (!first) f.fail("first_frame", "expected the first frame's number, an integer");
  track.first_frame = *first;
  bool any = false;
  for (CameraValue v : LensTrack::kTracked) {
    const char* name = camera_value_name(v);
    const auto range = std::find_if(std::begin(kNumbers), std::end(kNumbers),
                                    [&](const NumberField& n) { return n.value == v; });
    const double lo = range != std::end(kNumbers) ? range->lo : kMinTrackFstop;
    const double hi = range != std::end(kNumbers) ? range->hi : kMaxFstop;
    // tinygltf drops an empty array: it reads as absent.
    auto values = f.numbers(name, kMaxTrackFrames, lo, hi);
    if (!values) continue;
    track.values[size_t(v)] = std::move(*values);
    any = true;
  }
  if (!any)
    throw_input(f.file(), f.path(),
                "expected at least one of focal_length_mm, focus_distance_m, fstop, shift_x, "
                "shift_y (an array, one value per frame from first_frame on)");
  return track;
}

}  // namespace

bool CameraSource::names_any() const {
  for (const auto& v : values)
    if (v) return true;
  return lens_track.has_value();
}

CameraSource read_blender_camera_fields(const Fields& f, const char* name) {
  CameraSource s;
  s.name = name;
  s.path = f.path();
  s.expresses.fill(true);
  const auto named = [&](CameraValue v, std::optional<double> x) {
    s.values[size_t(v)] = x;
    s.paths[size_t(v)] = f.path() + "." + camera_value_name(v);
  };
  for (const NumberField& n : kNumbers)
    named(n.value, f.number(camera_value_name(n.value), n.lo, n.hi));
  if (const auto fit = f.word("sensor_fit"))
    named(CameraValue::kSensorFit, double(sensor_fit(f, *fit)));
  if (f.has("fstop")) {
    const auto n = f.type("fstop") == Fields::Type::kNumber ? f.number("fstop", -HUGE_VAL, HUGE_VAL)
                                                            : std::nullopt;
    const std::optional<double> fstop = n ? fstop_from(*n) : std::nullopt;
    if (!fstop) f.fail("fstop", (n ? number_text(*n) + ", " : std::string()) + kFstopExpected);
    named(CameraValue::kFstop, fstop);
  }
  const auto blades = f.whole("aperture_blades", 0, 64);
  if (blades == 1 || blades == 2) f.fail("aperture_blades", "expected 0 (round) or 3 to 64 blades");
  named(CameraValue::kApertureBlades, blades);
  s.lens_track = read_lens_track(f);
  for (CameraValue v : LensTrack::kTracked)
    s.track_paths[size_t(v)] = f.path() + "." + kPerFrame + "." + camera_value_name(v);
  if (!f.has(kPerFrame))
    s.track_paths[size_t(CameraValue::kFocusDistance)] =
        f.path() + "." + kFocusPerFrame + ".values";
  return s;
}

CameraSource read_ext_camera_physical(const Fields& f) {
  CameraSource s;
  s.name = "EXT_camera_physical";
  s.path = f.path();
  for (CameraValue v :
       {CameraValue::kFocalLength, CameraValue::kSensorWidth, CameraValue::kSensorHeight})
    s.expresses[size_t(v)] = true;
  if (const auto focal = f.number("focalLength", 1e-6, 1e2)) {
    s.values[size_t(CameraValue::kFocalLength)] = *focal * 1000;
    s.paths[size_t(CameraValue::kFocalLength)] = f.path() + ".focalLength";
  }
  if (const auto sensor = f.numbers("sensorSize", 2, 1e-6, 10)) {
    if (sensor->size() != 2) f.fail("sensorSize", "expected [width, height] in metres");
    s.values[size_t(CameraValue::kSensorWidth)] = (*sensor)[0] * 1000;
    s.values[size_t(CameraValue::kSensorHeight)] = (*sensor)[1] * 1000;
    s.paths[size_t(CameraValue::kSensorWidth)] = f.path() + ".sensorSize[0]";
    s.paths[size_t(CameraValue::kSensorHeight)] = f.path() + ".sensorSize[1]";
  }
  return s;
}

}  // namespace fb::gltf
