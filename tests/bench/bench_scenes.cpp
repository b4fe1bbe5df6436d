#include "tests/bench/bench_scenes.h"

#include <cmath>
#include <numbers>

#include "core/math/constants.h"

namespace fb::bench {
namespace {

// Area-weighted vertex normals: each face adds its unnormalised cross product to its corners.
std::vector<Vec3f> vertex_normals(const std::vector<Vec3f>& positions,
                                  const std::vector<uint32_t>& indices) {
  std::vector<Vec3d> sums(positions.size());
  for (size_t i = 0; i < indices.size(); i += 3) {
    const Vec3d p0(positions[indices[i]]), p1(positions[indices[i + 1]]),
        p2(positions[indices[i + 2]]);
    const Vec3d n = cross(p1 - p0, p2 - p0);
    for (int k = 0; k < 3; ++k)
      sums[indices[i + k]] += n;
  }
  std::vector<Vec3f> normals;
  normals.reserve(sums.size());
  for (const Vec3d& n : sums)
    normals.emplace_back(normalize(n));
  return normals;
}

Scene one_mesh_scene(std::string name, std::vector<Vec3f> positions, std::vector<uint32_t> indices,
                     SceneCamera camera) {
  Scene scene;
  TriangleMesh mesh;
  mesh.name = std::move(name);
  mesh.normals = vertex_normals(positions, indices);
  mesh.positions = std::move(positions);
  mesh.indices = std::move(indices);
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({0, Transform(), "mesh"});
  Material grey;
  grey.name = "grey";
  grey.base_color = {0.8f, 0.8f, 0.8f};
  scene.materials.push_back(grey);
  scene.cameras.push_back(std::move(camera));
  return scene;
}

SceneCamera perspective_camera(double focal_length_mm, const Transform& world_from_camera) {
  SceneCamera camera;
  camera.name = "bench";
  camera.source = "procedural";
  camera.physical.focal_length_mm = focal_length_mm;
  camera.physical.clip_near_m = 0.0;  // every hit counts, however close
  camera.world_from_camera = world_from_camera;
  return camera;
}

}  // namespace

Scene make_sphere_in(uint32_t segments) {
  const uint32_t bands = segments / 2 + 1;  // latitude bands, pole to pole
  const auto radius = [](double theta, double phi) {
    return 1.0 + 0.08 * std::sin(12 * theta) * std::cos(10 * phi) +
           0.03 * std::sin(31 * phi + 3 * theta) + 0.01 * std::cos(97 * theta - 53 * phi);
  };
  const auto vertex = [&](double theta, double phi) {
    const double r = radius(theta, phi);
    return Vec3f(Vec3d{r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                       r * std::sin(theta) * std::sin(phi)});
  };
  // North pole, bands - 1 rings of `segments` vertices, south pole.
  std::vector<Vec3f> positions{vertex(0, 0)};
  for (uint32_t ring = 1; ring < bands; ++ring)
    for (uint32_t s = 0; s < segments; ++s)
      positions.push_back(vertex(kPi * ring / bands, 2 * kPi * s / segments));
  positions.push_back(vertex(kPi, 0));
  const uint32_t south = uint32_t(positions.size() - 1);
  const auto ring_vertex = [&](uint32_t ring, uint32_t s) {
    return 1 + (ring - 1) * segments + s % segments;
  };

  // Counter-clockwise seen from outside (theta grows southwards, phi eastwards seen from +Y).
  std::vector<uint32_t> indices;
  for (uint32_t s = 0; s < segments; ++s) {
    indices.insert(indices.end(), {0, ring_vertex(1, s + 1), ring_vertex(1, s)});
    for (uint32_t ring = 1; ring + 1 < bands; ++ring) {
      const uint32_t a = ring_vertex(ring, s), b = ring_vertex(ring, s + 1),
                     c = ring_vertex(ring + 1, s), d = ring_vertex(ring + 1, s + 1);
      indices.insert(indices.end(), {a, b, c, b, d, c});
    }
    indices.insert(indices.end(),
                   {south, ring_vertex(bands - 1, s), ring_vertex(bands - 1, s + 1)});
  }
  // 18 mm on a 36 mm sensor: a 90 degree horizontal field of view from the centre.
  return one_mesh_scene("displaced_sphere", std::move(positions), std::move(indices),
                        perspective_camera(18.0, Transform()));
}

Scene make_terrain(uint32_t cells) {
  constexpr double kSizeM = 100.0;
  std::vector<Vec3f> positions;
  for (uint32_t j = 0; j <= cells; ++j)
    for (uint32_t i = 0; i <= cells; ++i) {
      const double x = kSizeM * (double(i) / cells - 0.5), z = kSizeM * (double(j) / cells - 0.5);
      const double y = 3.0 * std::sin(0.13 * x) * std::cos(0.11 * z) +
                       0.8 * std::sin(0.57 * x + 0.31 * z) + 0.15 * std::cos(2.3 * x - 1.7 * z);
      positions.push_back(Vec3f(Vec3d{x, y, z}));
    }
  std::vector<uint32_t> indices;
  for (uint32_t j = 0; j < cells; ++j)
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      indices.insert(indices.end(), {a, c, b, b, c, d});  // counter-clockwise seen from +Y
    }
  const Transform world_from_camera = Transform::look_at({0, 8, 55}, {0, 2, -10}, {0, 1, 0});
  return one_mesh_scene("terrain", std::move(positions), std::move(indices),
                        perspective_camera(24.0, world_from_camera));
}

}  // namespace fb::bench
