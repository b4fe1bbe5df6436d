/* FROZEN: core/sdk/filmback/plugin_abi.h as published before issue 14 grew fb_hit (surface) and
 * fb_scene_api (bsdf_eval, bsdf_sample, lights_crossed): `git show 9fc247c^:core/sdk/filmback/plugin_abi.h`.
 * Never edit it: the plugins in this folder are built against it to prove that a plugin built
 * against an older header still loads and runs (tests/sdk/abi_growth_test.cpp). */
/* filmback plugin ABI, version 1.
 *
 * The whole boundary between filmback and a plugin is this C header: one exported entry point per
 * shared library returns a plain descriptor, and every call after that goes through C function
 * pointers on plain C structs. No C++ type, exception or vtable crosses it, so a plugin built with
 * another compiler (or in another language) loads as long as it speaks this header. This is
 * Embree's model (opaque handles, version queries), not Mitsuba's C-named entry points that pass
 * C++ objects (see docs/architecture.md, "Plugin ABI").
 *
 * Handshake: the loader calls `filmback_plugin_v1()`, then checks `abi_version` and `struct_size`
 * (the first two fields, fixed forever) before it reads anything else; then the kind, the name
 * (which must match the file name libfilmback_<kind>_<name>.so) and the kind's function table,
 * which starts with its own struct_size.
 *
 * Spaces and units (docs/conventions.md): raster x right, y down, origin at the top-left corner of
 * the image; camera space looks down -Z with +Y up; render space is world space translated so that
 * the camera sits at the origin; metres, seconds, radiance in W sr^-1 m^-2.
 */
#ifndef FILMBACK_PLUGIN_ABI_H
#define FILMBACK_PLUGIN_ABI_H

#include <stddef.h>
#include <stdint.h>

#define FB_ABI_VERSION 1u
#define FB_ENTRY_POINT "filmback_plugin_v1"

#if defined(_WIN32)
#define FB_EXPORT __declspec(dllexport)
#else
#define FB_EXPORT __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- descriptor and parameters */

enum { FB_KIND_CAMERA = 1, FB_KIND_FILTER = 2, FB_KIND_INTEGRATOR = 3 };

enum {
  FB_PARAM_FLOAT = 1,  /* value.number[0] */
  FB_PARAM_INT = 2,    /* value.number[0], a whole number */
  FB_PARAM_BOOL = 3,   /* value.number[0], 0 or 1 */
  FB_PARAM_STRING = 4, /* value.text; `choices` may restrict it */
  FB_PARAM_RGB = 5     /* value.number[0..2]; typed as [r,g,b] or one grey value */
};

/* One entry of a plugin's parameter schema. The host parses `default_value` with the same parser
 * as user input, checks bounds and choices, and hands the plugin only validated values. */
typedef struct fb_param_desc {
  const char* name;          /* lower_snake_case, unit in the name where one applies */
  uint32_t type;             /* FB_PARAM_* */
  const char* default_value; /* as a user would type it */
  const char* unit;          /* "px", "mm", "m", "s", "" */
  const char* choices;       /* strings only: "a|b|c", or NULL for free text */
  double min_value;          /* numbers: inclusive bounds (use +-HUGE_VAL for none) */
  double max_value;
  const char* doc; /* one sentence */
} fb_param_desc;

/* A validated parameter value, passed to create() in schema order. */
typedef struct fb_value {
  double number[3];
  const char* text; /* valid only during create() */
} fb_value;

typedef struct fb_plugin {
  uint32_t abi_version; /* FB_ABI_VERSION */
  uint32_t struct_size; /* sizeof(fb_plugin) */
  uint32_t kind;        /* FB_KIND_* */
  const char* name;     /* short lower-case name: "perspective", "gaussian" */
  const char* version;  /* the plugin's own version, "1.0.0" */
  const char* summary;  /* one line */
  const fb_param_desc* params;
  uint32_t param_count;
  const void* api; /* fb_camera_api, fb_filter_api or fb_integrator_api, by kind */
} fb_plugin;

typedef const fb_plugin* (*fb_entry_point_fn)(void);

/* create() returns 0 on success; otherwise it writes a one-line reason into `error`. */
typedef struct fb_error_buffer {
  char* text;
  size_t capacity;
} fb_error_buffer;

/* ------------------------------------------------------------------------------------ camera */

enum { FB_PROJECTION_PERSPECTIVE = 1, FB_PROJECTION_ORTHOGRAPHIC = 2 };
enum { FB_SENSOR_FIT_AUTO = 0, FB_SENSOR_FIT_HORIZONTAL = 1, FB_SENSOR_FIT_VERTICAL = 2 };
/* SIMPLE: pixel = radiance, as Cycles. PHYSICAL: pixel = exposure (docs/camera-model.md). */
enum { FB_SENSOR_SIMPLE = 0, FB_SENSOR_PHYSICAL = 1 };

