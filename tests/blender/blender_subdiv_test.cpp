// Subdivision against Blender (subdiv_shot.py). Blender's own Subdivision Surface modifier
// evaluates cages (cubes with and without creases, the SIMPLE scheme, the limit surface off, open
// grids under both boundary rules, n-gons, triangles); filmback refines the same cages with the
// same settings and each vertex of Blender's mesh must have one of ours within kMaxVertexError.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "core/subdiv/refine_scene.h"
#include "tests/blender/blender_shot.h"
#include "tests/blender/checker_pixels.h"
#include "tests/support/blobs.h"
#include "tests/support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

// Both evaluate the limit surface through OpenSubdiv patches isolated `quality` levels deep
// (Blender's Far patch table, filmback's Bfr surfaces); measured agreement is ~2e-7 m on these
// 2 m cages (float rounding) except at smooth boundary corners (a grid's corners under "ALL"),
// where Blender's end patches converge to Bfr's as quality rises: 0.039 m at quality 1, 0.0025 m
// at 3, 3.9e-5 m at 6. The grid case is therefore built at quality 6 (docs/blender.md).
constexpr double kMaxVertexError = 1e-4;
// Normals: Blender computes its mesh's from the refined polygons (mesh_normals.cc), as filmback
// does (core/subdiv/mesh_normals.cpp). Measured on Debian's Blender 3.4.1: within 2e-5 degrees
// (float rounding) in every case; the limit surface's normals, which filmback used before, are
// 0.99 degrees off on the level-2 cube and 48 degrees next to its creases.
constexpr double kMaxNormalDegrees = 1e-3;

struct Case {
  std::string name;
  SubdivisionSurface surface;
  std::vector<Vec3f> blender;          // Blender's evaluated vertices
  std::vector<Vec3f> blender_normals;  // and their normals
  // uvs.txt: the corners of Blender's evaluated mesh, their vertices and UVs (glTF's v down).
  std::vector<std::pair<Vec3f, Vec2f>> blender_corners;
};

const std::pair<const char*, SubdivisionSettings::UvSmooth> kUvSmooth[] = {
    {"NONE", SubdivisionSettings::UvSmooth::kNone},
    {"PRESERVE_CORNERS", SubdivisionSettings::UvSmooth::kPreserveCorners},
    {"PRESERVE_CORNERS_AND_JUNCTIONS", SubdivisionSettings::UvSmooth::kPreserveCornersAndJunctions},
    {"PRESERVE_CORNERS_JUNCTIONS_AND_CONCAVE",
     SubdivisionSettings::UvSmooth::kPreserveCornersJunctionsAndConcave},
    {"PRESERVE_BOUNDARIES", SubdivisionSettings::UvSmooth::kPreserveBoundaries},
    {"SMOOTH_ALL", SubdivisionSettings::UvSmooth::kSmoothAll}};

