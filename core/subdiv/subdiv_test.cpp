// Refinement through the subdivision module (libfilmback_subdiv.so), as a render calls it.
#include "core/subdiv/refine_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "core/util/error.h"

namespace fb {
namespace {

// The cube [-1, 1]^3 as six quads, counter-clockwise seen from outside.
SubdivisionSurface cube(uint32_t level) {
  SubdivisionSurface s;
  s.name = "Cube";
  s.node = "nodes[0]";
  for (int i = 0; i < 8; ++i)
    s.cage_positions.push_back({i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f});
  s.cage_face_sizes.assign(6, 4);
  s.cage_face_vertices = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
  s.settings.levels_render = level;
  return s;
}

TriangleMesh refine(const SubdivisionSurface& s, SubdivMode mode = SubdivMode::kRender,
                    const SubdivView& view = {}, uint64_t cap = kMaxSubdivTriangles) {
  Scene scene;
  scene.file = "test.gltf";
  scene.subdivision_surfaces = {s};
  refine_subdivision_surfaces(scene, mode, view, cap);
  EXPECT_TRUE(scene.subdivision_surfaces.empty());
  EXPECT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.instances.size(), 1u);
  return scene.meshes.at(0);
}

// Each undirected edge of a closed, crack-free triangle mesh borders exactly two triangles, once
// in each direction.
void expect_watertight(const TriangleMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      ++directed[{m.indices[t + k], m.indices[t + (k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "open edge " << edge.first << "-" << edge.second;
  }
}

void expect_outward(const TriangleMesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(length(m.normals[v]), 1.f, 1e-5f) << v;
    EXPECT_GT(dot(m.normals[v], m.positions[v]), 0.f) << v;
  }
  // Geometric normals of the triangles point outward too (counter-clockwise as the cage).
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const Vec3f a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                c = m.positions[m.indices[t + 2]];
    EXPECT_GT(dot(cross(b - a, c - a), a + b + c), 0.f) << t / 3;
  }
}

TEST(Subdivision, CubeAtLevelsOneAndTwoHasCatmullClarksCounts) {
  // V' = V + E + F per level: 8+12+6 = 26, then 26+48+24 = 98; faces 6*4^L quads, two triangles
  // each.
  const TriangleMesh one = refine(cube(1)), two = refine(cube(2));
  EXPECT_EQ(one.positions.size(), 26u);
  EXPECT_EQ(one.triangle_count(), 48u);
  EXPECT_EQ(two.positions.size(), 98u);
  EXPECT_EQ(two.triangle_count(), 192u);
  expect_watertight(two);
  expect_outward(two);
  // On the limit surface, inside the cage's hull and symmetric under the cube's reflections.
  float max_coord = 0;
  for (const Vec3f& p : two.positions)
    max_coord = std::max({max_coord, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  EXPECT_LT(max_coord, 1.f);
  EXPECT_GT(max_coord, 0.5f);
}

TEST(Subdivision, LimitSurfaceIsInsideTheRefinedCage) {
  SubdivisionSurface s = cube(2);
  s.settings.use_limit_surface = false;
  const TriangleMesh refined = refine(s);
  const TriangleMesh limit = refine(cube(2));
  ASSERT_EQ(refined.positions.size(), limit.positions.size());
  int inside = 0;
  for (size_t v = 0; v < refined.positions.size(); ++v)
    inside += length(limit.positions[v]) < length(refined.positions[v]) - 1e-4f;
  // Every vertex of a convex cage's refinement moves inwards to its limit.
  EXPECT_EQ(inside, int(refined.positions.size()));
}

TEST(Subdivision, FullyCreasedCubeStaysACube) {
  SubdivisionSurface s = cube(2);
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t k = 0; k < 4; ++k) {
      const uint32_t a = s.cage_face_vertices[4 * f + k],
                     b = s.cage_face_vertices[4 * f + (k + 1) % 4];
      if (a < b) s.edge_creases.push_back({a, b, 1.0f});
    }
  ASSERT_EQ(s.edge_creases.size(), 12u);
  const TriangleMesh m = refine(s);
  for (const Vec3f& p : m.positions)
    EXPECT_NEAR(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1.f, 1e-6f);
  int corners = 0;
  for (const Vec3f& p : m.positions)
    corners += std::abs(p.x) > 1 - 1e-6f && std::abs(p.y) > 1 - 1e-6f && std::abs(p.z) > 1 - 1e-6f;
  EXPECT_EQ(corners, 8);
  // Without use_creases the same cage rounds off.
  s.settings.use_creases = false;
  const TriangleMesh round = refine(s);
  for (const Vec3f& p : round.positions)
    EXPECT_LT(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1.f);
}

TEST(Subdivision, BlendersCreaseIsTenTimesItsSquare) {
  EXPECT_EQ(crease_sharpness(0.f), 0.f);
  EXPECT_FLOAT_EQ(crease_sharpness(0.5f), 2.5f);
  EXPECT_FLOAT_EQ(crease_sharpness(1.f), 10.f);
}

TEST(Subdivision, SimpleSchemeKeepsTheCube) {
  SubdivisionSurface s = cube(2);
  s.settings.scheme = SubdivisionSettings::Scheme::kSimple;
  const TriangleMesh m = refine(s);
  EXPECT_EQ(m.positions.size(), 98u);
  for (const Vec3f& p : m.positions)
    EXPECT_NEAR(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1.f, 1e-6f);
}

TEST(Subdivision, AdaptiveAtUniformRatesMeetsTheUniformLimitSurface) {
  // Bfr's tessellation at 2^L segments per edge samples the same dyadic parameters as Far's level
  // L: two independent routes through OpenSubdiv to the same limit points.
  const SubdivisionSurface s = cube(2);
  const TriangleMesh uniform = refine(s);
  // Rates come from the distance between the cage corners' limit points (the corners of the
  // uniform mesh): 3.5 px each through an orthographic view gives rate 4 = 2^2.
  float corner = 0;  // the limit point of the cage corner (1, 1, 1) is (c, c, c)
  for (const Vec3f& p : uniform.positions)
    corner = std::max(corner, (p.x + p.y + p.z) / 3);
  const double scale = 3.5 / (2 * corner);
  const SubdivView view{Transform(), scale, scale, true};
  const TriangleMesh adaptive = refine(s, SubdivMode::kAdaptive, view);
  ASSERT_EQ(adaptive.positions.size(), uniform.positions.size());
  double worst = 0;
  for (const Vec3f& p : adaptive.positions) {
    double nearest = HUGE_VAL;
    for (const Vec3f& q : uniform.positions)
      nearest = std::min(nearest, double(length(p - q)));
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, 1e-6);
  expect_watertight(adaptive);
  expect_outward(adaptive);
}

TEST(Subdivision, AdaptiveRatesFollowTheCameraWithoutCracks) {
  // A perspective eye close to one corner: near edges get many segments, far ones few.
  const SubdivisionSurface s = cube(0);
  const Vec3d eye{1.5, 1.5, 1.5};
  const SubdivView view{Transform::translate(-eye), 20.0, 20.0, false};
  const TriangleMesh m = refine(s, SubdivMode::kAdaptive, view);
  expect_watertight(m);
  expect_outward(m);
  // Segment lengths as seen: none much longer than a pixel's worth of the nearer end's distance.
  double worst_px = 0;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const Vec3d a(m.positions[m.indices[t + k]]), b(m.positions[m.indices[t + (k + 1) % 3]]);
      const double d = std::min(length(a - eye), length(b - eye));
      worst_px = std::max(worst_px, length(a - b) * view.fx / d);
    }
  EXPECT_LT(worst_px, 2.5);  // diagonals of ~1 px cells, over the limit surface's stretch
  EXPECT_GT(m.triangle_count(), 500u);
}

TEST(Subdivision, AdaptiveRatesFollowTheProjectionOffTheAxis) {
  // The same cube at the same distance, on the view axis and 63 deg off it: a perspective image
  // stretches it there (radially by 1/cos^2, tangentially by 1/cos), and so do the rates.
  const SubdivView view{Transform(), 100.0, 100.0, false};
  SubdivisionSurface on_axis = cube(0), off_axis = cube(0);
  const double distance = std::sqrt(80.0);
  on_axis.world_from_object = Transform::translate({0, 0, -distance});
  off_axis.world_from_object = Transform::translate({8, 0, -4});
  const double ratio = double(refine(off_axis, SubdivMode::kAdaptive, view).triangle_count()) /
                       double(refine(on_axis, SubdivMode::kAdaptive, view).triangle_count());
  const double cos_angle = 4 / distance;
  EXPECT_GT(ratio, 0.7 / (cos_angle * cos_angle * cos_angle)) << ratio;
}

TEST(Subdivision, TooManyTrianglesIsAnErrorNamingTheSurface) {
  try {
    refine(cube(6), SubdivMode::kRender, {}, 1000);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test.gltf: subdivision surface 'Cube' (nodes[0])"), std::string::npos)
        << what;
    EXPECT_NE(what.find("49152 triangles, more than the limit of 1000"), std::string::npos) << what;
  }
}

TEST(Subdivision, AdaptiveCoarsensToTheCapWithAWarning) {
  Scene scene;
  scene.file = "test.gltf";
  scene.subdivision_surfaces = {cube(0)};
  const SubdivReport report = refine_subdivision_surfaces(
      scene, SubdivMode::kAdaptive, {Transform(), 1000.0, 1000.0, true}, 20000);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("limit of 20000 triangles"), std::string::npos);
  EXPECT_LE(scene.meshes.at(0).triangle_count(), 20000u);
  EXPECT_GT(scene.meshes.at(0).triangle_count(), 5000u);
}

// The cube with each face on its own UV island, a unit square at u = 2 f, corners (2f, 0)
// (2f + 1, 0) (2f + 1, 1) (2f, 1) in the face's order: every cage edge is a seam, so every face's
// vertices split from its neighbours'.
SubdivisionSurface cube_with_islands(uint32_t level) {
  SubdivisionSurface s = cube(level);
  SubdivisionUvMap map{"UVMap", {}};
  for (int f = 0; f < 6; ++f) {
    const float u = 2.f * float(f);
    map.corner_uvs.insert(map.corner_uvs.end(), {{u, 0}, {u + 1, 0}, {u + 1, 1}, {u, 1}});
  }
  s.uv_maps = {map};
  s.parts[0].slot_uv_maps[0] = 0;
  return s;
}

// The mesh's triangles with each vertex replaced by the first vertex at the same position (bit
// for bit): split vertices joined again.
TriangleMesh welded(const TriangleMesh& m) {
  std::map<std::array<uint32_t, 3>, uint32_t> first;
  TriangleMesh out = m;
  for (uint32_t& i : out.indices) {
    std::array<uint32_t, 3> bits;
    std::memcpy(bits.data(), &m.positions[i], sizeof bits);
    i = first.try_emplace(bits, i).first->second;
  }
  return out;
}

size_t distinct_positions(const TriangleMesh& m) {
  std::set<std::array<float, 3>> set;
  for (const Vec3f& p : m.positions)
    set.insert({p.x, p.y, p.z});
  return set.size();
}

// Each island's coordinates are the face's own parameters: with Keep Boundaries (Blender's
// default) a one-face island is bilinear, so level 2 puts them on the quarters.
void expect_island_grid(const TriangleMesh& m) {
  const std::vector<Vec2f>& uv = m.texturing.texcoords[0];
  ASSERT_EQ(uv.size(), m.positions.size());
  for (const Vec2f& t : uv) {
    EXPECT_NEAR(t.x * 4, std::round(t.x * 4), 1e-5) << t.x;
    EXPECT_NEAR(t.y * 4, std::round(t.y * 4), 1e-5) << t.y;
    const float island_u = t.x - 2 * std::floor(t.x / 2 + 0.25f);  // 0..1 within its island
    EXPECT_TRUE(island_u >= -1e-5f && island_u <= 1 + 1e-5f && t.y >= -1e-6f && t.y <= 1 + 1e-6f)
        << t.x << " " << t.y;
  }
}

TEST(Subdivision, UvSeamsSplitVerticesThatKeepOnePosition) {
  const SubdivisionSurface s = cube_with_islands(2);
  // Rate 4 on every edge, as level 2: 3.5 px between the limit corners (see above).
  float corner = 0;
  for (const Vec3f& p : refine(cube(2)).positions)
    corner = std::max(corner, (p.x + p.y + p.z) / 3);
  const double scale = 3.5 / (2 * corner);
  for (const SubdivMode mode : {SubdivMode::kRender, SubdivMode::kAdaptive}) {
    SCOPED_TRACE(mode == SubdivMode::kRender ? "render" : "adaptive");
    const TriangleMesh m = refine(s, mode, {Transform(), scale, scale, true});
    // 25 vertices per face of 16 quads; 98 surface points, as without UVs.
    EXPECT_EQ(m.positions.size(), 150u);
    EXPECT_EQ(m.triangle_count(), 192u);
    EXPECT_EQ(distinct_positions(m), 98u);
    expect_island_grid(m);
    expect_watertight(welded(m));
    expect_outward(m);
  }
}

TEST(Subdivision, AdaptiveSeamsStayClosedAtUnequalRates) {
  // A perspective eye near one corner gives the edges different rates; the seams' split points
  // must still coincide with their partners'.
  const SubdivisionSurface s = cube_with_islands(0);
  const Vec3d eye{1.5, 1.5, 1.5};
  const TriangleMesh m =
      refine(s, SubdivMode::kAdaptive, {Transform::translate(-eye), 20.0, 20.0, false});
  expect_watertight(welded(m));
  EXPECT_GT(m.positions.size(), distinct_positions(m));
  for (const Vec2f& t : m.texturing.texcoords[0])
    EXPECT_TRUE(t.x >= -1e-6f && t.x <= 11 + 1e-5f && t.y >= -1e-6f && t.y <= 1 + 1e-6f);
}

// A flat 3 x 3 grid of unit quads in z = 0, its UV map the vertices' own (x, y): no seam.
SubdivisionSurface planar_grid(SubdivisionSettings::UvSmooth uv_smooth) {
  SubdivisionSurface s;
  s.name = "Grid";
  for (int y = 0; y <= 3; ++y)
    for (int x = 0; x <= 3; ++x)
      s.cage_positions.push_back({float(x), float(y), 0.f});
  SubdivisionUvMap map{"UVMap", {}};
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 3; ++x) {
      const uint32_t a = 4 * y + x;
      s.cage_face_sizes.push_back(4);
      for (uint32_t v : {a, a + 1, a + 5, a + 4}) {
        s.cage_face_vertices.push_back(v);
        map.corner_uvs.push_back({s.cage_positions[v].x, s.cage_positions[v].y});
      }
    }
  s.uv_maps = {map};
  s.parts[0].slot_uv_maps[0] = 0;
  s.parts[0].tangent_slot = 0;
  s.settings.uv_smooth = uv_smooth;
  return s;
}

