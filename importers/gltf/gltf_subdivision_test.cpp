// nodes[i].extensions.FILMBACK_blender.subdivision: the cage is read and checked, and the node's
// own glTF mesh (the triangulated cage) is not rendered.
#include "importers/gltf/gltf_subdivision.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/util/error.h"
#include "importers/gltf/gltf_importer.h"
#include "support/gltf_builder.h"
#include "support/png.h"

namespace fb {
namespace {

// A quad cage: 4 vertices, one face; the glTF mesh is a single triangle standing in for the
// cage's triangulation, as other viewers would draw it.
const char* kQuadCage = R"("cage_positions": [0,0,0, 1,0,0, 1,1,0, 0,1,0],
  "cage_face_sizes": [4], "cage_face_vertices": [0,1,2,3])";

const char* kGlow = R"({"name": "Glow", "emissiveFactor": [1, 1, 1],
                 "pbrMetallicRoughness": {"metallicFactor": 0}})";
const char* kOnePrimitive = R"({"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]})";

// The file with `subdivision` on its node, whose mesh is `mesh`, and `materials`.
std::filesystem::path write_subdivision_gltf(const std::string& subdivision,
                                             const std::string& materials = kGlow,
                                             const std::string& mesh = kOnePrimitive,
                                             const std::string& extra = "") {
  const std::filesystem::path file = test::scratch_dir() / "cage.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["FILMBACK_blender"],
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"name": "Cube", "mesh": 0, "translation": [0, 0, -5],
             "extensions": {"FILMBACK_blender": {"subdivision": {)"
                      << subdivision << R"(}}}}],
  "materials": [)" << materials
                      << R"(],
  "meshes": [)" << mesh
                      << "]" << extra << R"(,
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
    "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
})";
  return file;
}

Scene import_subdivision(const std::string& subdivision) {
  Diagnostics diagnostics;
  Scene scene = import_gltf(write_subdivision_gltf(subdivision), diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u);
  return scene;
}

// The error message for `subdivision`, which must fail.
std::string subdivision_error(const std::string& subdivision) {
  try {
    import_subdivision(subdivision);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kPath = "cage.gltf: nodes[0].extensions.FILMBACK_blender.subdivision";

TEST(GltfSubdivision, ReadsTheCageAndSettingsAndDropsTheTriangulatedMesh) {
  const Scene scene =
      import_subdivision(std::string(kQuadCage) + R"(, "levels_render": 3, "quality": 3,
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
  const SubdivisionSettings s = import_subdivision(kQuadCage).subdivision_surfaces.at(0).settings;
  EXPECT_EQ(s.levels_render, 2u);
  EXPECT_EQ(s.scheme, SubdivisionSettings::Scheme::kCatmullClark);
  EXPECT_EQ(s.boundary_smooth, SubdivisionSettings::Boundary::kAll);
  EXPECT_TRUE(s.use_creases);
  EXPECT_TRUE(s.use_limit_surface);
}

// Nine UV maps (Blender allows eight): objects with members, since tinygltf drops empty ones.
std::string nine_maps() {
  std::string out;
  for (int i = 0; i < 9; ++i)
    out += std::string(i ? ", " : "") + R"({"name": "M)" + std::to_string(i) + R"("})";
  return out;
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
      {std::string(kQuadCage) + R"(, "uv_smooth": "SMOOTH")", ".uv_smooth",
       "expected NONE or PRESERVE_CORNERS or PRESERVE_CORNERS_AND_JUNCTIONS or "
       "PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE or PRESERVE_BOUNDARIES or SMOOTH_ALL"},
      {std::string(kQuadCage) + R"(, "uv_maps": {"name": "A"})", ".uv_maps",
       "expected an array of at most 8 UV maps"},
      {std::string(kQuadCage) + R"(, "uv_maps": [)" + nine_maps() + "]", ".uv_maps",
       "expected an array of at most 8 UV maps"},
      {std::string(kQuadCage) + R"(, "uv_maps": [1])", ".uv_maps[0]", "expected an object"},
      {std::string(kQuadCage) + R"(, "uv_maps": [{"uvs": [0,0, 1,0, 1,1, 0,1]}])", ".uv_maps[0]",
       "expected a string 'name'"},
      {std::string(kQuadCage) + R"(, "uv_maps": [{"name": "A", "uvs": [0,0, 1,0, 1,1, 0,1]},
                                                 {"name": "B", "uvs": [0,0, 1,0]}])",
       ".uv_maps[1].uvs", "4 elements, expected 8 (u, v for each of the cage's corners)"},
      {std::string(kQuadCage) + R"(, "uv_maps": [{"name": "A", "uvs": [0,0, 1,0, 1,1, 0]}])",
       ".uv_maps[0].uvs", "7 elements, expected a multiple of 2"},
      {std::string(kQuadCage) + R"(, "uv_maps": [{"name": "A", "uvs": [0,0, 1,"x", 1,1, 0,1]}])",
       ".uv_maps[0].uvs[3]", "expected a finite number"},
      {std::string(kQuadCage) + R"(, "uv_maps": [{"name": "A", "uvs": [0,0, 1,0, 1e39,1, 0,1]}])",
       ".uv_maps[0].uvs[4]", "expected a finite number"},
      {std::string(kQuadCage) + R"(, "face_primitives": [0, 0])", ".face_primitives",
       "2 elements, expected 1 (one per cage face)"},
      {std::string(kQuadCage) + R"(, "face_primitives": [1])", ".face_primitives[0]",
       "expected a primitive of the node's mesh from 0 to 0"},
  };
  for (const auto& c : cases) {
    const std::string what = subdivision_error(c.json);
    EXPECT_NE(what.find(kPath + c.where + ": " + c.what), std::string::npos)
        << c.json << "\n -> " << what;
  }
}

