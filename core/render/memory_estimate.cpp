#include "core/render/memory_estimate.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/accel/instancing.h"
#include "core/render/motion_vectors.h"
#include "core/render/tile_size.h"
#include "core/subdiv/face_varying.h"
#include "core/util/error.h"

namespace fb {
namespace {

// Render-space vertices, indices, normals and Embree's BVH per flattened triangle, measured on
// Embree 3.13 MEDIUM builds (notes/deps.md).
constexpr double kBytesPerTriangle = 120;

std::string gigabytes(double bytes) {
  return number_text(bytes / 1e9) + " GB";
}

}  // namespace

uint64_t default_memory_limit_bytes() {
  return uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE)) / 2;
}

PassFilmCounts pass_film_counts(const std::vector<std::string>& passes,
                                uint32_t cryptomatte_levels) {
  PassFilmCounts counts;
  counts.cryptomatte_levels = cryptomatte_levels;
  for (const std::string& pass : passes) {
    if (find_cryptomatte_pass(pass)) ++counts.cryptomatte_passes;
    if (pass == kVectorPass) counts.vector = true;
  }
  return counts;
}

MemoryEstimate estimate_memory(uint32_t width, uint32_t height, size_t channels,
                               Reconstruction reconstruction, uint32_t splat_margin_px,
                               const GeometryCounts& geometry, const PassFilmCounts& passes) {
  const double pixels = double(width) * height, c = double(channels);
  MemoryEstimate e;
  // core/film/film.h: a double sum per channel, a double weight and a 32-bit count per pixel; the
  // resolved float image, and its copy with a samples channel when a render is interrupted.
  e.film_bytes =
      pixels * ((c + 1) * sizeof(double) + sizeof(uint32_t) + (2 * c + 1) * sizeof(float));
  if (reconstruction == Reconstruction::kSplat) {
    // core/film/splat_tiles.h: each tile's sums cover the tile and its margin on every side.
    const double grown = 1.0 + 2.0 * splat_margin_px / kTileSize;
    e.splat_bytes = pixels * grown * grown * (c + 1) * sizeof(double);
  }
  // CryptomatteFilm: per pixel, pass and level a slot (an index and a float weight), per pixel a
  // float weight; MotionVectorFilm: four double sums and a double weight. Their channels (two per
  // level, and X, Y, Z, W) are floats in the resolved image and in its copy, as the film's are.
  if (passes.cryptomatte_passes > 0) {
    const double slots = double(passes.cryptomatte_passes) * passes.cryptomatte_levels;
    e.pass_bytes += pixels * (slots * (sizeof(uint32_t) + sizeof(float)) + sizeof(float) +
                              2 * 2 * slots * sizeof(float));
  }
  if (passes.vector) e.pass_bytes += pixels * (5 * sizeof(double) + 2 * 4 * sizeof(float));
  e.geometry_bytes = geometry.triangles * kBytesPerTriangle +
                     geometry.instances * kBytesPerInstance + geometry.texturing_bytes +
                     geometry.deformation_bytes;
  return e;
}

namespace {

double bytes_of(const VertexTextureData& t) {
  double bytes = double(t.tangents.size()) * sizeof(t.tangents[0]);
  for (const auto& uv : t.texcoords)
    bytes += double(uv.size()) * sizeof(Vec2f);
  return bytes;
}

}  // namespace

GeometryCounts& GeometryCounts::operator+=(const GeometryCounts& more) {
  triangles += more.triangles;
  instances += more.instances;
  texturing_bytes += more.texturing_bytes;
  deformation_bytes += more.deformation_bytes;
  return *this;
}

