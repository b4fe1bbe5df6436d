#include "support/textured_quad.h"

#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/png.h"

namespace fb::test {

std::vector<unsigned char> checker_png(int size, int check) {
  std::vector<unsigned char> rgba;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const unsigned char v = ((x / check + y / check) % 2) ? 255 : 0;
      rgba.insert(rgba.end(), {v, v, v, 255});
    }
  return png(size, size, rgba);
}

Scene textured_quad(const std::vector<Vec3f>& corners, bool ground, float metres_per_tile,
                    int texels, int check, double aspect_ratio,
                    const std::filesystem::path& gltf_file) {
  GltfBuilder gltf;
  GltfBuilder::Node quad;
  quad.mesh = gltf.mesh(corners, {0, 1, 2, 0, 2, 3}, gltf.material({0, 0, 0}, {1, 1, 1}));
  gltf.node(quad);
  GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(0.5, aspect_ratio, 0.05, 1000);
  gltf.node(camera);
  Diagnostics diagnostics;
  Scene scene = import_gltf(gltf.write(gltf_file), diagnostics);
  TriangleMesh& mesh = scene.meshes.at(0);
  mesh.texturing.texcoords[0].clear();
  for (const Vec3f& p : mesh.positions)
    mesh.texturing.texcoords[0].push_back(Vec2f{p.x, ground ? p.z : p.y} * (1.f / metres_per_tile));
  scene.images.push_back({"images[0]", {}, checker_png(texels, check)});
  scene.materials.at(mesh.material).textures.emissive.image = 0;
  return scene;
}

RenderOptions texture_render_options(uint32_t width, uint32_t height, uint32_t spp, bool footprint,
                                     uint64_t seed) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples_per_pixel = spp;
  options.integrator = "path:max_depth=0";
  options.filter = "box";
  options.seed = seed;
  options.texture_footprint = footprint;
  options.show_progress = false;
  return options;
}

}  // namespace fb::test
