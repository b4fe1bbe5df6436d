#include "core/render/memory_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/error.h"

namespace fb {
namespace {

TEST(MemoryEstimate, ParsesSizesInPowersOf1024) {
  EXPECT_EQ(parse_memory_size("8G"), 8ull << 30);
  EXPECT_EQ(parse_memory_size("512M"), 512ull << 20);
  EXPECT_EQ(parse_memory_size("1.5K"), 1536ull);
  EXPECT_EQ(parse_memory_size("2T"), 2ull << 40);
  EXPECT_EQ(parse_memory_size("100000"), 100000ull);
  for (const char* bad : {"", "G", "8GB", "8g", "-1G", "0", "0.5", "nan", "1e30T", "8 G"})
    EXPECT_THROW(parse_memory_size(bad), UsageError) << bad;
}

// Each term counted as core/film/film.h and splat_tiles.h allocate it.
TEST(MemoryEstimate, CountsFilmSplatTilesAndGeometry) {
  const MemoryEstimate importance =
      estimate_memory(100, 50, 3, Reconstruction::kImportance, 2, {1000, 0, 0});
  // per pixel: 4 double sums and weight, a 32-bit count, 3 + 4 floats of resolved images
  EXPECT_EQ(importance.film_bytes, 5000.0 * (4 * 8 + 4 + 7 * 4));
  EXPECT_EQ(importance.splat_bytes, 0);
  EXPECT_EQ(importance.geometry_bytes, 1000.0 * 120);
  const MemoryEstimate splat = estimate_memory(100, 50, 3, Reconstruction::kSplat, 2, {});
  EXPECT_EQ(splat.splat_bytes, 5000.0 * 1.25 * 1.25 * 4 * 8);  // 16 px tiles grown by 2 px a side
  EXPECT_EQ(splat.total(), splat.film_bytes + splat.splat_bytes);
}

// Counted as refinement makes them: a cube's 6 quads give 12 triangles at level 0, 24 quads at
// level 1 and 96 at level 2 (the 192 triangles of docs/cli.md's example plan line); a triangle
// becomes 3 quads at level 1.
TEST(MemoryEstimate, RefinedTrianglesFollowFromTheCage) {
  SubdivisionSurface cube;
  cube.cage_face_sizes.assign(6, 4);
  const double expected[] = {12, 48, 192, 768};
  for (uint32_t level = 0; level < 4; ++level) {
    cube.settings.levels_render = level;
    EXPECT_EQ(refined_triangles(cube), expected[level]) << level;
  }
  SubdivisionSurface triangle;
  triangle.cage_face_sizes = {3};
  triangle.settings.levels_render = 1;
  EXPECT_EQ(refined_triangles(triangle), 6);
  triangle.settings.levels_render = 11;  // Blender's highest
  EXPECT_EQ(refined_triangles(triangle), 6 * std::pow(4.0, 10));
}

// Texture coordinates and tangents, in the scene and in each instance's render copy.
TEST(MemoryEstimate, CountsTextureCoordinatesAndTangents) {
  Scene scene;
  TriangleMesh quad;
  quad.positions.resize(4);
  quad.texturing.texcoords[0].resize(4);
  quad.texturing.tangents.resize(4);
  scene.meshes = {quad, TriangleMesh{}};
  for (const uint32_t mesh : {0u, 0u, 1u}) {
    MeshInstance instance;
    instance.mesh = mesh;
    scene.instances.push_back(instance);
  }
  EXPECT_EQ(geometry_counts(scene).texturing_bytes, 3 * 4 * (8 + 16));
  const MemoryEstimate e = estimate_memory(10, 10, 3, Reconstruction::kImportance, 0,
                                           {2, 0, geometry_counts(scene).texturing_bytes});
  EXPECT_EQ(e.geometry_bytes, 2 * 120 + 288);
}

// Two triangles on four vertices.
TriangleMesh estimate_quad() {
  TriangleMesh quad;
  quad.positions.resize(4);
  quad.indices = {0, 1, 2, 0, 2, 3};
  return quad;
}

// A mesh several instances use is stored once (core/accel/instancing.h): its triangles and
// texturing once in the render, plus a record per instance; a mesh used once is flattened.
TEST(MemoryEstimate, CountsAnInstancedMeshOnceAndEachOfItsInstances) {
  Scene scene;
  scene.materials.push_back({});
  TriangleMesh quad = estimate_quad();
  quad.texturing.texcoords[0].resize(4);
  scene.meshes = {quad, quad};
  for (const uint32_t mesh : {0u, 0u, 0u, 1u}) {
    MeshInstance instance;
    instance.mesh = mesh;
    scene.instances.push_back(instance);
  }
  const GeometryCounts counts = geometry_counts(scene);
  EXPECT_EQ(counts.triangles, 2 + 2);  // mesh 0's one copy, mesh 1's one flattened instance
  EXPECT_EQ(counts.instances, 3);
  EXPECT_EQ(counts.texturing_bytes, 4 * 32);  // each mesh in the scene and in the render
}

// A skinned or morphed mesh is posed in a copy of it: its triangles count twice.
TEST(MemoryEstimate, CountsADeformedMeshsPosedCopy) {
  Scene scene;
  scene.materials.push_back({});
  scene.meshes = {estimate_quad()};
  scene.instances.push_back(MeshInstance{});
  EXPECT_EQ(geometry_counts(scene).triangles, 2);
  scene.deformations.push_back(MeshDeformation{});
  EXPECT_EQ(geometry_counts(scene).triangles, 4);
}

// Evaluated shapes are held by the scene, and a moving deformed mesh's render copy holds every
// motion step: a 1000-vertex mesh of 129 shapes needs about 6 MB more than one of 1 shape, and
// a limit between the two refuses it before anything is built.
TEST(MemoryEstimate, CountsEvaluatedShapesAndEveryMotionStep) {
  Scene scene;
  scene.materials.push_back({});
  TriangleMesh mesh;
  mesh.positions.resize(1000);
  mesh.normals.resize(1000);
  mesh.indices.resize(3000);
  scene.meshes = {mesh};
  scene.instances.push_back(MeshInstance{});
  MeshDeformation still;
  still.evaluated.times_s = {0};
  still.evaluated.shapes = {{mesh.positions, mesh.normals}};
  scene.deformations = {still};
  const GeometryCounts one = geometry_counts(scene);
  EXPECT_EQ(one.deformation_bytes, 1000 * 2 * sizeof(Vec3f));  // the shape, no motion steps
  MeshDeformation moving;
  for (size_t k = 0; k < kMaxEvaluatedShapes; ++k) {
    moving.evaluated.times_s.push_back(double(k));
    moving.evaluated.shapes.push_back({mesh.positions, mesh.normals});
    moving.evaluated.shapes.back().positions[0].x = float(k);
  }
  scene.deformations = {moving};
  const GeometryCounts many = geometry_counts(scene);
  const double per_shape = 1000 * 2 * sizeof(Vec3f);
  EXPECT_EQ(many.deformation_bytes, per_shape * (kMaxEvaluatedShapes + kMaxEvaluatedShapes - 1));
  const auto estimate = [](const GeometryCounts& counts) {
    return estimate_memory(64, 64, 3, Reconstruction::kImportance, 0, counts);
  };
  const uint64_t limit = uint64_t(estimate(one).total() + per_shape);
  EXPECT_NO_THROW(check_memory(estimate(one), limit, "--memory-limit", "shot.gltf"));
  EXPECT_THROW(check_memory(estimate(many), limit, "--memory-limit", "shot.gltf"), InputError);
}

// Issue 17's forest: 10,000 copies of a 100,000-triangle tree (10^9 triangles flattened) fits
// with a 1920 x 1080 film in 2 GiB, where flattened it needed 120 GB.
TEST(MemoryEstimate, TenThousandCopiesOfAHundredThousandTrianglesFitInTwoGibibytes) {
  Scene scene;
  scene.materials.push_back({});
  TriangleMesh tree;
  tree.positions.resize(50000);
  tree.indices.resize(300000);
  scene.meshes = {tree};
  scene.instances.assign(10000, MeshInstance{});
  const MemoryEstimate e =
      estimate_memory(1920, 1080, 3, Reconstruction::kImportance, 0, geometry_counts(scene));
  EXPECT_LT(e.total(), 0x1p31);
  EXPECT_EQ(e.geometry_bytes, 1e5 * 120 + 1e4 * kBytesPerInstance);
}

// A refined surface's texture coordinates, before it is refined: about a vertex per two
// triangles, times the cage's split along seams, for each slot a part reads, twice.
TEST(MemoryEstimate, RefinedTextureCoordinatesFollowFromTheCage) {
  SubdivisionSurface cube;
  for (int i = 0; i < 8; ++i)
    cube.cage_positions.push_back({float(i & 1), float((i >> 1) & 1), float(i >> 2)});
  cube.cage_face_sizes.assign(6, 4);
  cube.cage_face_vertices = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4,
                             2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
  cube.settings.levels_render = 2;
  EXPECT_EQ(refined_texturing_bytes(cube), 0);  // no part reads a UV map
  // Each face its own island at u = 2 f: 24 values for 8 vertices, a split of 3.
  SubdivisionUvMap map{"UVMap", {}};
  for (int f = 0; f < 6; ++f)
    for (const Vec2f corner : {Vec2f{0, 0}, Vec2f{1, 0}, Vec2f{1, 1}, Vec2f{0, 1}})
      map.corner_uvs.push_back({corner.x + 2.f * float(f), corner.y});
  cube.uv_maps = {map};
  cube.parts[0].slot_uv_maps = {0, 0};
  cube.parts[0].tangent_slot = 0;
  // 192 triangles, 96 * 3 vertices, two slots and a tangent (32 bytes), twice.
  EXPECT_EQ(refined_texturing_bytes(cube), 2 * 32 * 96 * 3);
  // The refinement makes 150 vertices (core/subdiv/subdiv_test.cpp): an upper bound.
  EXPECT_GT(refined_texturing_bytes(cube), 2 * 32 * 150);
}

// Counted as core/film/cryptomatte.h and motion_vector_film.h allocate them: at 4K with the three
// Cryptomatte passes at 16 levels, the passes outweigh the film several times over.
TEST(MemoryEstimate, CountsCryptomatteAndVectorPassFilms) {
  const PassFilmCounts passes =
      pass_film_counts({"Depth", "CryptoObject", "Vector", "CryptoMaterial"}, 6);
  EXPECT_EQ(passes.cryptomatte_passes, 2u);
  EXPECT_EQ(passes.cryptomatte_levels, 6u);
  EXPECT_TRUE(passes.vector);
  const MemoryEstimate e = estimate_memory(100, 50, 3, Reconstruction::kImportance, 0, {}, passes);
  // per pixel: 12 slots of 8 bytes and a float weight; 24 + 4 float channels, twice; the Vector
  // film's 5 doubles
  EXPECT_EQ(e.pass_bytes, 5000.0 * (12 * 8 + 4 + 2 * 28 * 4 + 5 * 8));
  EXPECT_EQ(e.total(), e.film_bytes + e.pass_bytes);
  EXPECT_EQ(estimate_memory(100, 50, 3, Reconstruction::kImportance, 0, {},
                            pass_film_counts({"Depth", "Normal"}, 6))
                .pass_bytes,
            0);
  const MemoryEstimate uhd =
      estimate_memory(3840, 2160, 4, Reconstruction::kImportance, 0, {},
                      pass_film_counts({"CryptoObject", "CryptoMaterial", "CryptoAsset"}, 16));
  EXPECT_GT(uhd.pass_bytes, 4 * uhd.film_bytes);
  try {
    check_memory(uhd, uint64_t(uhd.film_bytes) * 2, "--memory-limit", "s.gltf");
    FAIL() << "expected a refusal";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("Cryptomatte and Vector passes"), std::string::npos)
        << error.what();
  }
}

TEST(MemoryEstimate, RefusesOverTheLimitNamingBothNumbers) {
  const MemoryEstimate e =
      estimate_memory(4096, 4096, 3, Reconstruction::kImportance, 0, {1e6, 0, 0});
  EXPECT_NO_THROW(check_memory(e, uint64_t(e.total()) + 1, "--memory-limit", "s.gltf"));
  try {
    check_memory(e, 1ull << 30, "--memory-limit", "s.gltf");
    FAIL() << "expected a refusal";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "s.gltf: the render needs about 1.19374 GB (film 1.07374 GB, geometry and BVH "
                 "0.12 GB), more than the memory limit of 1.07374 GB (--memory-limit)");
  }
  EXPECT_GT(default_memory_limit_bytes(), 0u);
}

}  // namespace
}  // namespace fb
