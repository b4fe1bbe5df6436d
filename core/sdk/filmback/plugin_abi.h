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
 * Growth (docs/plugins.md, "ABI growth"): within ABI version 1 a struct only grows, by fields
 * appended at its end, and a plugin built against an older header keeps loading and running.
 * Every struct that may grow has its size said: its first field `struct_size` (fb_plugin, the
 * function tables, fb_camera_setup, fb_scene, fb_scene_api), or a size the integrator declares
 * (fb_integrator_api: hit_size, scene_size, scene_api_size).
 *  - What the plugin hands the host (fb_plugin, its function table) may have any size from the
 *    first published layout (tests/sdk/abi_frozen/filmback/plugin_abi.h) up to the host's: the
 *    host reads only the fields that size covers and takes the default each field documents for
 *    the rest.
 *  - What the host hands the plugin is filled only as far as the plugin's declared size covers:
 *    hit records are written with hit_size as their stride; fb_scene and its fb_scene_api say the
 *    plugin's scene_size and scene_api_size in their struct_size (a table no longer than the
 *    plugin knows). fb_camera_setup, which the plugin only reads, carries the host's struct_size;
 *    the plugin reads the fields it knows.
 *  - A plugin newer than the host (any of these sizes larger than the host's) is refused, naming
 *    the file and both sizes.
 * Structs without a size (fb_param_desc, fb_value, the samples, rays, fb_material, fb_light_sample,
 * fb_bsdf_sample, fb_light_crossing) are frozen. A growth must change sizeof: appended fields add
 * up to at least the struct's alignment (two uint32_t after a pointer-aligned struct, not one,
 * which would fall into its tail padding and leave two layouts the same size).
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
  double min_value;          /* numbers: inclusive bounds (use +-HUGE_VAL for none; a FLOAT
                                bounded by +HUGE_VAL also admits "inf") */
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

/* PANORAMIC: a projection of the plugin's own (equirectangular, fisheye, ...), whose values are its
   parameters; the view plane's values (focal length, sensor, shift) are the shot's as Blender has
   them, which some panoramas use (Cycles' equisolid fisheye). */
enum { FB_PROJECTION_PERSPECTIVE = 1, FB_PROJECTION_ORTHOGRAPHIC = 2, FB_PROJECTION_PANORAMIC = 3 };
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
  /* The lens, as the shot has it, kept for camera plugins built before camera parameters: a
     lens model declares its values as parameters (thinlens: fstop, focus_distance_m,
     aperture_blades, aperture_rotation_rad, aperture_ratio), which the host fills by name from the
     shot (docs/plugins.md, "Camera parameters"). */
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
  /* Appended after the first published layout (Growth): what the camera derives from its values,
     for `filmback info`, as lines "name: value unit" ("effective focal length: 50.02 mm"), written
     NUL-terminated into text[0..capacity), cut to fit. NULL when it has nothing to add. */
  void (*describe)(const void* instance, char* text, size_t capacity);
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
   * map applied. Fields appended to fb_hit reach only integrators that declare them:
   * fb_integrator_api.hit_size says how much of a record the plugin knows, and the host writes
   * that much. */
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
  /* How the surface scatters light at this hit, prepared by the host for the ray that found it
   * (its material's closures, textures evaluated, normals turned to the ray's side): pass the hit
   * to fb_scene_api's bsdf_eval() and bsdf_sample(). Opaque. A hit of intersect_batch keeps it
   * until the radiance() call that traced it returns; a hit of intersect() until 63 more rays have
   * been traced with intersect() on the same context. Appended after the first published layout:
   * the host reads it as NULL (no surface: bsdf_* find no light) from an older integrator. */
  const struct fb_surface* surface;
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
  float pdf; /* solid-angle pdf with the light choice; for delta lights the choice only */
  uint32_t is_delta;
} fb_light_sample;

/* What bsdf_sample() draws. */
enum {
  FB_BSDF_DELTA = 1u,       /* a perfectly specular lobe: pdf is its choice probability, and light
                               sampling (bsdf_eval) can never reach it: weight it fully */
  FB_BSDF_TRANSMISSION = 2u /* wi leaves through the surface, to the other side */
};

typedef struct fb_bsdf_sample {
  float wi[3];     /* render space, unit, away from the surface */
  float weight[3]; /* f |cos| / pdf */
  float pdf;       /* solid angle (of the whole surface's sampling, for MIS) */
  uint32_t flags;  /* FB_BSDF_* */
} fb_bsdf_sample;

/* A light a ray passes through on its way (lights are not surfaces: they neither stop nor shadow
 * rays, as in Cycles), with the pdf sample_light() would have chosen that point with, from the
 * ray's origin, for multiple importance sampling. */
