// The scene's render settings as a glTF file carries them: in the scene's FILMBACK_blender
// extension (written by the add-on in importers/blender/) or as custom properties in its `extras`
// under the extension's names. Names and units: docs/blender.md. The camera's values are read in
// gltf_camera_source.h.
#pragma once

#include "core/scene/scene.h"
#include "importers/gltf/gltf_json.h"

namespace fb::gltf {

// The scene's render settings, Blender's view settings among them.
ShotSettings read_shot_settings(const Fields& fields);

}  // namespace fb::gltf
