// What a render will hold at its peak, estimated before anything large is allocated, against a
// limit (docs/reliability.md, "Limits"): a scene or an image size that would not fit fails with an
// error naming the estimate and the limit instead of swapping or being killed by the kernel.
#pragma once

#include <cstdint>
#include <string>

#include "core/film/cryptomatte.h"
#include "core/film/film.h"
#include "core/scene/scene.h"
#include "core/scene/subdivision_surface.h"

namespace fb {

// Half of this machine's physical memory: the default --memory-limit.
uint64_t default_memory_limit_bytes();

// Bytes an instance traced as an Embree instance holds at most: RenderGeometry's record (its
// transforms and their normal transforms, 256 bytes per motion step), Embree's instance object and
// its share of the top-level BVH. Measured: 606 bytes through RenderGeometry::live_bytes(), and
// 430-760 bytes of resident memory per instance over 200,000 (docs/benchmarks.md, "Instances").
constexpr double kBytesPerInstance = 1024;

// What the render stores of a scene's meshes (core/accel/instancing.h): the render-space
// triangles of each flattened instance plus one copy of each instanced mesh; the instances traced
// as instances; the texture coordinates and tangents in the scene and in the render's copies;
// and each deformed (skinned, morphed or evaluated) mesh's posed copy, as many triangles again,
// with its motion steps' positions and normals.
struct GeometryCounts {
  double triangles = 0;
  double instances = 0;
  double texturing_bytes = 0;
  // Evaluated shapes held by the scene, and the motion steps past the first that the render's
  // copy of a deformed mesh holds when its pose can change.
  double deformation_bytes = 0;
  GeometryCounts& operator+=(const GeometryCounts& more);
};

GeometryCounts geometry_counts(const Scene& scene);

// The films kept beside the image for the passes --passes asks for: a Cryptomatte film of
// `cryptomatte_levels` slots per pixel for each Cryptomatte pass (core/film/cryptomatte.h), and
// the Vector pass's (core/film/motion_vector_film.h).
struct PassFilmCounts {
  uint32_t cryptomatte_passes = 0;
  uint32_t cryptomatte_levels = kDefaultCryptomatteLevels;
  bool vector = false;
};

// Those of `passes` (names as --passes takes them) with `cryptomatte_levels` slots.
PassFilmCounts pass_film_counts(const std::vector<std::string>& passes,
                                uint32_t cryptomatte_levels);

struct MemoryEstimate {
  double film_bytes = 0;      // sums, weights and counts; the resolved image and one copy of it
  double splat_bytes = 0;     // --reconstruction splat: the tiles' own sums
  double geometry_bytes = 0;  // stored triangles, their texture coordinates, Embree's BVHs,
                              // instances, deformed meshes' motion steps
  double pass_bytes = 0;      // Cryptomatte and Vector films, their channels in both images
  double total() const { return film_bytes + splat_bytes + geometry_bytes + pass_bytes; }
};

// For a film of width x height pixels with `channels` channels, the geometry `geometry` counts,
// when splatting, a filter reaching `splat_margin_px` pixels beyond each tile of 16 x 16, and the
// pass films `passes`.
MemoryEstimate estimate_memory(uint32_t width, uint32_t height, size_t channels,
                               Reconstruction reconstruction, uint32_t splat_margin_px,
                               const GeometryCounts& geometry, const PassFilmCounts& passes = {});

// Triangles that refining `surface` to its render level makes (--subdiv render), known from the
// cage before any refinement: a level-0 surface is its cage triangulated (n - 2 per n-gon); each
// Catmull-Clark or simple level makes n quads of an n-gon, then 4 of each quad.
double refined_triangles(const SubdivisionSurface& surface);

// The texture coordinates and tangents that refinement gives those triangles (and the render's
// copy of them), known from the cage: a closed mesh of quads has about one vertex per two
// triangles, and seams split vertices; the cage's own ratio of joined UV values to vertices
// bounds the split (a seam is a line, the surface grows as its area). Each slot a part fills is
// a Vec2f per vertex, tangents a float[4].
double refined_texturing_bytes(const SubdivisionSurface& surface);

// Throws InputError "SCENE: the render needs about ... GB (film ..., geometry ...), more than the
// memory limit of ... GB (SOURCE)" when the estimate exceeds `limit_bytes`; `source` says where
// the limit came from.
void check_memory(const MemoryEstimate& estimate, uint64_t limit_bytes, const std::string& source,
                  const std::string& scene);

// "8G", "512M", "1.5T", "100000000" (bytes; K, M, G, T are powers of 1024). Throws UsageError
// naming --memory-limit.
uint64_t parse_memory_size(const std::string& text);

}  // namespace fb
