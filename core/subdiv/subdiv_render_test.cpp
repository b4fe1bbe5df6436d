// The subdivision module end to end, through the built `filmback`: it is loaded only for a scene
// that has a subdivision surface (the dynamic loader's own log says which libraries a process
// opened), a missing module is an error naming the file, and adaptive refinement's silhouette
// converges to the limit surface's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/image/image_io.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status;
  std::string output;  // stdout and stderr
};

Outcome run(const std::string& command) {
  Outcome r{0, ""};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe))
    r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

fs::path work_dir() {
  const fs::path dir = fs::path(FILMBACK_SUBDIV_WORK_DIR) /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 1 m cube (cage [-0.5, 0.5]^3) glowing with radiance 1 on black, 3 m in front of a camera
// with a 30 deg vertical field of view; `subdivision` is the FILMBACK_blender object, or empty.
fs::path write_scene(const fs::path& dir, const std::string& subdivision) {
  std::vector<float> positions;
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis)
      positions.push_back((i >> axis) & 1 ? 0.5f : -0.5f);
  const std::vector<uint32_t> quads = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4,
                                       2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
  std::vector<uint32_t> triangles;
  for (size_t f = 0; f < quads.size(); f += 4)
    triangles.insert(triangles.end(),
                     {quads[f], quads[f + 1], quads[f + 2], quads[f], quads[f + 2], quads[f + 3]});
  std::ofstream bin(dir / "cube.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions.data()), 96);
  bin.write(reinterpret_cast<const char*>(triangles.data()), 144);
  std::ostringstream cage;
  cage << "\"cage_positions\": [";
  for (size_t i = 0; i < positions.size(); ++i)
    cage << (i ? "," : "") << positions[i];
  cage << "], \"cage_face_sizes\": [4,4,4,4,4,4], \"cage_face_vertices\": [";
  for (size_t i = 0; i < quads.size(); ++i)
    cage << (i ? "," : "") << quads[i];
  cage << "]";
  const std::string extension = subdivision.empty()
                                    ? ""
                                    : R"(, "extensions": {"FILMBACK_blender": {"subdivision": {)" +
                                          cage.str() + ", " + subdivision + "}}}";
  const fs::path file = dir / "cube.gltf";
  std::ofstream(file) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["FILMBACK_blender"],
  "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "Cube", "mesh": 0, "rotation": [0.1, 0.3, 0.05, 0.948])"
                      << extension << R"(},
            {"name": "Camera", "camera": 0, "translation": [0, 0, 3]}],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5235987755982988,
               "aspectRatio": 1.0, "znear": 0.1}}],
  "materials": [{"name": "Glow", "emissiveFactor": [1, 1, 1],
                 "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                 "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
                {"bufferView": 1, "componentType": 5125, "count": 36, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 144}],
  "buffers": [{"byteLength": 240, "uri": "cube.bin"}]
})";
  return file;
}

std::string render_command(const fs::path& scene, const std::string& options = "") {
  return std::string("'") + FILMBACK_EXE + "' render '" + scene.string() + "' -o '" +
         (scene.parent_path() / "out.exr").string() + "' --res 160x160 --spp 16 --filter box " +
         options;
}

