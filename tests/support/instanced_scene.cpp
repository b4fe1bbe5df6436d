#include "support/instanced_scene.h"

#include <array>
#include <cmath>

#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"

namespace fb::test {
namespace {

// A UV sphere of radius 0.5 with vertex normals, `segments` around.
void add_sphere(test::GltfBuilder& gltf, int material, std::vector<int>& meshes) {
  std::vector<Vec3f> positions, normals;
  std::vector<uint32_t> indices;
  const int segments = 24, rings = 12;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = float(M_PI) * float(r) / rings,
                  phi = 2 * float(M_PI) * float(s) / segments;
      const Vec3f n{std::sin(theta) * std::cos(phi), std::cos(theta),
                    std::sin(theta) * std::sin(phi)};
      normals.push_back(n);
      positions.push_back(n * 0.5f);
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t i = uint32_t(r * (segments + 1) + s), j = i + segments + 1;
      indices.insert(indices.end(), {i, i + 1, j, i + 1, j + 1, j});  // outward, counter-clockwise
    }
  meshes.push_back(gltf.mesh(positions, indices, material, 5125, normals));
}

}  // namespace

// Five uses of one sphere: plain; rotated and unevenly scaled; mirrored (negative determinant);
// nested under a rotated, scaled parent; and moving 0.4 m along +X over the first second.
Scene five_spheres() {
  test::GltfBuilder gltf;
  std::vector<int> meshes;
  add_sphere(gltf, gltf.material({0.8f, 0.5f, 0.2f}), meshes);
  const int sphere = meshes[0];
  const auto place = [&](const char* name, int mesh, std::array<double, 3> translation,
                         std::array<double, 4> rotation, std::array<double, 3> scale,
                         std::vector<int> children = {}, bool root = true) {
    test::GltfBuilder::Node node;
    node.name = name, node.mesh = mesh, node.translation = translation;
    node.rotation = rotation, node.scale = scale, node.children = std::move(children);
    return gltf.node(node, root);
  };
  place("plain", sphere, {0, 0, -4}, {0, 0, 0, 1}, {1, 1, 1});
  place("stretched", sphere, {1.2, 0.3, -5}, {0.2, 0.3, 0.1, 0.927}, {1, 0.6, 1.4});
  place("mirrored", sphere, {-1.2, 0, -4.5}, {0, 0.38, 0, 0.925}, {-1, 1.2, 1});
  const int child = place("nested", sphere, {0.3, 0, 0}, {0, 0, 0, 1}, {0.5, 0.4, 0.5}, {}, false);
  place("parent", -1, {0, 1.3, -6}, {0.3, 0, 0.2, 0.933}, {2, 1.5, 2}, {child});
  const int moving = place("moving", sphere, {0, -1.2, -4}, {0, 0, 0, 1}, {1, 1, 1});
  gltf.animate(moving, "translation", {0.f, 1.f}, {0.f, -1.2f, -4.f, 0.4f, -1.2f, -4.f});
  const auto file = gltf.write(test::scratch_dir() / "five_spheres.gltf");
  Diagnostics diagnostics;
  return import_gltf(file, diagnostics);
}

}  // namespace fb::test