typedef struct fb_light_crossing {
  float radiance[3]; /* arriving along the ray, W sr^-1 m^-2 */
  float pdf;         /* solid angle, with the light choice */
  float t;           /* distance along the ray; HUGE_VAL for a distant light (a sun's disk) */
} fb_light_crossing;

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
  /* The surface at `hit` (fb_hit.surface): f(wo, wi) |cos(n, wi)| summed over its closures, wo
   * being the direction back along the hit's ray, and in *pdf the solid-angle pdf with which
   * bsdf_sample() would draw wi (0 where it never does: weight light sampling fully there).
   * Directions in render space, unit, away from the surface. */
  void (*bsdf_eval)(fb_trace_context* context, const fb_hit* hit, const float wi[3], float f_cos[3],
                    float* pdf);
  /* Draws a direction from the surface at `hit` with three sample values (a closure choice and a
   * 2-D point, as next_samples() hands them out). Returns 0 when the sample carries no light. */
  int (*bsdf_sample)(fb_trace_context* context, const fb_hit* hit, const float u[3],
                     fb_bsdf_sample* sample);
  /* The lights `ray` passes through before distance `t_end` (its hit, or HUGE_VAL when it
   * escapes: then the distant lights whose disk it points into count too), nearest first, at most
   * `capacity` of them. Lights with a size (a point or spot light's radius, area lights, a sun's
   * angle) are found so; delta lights never are. Returns how many it wrote. */
  uint32_t (*lights_crossed)(fb_trace_context* context, const fb_ray* ray, float t_end,
                             fb_light_crossing* crossings, uint32_t capacity);
  /* Appended by issue 19 (Growth): a point on lamp `lamp` (the scene's
   * lights, 0 .. fb_scene.lamp_count - 1; not emissive triangles nor the world) as seen from
   * `position`, with two sample values (a POV-Ray area light's grid point, a point on a light with
   * a size), without a choice among lights: pdf is 1 for a delta light. For integrators that sum
   * over every light, as POV-Ray does. `u` NULL asks for the lamp's centre (a POV-Ray area
   * light's, which POV-Ray lights from while its grid shadows; u = (0.5, 0.5) for a light with a
   * size). Returns 0 when the sample carries no light. */
  int (*sample_lamp)(fb_trace_context* context, uint32_t lamp, const float position[3],
                     const float u[2], fb_light_sample* sample);
  /* Appended by issue 20 (Growth): the summed weights of the surface's closures of one kind at
   * `hit` (FB_CLOSURE_DIFFUSE, _GLOSSY, _TRANSMISSION): each closure's colour times its share of
   * the material, its Fresnel factor left in its evaluation, as Cycles 3.4 sums them into the
   * DiffCol, GlossCol and TransCol passes (docs/blender.md, "Passes"). Zero for a hit without a
   * surface or an unknown kind. */
  void (*closure_weight)(fb_trace_context* context, const fb_hit* hit, uint32_t kind,
                         float weight[3]);
  /* Appended by issue 19 (Growth, fog): the medium that fills the scene (POV-Ray's fog) along
   * `ray` up to distance `t_end` (its hit, or HUGE_VAL when it escapes): the radiance from the far
   * end is to be multiplied by transmittance[] and emitted[] added, per channel. `povray_blend`
   * nonzero asks for POV-Ray's blend (its fog's filter and transmit included), 0 for the physical
   * medium it maps to (docs/pov.md, "Fog"). Returns 0, writing nothing, when the scene has no
   * such medium. */
  int (*medium_segment)(fb_trace_context* context, const fb_ray* ray, float t_end, int povray_blend,
                        float transmittance[3], float emitted[3]);
} fb_scene_api;

/* The kinds of closure fb_scene_api.closure_weight() sums, Cycles' CLOSURE_IS_BSDF_DIFFUSE,
 * _GLOSSY and _TRANSMISSION (a multiscatter glass, one closure for both, is transmission). */
#define FB_CLOSURE_DIFFUSE 0u
#define FB_CLOSURE_GLOSSY 1u
#define FB_CLOSURE_TRANSMISSION 2u

/* POV-Ray's finish and interior as the scene wrote them (docs/pov.md, "The povray integrator"),
 * for an integrator that lights a surface as POV-Ray 3.7 does rather than physically. Colours
 * decoded to linear as the scene's pigments are; amounts as written. Frozen: a later need appends
 * a new array to fb_povray_scene. */
