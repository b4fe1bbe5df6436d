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

#define FB_SUBDIV_ABI_VERSION 3u
#define FB_SUBDIV_ENTRY_POINT "filmback_subdiv_refine"
#define FB_SUBDIV_FREE_POINT "filmback_subdiv_free"

enum { FB_SUBDIV_CATMULL_CLARK = 0, FB_SUBDIV_BILINEAR = 1 };
enum { FB_SUBDIV_BOUNDARY_EDGE_ONLY = 0, FB_SUBDIV_BOUNDARY_EDGE_AND_CORNER = 1 };
/* Where face-varying data is interpolated linearly: Sdc::Options::FVarLinearInterpolation, in its
 * order (NONE: smooth everywhere; ALL: linear everywhere). */
enum {
  FB_SUBDIV_FVAR_LINEAR_NONE = 0,
  FB_SUBDIV_FVAR_LINEAR_CORNERS_ONLY = 1,
  FB_SUBDIV_FVAR_LINEAR_CORNERS_PLUS1 = 2,
  FB_SUBDIV_FVAR_LINEAR_CORNERS_PLUS2 = 3,
  FB_SUBDIV_FVAR_LINEAR_BOUNDARIES = 4,
  FB_SUBDIV_FVAR_LINEAR_ALL = 5
};

/* A face-varying channel of texture coordinates: the values, and the value each face corner takes
 * (one per entry of face_vertices). Faces whose corners at a vertex take different values meet
 * at a seam there. */
typedef struct fb_subdiv_uv_channel {
  const float* values; /* u, v per value */
  uint32_t value_count;
  const uint32_t* corner_values;
} fb_subdiv_uv_channel;

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
  const fb_subdiv_uv_channel* uv_channels;
  uint32_t uv_channel_count;
  uint32_t fvar_linear; /* FB_SUBDIV_FVAR_LINEAR_* */
} fb_subdiv_cage;

/* What to make of it. With edge_rates: each cage face tessellated on the limit surface with the
 * given number of segments on each of its edges (one rate per entry of face_vertices: the edge
 * from vertex k to k+1), sharing the points of shared edges so the result has no cracks; rates
 * of 2^level everywhere give the vertices of uniform refinement, on the limit surface. With
 * edge_rates null: uniform refinement to `level` without the limit (Blender's
 * use_limit_surface off). Normals: with polygon_normals, those Blender computes for the refined
 * mesh (its polygons' normals averaged at each vertex, weighted by their corner angles: what
 * Cycles renders for a Subdivision Surface modifier's mesh); else the limit surface's (Cycles'
 * adaptive subdivision). */
typedef struct fb_subdiv_request {
  uint32_t struct_size;
  uint32_t level;
  const uint32_t* edge_rates;
  uint32_t quality;       /* limit evaluation: patches isolated this many levels (Blender's) */
  uint32_t cage_limit;    /* non-zero: only the cage's vertices pushed to the limit, no triangles */
  uint64_t max_triangles; /* refuse (with an error) to make more */
  uint32_t triangle_faces;  /* non-zero: say which cage face each triangle comes from */
  uint32_t polygon_normals; /* non-zero: Blender's normals of the refined mesh (see above) */
} fb_subdiv_request;

/* A triangle mesh with smooth normals (the request's), owned by the module.
 * With texture coordinates its vertices are split along the seams of every channel: each vertex
 * has one value per channel, and the split vertices of one surface point have the same position
 * and normal, bit for bit. */
typedef struct fb_subdiv_mesh {
  float* positions;
  float* normals;
  float* uvs;        /* uv_channel_count blocks of vertex_count (u, v) pairs, the cage's order */
  uint32_t* indices; /* three per triangle, counter-clockwise as the cage */
  uint32_t* triangle_faces; /* when asked: the cage face of each triangle */
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
