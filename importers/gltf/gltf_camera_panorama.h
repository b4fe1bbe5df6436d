// A panoramic camera in the FILMBACK_blender camera extension: "panorama": {"type": KIND,
// PARAMETER: number, ...}, the projection kind (a row of core/render/shot_plan.cpp's
// kModelPlugins) and its values under the camera plugin's parameter names, in Blender's units
// (docs/blender.md, "Cameras").
#pragma once

#include <optional>
#include <string>

#include "core/scene/camera.h"

namespace tinygltf {
class Value;
}

namespace fb::gltf {

// The camera model `blender_camera` (the extension object at `path` in `file`) names, if any.
// Throws InputError naming the JSON path for an unknown type, a key the type does not take, or a
// value that is not a finite number; the plugin's schema checks each value's range.
std::optional<CameraModel> read_panorama(const tinygltf::Value& blender_camera,
                                         const std::string& path, const std::string& file);

}  // namespace fb::gltf
