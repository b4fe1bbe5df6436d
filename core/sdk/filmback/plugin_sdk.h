// Conveniences for writing a plugin in C++. Everything here is inline: a plugin links nothing of
// filmback's, it only includes headers (docs/plugins.md).
#pragma once

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "plugin_abi.h"
#include "vec.h"

namespace fb {

// printf-style one-line reason for a failed create().
inline int fail(fb_error_buffer error, const char* format, ...) {
  if (error.text && error.capacity > 0) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(error.text, error.capacity, format, args);
    va_end(args);
  }
  return 1;
}

// create() for a class constructible from its validated parameters; no exception leaves it.
template <typename T, typename... Args>
int create_instance(void** instance, fb_error_buffer error, Args&&... args) {
  try {
    *instance = new T(std::forward<Args>(args)...);
    return 0;
  } catch (const std::exception& e) {
    return fail(error, "%s", e.what());
  } catch (...) {
    return fail(error, "unknown error while creating the plugin instance");
  }
}

template <typename T>
void destroy_instance(void* instance) {
  delete static_cast<T*>(instance);
}

// ------------------------------------------------------------------ parameters, by name
//
// create() receives the validated values in the order of the plugin's schema. A plugin reads them
// through handles found by name, so that its code never depends on that order:
//
//   constexpr fb_param_desc kParams[] = {{"radius", FB_PARAM_FLOAT, ...}, {"sigma", ...}};
//   constexpr auto kSigma = fb::param<double>(kParams, "sigma");  // looked up once
//   explicit Gaussian(const fb_value* values) : sigma_(kSigma(values)) {}
//
// A handle knows its parameter's place and C++ type: double or float (FB_PARAM_FLOAT), int
// (FB_PARAM_INT), bool (FB_PARAM_BOOL), const char* (FB_PARAM_STRING: valid only during create(),
// copy what you keep) or fb::Rgb (FB_PARAM_RGB). Made in a constexpr, a name the schema lacks or a
// type that is not the parameter's fails to compile; made at run time, it throws
// std::invalid_argument, which create() reports.
template <typename T>
constexpr uint32_t param_type_of() {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, float>)
    return FB_PARAM_FLOAT;
  else if constexpr (std::is_same_v<T, int>)
    return FB_PARAM_INT;
  else if constexpr (std::is_same_v<T, bool>)
    return FB_PARAM_BOOL;
  else if constexpr (std::is_same_v<T, const char*>)
    return FB_PARAM_STRING;
  else {
    static_assert(std::is_same_v<T, Rgb>,
                  "parameters read as double, float, int, bool, "
                  "const char* or fb::Rgb");
    return FB_PARAM_RGB;
  }
}

template <typename T>
class Param {
 public:
  constexpr explicit Param(uint32_t index) : index_(index) {}
  constexpr uint32_t index() const { return index_; }
  // This parameter's value among create()'s `values`.
  T operator()(const fb_value* values) const {
    const fb_value& v = values[index_];
    if constexpr (std::is_same_v<T, const char*>)
      return v.text;
    else if constexpr (std::is_same_v<T, bool>)
      return v.number[0] != 0;
    else if constexpr (std::is_same_v<T, Rgb>)
      return Rgb(float(v.number[0]), float(v.number[1]), float(v.number[2]));
    else
      return T(v.number[0]);
  }

 private:
  uint32_t index_;
};

// The handle of parameter `name` in `schema` (count entries), typed T.
template <typename T>
constexpr Param<T> param(const fb_param_desc* schema, size_t count, std::string_view name) {
  for (size_t i = 0; i < count; ++i) {
    if (!schema[i].name || name != schema[i].name) continue;
    if (schema[i].type != param_type_of<T>())
      throw std::invalid_argument("parameter '" + std::string(name) +
                                  "' is not of the type the plugin reads it as");
    return Param<T>(uint32_t(i));
  }
  throw std::invalid_argument("the plugin reads a parameter '" + std::string(name) +
                              "' its schema lacks");
}

template <typename T, size_t N>
constexpr Param<T> param(const fb_param_desc (&schema)[N], std::string_view name) {
  return param<T>(schema, N, name);
}

// The first hits of a batch of camera rays, traced as one coherent batch (Embree packets): rays
// that start together are several times cheaper this way. Valid until the next call on this thread.
inline const fb_hit* first_hits(const fb_scene& scene, fb_trace_context* context,
                                const fb_ray* rays, size_t count) {
  thread_local std::vector<fb_hit> hits;
  hits.resize(count);
  scene.api->intersect_batch(context, rays, count, hits.data());
  return hits.data();
}