/* The shot's physical camera, as Blender describes it (docs/camera-model.md). */
typedef struct fb_camera_setup {
  uint32_t struct_size;
  uint32_t projection; /* FB_PROJECTION_* */
  uint32_t image_width_px;
  uint32_t image_height_px;
  double pixel_aspect; /* pixel width / pixel height */
  double focal_length_mm;
  double sensor_width_mm;
  double sensor_height_mm;
  uint32_t sensor_fit; /* FB_SENSOR_FIT_* */
  double shift_x;      /* fraction of the fitted image side */
  double shift_y;
  double ortho_scale_m; /* orthographic: view extent along the fitted side */
  double clip_near_m;   /* depth along the view axis */
  double clip_far_m;    /* HUGE_VAL for none */
  /* the lens */
  double fstop;                 /* HUGE_VAL: a pinhole */
  double focus_distance_m;      /* along the view axis; HUGE_VAL: focused at infinity */
  uint32_t aperture_blades;     /* 0: a round aperture */
  double aperture_rotation_rad; /* of the blades */
  double aperture_ratio;        /* anamorphic: the aperture's x is divided by it (Cycles) */
  /* the sensor */
  uint32_t sensor_model;  /* FB_SENSOR_* */
  double exposure_time_s; /* PHYSICAL only */
  double iso;             /* PHYSICAL only: ISO 12232 speed, 100 = unit gain */
} fb_camera_setup;

typedef struct fb_camera_sample {
  float film_x, film_y; /* raster position, px */
  float lens_u, lens_v; /* [0,1)^2, drawn only if the camera needs lens samples */
  float time_s; /* s after the frame's time, within the shutter; drawn only if something moves
                  while it is open (or the camera needs time), else 0 */
} fb_camera_sample;

typedef struct fb_camera_ray {
  float origin[3];    /* camera space, m */
  float direction[3]; /* camera space, unit length */
  float t_min, t_max; /* clip range along this ray */
  float weight;       /* 0: no ray for this sample */
} fb_camera_ray;

enum { FB_CAMERA_NEEDS_LENS = 1u, FB_CAMERA_NEEDS_TIME = 2u };

typedef struct fb_camera_api {
  uint32_t struct_size;
  int (*create)(const fb_value* params, const fb_camera_setup* setup, void** instance,
                fb_error_buffer error);
  void (*destroy)(void* instance);
  uint32_t (*needs)(const void* instance); /* FB_CAMERA_NEEDS_* */
  /* One call per batch (a tile's worth) keeps the indirection off the per-ray path. */
  void (*generate_rays)(const void* instance, const fb_camera_sample* samples, size_t count,
                        fb_camera_ray* rays);
} fb_camera_api;

/* ------------------------------------------------------------------------------------ filter */

typedef struct fb_filter_sample {
  float x, y;   /* offset from the pixel centre, px */
  float weight; /* f(x,y) / pdf(x,y): constant for exactly sampled positive filters */
} fb_filter_sample;

typedef struct fb_filter_api {
  uint32_t struct_size;
  int (*create)(const fb_value* params, void** instance, fb_error_buffer error);
  void (*destroy)(void* instance);
  void (*radius)(const void* instance, float radius_px[2]); /* zero beyond it */
  float (*evaluate)(const void* instance, float x, float y);
  double (*integral)(const void* instance); /* of evaluate over R^2 */
  void (*sample)(const void* instance, const float* u /* 2 per sample */, size_t count,
                 fb_filter_sample* samples);
} fb_filter_api;

/* -------------------------------------------------------------------------------- integrator */

typedef struct fb_ray {
  float origin[3]; /* render space: world translated so the camera is at the origin */
  float direction[3];
  float t_min, t_max;
  float time_s; /* the camera ray's time (fb_camera_sample); rays a path spawns keep it */
} fb_ray;

#define FB_NONE 0xffffffffu

typedef struct fb_hit {
  float t;
  float position[3];
  float position_error[3];   /* conservative bound on |position - exact|, per axis */
  float geometric_normal[3]; /* unit; the triangle's winding decides its side */
  float shading_normal[3];   /* unit; interpolated vertex normal, same side as geometric */
  uint32_t material;         /* index into fb_scene.materials */
  uint32_t emitter;          /* emissive-triangle light index, or FB_NONE */
  /* The surface at the hit, its material's textures evaluated by the host (glTF
   * metallic-roughness, docs/plugins.md "Surfaces"). shading_normal above already has the normal
   * map applied. These fields were appended to fb_hit together with fb_integrator_api.hit_size:
   * an integrator built before them has a smaller function table and is refused at load time. */
  float base_color[3]; /* linear reflectance (metals: the colour at normal incidence) */
  float metallic;      /* 0 dielectric ... 1 metal */
  float roughness;     /* perceptual, as glTF and Blender: GGX alpha = roughness^2 */
  /* fraction of the dielectric base that refracts (KHR_materials_transmission) */
  float transmission;
  float ior;      /* index of refraction of the material (outside it: 1) */
  float specular; /* scales the dielectric Fresnel (KHR_materials_specular); 0: Lambertian */
  /* radiance leaving the front face (both faces if double-sided), W sr^-1 m^-2 */
  float emission[3];
  /* unit; the interpolated vertex normal before the normal map (shading_normal without it), for
   * the shadowing term of bumped diffuse surfaces (filmback/bsdf.h) */
  float smooth_normal[3];
  /* Where rays towards lights leave: position lifted onto the smooth surface the triangle's vertex
   * normals describe (Hanika 2021, "Hacking the Shadow Terminator"), so that the flat facets of a
   * coarse mesh with smooth normals do not shadow it along the terminator. Equal to position where
   * the surface is flat, concave or has no vertex normals; position_error bounds it too. */
  float shadow_position[3];
} fb_hit;

