#include "core/render/cryptomatte_layers.h"

namespace fb {

std::vector<CryptomatteLayer> cryptomatte_layers(const Scene& scene,
                                                 const std::vector<std::string>& passes) {
  std::vector<CryptomatteLayer> layers;
  for (const std::string& pass : passes) {
    const CryptomatteKey* key = find_cryptomatte_pass(pass);
    if (!key) continue;
    CryptomatteLayer& layer = layers.emplace_back(CryptomatteLayer{pass, *key, {}});
    if (*key == CryptomatteKey::kMaterial) {
      for (const Material& material : scene.materials)
        layer.names.push_back(material.name);
      continue;
    }
    const bool asset = *key == CryptomatteKey::kAsset;
    for (const MeshInstance& instance : scene.instances)
      layer.names.push_back(asset && instance.asset < scene.assets.size()
                                ? scene.assets[instance.asset]
                                : instance.node);
    for (const Solid& solid : scene.solids)
      layer.names.push_back(solid.name);
  }
  return layers;
}

}  // namespace fb
