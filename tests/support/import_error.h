// Importing the glTF files tests write: what a deliberately broken file says, and a built scene.
#pragma once

#include <filesystem>
#include <string>

#include "core/scene/scene.h"
#include "support/gltf_builder.h"

namespace fb::test {

// The InputError importing `file` raises, or "" when it imports.
std::string import_error(const std::filesystem::path& file);

// Writes `gltf` into the scratch folder as `name` and imports it (warnings ignored).
Scene import_built(GltfBuilder& gltf, const char* name);

}  // namespace fb::test
