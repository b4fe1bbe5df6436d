// The sources of a glTF camera's physical values, each read alone: the FILMBACK_blender extension
// (written by the add-on in importers/blender/), EXT_camera_physical, and custom properties in
// `extras` under the extension's names (docs/blender.md, "Cameras"). gltf_camera.cpp decides
// between them; nothing here mixes two sources.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "core/scene/camera.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

struct CameraSource {
  std::string name;  // "FILMBACK_blender", "EXT_camera_physical", "extras"
  std::string path;  // the JSON path of its object
  // What the source can say: all of Blender's camera for ours and extras, focal length and sensor
  // for EXT_camera_physical.
  std::array<bool, kCameraValueCount> expresses{};
  std::array<std::optional<double>, kCameraValueCount> values;  // what it names
  std::array<std::string, kCameraValueCount> paths;             // the JSON path of each
  std::optional<LensTrack> lens_track;                          // per_frame
  std::array<std::string, kCameraValueCount> track_paths;       // JSON path of each tracked list

  bool names_any() const;
};

// FILMBACK_blender or extras (`name`): Blender's names and units. F-Stop through fstop_from.
CameraSource read_blender_camera_fields(const Fields& fields, const char* name);

// EXT_camera_physical (KhronosGroup/glTF pull request 2608): focalLength and sensorSize, metres.
CameraSource read_ext_camera_physical(const Fields& fields);

}  // namespace fb::gltf
