// libFuzzer harness: the glTF importer, exactly as `filmback render` runs it (import_gltf: the GLB
// container and JSON depth checks, tinygltf with filmback's confined file callbacks, then every
// validation of the importer) on a .gltf, or a .glb when the input starts with "glTF". The scene's
// folder holds an external buffer, an image and a symbolic link out of the folder, and a file sits
// outside it, so that URIs found by the fuzzer reach real files. Any exception other than the
// importer's own errors is a finding, as is anything the sanitizers report.
#include <cstring>

#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "tests/fuzz/scratch_folder.h"

namespace {

const fb::fuzz::ScratchFolder& folder() {
  static const fb::fuzz::ScratchFolder f("gltf");
  static const bool filled = [] {
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    f.write("scene/triangle.bin", reinterpret_cast<const uint8_t*>(triangle), sizeof triangle);
    f.write("scene/texture.png", "not decoded at import");
    f.write("outside.bin", reinterpret_cast<const uint8_t*>(triangle), sizeof triangle);
    f.link("scene/link.bin", "../outside.bin");
    return true;
  }();
  (void)filled;
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const auto scene = folder().write(binary ? "scene/scene.glb" : "scene/scene.gltf", data, size);
  fb::Diagnostics diagnostics;
  try {
    fb::import_gltf(scene, diagnostics);
  } catch (const fb::InputError&) {
  } catch (const fb::UsageError&) {
  }
  return 0;
}
