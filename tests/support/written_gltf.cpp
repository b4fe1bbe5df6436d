#include "support/written_gltf.h"

#include <gtest/gtest.h>

#include <string>

#include "core/util/diagnostics.h"
#include "importers/gltf/gltf_writer.h"

namespace fb::test {

tinygltf::Model written_gltf(const Scene& scene, const std::filesystem::path& file) {
  Diagnostics diagnostics;
  write_gltf(scene, file, diagnostics);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  if (!loader.LoadASCIIFromFile(&model, &error, &warning, file.string()))
    ADD_FAILURE() << file << ": " << error;
  return model;
}

}  // namespace fb::test