// How far texture coordinates are from a point's (x, y).
double uv_distance(Vec2f uv, Vec3f p) {
  return std::hypot(double(uv.x) - p.x, double(uv.y) - p.y);
}

TEST(Subdivision, SmoothAllUvsFollowTheSurfaceAndNoneStaysBilinear) {
  using UvSmooth = SubdivisionSettings::UvSmooth;
  // Smooth All (OpenSubdiv's FVAR_LINEAR_NONE) refines the coordinates by the rules the positions
  // follow (boundary All: VTX_BOUNDARY_EDGE_ONLY), so a UV map equal to (x, y) stays equal to the
  // refined surface's (x, y), boundary included.
  const TriangleMesh smooth = refine(planar_grid(UvSmooth::kSmoothAll));
  EXPECT_EQ(smooth.positions.size(), 169u);  // 13 x 13: no split
  double worst = 0;
  for (size_t v = 0; v < smooth.positions.size(); ++v)
    worst = std::max(worst, uv_distance(smooth.texturing.texcoords[0][v], smooth.positions[v]));
  EXPECT_LT(worst, 1e-5);
  // None (FVAR_LINEAR_ALL) interpolates the cage's coordinates bilinearly: quarters of the
  // cage's unit squares, while the surface itself shrinks away from the boundary.
  const TriangleMesh linear = refine(planar_grid(UvSmooth::kNone));
  EXPECT_EQ(linear.positions.size(), 169u);
  double apart = 0;
  for (size_t v = 0; v < linear.positions.size(); ++v) {
    const Vec2f t = linear.texturing.texcoords[0][v];
    EXPECT_NEAR(t.x * 4, std::round(t.x * 4), 1e-5);
    EXPECT_NEAR(t.y * 4, std::round(t.y * 4), 1e-5);
    apart = std::max(apart, uv_distance(t, linear.positions[v]));
  }
  EXPECT_GT(apart, 0.1);
  // Keep Boundaries (the default) pins the boundary to the cage's coordinates: a corner of the
  // grid keeps (0, 0) while its surface point moves in.
  const TriangleMesh kept = refine(planar_grid(UvSmooth::kPreserveBoundaries));
  bool corner = false;
  for (const Vec2f& t : kept.texturing.texcoords[0])
    corner = corner || (t.x == 0.f && t.y == 0.f);
  EXPECT_TRUE(corner);
}

