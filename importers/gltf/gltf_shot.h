// Blender's physical camera and shot settings as a glTF file carries them: in the FILMBACK_blender
// extension (written by the add-on in importers/blender/), in EXT_camera_physical, or as custom
// properties in `extras` under the extension's names. Names and units: docs/blender.md.
#pragma once

#include <optional>

#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "core/util/diagnostics.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// Overrides the fields of `camera` that `fields` names; returns whether it named any.
bool apply_camera_fields(const Fields& fields, PhysicalCamera& camera);

// EXT_camera_physical (KhronosGroup/glTF pull request 2608): focalLength and sensorSize, in
// metres. Returns whether it named either.
bool apply_ext_camera_physical(const Fields& fields, PhysicalCamera& camera);

// focus_distance_per_frame_m: {"first_frame": F, "values": [m, ...]}.
std::optional<FocusTrack> read_focus_track(const Fields& fields);

// The scene's render settings, Blender's view settings among them.
ShotSettings read_shot_settings(const Fields& fields);

}  // namespace fb::gltf
