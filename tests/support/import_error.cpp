#include "support/import_error.h"

#include "core/util/diagnostics.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"

namespace fb::test {

std::string import_error(const std::filesystem::path& file) {
  Diagnostics diagnostics;
  try {
    import_gltf(file, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Scene import_built(GltfBuilder& gltf, const char* name) {
  Diagnostics diagnostics;
  return import_gltf(gltf.write(scratch_dir() / name), diagnostics);
}

}  // namespace fb::test