typedef struct fb_pov_finish {
  uint32_t present; /* 0: the material has no POV-Ray finish (not from a .pov scene) */
  float pigment[3]; /* the pigment's colour (a pattern's average) */
  /* fb_hit.base_color is the pigment at the hit times this (diffuse, or 1 for metals and
   * transparent pigments, docs/pov.md "Finishes and interiors"); 0 (no diffuse): fb_hit.emission
   * is the pigment at the hit times ambient + emission, or read `pigment` where they are 0 */
  float pigment_scale;
  float filter, transmit; /* the pigment's (0 for a patterned pigment: not known per hit) */
  /* the probability that intersect() keeps a hit on it: 1 - transmit where the host blends a
   * transmitting pigment's coverage stochastically (docs/plugins.md, end), else 1 */
  float coverage;
  float ambient[3];  /* finish ambient times the scene's ambient_light */
  float emission[3]; /* finish emission */
  float diffuse, brilliance;
  float phong, phong_size;
  float specular, roughness; /* Blinn exponent 1 / roughness */
  float metallic;            /* highlights tinted by the pigment */
  float reflection_min[3], reflection_max[3];
  float reflection_falloff;  /* exponent on (1 - cos) between min and max */
  float reflection_exponent; /* applied to the reflected colour */
  uint32_t reflection_fresnel;
  float reflection_metallic; /* reflection tinted by the pigment */
  float ior;                 /* the interior's; 1: none or not refracting */
} fb_pov_finish;

/* A POV-Ray scene's global_settings and finishes; fb_scene.povray, NULL for other scenes. */
typedef struct fb_povray_scene {
  uint32_t struct_size;          /* sizeof(fb_povray_scene) as the host built it; it may grow */
  uint32_t max_trace_level;      /* global_settings max_trace_level (POV-Ray's default 5) */
  float adc_bailout;             /* global_settings adc_bailout (default 1/255) */
  uint32_t finish_count;         /* fb_scene.material_count */
  const fb_pov_finish* finishes; /* one per material, by index */
  /* Appended by issue 19 (Growth, gamma): the exponent g that decoded the scene's colours (its
   * assumed_gamma; 2.2 for a legacy scene, docs/pov.md "Colours and assumed_gamma"). POV-Ray
   * lights in the scene's own values and decodes the pixel by g at the end: an integrator that
   * does so raises the decoded colours to 1/g first. 1 for a linear scene. */
  float colour_gamma;
  float
      ambient_light[3]; /* global_settings ambient_light, decoded (fb_pov_finish.ambient has it) */
} fb_povray_scene;

/* The homogeneous medium inside a material's closed surfaces (POV-Ray's interior media, docs/pov.md
 * "Media"): a ray is in it between its entry into such a surface (the side its geometric normal
 * faces) and its exit. Coefficients per metre. Frozen: a later need appends a new array. */
typedef struct fb_medium {
  uint32_t present;    /* 0: the material holds no medium */
  float absorption[3]; /* sigma_a, m^-1 */
  float scattering[3]; /* sigma_s, m^-1, isotropic phase */
  float emission[3];   /* radiance added per metre of path, W sr^-1 m^-3 */
  /* POV-Ray's attenuation: absorption + its `extinction` times scattering */
  float povray_extinction[3];
  /* How many points along a segment POV-Ray 3.7 sums the medium's light at (its samples and
   * intervals, docs/pov.md "Media") */
  uint32_t povray_points;
} fb_medium;

typedef struct fb_scene {
  uint32_t struct_size;
  const fb_scene_api* api;
  const fb_material* materials;
  uint32_t material_count;
  float background[3];  /* uniform radiance of rays that escape (api->background() is the world) */
  float scene_radius_m; /* a sphere of this radius about the camera holds the whole scene */
  float view_axis[3];   /* unit: where the camera looks; depth = dot(position, view_axis) */
  /* Appended together by issue 19 (Growth): a POV-Ray scene's finishes
   * (NULL for other scenes), and how many lamps fb_scene_api.sample_lamp() takes. */
  const fb_povray_scene* povray;
  uint32_t lamp_count;
  /* Appended by issue 19 (Growth, media): one per material, by index; NULL when no material
   * holds a medium (then no ray is ever in one). */
  const fb_medium* media;
} fb_scene;

/* The most channels the host takes from an integrator. 16 in the first published layout; 32 since
 * render passes (filmback/render_passes.h): the beauty and every pass is 22. A host limit, not a
 * layout: a plugin that reports more than a host takes is refused by that host, naming both. */
#define FB_MAX_CHANNELS 32u

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
  /* sizeof(fb_hit) as the plugin was built: the host writes hit records of this size (and with
   * this stride) into the plugin's memory, and reads no more of a record the plugin hands it. */
  uint32_t hit_size;
  /* sizeof(fb_scene) and sizeof(fb_scene_api) as the plugin was built: the host says them in the
   * struct_size of the scene and the function table it hands radiance(). Appended after the first
   * published layout: a table without them (struct_size 48 on LP64) gets that layout's sizes. */
  uint32_t scene_size;
  uint32_t scene_api_size;
} fb_integrator_api;

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* FILMBACK_PLUGIN_ABI_H */