TEST(SubdivModule, LoadedOnlyForScenesWithSubdivisionSurfaces) {
  const fs::path dir = work_dir();
  // LD_DEBUG=files: glibc's loader logs every shared object the process opens, dlopen() included.
  const Outcome plain = run("LD_DEBUG=files " + render_command(write_scene(dir, "")));
  ASSERT_EQ(plain.status, 0) << plain.output;
  ASSERT_NE(plain.output.find("libembree3"), std::string::npos) << "no loader log?";
  EXPECT_EQ(plain.output.find("libosdCPU"), std::string::npos);
  EXPECT_EQ(plain.output.find("libfilmback_subdiv"), std::string::npos);

  const Outcome subdivided =
      run("LD_DEBUG=files " + render_command(write_scene(dir, R"("levels_render": 2)")));
  ASSERT_EQ(subdivided.status, 0) << subdivided.output;
  EXPECT_NE(subdivided.output.find("libosdCPU"), std::string::npos);
  EXPECT_NE(subdivided.output.find("libfilmback_subdiv.so"), std::string::npos);
  EXPECT_NE(subdivided.output.find("'Cube' level 2: 192 triangles"), std::string::npos)
      << subdivided.output;
  // `info` describes the cage without refining it: no module either.
  const Outcome info = run("LD_DEBUG=files '" + std::string(FILMBACK_EXE) + "' info '" +
                           (dir / "cube.gltf").string() + "'");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("Cube  cage of 6 faces, 8 vertices, 0 creased edges; Catmull-Clark "
                             "level 2, material 'Glow'"),
            std::string::npos)
      << info.output;
  EXPECT_EQ(info.output.find("libosdCPU"), std::string::npos);
}

TEST(SubdivModule, MissingModuleIsAnErrorNamingTheFile) {
  const fs::path dir = work_dir();
  const Outcome r = run("FILMBACK_SUBDIV_MODULE=/nonexistent/libfilmback_subdiv.so " +
                        render_command(write_scene(dir, R"("levels_render": 1)")));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("error: /nonexistent/libfilmback_subdiv.so: cannot load the "
                          "subdivision module"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

// The cube's image: flux (radiance 1 on black, box filter) is its projected area in pixels.
struct Silhouette {
  double area_px = 0;
  unsigned long triangles = 0;
};

Silhouette render_silhouette(const fs::path& scene, const std::string& options) {
  const Outcome r = run(render_command(scene, options));
  EXPECT_EQ(r.status, 0) << r.output;
  Silhouette s;
  std::smatch m;
  if (std::regex_search(r.output, m, std::regex(R"('Cube' [^:]*: (\d+) triangles)")))
    s.triangles = std::stoul(m[1]);
  const Image image = read_image(scene.parent_path() / "out.exr");
  const size_t n = image.channels.size();
  for (size_t c = 0; c < n; ++c)
    if (image.channels[c] == "R" || image.channels[c] == "G" || image.channels[c] == "B")
      for (size_t i = c; i < image.pixels.size(); i += n)
        s.area_px += image.pixels[i] / 3;
  return s;
}

TEST(SubdivModule, AdaptiveSilhouetteConvergesToTheLimitSurface) {
  const fs::path dir = work_dir();
  const fs::path level6 = write_scene(dir, R"("levels_render": 6)");
  const Silhouette reference = render_silhouette(level6, "");
  const Silhouette adaptive = render_silhouette(level6, "--subdiv adaptive");
  const Silhouette level1 = render_silhouette(write_scene(dir, R"("levels_render": 1)"), "");
  const Silhouette level2 = render_silhouette(write_scene(dir, R"("levels_render": 2)"), "");
  std::printf(
      "silhouette area (px): level 1 %.1f (%lu triangles), level 2 %.1f (%lu), adaptive "
      "%.1f (%lu), level 6 %.1f (%lu)\n",
      level1.area_px, level1.triangles, level2.area_px, level2.triangles, adaptive.area_px,
      adaptive.triangles, reference.area_px, reference.triangles);
  const auto error = [&](const Silhouette& s) {
    return std::abs(s.area_px - reference.area_px) / reference.area_px;
  };
  EXPECT_GT(error(level1), error(level2));
  EXPECT_GT(error(level2), error(adaptive));
  EXPECT_LT(error(adaptive), 1e-3);
  // Segments of about a pixel make about two triangles per pixel of each patch's image; the
  // patches facing away are tessellated too (they may be seen in reflections or cast shadows),
  // so about 6 per pixel of the silhouette (measured 5.7), fewer than level 6's 49152.
  EXPECT_LT(double(adaptive.triangles), 8 * reference.area_px);
  EXPECT_GT(double(adaptive.triangles), 2 * reference.area_px);
  EXPECT_LT(adaptive.triangles, reference.triangles);
}

}  // namespace
}  // namespace fb