std::vector<Case> read_cases(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::vector<Case> cases;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string kind;
    s >> kind;
    if (kind == "case") {
      Case c;
      std::string key, scheme, boundary;
      int use_creases = 1, use_limit = 1;
      s >> c.name >> key >> c.surface.settings.levels_render >> key >> scheme >> key >> boundary >>
          key >> use_creases >> key >> use_limit >> key >> c.surface.settings.quality;
      SubdivisionSettings& st = c.surface.settings;
      st.scheme = scheme == "SIMPLE" ? SubdivisionSettings::Scheme::kSimple
                                     : SubdivisionSettings::Scheme::kCatmullClark;
      st.boundary_smooth = boundary == "PRESERVE_CORNERS"
                               ? SubdivisionSettings::Boundary::kPreserveCorners
                               : SubdivisionSettings::Boundary::kAll;
      st.use_creases = use_creases != 0;
      st.use_limit_surface = use_limit != 0;
      if (std::string word; s >> key >> word)  // uvs.txt's cases: uv_smooth, and a UV map
        for (const auto& [name, value] : kUvSmooth)
          if (word == name) {
            st.uv_smooth = value;
            c.surface.uv_maps = {{"UVMap", {}}};
            c.surface.parts[0].slot_uv_maps[0] = 0;
          }
      c.surface.name = c.name;
      c.surface.node = c.name;
      cases.push_back(std::move(c));
    } else if (kind == "v") {
      float x, y, z;
      s >> x >> y >> z;
      cases.back().surface.cage_positions.push_back({x, y, z});
    } else if (kind == "r") {
      float x, y, z, nx, ny, nz;
      s >> x >> y >> z >> nx >> ny >> nz;
      cases.back().blender.push_back({x, y, z});
      cases.back().blender_normals.push_back({nx, ny, nz});
    } else if (kind == "f") {
      uint32_t n = 0, v;
      while (s >> v) {
        cases.back().surface.cage_face_vertices.push_back(v);
        ++n;
      }
      cases.back().surface.cage_face_sizes.push_back(n);
    } else if (kind == "e") {
      EdgeCrease e;
      s >> e.v0 >> e.v1 >> e.weight;
      cases.back().surface.edge_creases.push_back(e);
    } else if (kind == "t") {  // Blender's v runs up, glTF's (and the add-on's) down
      float u, v;
      s >> u >> v;
      cases.back().surface.uv_maps.at(0).corner_uvs.push_back({u, 1 - v});
    } else if (kind == "l") {
      float x, y, z, u, v;
      s >> x >> y >> z >> u >> v;
      cases.back().blender_corners.push_back({{x, y, z}, {u, 1 - v}});
    } else if (kind == "c") {
      VertexCrease c;
      s >> c.vertex >> c.weight;
      cases.back().surface.vertex_creases.push_back(c);
    }
  }
  return cases;
}