GeometryCounts geometry_counts(const Scene& scene) {
  const std::vector<bool> instanced = instanced_meshes(scene, Instancing::kRepeated);
  GeometryCounts counts;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    counts.texturing_bytes += bytes_of(scene.meshes[m].texturing);
    if (!instanced[m]) continue;  // the render's one object-space copy
    counts.triangles += double(scene.meshes[m].triangle_count());
    counts.texturing_bytes += bytes_of(scene.meshes[m].texturing);
  }
  for (const MeshInstance& instance : scene.instances) {
    const TriangleMesh& mesh = scene.meshes[instance.mesh];
    if (instanced[instance.mesh]) {
      counts.instances += 1;
    } else {
      counts.triangles += double(mesh.triangle_count());
      counts.texturing_bytes += bytes_of(mesh.texturing);
    }
  }
  // Each deformed mesh is posed in a copy of it (RenderGeometry::add_deformed_mesh): counted as
  // its triangles once more, which bounds the copy (a render triangle costs more). A deformed
  // mesh whose pose changes anywhere on the timeline may move within the shutter: its render
  // copy then holds every motion step's positions and normals (at most deformation_motion_steps:
  // a skin's count is chosen by its motion when the geometry is built, so the bound is counted),
  // and the scene holds the evaluated shapes it was given. Rigid motion's steps are not counted
  // (docs/camera-model.md, "Time and motion").
  const double forever = std::numeric_limits<double>::infinity();
  for (const MeshDeformation& d : scene.deformations) {
    const TriangleMesh& mesh = scene.meshes[d.mesh];
    counts.triangles += double(mesh.triangle_count());
    counts.texturing_bytes += bytes_of(mesh.texturing);
    for (const DeformedShape& shape : d.evaluated.shapes)
      counts.deformation_bytes +=
          double(shape.positions.size() + shape.normals.size()) * sizeof(Vec3f);
    if (!deforms(d, scene.hierarchy, -forever, forever)) continue;
    const double per_step = double(mesh.positions.size() + mesh.normals.size()) * sizeof(Vec3f);
    counts.deformation_bytes += per_step * (deformation_motion_steps(d) - 1);
  }
  return counts;
}

double refined_texturing_bytes(const SubdivisionSurface& surface) {
  double per_vertex = 0;
  for (const SubdivisionPart& part : surface.parts) {
    double bytes = part.tangent_slot < VertexTextureData::kSets ? sizeof(float[4]) : 0;
    for (uint32_t map : part.slot_uv_maps)
      bytes += map < surface.uv_maps.size() ? sizeof(Vec2f) : 0;
    per_vertex = std::max(per_vertex, bytes);
  }
  if (per_vertex == 0) return 0;
  double split = 1;
  const uint32_t vertices = uint32_t(surface.cage_positions.size());
  for (const SubdivisionUvMap& map : surface.uv_maps)
    split =
        std::max(split, double(join_uv_corners(surface.cage_face_sizes, surface.cage_face_vertices,
                                               vertices, map.corner_uvs)
                                   .value_count()) /
                            std::max(vertices, 1u));
  const double vertices_made = refined_triangles(surface) / 2 * split;
  return 2 * per_vertex * vertices_made;  // the scene's mesh and the render's copy
}

double refined_triangles(const SubdivisionSurface& surface) {
  const uint32_t level = surface.settings.levels_render;
  double corners = 0;
  for (uint32_t n : surface.cage_face_sizes)
    corners += n;
  if (level == 0) return corners - 2.0 * double(surface.cage_face_sizes.size());
  return 2 * corners * std::pow(4.0, double(level) - 1);
}

void check_memory(const MemoryEstimate& e, uint64_t limit_bytes, const std::string& source,
                  const std::string& scene) {
  if (e.total() <= double(limit_bytes)) return;
  std::string parts = "film " + gigabytes(e.film_bytes);
  if (e.splat_bytes > 0) parts += ", splat tiles " + gigabytes(e.splat_bytes);
  parts += ", geometry and BVH " + gigabytes(e.geometry_bytes);
  if (e.pass_bytes > 0) parts += ", Cryptomatte and Vector passes " + gigabytes(e.pass_bytes);
  throw InputError(scene + ": the render needs about " + gigabytes(e.total()) + " (" + parts +
                   "), more than the memory limit of " + gigabytes(double(limit_bytes)) + " (" +
                   source + ")");
}

uint64_t parse_memory_size(const std::string& text) {
  double value = 0;
  const char* end = text.data() + text.size();
  const auto [rest, ec] = std::from_chars(text.data(), end, value);
  double scale = 1;
  if (rest + 1 == end) {
    switch (*rest) {
      case 'K':
        scale = 0x1p10;
        break;
      case 'M':
        scale = 0x1p20;
        break;
      case 'G':
        scale = 0x1p30;
        break;
      case 'T':
        scale = 0x1p40;
        break;
      default:
        scale = 0;
    }
  }
  const double bytes = value * scale;
  if (ec != std::errc() || (rest != end && rest + 1 != end) || !(bytes >= 1) || bytes > 0x1p63)
    throw UsageError("--memory-limit '" + text +
                     "': expected a size in bytes, or with K, M, G or T (powers of 1024), e.g. 8G");
  return uint64_t(bytes);
}

}  // namespace fb
