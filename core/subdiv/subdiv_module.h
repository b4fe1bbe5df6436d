/* The C entry point of libfilmback_subdiv.so, the one library that links OpenSubdiv. The core
 * dlopen()s it only when a scene holds a subdivision surface (core/subdiv/subdiv_loader.h), so a
 * scene without one never loads OpenSubdiv. Plain C: the module and the core agree on nothing but
 * these structs. */
#ifndef FILMBACK_SUBDIV_MODULE_H
#define FILMBACK_SUBDIV_MODULE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FB_SUBDIV_ABI_VERSION 1u
#define FB_SUBDIV_ENTRY_POINT "filmback_subdiv_refine"
#define FB_SUBDIV_FREE_POINT "filmback_subdiv_free"

enum { FB_SUBDIV_CATMULL_CLARK = 0, FB_SUBDIV_BILINEAR = 1 };
enum { FB_SUBDIV_BOUNDARY_EDGE_ONLY = 0, FB_SUBDIV_BOUNDARY_EDGE_AND_CORNER = 1 };

/* A cage: vertices, faces (sizes and counter-clockwise vertex lists) and creases as OpenSubdiv
 * sharpness (Blender's crease already converted). */
typedef struct fb_subdiv_cage {
  uint32_t struct_size;
  uint32_t abi_version;
  const float* positions; /* xyz per vertex */
  uint32_t vertex_count;
  const uint32_t* face_sizes;
  uint32_t face_count;
  const uint32_t* face_vertices;
  const uint32_t* crease_edges; /* v0, v1 per creased edge */
  const float* crease_edge_sharpness;
  uint32_t crease_edge_count;
  const uint32_t* crease_vertices;
  const float* crease_vertex_sharpness;
  uint32_t crease_vertex_count;
  uint32_t scheme;   /* FB_SUBDIV_CATMULL_CLARK or FB_SUBDIV_BILINEAR */
  uint32_t boundary; /* FB_SUBDIV_BOUNDARY_* */
} fb_subdiv_cage;

/* What to make of it. With edge_rates: each cage face tessellated on the limit surface with the
 * given number of segments on each of its edges (one rate per entry of face_vertices: the edge
 * from vertex k to k+1), sharing the points of shared edges so the result has no cracks; rates
 * of 2^level everywhere give the vertices of uniform refinement, on the limit surface. With
 * edge_rates null: uniform refinement to `level` without the limit (Blender's
 * use_limit_surface off), normals still from the limit surface. */
typedef struct fb_subdiv_request {
  uint32_t struct_size;
  uint32_t level;
  const uint32_t* edge_rates;
  uint32_t quality;       /* limit evaluation: patches isolated this many levels (Blender's) */
  uint32_t cage_limit;    /* non-zero: only the cage's vertices pushed to the limit, no triangles */
  uint64_t max_triangles; /* refuse (with an error) to make more */
} fb_subdiv_request;

/* A triangle mesh with smooth normals (from the limit surface's tangents), owned by the module. */
typedef struct fb_subdiv_mesh {
  float* positions;
  float* normals;
  uint32_t* indices; /* three per triangle, counter-clockwise as the cage */
  uint64_t vertex_count;
  uint64_t triangle_count;
  char error[512]; /* set when the call returns non-zero */
} fb_subdiv_mesh;

typedef int (*fb_subdiv_refine_fn)(const fb_subdiv_cage* cage, const fb_subdiv_request* request,
                                   fb_subdiv_mesh* out);
typedef void (*fb_subdiv_free_fn)(fb_subdiv_mesh* mesh);

#ifdef __cplusplus
}
#endif

#endif
