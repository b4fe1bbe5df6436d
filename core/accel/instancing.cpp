#include "core/accel/instancing.h"

namespace fb {

std::vector<bool> instanced_meshes(const Scene& scene, Instancing policy) {
  std::vector<bool> instanced(scene.meshes.size(), false);
  if (policy == Instancing::kNever) return instanced;
  std::vector<uint32_t> uses(scene.meshes.size(), 0);
  for (const MeshInstance& instance : scene.instances)
    uses[instance.mesh] = std::min<uint32_t>(uses[instance.mesh] + 1, 2);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    const Material& material = scene.materials[mesh.material];
    const bool can = !mesh.indices.empty() && !(max_component(material.emission) > 0.f) &&
                     !material.base_color_pattern;
    instanced[m] = can && (policy == Instancing::kAlways ? uses[m] >= 1 : uses[m] >= 2);
  }
  return instanced;
}

}  // namespace fb