/* A material's constant factors. The layout is frozen: what a material has beyond these reaches
 * integrators evaluated per hit, in fb_hit. */
typedef struct fb_material {
  float base_color[3];   /* base colour factor; textures may modulate it per hit */
  float emission[3];     /* radiance, W sr^-1 m^-2, before emissive textures */
  uint32_t double_sided; /* emission leaves the back face too */
} fb_material;

typedef struct fb_light_sample {
  float radiance[3];  /* arriving at the shading point: L (area), I/d^2 (point, spot), E (sun) */
  float direction[3]; /* unit, from the shading point towards the light */
  /* to the light point; HUGE_VAL for a directional light; 0 for a light nothing shadows (POV-Ray's
   * `shadowless`): trace no shadow ray (a shadow ray of length 0 is never occluded either) */
  float distance;
  float pdf;          /* solid-angle pdf with the light choice; for delta lights the choice only */
  uint32_t is_delta;
} fb_light_sample;

typedef struct fb_trace_context fb_trace_context; /* per-thread host state: opaque */

/* What the host offers an integrator. All calls are thread-safe with distinct contexts. A ray
 * with a NaN, or a coordinate beyond 1e18, is not traced: it misses and is not occluded. */
typedef struct fb_scene_api {
  uint32_t struct_size;
  int (*intersect)(fb_trace_context* context, const fb_ray* ray, fb_hit* hit);
  /* The same for `count` rays at once, traced as coherent packets: for rays that start together
   * and point alike (camera rays), several times faster than one at a time. A miss leaves
   * hits[i].t = +infinity and the rest of hits[i] unset. Its rays are taken for camera rays: area
   * lights, which Cycles does not show to the camera, are not hit (as by `occluded`). */
  void (*intersect_batch)(fb_trace_context* context, const fb_ray* rays, size_t count,
                          fb_hit* hits);
  int (*occluded)(fb_trace_context* context, const fb_ray* ray);
  /* Picks a light (punctual or emissive triangle) and a point on it, as seen from `position`.
   * Returns 0 when the scene has no light or the sample carries no energy. */
  int (*sample_light)(fb_trace_context* context, const float position[3], const float u[3],
                      fb_light_sample* sample);
  /* Solid-angle pdf with which sample_light() would have chosen `hit` (an emitter) from
   * `position`: for multiple importance sampling of emission found by BSDF sampling. */
  float (*light_pdf)(fb_trace_context* context, const float position[3], const fb_hit* hit);
  /* The next `count` sample dimensions of path `path` of the current batch: multiples of 2^-24
   * in [0,1), as every sample value the host hands out. The host stratifies a request as one
   * 1-D value (when `count` is odd) followed by 2-D pairs, so ask for what belongs together in
   * one call: a choice and a 2-D point (3 values), or a 2-D point alone (2). */
  void (*next_samples)(fb_trace_context* context, size_t path, float* u, uint32_t count);
  /* Radiance of the world reaching a ray that escapes along `direction` (a uniform background or
   * an environment image), and in *pdf the solid-angle pdf with which sample_light() would have
   * chosen that direction: 0 when light sampling never picks the world (weight it fully). */
  void (*background)(fb_trace_context* context, const float direction[3], float radiance[3],
                     float* pdf);
} fb_scene_api;

typedef struct fb_scene {
  uint32_t struct_size;
  const fb_scene_api* api;
  const fb_material* materials;
  uint32_t material_count;
  float background[3];  /* uniform radiance of rays that escape (api->background() is the world) */
  float scene_radius_m; /* a sphere of this radius about the camera holds the whole scene */
  float view_axis[3];   /* unit: where the camera looks; depth = dot(position, view_axis) */
} fb_scene;

#define FB_MAX_CHANNELS 16u

typedef struct fb_integrator_api {
  uint32_t struct_size;
  int (*create)(const fb_value* params, void** instance, fb_error_buffer error);
  void (*destroy)(void* instance);
  /* Names of the values radiance() writes per ray, e.g. "R","G","B","depth.Z". At most
   * FB_MAX_CHANNELS; the first three are the image's colour. */
  uint32_t (*channels)(const void* instance, const char** names, uint32_t capacity);
  /* values[i * channel_count + c] for ray i; one call per batch of camera rays. */
  void (*radiance)(const void* instance, const fb_scene* scene, fb_trace_context* context,
                   const fb_ray* rays, size_t count, float* values);
  /* sizeof(fb_hit) as the plugin was built: the host writes hit records into the plugin's
   * memory, so the loader refuses a plugin whose records are not this host's. */
  uint32_t hit_size;
} fb_integrator_api;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* FILMBACK_PLUGIN_ABI_H */