// Function tables for C++ classes, so a plugin writes only its maths. A constructor that finds
// its parameters or setup unusable throws std::invalid_argument; the message reaches the user.
//
//   Camera(const fb_value* params, const fb_camera_setup& setup);
//   uint32_t needs() const;
//   void generate(const fb_camera_sample& sample, fb_camera_ray& ray) const;
//   std::string describe() const;               (optional: lines for `filmback info`)
template <typename Camera>
constexpr fb_camera_api camera_api() {
  using Describe = void (*)(const void*, char*, size_t);
  Describe describe = nullptr;
  if constexpr (requires(const Camera& c) { std::string(c.describe()); })
    describe = [](const void* self, char* text, size_t capacity) {
      if (capacity == 0) return;
      text[0] = '\0';
      try {  // no exception crosses the C boundary; a failed description is an empty one
        const std::string lines = static_cast<const Camera*>(self)->describe();
        const size_t n = std::min(lines.size(), capacity - 1);
        lines.copy(text, n);
        text[n] = '\0';
      } catch (...) {
      }
    };
  return {sizeof(fb_camera_api),
          [](const fb_value* params, const fb_camera_setup* setup, void** instance,
             fb_error_buffer error) {
            return create_instance<Camera>(instance, error, params, *setup);
          },
          destroy_instance<Camera>,
          [](const void* self) { return static_cast<const Camera*>(self)->needs(); },
          [](const void* self, const fb_camera_sample* samples, size_t count, fb_camera_ray* rays) {
            const auto& camera = *static_cast<const Camera*>(self);
            for (size_t i = 0; i < count; ++i)
              camera.generate(samples[i], rays[i]);
          },
          describe};
}

//   Filter(const fb_value* params);
//   float radius() const;                       (the same on both axes)
//   float evaluate(float x, float y) const;
//   double integral() const;
//   fb_filter_sample sample(float ux, float uy) const;
template <typename Filter>
constexpr fb_filter_api filter_api() {
  return {sizeof(fb_filter_api),
          [](const fb_value* params, void** instance, fb_error_buffer error) {
            return create_instance<Filter>(instance, error, params);
          },
          destroy_instance<Filter>,
          [](const void* self, float r[2]) {
            r[0] = r[1] = static_cast<const Filter*>(self)->radius();
          },
          [](const void* self, float x, float y) {
            return static_cast<const Filter*>(self)->evaluate(x, y);
          },
          [](const void* self) { return static_cast<const Filter*>(self)->integral(); },
          [](const void* self, const float* u, size_t count, fb_filter_sample* samples) {
            const auto& filter = *static_cast<const Filter*>(self);
            for (size_t i = 0; i < count; ++i)
              samples[i] = filter.sample(u[2 * i], u[2 * i + 1]);
          }};
}

//   Integrator(const fb_value* params);
//   static constexpr const char* kChannels[] = {"R", "G", "B", ...};
//     or, when the channels depend on the parameters (render passes, filmback/render_passes.h):
//   const std::vector<std::string>& channel_names() const;
//   void radiance(const fb_scene& scene, fb_trace_context* context, const fb_ray* rays,
//                 size_t count, float* values) const;   (values: count x channels)
template <typename Integrator>
constexpr fb_integrator_api integrator_api() {
  using Channels = uint32_t (*)(const void*, const char**, uint32_t);
  Channels channels = nullptr;
  if constexpr (requires(const Integrator& i) { i.channel_names().size(); }) {
    channels = [](const void* self, const char** names, uint32_t capacity) {
      const auto& list = static_cast<const Integrator*>(self)->channel_names();
      for (uint32_t i = 0; i < list.size() && i < capacity; ++i)
        names[i] = list[i].c_str();
      return uint32_t(list.size());
    };
  } else {
    constexpr size_t kCount = sizeof Integrator::kChannels / sizeof Integrator::kChannels[0];
    static_assert(kCount >= 3 && kCount <= FB_MAX_CHANNELS);
    channels = [](const void*, const char** names, uint32_t capacity) {
      for (uint32_t i = 0; i < kCount && i < capacity; ++i)
        names[i] = Integrator::kChannels[i];
      return uint32_t(kCount);
    };
  }
  return {sizeof(fb_integrator_api),
          [](const fb_value* params, void** instance, fb_error_buffer error) {
            return create_instance<Integrator>(instance, error, params);
          },
          destroy_instance<Integrator>,
          channels,
          [](const void* self, const fb_scene* scene, fb_trace_context* context, const fb_ray* rays,
             size_t count, float* values) {
            static_cast<const Integrator*>(self)->radiance(*scene, context, rays, count, values);
          },
          sizeof(fb_hit),
          sizeof(fb_scene),
          sizeof(fb_scene_api)};
}

// The plugin's descriptor; its kind follows from the type of its function table.
template <typename Api>
constexpr uint32_t kind_of() {
  if constexpr (std::is_same_v<Api, fb_camera_api>)
    return FB_KIND_CAMERA;
  else if constexpr (std::is_same_v<Api, fb_filter_api>)
    return FB_KIND_FILTER;
  else {
    static_assert(std::is_same_v<Api, fb_integrator_api>, "not a filmback function table");
    return FB_KIND_INTEGRATOR;
  }
}

template <typename Api, size_t N>
constexpr fb_plugin describe(const char* name, const char* version, const char* summary,
                             const fb_param_desc (&params)[N], const Api& api) {
  return {FB_ABI_VERSION, sizeof(fb_plugin), kind_of<Api>(),
          name,           version,           summary,
          params,         uint32_t(N),       &api};
}

template <typename Api>
constexpr fb_plugin describe(const char* name, const char* version, const char* summary,
                             const Api& api) {
  return {
      FB_ABI_VERSION, sizeof(fb_plugin), kind_of<Api>(), name, version, summary, nullptr, 0, &api};
}

}  // namespace fb

// The one symbol a plugin exports (plugin_abi.h), returning its fb::describe() descriptor.
#define FB_PLUGIN_ENTRY(descriptor)                                \
  extern "C" FB_EXPORT const fb_plugin* filmback_plugin_v1(void) { \
    return &(descriptor);                                          \
  }
