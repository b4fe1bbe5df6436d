// Getting a glTF file into tinygltf safely: the checks tinygltf does not make on untrusted bytes,
// and file access confined to the scene's own folder.
#pragma once

#include <filesystem>

namespace tinygltf {
class Model;
}

namespace fb::gltf {

// JSON nested deeper than this is refused: tinygltf copies extras and extensions recursively, so a
// small file of nested brackets would otherwise exhaust the stack.
constexpr int kMaxJsonDepth = 128;

// Largest external buffer or image file read (tinygltf works with 32-bit sizes).
constexpr uintmax_t kMaxExternalFileBytes = uintmax_t(1) << 31;

// Reads `file` (.gltf or .glb) into `model`. Throws InputError naming the file and, for JSON, the
// line and column. External buffers and images resolve only to regular files inside the scene's
// folder; `data:` URIs are decoded by tinygltf.
void load_model(const std::filesystem::path& file, tinygltf::Model& model);

// An external file that the scene names outside tinygltf's loader (an environment image): `uri`,
// relative to `scene_file`'s folder, under the same rules as buffers and images. Throws
// InputError naming the scene file, `where` (its JSON path) and what is wrong.
std::filesystem::path confined_external_file(const std::filesystem::path& scene_file,
                                             const std::string& uri, const std::string& where);

}  // namespace fb::gltf
