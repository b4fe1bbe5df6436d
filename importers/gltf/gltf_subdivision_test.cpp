// nodes[i].extensions.FILMBACK_blender.subdivision: the cage is read and checked, and the node's
// own glTF mesh (the triangulated cage) is not rendered.
#include "importers/gltf/gltf_subdivision.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"

namespace fb {
namespace {

// A quad cage: 4 vertices, one face; the glTF mesh is a single triangle standing in for the
// cage's triangulation, as other viewers would draw it.
const char* kQuadCage = R"("cage_positions": [0,0,0, 1,0,0, 1,1,0, 0,1,0],
  "cage_face_sizes": [4], "cage_face_vertices": [0,1,2,3])";

std::filesystem::path write_gltf(const std::string& subdivision) {
  const std::filesystem::path file = test::scratch_dir() / "cage.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["FILMBACK_blender"],
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"name": "Cube", "mesh": 0, "translation": [0, 0, -5],
             "extensions": {"FILMBACK_blender": {"subdivision": {)"
                      << subdivision << R"(}}}}],
  "materials": [{"name": "Glow", "emissiveFactor": [1, 1, 1],
                 "pbrMetallicRoughness": {"metallicFactor": 0}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
    "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
})";
  return file;
}

Scene import(const std::string& subdivision) {
  Diagnostics diagnostics;
  Scene scene = import_gltf(write_gltf(subdivision), diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u);
  return scene;
}

// The error message for `subdivision`, which must fail.
std::string error_of(const std::string& subdivision) {
  try {
    import(subdivision);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kPath = "cage.gltf: nodes[0].extensions.FILMBACK_blender.subdivision";

TEST(GltfSubdivision, ReadsTheCageAndSettingsAndDropsTheTriangulatedMesh) {
  const Scene scene = import(std::string(kQuadCage) + R"(, "levels_render": 3, "quality": 3,
      "scheme": "SIMPLE", "boundary_smooth": "PRESERVE_CORNERS", "use_creases": false,
      "use_limit_surface": false, "uv_smooth": "PRESERVE_BOUNDARIES",
      "edge_creases": [1, 2, 0.5], "vertex_creases": [3, 1.0])");
  EXPECT_TRUE(scene.meshes.empty());
  EXPECT_TRUE(scene.instances.empty());
  ASSERT_EQ(scene.subdivision_surfaces.size(), 1u);
  const SubdivisionSurface& s = scene.subdivision_surfaces[0];
  EXPECT_EQ(s.name, "Cube");
  EXPECT_EQ(s.parts.at(0).material, 0u);
  EXPECT_EQ(s.cage_positions.size(), 4u);
  EXPECT_EQ(s.cage_positions[2].x, 1.f);
  EXPECT_EQ(s.cage_positions[2].y, 1.f);
  EXPECT_EQ(s.cage_face_sizes, std::vector<uint32_t>{4});
  EXPECT_EQ(s.cage_face_vertices, (std::vector<uint32_t>{0, 1, 2, 3}));
  ASSERT_EQ(s.edge_creases.size(), 1u);
  EXPECT_EQ(s.edge_creases[0].v0, 1u);
  EXPECT_EQ(s.edge_creases[0].v1, 2u);
  EXPECT_EQ(s.edge_creases[0].weight, 0.5f);
  ASSERT_EQ(s.vertex_creases.size(), 1u);
  EXPECT_EQ(s.vertex_creases[0].vertex, 3u);
  EXPECT_EQ(s.settings.levels_render, 3u);
  EXPECT_EQ(s.settings.scheme, SubdivisionSettings::Scheme::kSimple);
  EXPECT_EQ(s.settings.boundary_smooth, SubdivisionSettings::Boundary::kPreserveCorners);
  EXPECT_FALSE(s.settings.use_creases);
  EXPECT_FALSE(s.settings.use_limit_surface);
  EXPECT_EQ(s.world_from_object.point({0, 0, 0}).z, -5.0);
}

TEST(GltfSubdivision, DefaultsAreBlenders) {
  const SubdivisionSettings s = import(kQuadCage).subdivision_surfaces.at(0).settings;
  EXPECT_EQ(s.levels_render, 2u);
  EXPECT_EQ(s.scheme, SubdivisionSettings::Scheme::kCatmullClark);
  EXPECT_EQ(s.boundary_smooth, SubdivisionSettings::Boundary::kAll);
  EXPECT_TRUE(s.use_creases);
  EXPECT_TRUE(s.use_limit_surface);
}

TEST(GltfSubdivision, BadCagesAreErrorsWithTheJsonPath) {
  const std::string positions = R"("cage_positions": [0,0,0, 1,0,0, 1,1,0, 0,1,0])";
  const struct {
    std::string json, where, what;
  } cases[] = {
      {R"("cage_face_sizes": [4], "cage_face_vertices": [0,1,2,3])", "",
       "expected an array 'cage_positions'"},
      {R"("cage_positions": [0,0,0, 1,0], "cage_face_sizes": [3], "cage_face_vertices": [0,1,2])",
       ".cage_positions", "5 elements, expected a multiple of 3"},
      {R"("cage_positions": [0,0,0, 1,0,0, 1,"x",0], "cage_face_sizes": [3],
          "cage_face_vertices": [0,1,2])",
       ".cage_positions[7]", "expected a finite number"},
      {positions + R"(, "cage_face_sizes": [2, 2], "cage_face_vertices": [0,1,2,3])",
       ".cage_face_sizes[0]", "expected a face size from 3 to 65535"},
      {positions + R"(, "cage_face_sizes": [4], "cage_face_vertices": [0,1,2])",
       ".cage_face_vertices", "3 vertex indices, expected 4 (the sum of cage_face_sizes)"},
      {positions + R"(, "cage_face_sizes": [4], "cage_face_vertices": [0,1,2,4])",
       ".cage_face_vertices[3]", "expected a vertex index from 0 to 3"},
      {positions + R"(, "cage_face_sizes": [4], "cage_face_vertices": [0,1,2,1])",
       ".cage_face_sizes[0]", "the face uses a vertex twice"},
      {std::string(kQuadCage) + R"(, "edge_creases": [0, 1, 1.5])", ".edge_creases[2]",
       "expected a crease weight in [0, 1]"},
      {std::string(kQuadCage) + R"(, "edge_creases": [0, 2, 1])", ".edge_creases[0]",
       "vertices 0 and 2 are not joined by a cage edge"},
      {std::string(kQuadCage) + R"(, "vertex_creases": [9, 1])", ".vertex_creases[0]",
       "expected a vertex index from 0 to 3"},
      {std::string(kQuadCage) + R"(, "levels_render": 12)", ".levels_render",
       "expected a whole number in [0, 11]"},
      {std::string(kQuadCage) + R"(, "scheme": "LOOP")", ".scheme",
       "expected CATMULL_CLARK or SIMPLE"},
      {std::string(kQuadCage) + R"(, "use_creases": 1)", ".use_creases", "expected true or false"},
  };
  for (const auto& c : cases) {
    const std::string what = error_of(c.json);
    EXPECT_NE(what.find(kPath + c.where + ": " + c.what), std::string::npos)
        << c.json << "\n -> " << what;
  }
}

}  // namespace
}  // namespace fb
