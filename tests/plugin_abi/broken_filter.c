/* A filter plugin with at most one defect, chosen at compile time. tests/plugin_abi/CMakeLists.txt
 * builds this file once per defect (and twice without one, under file names that contradict the
 * descriptor); loader_errors_test.cpp checks that the loader names each file and says what is
 * wrong. Without a DEFECT_* macro it is a valid box filter of radius 0.5 px called PLUGIN_NAME. */
#include <filmback/plugin_abi.h>

#include <stdint.h>
#include <stdio.h>

#ifndef PLUGIN_NAME
#error "define PLUGIN_NAME, the name the descriptor declares"
#endif

/* DEFECT_NO_ENTRY_POINT: the descriptor is exported under another name, as by a typo or a
 * pre-release plugin, so the library holds no filmback_plugin_v1. */
#ifdef DEFECT_NO_ENTRY_POINT
#define ENTRY_POINT filmback_plugin_v0
#else
#define ENTRY_POINT filmback_plugin_v1
#endif

/* DEFECT_ABI_VERSION: built for a plugin ABI this filmback does not speak. */
#ifdef DEFECT_ABI_VERSION
#define ABI_VERSION (FB_ABI_VERSION + 1u)
#else
#define ABI_VERSION FB_ABI_VERSION
#endif

/* DEFECT_BAD_DEFAULT: the default lies outside the parameter's own bounds. */
#ifdef DEFECT_BAD_DEFAULT
#define RADIUS_DEFAULT "-1"
#else
#define RADIUS_DEFAULT "0.5"
#endif

/* DEFECT_NULL_FUNCTION: the function table leaves sample() out. */
#ifdef DEFECT_NULL_FUNCTION
#define SAMPLE_FUNCTION NULL
#else
#define SAMPLE_FUNCTION sample
#endif

/* DEFECT_DESCRIPTOR_SIZE and DEFECT_TABLE_SIZE: the descriptor or the filter table as a newer SDK
 * might have grown it, with the size fields saying so. */
typedef struct descriptor {
  fb_plugin plugin;
#ifdef DEFECT_DESCRIPTOR_SIZE
  const void* field_of_a_newer_sdk;
#endif
} descriptor;

typedef struct function_table {
  fb_filter_api filter;
#ifdef DEFECT_TABLE_SIZE
  void (*function_of_a_newer_sdk)(void);
#endif
} function_table;

/* DEFECT_MISSING_SYMBOL: create() calls a function the plugin brings no library for (`unresolved`),
 * or one from a library the dynamic loader cannot find (`nolibrary`, linked against
 * absent_library.c without a run path). `unresolved` links only because it is built without
 * -Wl,--no-undefined; the loader's RTLD_NOW must refuse both, saying what is missing. */
#ifdef DEFECT_MISSING_SYMBOL
extern int fb_test_absent_function(void);
#endif

static int instance; /* a box of fixed radius has no state; create() hands out this address */

static int create(const fb_value* values, void** out, fb_error_buffer error) {
#ifdef DEFECT_CREATE_CRASHES
  /* DEFECT_CREATE_CRASHES: create() writes through a stray pointer (SIGSEGV). Not a null pointer,
   * which UndefinedBehaviorSanitizer would stop at first in a sanitized build; read from a
   * volatile, so that no compiler sees the constant address. */
  volatile uintptr_t stray = 16;
  *(volatile int*)stray = 1;
#endif
#ifdef DEFECT_CREATE_FAILS
  /* DEFECT_CREATE_FAILS: the library is well formed, but create() refuses with a reason. */
  snprintf(error.text, error.capacity, "this test filter always refuses (radius %.1f px)",
           values[0].number[0]);
  return 1;
#endif
#ifdef DEFECT_MISSING_SYMBOL
  if (fb_test_absent_function() != 0) return 1;
#endif
  (void)values;
  (void)error;
  *out = &instance;
  return 0;
}

static void destroy(void* self) {
  (void)self;
}

static void radius(const void* self, float radius_px[2]) {
  (void)self;
#ifdef DEFECT_RADIUS_CRASHES
  /* DEFECT_RADIUS_CRASHES: create() succeeds, radius() faults, before any pixel is rendered. */
  volatile uintptr_t stray = 16;
  *(volatile int*)stray = 1;
#endif
  radius_px[0] = radius_px[1] = 0.5f;
}

static float evaluate(const void* self, float x, float y) {
  (void)self;
  return x >= -0.5f && x <= 0.5f && y >= -0.5f && y <= 0.5f ? 1.f : 0.f;
}

static double integral(const void* self) {
  (void)self;
  return 1.0;
}

#ifndef DEFECT_NULL_FUNCTION
static void sample(const void* self, const float* u, size_t count, fb_filter_sample* samples) {
  (void)self;
  for (size_t i = 0; i < count; ++i) {
    samples[i].x = u[2 * i] - 0.5f;
    samples[i].y = u[2 * i + 1] - 0.5f;
    samples[i].weight = 1.f;
  }
}
#endif

static const fb_param_desc params[] = {
    {"radius", FB_PARAM_FLOAT, RADIUS_DEFAULT, "px", NULL, 0.5, 0.5, "half-width of the box"},
};

/* Designated initialisers leave a grown struct's extra field zero. */
static const function_table table = {.filter = {sizeof(function_table), create, destroy, radius,
                                                evaluate, integral, SAMPLE_FUNCTION}};

/* DEFECT_DESCRIPTOR_CRASHES: the name points at unmapped memory, so the loader's first look at it
 * faults (SIGSEGV). */
#ifdef DEFECT_DESCRIPTOR_CRASHES
#define DESCRIPTOR_NAME ((const char*)16)
#else
#define DESCRIPTOR_NAME PLUGIN_NAME
#endif

static const descriptor desc = {.plugin = {ABI_VERSION, sizeof(descriptor), FB_KIND_FILTER,
                                           DESCRIPTOR_NAME, "1.0.0",
                                           "Test filter for the loader's error messages", params,
                                           sizeof params / sizeof params[0], &table}};

FB_EXPORT const fb_plugin* ENTRY_POINT(void) {
  return &desc.plugin;
}
