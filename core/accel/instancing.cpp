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
    if (mesh.indices.empty() || uses[m] < (policy == Instancing::kAlways ? 1 : 2)) continue;
    const Material& material = scene.materials[mesh.material];
    // POV-Ray's patterns, normals and layers are evaluated at the hit's world position
    instanced[m] = !(max_component(material.emission) > 0.f) && !material.base_color_pattern &&
                   !material.normal_pattern && material.layers.empty();
  }
  return instanced;
}

}  // namespace fb
