// Writes small glTF files for tests through tinygltf's own serialiser, so test scenes are valid
// glTF produced independently of filmback's importer.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <filmback/vec.h>

namespace fb::test {

// A fresh, empty folder under the system temp dir, named after the running test.
std::filesystem::path scratch_dir();

// RFC 4648 base64, for data: URIs in hand-written glTF files.
std::string base64(const std::vector<unsigned char>& bytes);

class GltfBuilder {
 public:
  GltfBuilder();
  ~GltfBuilder();

  // A Lambertian material: metallic 0 and no specular layer (KHR_materials_specular 0).
  int material(Rgb base_color, Rgb emission = {}, double emissive_strength = 1.0,
               bool double_sided = true);
  // Triangles with optional normals; indices of the given component type (5121, 5123, 5125) or
  // none (-1: non-indexed, positions taken three at a time).
  int mesh(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices, int material,
           int index_component_type = 5125, const std::vector<Vec3f>& normals = {});
  int perspective_camera(double yfov, double aspect_ratio, double znear, double zfar,
                         const std::string& name = "");
  int orthographic_camera(double xmag, double ymag, double znear, double zfar);
  int point_light(Rgb color, double intensity_cd);

  // A skin of the joints `joints` (node indices) with their inverse bind matrices, 16
  // column-major values per joint (empty: none written, each the identity).
  int skin(const std::vector<int>& joints, const std::vector<float>& inverse_binds = {});
  // JOINTS_<set> (unsigned shorts) and WEIGHTS_<set> (floats) of `mesh`'s first primitive, four
  // of each per vertex.
  void skin_weights(int mesh, int set, const std::vector<uint16_t>& joints,
                    const std::vector<float>& weights);

  // A morph target of `mesh`'s first primitive: POSITION displacements, and NORMAL ones unless
  // empty.
  void morph_target(int mesh, const std::vector<Vec3f>& positions,
                    const std::vector<Vec3f>& normals = {});
  // A sparse VEC3 float accessor (glTF 2.0 §3.6.2.3) of `count` elements: accessor `base`'s
  // data, or zeros without a bufferView when `base` is -1, with `values` at `indices` (written
  // as `index_component_type`: 5121, 5123, 5125). `sparse_count` replaces sparse.count, which is
  // otherwise the number of indices.
  int sparse_vec3(size_t count, const std::vector<uint32_t>& indices,
                  const std::vector<Vec3f>& values, int base = -1, int index_component_type = 5125,
                  int sparse_count = -1);
  // Sets attribute `name` of `mesh`'s first primitive to `accessor`.
  void attribute(int mesh, const std::string& name, int accessor);
  // A morph target of `mesh`'s first primitive whose POSITION is `positions`.
  void morph_target_accessor(int mesh, int positions);
  // The mesh's default morph weights.
  void morph_weights(int mesh, const std::vector<double>& weights);

  // FILMBACK_deformation on `node` (whose mesh has one primitive): its shapes at `times_s`,
  // positions per time, and normals per time unless empty.
  void evaluated_shapes(int node, const std::vector<double>& times_s,
                        const std::vector<std::vector<Vec3f>>& positions,
                        const std::vector<std::vector<Vec3f>>& normals = {},
                        bool world_space = false);

  struct Node {
    std::string name;
    int mesh = -1, camera = -1, light = -1, skin = -1;
    std::array<double, 3> translation{0, 0, 0};
    std::array<double, 4> rotation{0, 0, 0, 1};  // x, y, z, w
    std::array<double, 3> scale{1, 1, 1};
    std::vector<double> matrix;  // column-major 16 values; overrides TRS when set
    std::vector<int> children;
    std::vector<double> weights;  // morph weights overriding the mesh's
  };
  int node(const Node& node, bool root = true);
  // A channel of animation 0 moving `path` ("translation", "rotation", "scale", "weights") of
  // `node`: key times in s and 3 or 4 values per key, or one per morph target (CUBICSPLINE:
  // in-tangent, value, out-tangent per key).
  void animate(int node, const std::string& path, const std::vector<float>& times_s,
               const std::vector<float>& values, const std::string& interpolation = "LINEAR");

  // Writes .gltf (JSON, buffers embedded as data: URIs) or .glb, by extension.
  std::filesystem::path write(const std::filesystem::path& file);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fb::test