TEST(Subdivision, NormalMapTangentsFollowTheUvs) {
  // u runs along +x on the grid: the tangent is +x, and the bitangent (-v direction) is -y, which
  // is w (n x t) with n = +z: w = -1.
  const TriangleMesh m = refine(planar_grid(SubdivisionSettings::UvSmooth::kSmoothAll));
  ASSERT_EQ(m.texturing.tangents.size(), m.positions.size());
  for (const auto& t : m.texturing.tangents) {
    EXPECT_NEAR(t[0], 1.f, 1e-4f);
    EXPECT_EQ(t[3], -1.f);
  }
}

TEST(Subdivision, EachPartBecomesAMeshWithItsMaterial) {
  // The cube's top face (+z, the second cage face) wears material 7, the others material 3; the
  // top reads the UV map, the others none.
  SubdivisionSurface s = cube_with_islands(1);
  s.parts = {{3}, {7}};
  s.parts[1].slot_uv_maps[0] = 0;
  s.face_parts = {0, 1, 0, 0, 0, 0};
  Scene scene;
  scene.file = "test.gltf";
  scene.subdivision_surfaces = {s};
  const SubdivReport report = refine_subdivision_surfaces(scene, SubdivMode::kRender, {});
  ASSERT_EQ(scene.meshes.size(), 2u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.meshes[0].material, 3u);
  EXPECT_EQ(scene.meshes[1].material, 7u);
  EXPECT_EQ(scene.meshes[0].triangle_count(), 40u);
  EXPECT_EQ(scene.meshes[1].triangle_count(), 8u);
  EXPECT_EQ(scene.meshes[1].positions.size(), 9u);  // its own vertices only
  EXPECT_TRUE(scene.meshes[0].texturing.texcoords[0].empty());
  ASSERT_EQ(scene.meshes[1].texturing.texcoords[0].size(), 9u);
  for (const Vec3f& p : scene.meshes[1].positions)
    EXPECT_GE(p.z, 0.5f);  // the top face's limit, edges included
  EXPECT_NE(report.summary.find("48 triangles"), std::string::npos) << report.summary;
}

TEST(Subdivision, UnrefinedSurfacesAreInTheSceneBounds) {
  // A scene of nothing but a subdivision surface is framed (default camera) by its cage, which
  // bounds the surface.
  Scene scene;
  SubdivisionSurface s = cube(2);
  s.world_from_object = Transform::translate({10, 0, 0});
  scene.subdivision_surfaces = {s};
  const Bounds3d bounds = scene.world_bounds(0);
  EXPECT_EQ(bounds.lo.x, 9.0);
  EXPECT_EQ(bounds.hi.x, 11.0);
  EXPECT_EQ(bounds.hi.z, 1.0);
}

}  // namespace
}  // namespace fb