// A two-quad cage (vertices 0..5, faces 0 1 4 3 and 1 2 5 4) with UV maps "A" and "B".
const char* kStripCage = R"("cage_positions": [0,0,0, 1,0,0, 2,0,0, 0,1,0, 1,1,0, 2,1,0],
  "cage_face_sizes": [4, 4], "cage_face_vertices": [0,1,4,3, 1,2,5,4],
  "uv_maps": [{"name": "A", "uvs": [0,0, 1,0, 1,1, 0,1, 1,0, 2,0, 2,1, 1,1]},
              {"name": "B", "uvs": [0,0, 0,1, 1,1, 1,0, 0,1, 0,2, 1,2, 1,1]}])";

// A Blender material whose base colour is an image read through UV map `uv_map` ("" for the
// active render map), and a normal map through the same.
std::string textured_material(const std::string& name, const std::string& uv_map) {
  const std::string texture =
      R"({"uri": "tex.png", "colorspace": "sRGB", "uv_map": ")" + uv_map + R"("})";
  return R"({"name": ")" + name +
         R"(", "extensions": {"FILMBACK_blender": {"blender_version": [3, 4, 1], "surface": 0,
     "nodes": [{"type": "PRINCIPLED", "name": "Principled BSDF", "inputs": {
       "base_color": {"texture": )" +
         texture + R"(}, "normal": {"normal_map": {"texture": )" + texture +
         R"(, "strength": 1, "space": "TANGENT", "uv_map": ")" + uv_map + R"("}}}}]}}})";
}

// A white texel as tex.png beside `gltf`.
std::filesystem::path with_texture(const std::filesystem::path& gltf) {
  const std::vector<unsigned char> texels = test::png(1, 1, {255, 255, 255, 255});
  std::ofstream(gltf.parent_path() / "tex.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(texels.data()), std::streamsize(texels.size()));
  return gltf;
}

TEST(GltfSubdivision, UvMapsAreFoundByNameAndUnreadOnesDropped) {
  Diagnostics diagnostics;
  const Scene scene =
      import_gltf(with_texture(write_subdivision_gltf(
                      std::string(kStripCage) + R"(, "uv_smooth": "SMOOTH_ALL")",
                      textured_material("Textured", "B"),
                      R"({"primitives": [{"attributes": {"POSITION": 0}, "material": 0}],
                     "extensions": {"FILMBACK_blender": {"uv_maps": ["A", "B"]}}})")),
                  diagnostics);
  EXPECT_EQ(diagnostics.count(), 0u);
  const SubdivisionSurface& s = scene.subdivision_surfaces.at(0);
  EXPECT_EQ(s.settings.uv_smooth, SubdivisionSettings::UvSmooth::kSmoothAll);
  ASSERT_EQ(s.uv_maps.size(), 1u);  // "A" is read by no material
  EXPECT_EQ(s.uv_maps[0].name, "B");
  ASSERT_EQ(s.uv_maps[0].corner_uvs.size(), 8u);
  EXPECT_EQ(s.uv_maps[0].corner_uvs[5].y, 2.f);
  ASSERT_EQ(s.parts.size(), 1u);
  EXPECT_EQ(s.parts[0].slot_uv_maps[0], 0u);
  EXPECT_EQ(s.parts[0].slot_uv_maps[1], kNoUvMap);
  EXPECT_EQ(s.parts[0].tangent_slot, 0u);  // the normal map's tangents from that map
}

TEST(GltfSubdivision, TheActiveRenderMapIsTheMeshsAndAMissingMapIsAWarning) {
  Diagnostics diagnostics;
  const Scene scene = import_gltf(
      with_texture(write_subdivision_gltf(
          kStripCage, textured_material("Textured", "") + "," + textured_material("Elsewhere", "C"),
          R"({"primitives": [{"attributes": {"POSITION": 0}, "material": 0},
                                    {"attributes": {"POSITION": 0}, "material": 1}],
                     "extensions": {"FILMBACK_blender": {"uv_maps": ["A", "B"],
                                                         "active_render_uv_map": "B"}}})")),
      diagnostics);
  const SubdivisionSurface& s = scene.subdivision_surfaces.at(0);
  // Without face_primitives every face wears the first primitive's material.
  ASSERT_EQ(s.parts.size(), 1u);
  EXPECT_EQ(s.parts[0].material, 0u);
  ASSERT_EQ(s.uv_maps.size(), 1u);
  EXPECT_EQ(s.uv_maps[0].name, "B");
  EXPECT_EQ(diagnostics.count(), 0u);

  // Faces on both primitives: "Elsewhere" reads "C", which the cage lacks: map 0 ("A") stands in,
  // as TEXCOORD_0 does for a triangle mesh, with a warning.
  const Scene both =
      import_gltf(with_texture(write_subdivision_gltf(
                      std::string(kStripCage) + R"(, "face_primitives": [1, 0])",
                      textured_material("Textured", "") + "," + textured_material("Elsewhere", "C"),
                      R"({"primitives": [{"attributes": {"POSITION": 0}, "material": 0},
                                    {"attributes": {"POSITION": 0}, "material": 1}],
                     "extensions": {"FILMBACK_blender": {"uv_maps": ["A", "B"],
                                                         "active_render_uv_map": "B"}}})")),
                  diagnostics);
  EXPECT_EQ(diagnostics.count(), 1u);
  const SubdivisionSurface& t = both.subdivision_surfaces.at(0);
  ASSERT_EQ(t.parts.size(), 2u);
  EXPECT_EQ(t.parts[0].material, 1u);  // face 0's
  EXPECT_EQ(t.parts[1].material, 0u);
  EXPECT_EQ(t.face_parts, (std::vector<uint32_t>{0, 1}));
  ASSERT_EQ(t.uv_maps.size(), 2u);
  EXPECT_EQ(t.uv_maps[t.parts[0].slot_uv_maps[0]].name, "A");
  EXPECT_EQ(t.uv_maps[t.parts[1].slot_uv_maps[0]].name, "B");
}

TEST(GltfSubdivision, AGltfTextureNeedsItsTexcoordAmongTheCagesMaps) {
  const std::string material = R"({"name": "Tex", "pbrMetallicRoughness": {
      "baseColorTexture": {"index": 0, "texCoord": 1}}})";
  const std::string images = R"(, "textures": [{"source": 0}], "images": [{"uri": "tex.png"}])";
  const std::string cage =
      std::string(kQuadCage) + R"(, "uv_maps": [{"name": "A", "uvs": [0,0, 1,0, 1,1, 0,1]}])";
  try {
    Diagnostics diagnostics;
    import_gltf(with_texture(write_subdivision_gltf(cage, material, kOnePrimitive, images)),
                diagnostics);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(kPath + ".uv_maps: material 'Tex' reads TEXCOORD_1, and the cage has 1 "
                                "UV maps; expected UV map 1"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace fb
