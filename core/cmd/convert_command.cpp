#include <iostream>

#include "core/cmd/commands.h"
#include "core/tessellate/tessellate.h"
#include "core/util/error.h"
#include "importers/gltf/gltf_writer.h"

namespace fb {

int run_convert(ConvertCommand& c) {
  if (c.output.extension() != ".gltf")
    throw UsageError("output '" + c.output.string() + "': expected a .gltf file name");
  const std::filesystem::path folder = c.output.has_parent_path() ? c.output.parent_path() : ".";
  if (!std::filesystem::is_directory(folder))
    throw UsageError("output '" + c.output.string() + "': the folder '" + folder.string() +
                     "' does not exist");
  if (!c.resolution.empty()) c.import.resolution = parse_resolution(c.resolution);

  Diagnostics diagnostics;
  Scene scene = import_scene(c.input, c.import, diagnostics);
  TessellationOptions tessellation;  // glTF has only triangles
  if (c.tolerance_m) tessellation.tolerance_m = *c.tolerance_m, tessellation.relative_tolerance = 0;
  tessellate_solids(scene, tessellation, diagnostics);
  write_gltf(scene, c.output, diagnostics);
  diagnostics.print(std::cerr);
  std::cout << "filmback: wrote " << c.output.string() << ": " << scene.meshes.size() << " meshes, "
            << scene.triangle_count() << " triangles, " << scene.materials.size() << " materials, "
            << scene.lights.size() << " lights, " << scene.cameras.size() << " cameras\n";
  return 0;
}

}  // namespace fb
