#include "importers/import_scene.h"

#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "importers/pov/pov_importer.h"

namespace fb {

bool import_reads_frame(const std::filesystem::path& file) {
  return file.extension() == ".pov";
}

Scene import_scene(const std::filesystem::path& file, const ImportOptions& options,
                   Diagnostics& diagnostics) {
  const std::string ext = file.extension().string();
  if (ext == ".gltf" || ext == ".glb") return import_gltf(file, diagnostics);
  if (ext == ".pov") return import_pov(file, options, diagnostics);
  throw UsageError("'" + file.string() + "': unknown scene type '" + ext +
                   "' (expected .gltf, .glb or .pov)");
}

}  // namespace fb