// The cases subdiv_shot.py writes to `file` in its `mode`, run by `blender` in work/subdiv_MODE.
// Throws std::runtime_error with the end of Blender's log when it fails.
std::vector<Case> blender_cases(const fs::path& blender, const std::string& mode,
                                const std::string& file) {
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / ("subdiv_" + mode);
  fs::remove_all(work);
  fs::create_directories(work);
  run_logged(quoted(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                 quoted(FILMBACK_MAKE_SHOT_PY) + " -- " + quoted(work) + " " + mode,
             work / "blender.log");
  return read_cases(work / file);
}

TriangleMesh refine(const SubdivisionSurface& surface) {
  Scene scene;
  scene.file = "meshes.txt";
  scene.subdivision_surfaces = {surface};
  refine_subdivision_surfaces(scene, SubdivMode::kRender, {});
  return scene.meshes.at(0);
}

// The largest distance from a vertex of `a` to the nearest vertex of `b`.
double farthest_nearest(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b) {
  double worst = 0;
  for (const Vec3f& p : a) {
    double nearest = HUGE_VAL;
    for (const Vec3f& q : b)
      nearest = std::min(nearest, double(length(p - q)));
    worst = std::max(worst, nearest);
  }
  return worst;
}

// For each of Blender's vertices, the angle in degrees between its normal and that of our vertex
// nearest to it (split vertices of one point share their normal): the worst.
double worst_normal_degrees(const Case& c, const TriangleMesh& ours) {
  double worst = 0;
  for (size_t i = 0; i < c.blender.size(); ++i) {
    size_t nearest = 0;
    for (size_t j = 1; j < ours.positions.size(); ++j)
      if (length(c.blender[i] - ours.positions[j]) < length(c.blender[i] - ours.positions[nearest]))
        nearest = j;
    // In double: a float dot product cannot resolve angles under 0.02 degrees.
    const Vec3d a = normalize(Vec3d(c.blender_normals[i])),
                b = normalize(Vec3d(ours.normals[nearest]));
    worst = std::max(worst, std::atan2(length(cross(a, b)), dot(a, b)) * 180 / M_PI);
  }
  return worst;
}

using BlenderSubdiv = WithBlender<>;

TEST_F(BlenderSubdiv, RefinementMatchesBlendersEvaluatedMesh) {
  const std::vector<Case> cases = blender_cases(blender, "mesh", "meshes.txt");
  ASSERT_EQ(cases.size(), 10u);
  std::printf("%-22s %8s %8s %12s %12s %12s\n", "case", "blender", "filmback", "max |d| (m)",
              "10c instead", "normal (deg)");
  for (const Case& c : cases) {
    const TriangleMesh ours = refine(c.surface);
    const double error = std::max(farthest_nearest(c.blender, ours.positions),
                                  farthest_nearest(ours.positions, c.blender));
    // The alternative reading of Blender's crease, sharpness 10 c rather than 10 c^2: the same
    // cage with each weight replaced by sqrt(c). It must be measurably worse where creases are
    // fractional, which is what pins the rule down.
    double linear_error = NAN;
    if (c.surface.settings.use_creases && !c.surface.edge_creases.empty()) {
      SubdivisionSurface linear = c.surface;
      for (EdgeCrease& e : linear.edge_creases)
        e.weight = std::sqrt(e.weight);
      for (VertexCrease& v : linear.vertex_creases)
        v.weight = std::sqrt(v.weight);
      linear_error = farthest_nearest(c.blender, refine(linear).positions);
    }
    const double normal_error = worst_normal_degrees(c, ours);
    std::printf("%-22s %8zu %8zu %12.3g %12.3g %12.3g\n", c.name.c_str(), c.blender.size(),
                ours.positions.size(), error, linear_error, normal_error);
    EXPECT_EQ(ours.positions.size(), c.blender.size()) << c.name;
    EXPECT_LT(error, kMaxVertexError) << c.name;
    EXPECT_LT(normal_error, kMaxNormalDegrees) << c.name;
    if (c.name == "cube_creases") {
      EXPECT_GT(linear_error, 100 * kMaxVertexError);
    }
  }
}

// The same comparison for texture coordinates (subdiv_shot.py's "uv" cases): each corner of
// Blender's evaluated mesh must have one of filmback's vertices at its position (within
// kMaxUvCasePositionError) with its UV (within kMaxUvError), and each of filmback's vertices one
// of Blender's corners; and the vertices split along the seams as Blender's corners do (its
// corners' UVs at one vertex, joined within kSameUv, are as many as filmback's vertices there).
// Measured on Debian's Blender 3.4.1 (docs/blender.md, "Subdivision"): UVs within 2.4e-7 of
// Blender's under Keep Boundaries and None, at levels 1 and 2, with and without the limit
// surface, on quads, n-gons and triangles; positions within 1.9e-7 m. kMaxUvError leaves a
// factor of 40 for other builds' rounding and is 1/6000 of the smallest UV step here (1/16 of a
// 1/4-wide face), while the next rule gives UVs 0.04 to 0.09 off (printed), so a wrong uv_smooth
// mapping fails.
constexpr double kMaxUvError = 1e-5;
constexpr double kMaxUvCasePositionError = 1e-5;
constexpr double kSameUv = 1e-5;

// Under Smooth All the UV islands' corners are smooth face-varying corners, where Blender's patch
// table (isolated `quality` levels deep, Gregory end caps) approximates the limit that Bfr
// evaluates, as it does for positions at smooth boundary corners: measured 9.2e-4 at quality 3
// (Blender's default) and 1.45e-5 at quality 6, shrinking as 4^-quality, nowhere else. The bound
// follows that law with a margin of 1.5.
double max_smooth_all_uv_error(uint32_t quality) {
  return 1.5e-3 * std::pow(4.0, 3.0 - quality);
}

struct UvMatch {
  double uv = 0, position = 0;  // the worst distances
};

// For each corner of `from`, the one of `to` nearest in position (ties within 1e-5 m broken by
// the nearest UV): the worst UV and position distances.
UvMatch worst_match(const std::vector<std::pair<Vec3f, Vec2f>>& from,
                    const std::vector<std::pair<Vec3f, Vec2f>>& to) {
  UvMatch worst;
  for (const auto& [p, uv] : from) {
    double nearest = HUGE_VAL;
    for (const auto& q : to)
      nearest = std::min(nearest, double(length(p - q.first)));
    double uv_error = HUGE_VAL;
    for (const auto& q : to)
      if (double(length(p - q.first)) <= nearest + 1e-5)
        uv_error =
            std::min(uv_error, std::hypot(double(uv.x) - q.second.x, double(uv.y) - q.second.y));
    worst.uv = std::max(worst.uv, uv_error);
    worst.position = std::max(worst.position, nearest);
  }
  return worst;
}

// Blender's corners joined into vertices: at each position, the distinct UVs (within kSameUv).
size_t split_vertices(const std::vector<std::pair<Vec3f, Vec2f>>& corners) {
  std::vector<std::pair<Vec3f, Vec2f>> distinct;
  for (const auto& c : corners) {
    bool known = false;
    for (const auto& d : distinct)
      known = known || (length(c.first - d.first) < 1e-5f &&
                        std::hypot(double(c.second.x) - d.second.x,
                                   double(c.second.y) - d.second.y) < kSameUv);
    if (!known) distinct.push_back(c);
  }
  return distinct.size();
}

TEST_F(BlenderSubdiv, UvsMatchBlendersEvaluatedCorners) {
  const std::vector<Case> cases = blender_cases(blender, "uv", "uvs.txt");
  ASSERT_EQ(cases.size(), 13u);
  std::printf("%-34s %8s %8s %8s %12s %12s %14s\n", "case", "corners", "blender", "filmback",
              "max |d uv|", "max |d| (m)", "other rule uv");
  for (const Case& c : cases) {
    ASSERT_FALSE(c.surface.uv_maps.empty()) << c.name;
    const TriangleMesh ours = refine(c.surface);
    const std::vector<Vec2f>& uv = ours.texturing.texcoords[0];
    ASSERT_EQ(uv.size(), ours.positions.size()) << c.name;
    std::vector<std::pair<Vec3f, Vec2f>> vertices;
    for (size_t v = 0; v < uv.size(); ++v)
      vertices.push_back({ours.positions[v], uv[v]});
    const UvMatch to_ours = worst_match(c.blender_corners, vertices);
    const UvMatch to_blender = worst_match(vertices, c.blender_corners);
    const size_t blender_vertices = split_vertices(c.blender_corners);
    // What the next rule in Blender's list would give: how far apart the rules are here.
    SubdivisionSurface other = c.surface;
    other.settings.uv_smooth = other.settings.uv_smooth == SubdivisionSettings::UvSmooth::kSmoothAll
                                   ? SubdivisionSettings::UvSmooth::kPreserveBoundaries
                                   : SubdivisionSettings::UvSmooth::kSmoothAll;
    const TriangleMesh theirs = refine(other);
    std::vector<std::pair<Vec3f, Vec2f>> other_vertices;
    for (size_t v = 0; v < theirs.positions.size(); ++v)
      other_vertices.push_back({theirs.positions[v], theirs.texturing.texcoords[0][v]});
    const double other_error = worst_match(c.blender_corners, other_vertices).uv;
    std::printf("%-34s %8zu %8zu %8zu %12.3g %12.3g %14.3g\n", c.name.c_str(),
                c.blender_corners.size(), blender_vertices, vertices.size(),
                std::max(to_ours.uv, to_blender.uv),
                std::max(to_ours.position, to_blender.position), other_error);
    EXPECT_EQ(vertices.size(), blender_vertices) << c.name;
    EXPECT_LT(std::max(to_ours.uv, to_blender.uv),
              c.surface.settings.uv_smooth == SubdivisionSettings::UvSmooth::kSmoothAll
                  ? max_smooth_all_uv_error(c.surface.settings.quality)
                  : kMaxUvError)
        << c.name;
    EXPECT_GT(other_error, 100 * kMaxUvError) << c.name;
    EXPECT_LT(std::max(to_ours.position, to_blender.position), kMaxUvCasePositionError) << c.name;
  }
}

// The subdivided-mesh shot: a creased cube with Blender's Subdivision Surface modifier (render
// level 2), glowing on black among four marker spheres, rendered by Cycles from the .blend and by
// filmback from the export (the cage and the modifier's settings, refined by the module). The
// object's image is its silhouette times its radiance: its flux-weighted centroid and its flux
// (area) must agree, and so must the markers' centroids.
constexpr double kMaxObjectCentroidErrorPx = 0.1;
constexpr double kMaxObjectFluxError = 0.01;
constexpr double kMaxMarkerCentroidErrorPx = 0.05;
constexpr double kMatchRadiusPx = 2.0;

const Blob* nearest_blob(const std::vector<Blob>& blobs, double x_px, double y_px) {
  for (const Blob& blob : blobs)
    if (std::hypot(blob.x_px - x_px, blob.y_px - y_px) < kMatchRadiusPx) return &blob;
  return nullptr;
}

TEST_F(BlenderSubdiv, SubdividedObjectMatchesCycles) {
  const ShotRenders r = render_shot(
      blender, "subdiv", fs::path(FILMBACK_BLENDER_WORK_DIR) / "subdiv", FILMBACK_MAKE_SHOT_PY);
  ASSERT_NE(r.filmback_log.find("'SubdividedCube' level 2: 192 triangles"), std::string::npos)
      << r.filmback_log;
  const std::vector<Blob> cycles = find_blobs(r.cycles, 0.0);
  const std::vector<Blob> filmback = find_blobs(r.filmback, 0.0);
  ASSERT_EQ(cycles.size(), r.markers.size() + 1) << "blobs in the Cycles render";
  ASSERT_EQ(filmback.size(), r.markers.size() + 1) << "blobs in the filmback render";
  const auto largest = [](const std::vector<Blob>& blobs) {
    return *std::max_element(blobs.begin(), blobs.end(),
                             [](const Blob& a, const Blob& b) { return a.flux < b.flux; });
  };
  const Blob cycles_object = largest(cycles), filmback_object = largest(filmback);
  const double dx = filmback_object.x_px - cycles_object.x_px;
  const double dy = filmback_object.y_px - cycles_object.y_px;
  const double flux_error = filmback_object.flux / cycles_object.flux - 1;
  std::printf(
      "subdivided object: Cycles centroid (%.3f, %.3f) flux %.2f, filmback (%.3f, %.3f) "
      "flux %.2f: offset (%+.4f, %+.4f) px, flux %+.3f %%; Blender %.1f s (Cycles %.1f s), "
      "filmback %.1f s\n",
      cycles_object.x_px, cycles_object.y_px, cycles_object.flux, filmback_object.x_px,
      filmback_object.y_px, filmback_object.flux, dx, dy, 100 * flux_error, r.blender_s, r.cycles_s,
      r.filmback_s);
  EXPECT_LT(std::hypot(dx, dy), kMaxObjectCentroidErrorPx);
  EXPECT_LT(std::abs(flux_error), kMaxObjectFluxError);
  for (const Record& m : r.markers) {
    const double x = m.number("image_x_px"), y = m.number("image_y_px");
    const Blob* c = nearest_blob(cycles, x, y);
    const Blob* f = nearest_blob(filmback, x, y);
    ASSERT_TRUE(c && f) << m.text("name");
    std::printf("marker %-13s expected (%.3f, %.3f) Cycles (%.3f, %.3f) filmback (%.3f, %.3f)\n",
                m.text("name").c_str(), x, y, c->x_px, c->y_px, f->x_px, f->y_px);
    EXPECT_LT(std::hypot(f->x_px - c->x_px, f->y_px - c->y_px), kMaxMarkerCentroidErrorPx)
        << m.text("name");
  }
}

// The textured shot (subdiv_shot.py "textured"): a cube with Blender's default unwrap, half of
// its faces in a second material that reads a second UV map shifted by one square, and a torus
// with waved UVs, both subdivided (level 2, uv_smooth PRESERVE_BOUNDARIES) and emitting the
// checker through their UV maps. Every pixel is the texture where the refined UVs put it, so red
// in one render and white in the other is a misplaced UV (or a face given the wrong material or
// map). Measured (Debian's Blender 3.4.1, 64 spp): no misplaced pixel of 36 000, about 17 900 of
// them on the checker; image means within 0.01 %. The bound allows 36 pixels (0.1 %) of edge
// noise; the same export refined with uv_smooth None misplaces about 400 pixels, with Smooth All
// about 500, and with every cube face in its first primitive's material (face_primitives
// ignored) about 1100 (printed each run), so the rule and the parts are what is tested.
constexpr double kMaxMisplacedFraction = 0.001;
constexpr double kMaxTexturedMeanError = 0.01;

// `shot.gltf` with each `from` replaced by `to`, rendered as render_shot renders it, as
// `name`.gltf: its misplaced pixels against Cycles.
size_t misplaced_when_edited(const fs::path& work, const ShotRenders& r, const std::string& name,
                             const std::string& from, const std::string& to) {
  std::string gltf = read_text(work / "shot.gltf");
  size_t replaced = 0;
  for (size_t at = gltf.find(from); at != std::string::npos; at = gltf.find(from, at + to.size()))
    gltf.replace(at, from.size(), to), ++replaced;
  if (replaced == 0) throw std::runtime_error("shot.gltf has no " + from);
  const fs::path file = work / (name + ".gltf"), image = work / (name + ".exr");
  std::ofstream(file) << gltf;
  run_logged(quoted(FILMBACK_EXE) + " render " + quoted(file) + " -o " + quoted(image) + " --spp " +
                 r.shot.text("samples"),
             work / (name + ".log"));
  return compare_checkers(r.cycles, read_image(image)).misplaced;
}

TEST_F(BlenderSubdiv, TexturedSubdividedObjectsMatchCycles) {
  const fs::path work = fs::path(FILMBACK_BLENDER_WORK_DIR) / "subdiv_textured";
  const ShotRenders r = render_shot(blender, "textured", work, FILMBACK_MAKE_SHOT_PY);
  ASSERT_EQ(r.cycles.width, r.filmback.width);
  ASSERT_EQ(r.cycles.height, r.filmback.height);
  ASSERT_NE(r.filmback_log.find("'Cube' level 2: 192 triangles"), std::string::npos)
      << r.filmback_log;
  const CheckerAgreement a = compare_checkers(r.cycles, r.filmback);
  double sum_c = 0, sum_f = 0;
  for (uint32_t y = 0; y < r.cycles.height; ++y)
    for (uint32_t x = 0; x < r.cycles.width; ++x)
      for (size_t ch = 0; ch < 3; ++ch)
        sum_c += r.cycles.at(x, y, ch), sum_f += r.filmback.at(x, y, ch);
  const double pixels = double(r.cycles.width) * r.cycles.height;
  const std::string rule = "\"PRESERVE_BOUNDARIES\"";
  const size_t none = misplaced_when_edited(work, r, "uv_smooth_none", rule, "\"NONE\"");
  const size_t smooth_all = misplaced_when_edited(work, r, "uv_smooth_all", rule, "\"SMOOTH_ALL\"");
  // An unknown member is ignored: every face then wears the first primitive's material.
  const size_t one_part =
      misplaced_when_edited(work, r, "one_part", "\"face_primitives\"", "\"ignored\"");
  std::printf(
      "textured subdivided shot: %zu red-square pixels in Cycles; red/white disagreements %zu "
      "(%.3f %%), edge pixels moved %zu; filmback/Cycles mean %.5f; disagreements with uv_smooth "
      "NONE %zu, SMOOTH_ALL %zu, without face_primitives %zu; Blender %.1f s, filmback %.1f s\n",
      a.red, a.misplaced, 100 * double(a.misplaced) / pixels, a.edge_moved, sum_f / sum_c, none,
      smooth_all, one_part, r.blender_s, r.filmback_s);
  EXPECT_GT(a.red, size_t(0.1 * pixels)) << "the checker is not in view";
  EXPECT_LE(double(a.misplaced), kMaxMisplacedFraction * pixels);
  EXPECT_LT(std::abs(sum_f / sum_c - 1), kMaxTexturedMeanError);
  EXPECT_GT(double(none), 5 * kMaxMisplacedFraction * pixels);
  EXPECT_GT(double(smooth_all), 5 * kMaxMisplacedFraction * pixels);
  EXPECT_GT(double(one_part), 5 * kMaxMisplacedFraction * pixels);
}

}  // namespace
}  // namespace fb::test
