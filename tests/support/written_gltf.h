// A scene as `filmback convert` writes it, read back by tinygltf alone: the JSON any glTF viewer
// gets, for tests of what the writer puts in it.
#pragma once

#include <tiny_gltf.h>

#include <filesystem>

#include "core/scene/scene.h"

namespace fb::test {

// Writes `scene` to `file` (write_gltf) and returns the file as tinygltf reads it; a test failure
// and an empty model when tinygltf cannot read it.
tinygltf::Model written_gltf(const Scene& scene, const std::filesystem::path& file);

}  // namespace fb::test
